/* pov: POV-Ray 3.7 scene language (SDL) for a tabulated isotropic BRDF.
 *
 * POV-Ray has no programmable BRDF, so the BRDF is written as a "lit table"
 * (measured in /work/shared/notes/pov.md): a pigment of pi*f_r as nested
 * blend maps, outer `slope { L }` (value 1 - theta_i/pi, world space, sees
 * the bumped normal) and inner `aoi` (value 1 - theta_o/pi), with
 * `finish { diffuse 1 brilliance 1 ambient 0 emission 0 specular 0 }`.
 * POV-Ray multiplies by cos(theta_i), the light colour and the light's
 * visibility, so shadows and area lights stay right.  delta_phi needs no
 * pattern: for an isotropic BRDF cos(gamma) = cos ti cos to + sin ti sin to
 * cos(dphi), gamma the light-view angle, which is constant for a parallel
 * light and an orthographic camera, and otherwise becomes a third, outer
 * `function` axis.  Two lights use a one-pass mixture table; more lights
 * per-light passes summed by POV-Ray from .hdr images, or a separable fit. */
#ifndef SKINBAKE_POV_H
#define SKINBAKE_POV_H
#include <stdint.h>
#include <stdio.h>

#include "export/pov/scene.h"

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

/* Table axis over [0, pi/2] with exactly n nodes (2 <= n <= 255),
 * ascending: 0, pi/2, the hints in between (if they fit), and the largest
 * gaps bisected until there are n.  Returns n. */
int pov_axis(const double *hint, int n_hint, int n, double *out);

/* An analytic skin-like BRDF for tests and `export pov --analytic`: Lambert
 * albedo (0.62, 0.42, 0.33) through Schlick-Fresnel transmission (n = 1.4)
 * at entry and exit, plus a GGX lobe (alpha = 0.35, Schlick Fresnel, Smith
 * masking).  ctx is unused. */
void pov_brdf_analytic(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3]);

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

/* Lower limits on table size: 1 <= node counts; blend maps hold at most
 * 256 entries, so n_theta <= 255. */
#define POV_MAX_NODES 255

/* cos(gamma) at point p: gamma the angle between the directions from p to
 * the light and to the camera. */
double pov_cos_gamma(const struct pov_light *l, const struct pov_view *v, const double p[3]);
/* delta_phi [rad] in [0, pi] from (theta_i, theta_o, cos gamma). */
double pov_dphi(double theta_i, double theta_o, double cos_gamma);
/* Range of cos(gamma) over the box [lo, hi] (sampled on a 9^3 grid). */
void pov_cos_gamma_range(const struct pov_light *l, const struct pov_view *v, const double lo[3],
    const double hi[3], double *cmin, double *cmax);

/* `#declare NAME = pigment { ... }`: the lit table for one light.  n_theta
 * nodes in theta_i and theta_o (uniform over [0, 90] degrees); if gamma
 * varies over [lo, hi] by more than 0.05 degrees, an outer function axis of
 * n_gamma nodes.  Returns the gamma nodes used (1 = 2-D table). */
int pov_write_key_pigment(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light *l,
    const struct pov_view *v, const double lo[3], const double hi[3], int n_theta, int n_gamma);

/* `#declare NAME = pigment { ... }`: the two-light mixture table (slope L1 x
 * slope L2 x aoi, n_mix nodes each).  Leaves hold sum_k w_k pi f_k with
 * w_k = E_k cos ti_k / sum_j E_j cos ti_j per channel: exact where both
 * lights are visible.  gamma per light is taken at the centre of [lo, hi];
 * *gamma_spread [rad] reports how much it varies there (0 when exact). */
void pov_write_mixture_pigment(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light l[2],
    const struct pov_view *v, const double lo[3], const double hi[3], int n_mix, double *gamma_spread);

/* Separable fallback: pigment A(theta_o) through `aoi`, finish brilliance b,
 * fitted by weighted least squares to pi f cos ti over the hemispheres. */
#define POV_SEP_NODES 33
struct pov_separable {
	double brilliance;		/* POV finish brilliance b [-] */
	double a[POV_SEP_NODES][3];	/* pigment at theta_o = 90 deg * k/(N-1) [-] */
	double rms;			/* fit error: rms(model - target)/rms(target) [-] */
	double mean;			/* fit error: mean|model - target|/mean(target) [-] */
};
void pov_fit_separable(const struct pov_brdf *f, struct pov_separable *out);
void pov_write_separable_pigment(FILE *fp, const char *name, const struct pov_separable *sep);

/* bump_size for a height map spanning h_range_um over n_px pixels per tile
 * of tile_mm: POV tilts the normal by tan = bump_size * (h[i+1] - h[i]) per
 * pixel (h in [0, 1]), so B = H_range * n_px / tile (same units). */
double pov_bump_size(double h_range_um, int n_px, double tile_mm);

/* Box-filter a square 16-bit height tile (n x n, values 0..65535 spanning
 * [h_min, h_max] um) by factor f (a divisor of n): the result (n/f)^2,
 * re-encoded over its own range [*o_min, *o_max] um; caller frees.  Blocks
 * are aligned, so a tileable map stays tileable.  Used to match the bump
 * map's texels to the image's pixel footprint: relief far below a pixel
 * only adds aliasing noise to POV-Ray's per-sample normals. */
uint16_t *pov_filter_height(const uint16_t *px, int n, double h_min, double h_max, int f, double *o_min,
    double *o_max);
/* The filter factor (a power of two dividing n, result >= 16 px) that
 * brings texels of texel_units to at most half a pixel_units footprint. */
int pov_filter_factor(int n, double texel_units, double pixel_units);

/* Everything the exporter knows about one skin of the scene. */
struct pov_skin {
	struct pov_brdf brdf;
	double albedo_rgb[3];	/* diffuse albedo at normal incidence (lambert/phong stand-ins) [-] */
	double ior;		/* top-surface index for reflection { fresnel } [-] */
	const char *height_png;	/* height map file name inside the output directory, or NULL */
	double bump_size;	/* POV bump_size [-] */
	double tile_units;	/* tile edge [scene units] */
};

struct pov_options {
	const char *base;	/* output base name: BASE.inc, BASE.pov, BASE.ini */
	int n_theta;		/* key-table nodes in theta_i and theta_o */
	int n_gamma;		/* gamma-axis nodes where gamma varies */
	int n_mix;		/* mixture-table nodes per axis */
	int write_scene;	/* 0: only the include (no objects) */
	const char *shapes_inc;	/* file name of the shape macros in the output dir, or NULL */
};

/* What pov_export decided and measured, for the CLI to print. */
struct pov_report {
	enum scene_strategy strategy;	/* resolved (never AUTO) */
	int n_gamma_used;		/* max gamma nodes over the key tables (1 = 2-D) */
	double mix_gamma_spread;	/* mixture: gamma variation not in the table [rad] */
	double sep_rms;			/* separable: worst rms fit error over skins [-] */
	double sep_mean;		/* separable: worst mean fit error over skins [-] */
	int n_files;
	char *files[8];			/* written file names (caller frees via pov_report_free) */
};
void pov_report_free(struct pov_report *r);

/* The light strategy for scene s: the scene's choice, or AUTO -> key for one
 * light, mixture for two, passes for more. */
enum scene_strategy pov_strategy(const struct scene *s);

/* Write BASE.inc (and with write_scene BASE.pov and BASE.ini; for passes
 * also BASE_combine.pov and BASE_combine.ini) into outdir.  Every file goes
 * through a temporary name and all are renamed into place only when all
 * were written.  -1 and *cause on failure. */
int pov_export(const struct scene *s, const struct pov_skin *skins, const struct pov_options *o,
    const char *outdir, struct pov_report *r, char **cause);
#endif
