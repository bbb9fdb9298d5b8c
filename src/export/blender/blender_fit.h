/* blender_fit: the general mode's closure mixture fitted to a BRDF, so that
 * Blender's ordinary shaders (any lights, no view layers) render the baked
 * skin.  The model is what Cycles 3.4 renders for the node tree that
 * exporters/blender/import_skin.py builds from it, each term checked
 * against Cycles renders (exporters/blender/README.md, "General mode"):
 *
 *   pi f(l, v, dphi) = s(v) (1 - F_L / 2 + RR (F_L + F_V + F_L F_V (RR - 1)))
 *                          Principled BSDF, subsurface 1 (random walk), specular 0,
 *                          roughness r = 0.02: a Lambert exit with the Disney light
 *                          falloff, plus its retro-reflection term, F = (1 - cos)^5,
 *                          RR = r (1 + l.v); r > 0 because EEVEE renders NaN pixels
 *                          with roughness 0
 *                    + g(v) pi f_AS(e; l, v)                     Glossy BSDF,
 *                          Ashikhmin-Shirley, exponent e: a broad forward lobe
 *                    + pi f_GGX(alpha, n; l, v)                  Principled BSDF,
 *                          black base, specular of index n, roughness sqrt(alpha)
 *
 * with f_AS = (e + 1) / (8 pi) (n.h)^e / ((h.l) max(cos_l, cos_v)) and the
 * view-dependent RGB weights s(v), g(v) given at n_view cosine nodes
 * (linear between them: a ColorRamp on N.I in Blender).  At each node the
 * weights are the non-negative least-squares fit of the relative error,
 * weighted by cos_l cos_v (projected solid angle), over light directions and
 * azimuths with cosines >= cos_min; the specular lobe is the bake's own
 * (index and GGX alpha of the model), kept only when that fits better.
 *
 * Cycles 4.x and 5.x rebuilt the Principled BSDF: its random-walk subsurface
 * light follows the cosine law exactly (no light falloff, no retro-reflection;
 * measured, exporters/blender/README.md) and depends on the view and on the
 * Base Colour only.  The model BLENDER_FIT_LAMBERT has the subsurface term
 * s(v) * 1; the importer renders s(v) with the Base Colour that Blender's
 * measured response R(base, cos_view) turns into s at each node
 * (skinbake_import/calibration.py). */
#ifndef SKINBAKE_BLENDER_FIT_H
#define SKINBAKE_BLENDER_FIT_H

#include <stddef.h>
#include <stdint.h>

#include "export/source.h"

#define BLENDER_FIT_SSS_ROUGHNESS 0.02	/* Roughness of the subsurface closure [-] */
#define BLENDER_FIT_VIEW_NODES 32	/* cos_view nodes j / 31 (a ColorRamp holds up to 32) */

enum blender_fit_model {
	BLENDER_FIT_CYCLES3,	/* subsurface term 1 - F_L / 2 + retro-reflection (Cycles 3.x) */
	BLENDER_FIT_LAMBERT	/* subsurface term 1 (Cycles 4.x, 5.x) */
};

struct blender_fit {
	enum blender_fit_model model;	/* the subsurface term */
	int n_view;					/* cos_view nodes j / (n_view - 1) [-] */
	double sss_rgb[BLENDER_FIT_VIEW_NODES][3];	/* s(v): subsurface colour [-] */
	double glossy_rgb[BLENDER_FIT_VIEW_NODES][3];	/* g(v): Ashikhmin-Shirley colour [-] */
	double glossy_exponent;				/* e [-] */
	double glossy_roughness;			/* Blender Roughness: alpha^2 = 2 / (e + 2), roughness = sqrt(alpha) [-] */
	int specular;					/* 1: the specular lobe is part of the mixture */
	double spec_ior;				/* index of the Principled specular [-] */
	double spec_alpha;				/* its GGX alpha [-] */
	double cos_min;					/* smallest cos_light and cos_view fitted [-] */
	double rms_weighted[3];	/* RMS relative error, weight cos_l cos_v, per RGB [-] */
	double rms_uniform[3];	/* RMS relative error, uniform in cos_l, cos_v, dphi [-] */
	double max_rel[3];	/* largest |relative error| [-] */
	int n_checked;		/* directions in the error grid (not at the fit nodes) */
};

/* Fit the mixture to m->f_rgb over cos_light, cos_view >= cos_min =
 * max(cos(largest albedo node), 0.1): the bake's incidence range.  Returns 0,
 * or -1 and *cause when the BRDF gives no usable values. */
int blender_fit_general(const struct brdf_source *m, struct blender_fit *fit, char **cause);
/* The same with the subsurface term of MODEL (blender_fit_general: BLENDER_FIT_CYCLES3). */
int blender_fit_general_model(const struct brdf_source *m, enum blender_fit_model model,
    struct blender_fit *fit, char **cause);
/* pi f of the fitted mixture at cos_light, cos_view in (0, 1] and dphi in
 * [0, pi], with the weights interpolated linearly in cos_view. */
void blender_fit_eval(const struct blender_fit *fit, double cos_l, double cos_v, double dphi,
    double pi_f[3]);

/* Add to an image set's manifest (written by blender.c): "general_fit" (the
 * fit above, or null with "general_fit_error"), "general_fit_v4" (the
 * BLENDER_FIT_LAMBERT fit, or null with "general_fit_v4_error"), detail.mean_normal_z and
 * exact.reference.radiance_detail_rgb (blender_detail.h) for the detail
 * normal map NORMAL of W x H texels and the atlas LUT. */
struct json_object;
void blender_fit_manifest(struct json_object *manifest, const struct brdf_source *m,
    const double sun[3], const double view[3], double sun_strength, const float *lut, int lut_cos,
    int lut_phi, const uint16_t *normal, int w, int h);
#endif
