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
#include "export/blender/blender_sss_thick.h"

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
	/* Per version: the thickness weight (blender_sss_wrap only; has 0 otherwise). */
	struct blender_thick thick[BLENDER_SSS_MAX];
};

/* The Blender "major.minor" a table was measured on, into BUF. */
void blender_sss_series(const struct sss_table *t, char *buf, size_t n);

/* Fit Cycles' closure of every calibrated version to the source's bake and
 * make the source's f_rgb the remainder (W must outlive the source's use).
 * -1 and *cause when the source has no bake with a radial profile or Cycles
 * no calibration. */
int blender_sss_wrap(struct brdf_source *src, struct blender_sss *w, char **cause);
/* Its two steps: fit every calibrated version to bake B (w->n, w->fit[]),
 * and, with W's fits however they were made (e.g. interpolated between
 * family members, export/sss_family.h), make SRC's f_rgb the remainder. */
int blender_sss_fit(const struct bake *b, struct blender_sss *w, char **cause);
void blender_sss_wrap_fitted(struct brdf_source *src, struct blender_sss *w);

/* --mode auto, export blender's default, on a bake: 1 with SRC wrapped as by
 * blender_sss_wrap where the fit can be made; else 0, SRC untouched (the set
 * stays exact): with TEXTURES (the importer gives the fitted node no detail
 * normal map, so it would flatten the relief of most of the red light: the
 * node is about 94 % of it on a flat box), or when the fit fails (no Rd(r)).
 * *NOTE says which and why (caller frees). */
int blender_sss_auto(struct brdf_source *src, int textures, struct blender_sss *w, char **note);

/* Version v's lambert_extra at view angle theta_o [rad]: the largest far
 * field of the versions less its own, per R, G, B (pi f [-]). */
void blender_sss_extra(const struct blender_sss *w, int v, double theta_o, double rgb[3]);

/* The theta_o nodes [deg] of the far fields and lambert_extra in the manifest. */
#define BLENDER_SSS_N_VIEW 6
extern const double blender_sss_view_deg[BLENDER_SSS_N_VIEW];

/* The manifest section "translucent" (JSON text, caller frees); maps[v]
 * (maps NULL, or an entry NULL: none) is JSON text added to version v's
 * entry as "maps" (the per-texel files of a family set). */
char *blender_sss_json(const struct blender_sss *w, const char *const *maps);
#endif
