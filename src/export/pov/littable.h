/* littable: a tabulated isotropic BRDF as a POV-Ray 3.7 "lit table"
 * (measured in /work/shared/notes/pov.md).  POV-Ray has no programmable
 * BRDF, so the pigment holds pi*f_r as nested blend maps: outer
 * `slope { L }` (value 1 - theta_i/pi, world space, sees the bumped normal),
 * inner `aoi` (value 1 - theta_o/pi), with
 * `finish { diffuse 1 brilliance 1 ambient 0 emission 0 specular 0 }`.
 * POV-Ray multiplies by cos(theta_i), the light colour and the light's
 * visibility, so shadows and area lights stay right.  delta_phi needs no
 * pattern: for an isotropic BRDF cos(gamma) = cos ti cos to + sin ti sin to
 * cos(dphi), gamma the light-view angle, which is constant for a parallel
 * light and an orthographic camera, and otherwise becomes a third, outer
 * `function` axis.  Two lights fit a one-pass mixture table. */
#ifndef SKINBAKE_LITTABLE_H
#define SKINBAKE_LITTABLE_H
#include <stdio.h>

/* Total BRDF (diffuse + surface specular) in linear RGB [1/sr] at incidence
 * theta_i, exit theta_o in [0, pi/2] and delta_phi in [0, pi] [rad]
 * (delta_phi = 0 back toward the light). */
typedef void (*pov_brdf_fn)(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3]);

struct pov_brdf {
	pov_brdf_fn f_rgb;
	void *ctx;
	/* Optional: the source table's own nodes [rad].  Table rows are put
	 * on them (then filled to the requested count), so the blend maps'
	 * bilinear interpolation follows the source's piecewise-linear one. */
	int n_ti_hint, n_to_hint;
	const double *ti_hint, *to_hint;
};

/* Blend maps hold at most 256 entries (one is the extra entry at aoi 0), so
 * a table axis has at most 255 nodes. */
#define LITTABLE_MAX_NODES 255

/* Table axis over [0, pi/2] with exactly n nodes (2 <= n <= 255),
 * ascending: 0, pi/2, the hints in between (if they fit), and the largest
 * gaps bisected until there are n.  Returns n. */
int littable_axis(const double *hint, int n_hint, int n, double *out);

/* An analytic skin-like BRDF for tests and `export pov --analytic`: Lambert
 * albedo (0.62, 0.42, 0.33) through Schlick-Fresnel transmission (n = 1.4)
 * at entry and exit, plus a GGX lobe (alpha = 0.35, Schlick Fresnel, Smith
 * masking).  ctx is unused. */
void littable_brdf_analytic(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3]);

/* A light and a view as the table generator needs them. */
struct pov_light {
	int parallel;		/* 1 parallel (dir used), 0 point (pos used) */
	double pos[3];		/* point light position [units] */
	double dir[3];		/* parallel: unit direction toward the light */
	double rgb[3];		/* POV light colour (irradiance at normal incidence) [-] */
};

struct pov_view {
	int ortho;		/* 1 orthographic (dir used), 0 perspective (pos used) */
	double pos[3];		/* camera location [units] */
	double dir[3];		/* unit direction from the scene toward the camera */
};

/* Unit directions from point p toward the light and toward the camera. */
void littable_light_dir(const struct pov_light *l, const double p[3], double out[3]);
void littable_view_dir(const struct pov_view *v, const double p[3], double out[3]);
/* cos(gamma) at point p: gamma the angle between the directions from p to
 * the light and to the camera. */
double littable_cos_gamma(const struct pov_light *l, const struct pov_view *v, const double p[3]);
/* delta_phi [rad] in [0, pi] from (theta_i, theta_o, cos gamma). */
double littable_dphi(double theta_i, double theta_o, double cos_gamma);
/* Range of cos(gamma) over the box [lo, hi] (sampled on a 9^3 grid). */
void littable_cos_gamma_range(const struct pov_light *l, const struct pov_view *v, const double lo[3],
    const double hi[3], double *cmin, double *cmax);

/* `#declare NAME = pigment { ... }`: the lit table for one light.  n_theta
 * nodes in theta_i and theta_o (uniform over [0, 90] degrees); if gamma
 * varies over [lo, hi] by more than 0.05 degrees, an outer function axis of
 * n_gamma nodes.  Returns the gamma nodes used (1 = 2-D table). */
int littable_write_key(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light *l,
    const struct pov_view *v, const double lo[3], const double hi[3], int n_theta, int n_gamma);

/* The two-light mixture leaf: sum_k w_k pi f_k with w_k = E_k cos ti_k /
 * sum_j E_j cos ti_j per channel (the mean of pi f_k where both are dark),
 * gamma_k given as cos_gamma[k]. */
void littable_mixture_value(const struct pov_brdf *f, const struct pov_light l[2], const double ti[2], double to,
    const double cos_gamma[2], double out[3]);

/* `#declare NAME = pigment { ... }`: the two-light mixture table (slope L1 x
 * slope L2 x aoi, n_mix nodes each) of littable_mixture_value: exact where
 * both lights are visible.  gamma per light is taken at the centre of
 * [lo, hi]; *gamma_spread [rad] reports how much it varies there (0 when
 * exact). */
void littable_write_mixture(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light l[2],
    const struct pov_view *v, const double lo[3], const double hi[3], int n_mix, double *gamma_spread);
#endif
