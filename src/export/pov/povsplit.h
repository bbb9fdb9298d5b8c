/* povsplit: the skin's diffuse light under a relief smoothed by its own
 * subsurface transport (issue 24, docs/relief.md section 7).  The diffuse
 * light of skin leaves the surface 0.1-1 mm from where it entered, wider
 * than a furrow cell, so the furrows barely shade it; the surface specular
 * is reflected where it lands and sees the whole relief.  To first order in
 * the slopes the diffuse exitance is the irradiance convolved with the
 * normalised profile Rd(r), i.e. the shading of the height map convolved
 * with it.  The export then writes the skin as an average of two textures
 * (each with `finish { diffuse 2 }`, so their sum):
 *
 *   [1 pigment { DIFFUSE table } normal { height map * K }]
 *   [1 pigment { SPECULAR table } normal { height map }]
 *
 * K is the bake's Rd(r) at normal incidence, luminance-weighted over R, G,
 * B and normalised, binned into Gaussians of mean radius texel * 2^(j/2)
 * (each three periodic box passes per axis); its power closer than half a
 * texel stays sharp.  Without a radial profile, one Gaussian of the bake's
 * mean exit radius. */
#ifndef SKINBAKE_POVSPLIT_H
#define SKINBAKE_POVSPLIT_H
#include "bake/bakedir.h"
#include "export/pov/bumpmap.h"

#define POVSPLIT_MAX_G 40

/* The kernel K as a sum of Gaussians plus an unblurred share. */
struct povsplit_kernel {
	int n;				/* Gaussians */
	double w[POVSPLIT_MAX_G];	/* their weights [-] (with w0, sum 1) */
	double sigma_px[POVSPLIT_MAX_G];	/* their standard deviations [texels] */
	double w0;			/* the share left sharp [-] */
	double mean_um;			/* K's mean radius [um] */
};

/* The specular part of a bake with the GGX alpha of its surface widened by
 * the relief a bump map no longer shows (Toksvig's alpha^2 = alpha_skin^2 +
 * alpha_relief^2, docs/relief.md section 6); at the bake's own alpha, the
 * bake's lobe (bake_eval_specular, with its macro-scale roughness), else
 * the facet lobe at alpha (the macro roughness left out). */
struct povsplit_spec {
	const struct bake *b;
	double alpha;		/* GGX alpha used [-] */
};

/* The whole-face specular lobe at head distance, relief included:
 * Beckmann m = 0.35 (Donner & Jensen 2006/2008; d'Eon & Luebke's m = 0.3
 * after Weyrich 2006; notes/skin-optics.md).  Toksvig's alpha_relief is an
 * upper bound (docs/relief.md section 6: it counts the shadowed, masked
 * furrow flanks), so the widened alpha stops here. */
#define POVSPLIT_ALPHA_WHOLE 0.35

/* The diffuse (table) part of a bake in linear sRGB [1/sr] (ctx: the const
 * struct bake *), and the specular part (ctx: a struct povsplit_spec *). */
void povsplit_diffuse(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3]);
void povsplit_specular(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3]);

/* Mean |grad h|^2 of a height map [-] (slopes in height per length). */
double povsplit_slope2(const struct bumpmap *h);

/* The whole directional-hemispherical albedo of bake B at its n albedo
 * nodes th: the diffuse table's (diffuse, [3][n]) plus the surface
 * specular's, integrated numerically (96 x 96 nodes in cos theta_o and
 * delta_phi).  What a uniform sky of unit radiance gives back toward
 * theta_o (reciprocity), the fill of povinc.c.  Returns [3][n]; caller
 * frees. */
double *povsplit_fill_curve(const struct bake *b, int n, const double *th, const double *diffuse);

/* The fill bounced once off the skin itself, for the occluded part of the
 * hemisphere (povao.h, povscene.c): skin seen in an occluded direction is
 * taken as lit by the fill alone, so it sends back its white-sky albedo
 * A = integral of a(mu) 2 mu dmu over mu = cos theta in [0, 1] times the
 * fill, and the surface returns a(theta_o) x A x fill.  a is a fill curve
 * ([3][n] at th, radians, ascending; linear in theta between nodes, held
 * beyond them, as the aoi pigment interpolates it).  Returns [3][n] =
 * a x A per channel and, if white is not NULL, A; caller frees. */
double *povsplit_bounce_curve(int n, const double *th, const double *a, double white[3]);

/* K of bake B on texels of texel_um; -1 when B has neither a profile nor a
 * mean exit radius. */
int povsplit_kernel_make(const struct bake *b, double texel_um, struct povsplit_kernel *k);

/* out = K * h over an n x n periodic map (out may not be h). */
void povsplit_blur(const double *h, int n, const struct povsplit_kernel *k, double *out);

/* *out: h blurred by K (a new map of the same tile and size); *slope_ratio
 * the RMS slope of *out over that of h (the diffuse shading's contrast
 * left) [-].  -1 and *cause without a kernel. */
int povsplit_make(const struct bumpmap *h, const struct bake *b, struct bumpmap *out,
    struct povsplit_kernel *k, double *slope_ratio, char **cause);
#endif
