/* blender_sss: the translucent mode of the Blender export (issue 27,
 * docs/translucency.md).  Cycles' Subsurface Scattering node (random walk)
 * is fitted to the bake's Rd(r) from the calibration (export/sss_fit.h); its
 * far field, measured, is Lambertian with albedo = its colour (pi f = colour
 * within 0.5 % for theta_i, theta_o up to 85 degrees, a little above at the
 * darkest colours).  The exact mode's table (brdf_lut.exr) then holds the
 * remainder: the baked BRDF (diffuse + surface specular) minus the node's far
 * field from the calibration, never negative, and the importer adds the node
 * beside it (manifest section "translucent"). */
#ifndef SKINBAKE_BLENDER_SSS_H
#define SKINBAKE_BLENDER_SSS_H
#include "export/source.h"
#include "export/sss_fit.h"

struct blender_sss {
	struct sss_fit fit;		/* the closure's parameters and residuals */
	brdf_rgb_fn f_rgb;		/* the source's own BRDF */
	void *ctx;
	double clipped;			/* largest share of the table the remainder clipped at 0 [-] */
};

/* Fit Cycles' closure to the source's bake and make the source's f_rgb the
 * remainder (W must outlive the source's use).  -1 and *cause when the
 * source has no bake with a radial profile or Cycles no calibration. */
int blender_sss_wrap(struct brdf_source *src, struct blender_sss *w, char **cause);

/* The manifest section "translucent" (JSON text, caller frees). */
char *blender_sss_json(const struct blender_sss *w);
#endif
