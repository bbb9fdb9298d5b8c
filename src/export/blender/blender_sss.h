/* blender_sss: the translucent mode of the Blender export (issue 27,
 * docs/translucency.md).  Cycles' Subsurface Scattering node is fitted to
 * the bake's Rd(r) from the calibration of each Blender version measured
 * (blender_sss_tables: Debian's 3.4 "Random Walk", the bpy venvs' 4.5 and
 * 5.0 "Random Walk (Skin)"; export/sss_fit.h), so one image set serves
 * every calibrated Blender and the importer picks its own.  The node's far
 * field, measured, does not depend on theta_i (the walk enters through a
 * cosine-weighted direction); in 3.4 it is Lambertian (G(0) / pi), in 4.5
 * and 5.0 it rises toward grazing exit (0.92 G(0) / pi at theta_o = 0,
 * 1.22 at 85 degrees, colour 0.15).  The exact mode's table (brdf_lut.exr)
 * holds the remainder: the baked BRDF (diffuse + surface specular) minus the
 * largest of the versions' far fields at each angle, never negative; each
 * version's node comes with a diffuse term of the difference, a function of
 * theta_o (lambert_extra at theta_o_deg), so every version adds up to the
 * table (manifest section "translucent"). */
#ifndef SKINBAKE_BLENDER_SSS_H
#define SKINBAKE_BLENDER_SSS_H
#include "export/source.h"
#include "export/sss_fit.h"

#define BLENDER_SSS_MAX 8

/* The Cycles calibrations, oldest Blender first, NULL-terminated
 * (generated: blender_sss_table.c, scripts/calibrate-translucency.py). */
extern const struct sss_table *const blender_sss_tables[];

struct blender_sss {
	int n;				/* calibrated versions fitted */
	struct sss_fit fit[BLENDER_SSS_MAX];	/* per version: the node's parameters, residuals */
	brdf_rgb_fn f_rgb;		/* the source's own BRDF */
	void *ctx;
	double clipped;			/* largest share of the table the remainder clipped at 0 [-] */
};

/* The Blender "major.minor" a table was measured on, into BUF. */
void blender_sss_series(const struct sss_table *t, char *buf, size_t n);

/* Fit Cycles' closure of every calibrated version to the source's bake and
 * make the source's f_rgb the remainder (W must outlive the source's use).
 * -1 and *cause when the source has no bake with a radial profile or Cycles
 * no calibration. */
int blender_sss_wrap(struct brdf_source *src, struct blender_sss *w, char **cause);

/* The manifest section "translucent" (JSON text, caller frees). */
char *blender_sss_json(const struct blender_sss *w);
#endif
