/* bakefile: read a bake directory written by `skinbake bake` and evaluate
 * the baked BRDF.  Exporters (POV-Ray, Blender) and `skinbake eval` use only
 * this interface.
 *
 * Directory layout (see README "Bake outputs"):
 *   manifest.json   everything below, plus preset, layers per wavelength, settings
 *   brdf.exr        float32, width n_phi, height n_ti * n_to, row = ti * n_to + to,
 *                   column = phi; channels "fr.<WL>nm" (diffuse BRDF [1/sr]) and
 *                   "fr_err.<WL>nm" (its standard error) per integer wavelength WL
 *   brdf_rgb.exr    same layout, channels R, G, B: linear sRGB (D65) diffuse BRDF
 *   albedo.exr      width n_ti, height 1: "albedo.<WL>nm" and R, G, B
 *   albedo.png      8-bit sRGB preview
 *
 * Angles: theta_i at nodes (the incidence angles simulated); theta_o and
 * delta_phi at bin centres (uniform bins over [0, 90] and [0, 180] degrees;
 * each value is the bin mean).  delta_phi = 0 is back toward the light,
 * pi the mirror side.  All angles here are radians.
 *
 * The surface specular part (rough Fresnel reflection at the top surface) is
 * not in the tables: it is analytic, from `ior` and `roughness`. */
#ifndef SKINBAKE_BAKEFILE_H
#define SKINBAKE_BAKEFILE_H
#include "base/outdir.h"
#include "engine/specular.h"

struct bake {
	char *dir;		/* the bake directory */
	char *preset;		/* preset name */
	int n_wl;		/* wavelengths */
	double *wl_nm;		/* [n_wl] wavelengths [nm] */
	int n_ti, n_to, n_phi;	/* table axes */
	double *theta_i;	/* [n_ti] incidence nodes [rad], ascending */
	double *theta_o;	/* [n_to] outgoing bin centres [rad] */
	double *phi;		/* [n_phi] delta_phi bin centres [rad] */
	float *fr;		/* [n_wl][n_ti][n_to][n_phi] diffuse BRDF [1/sr] */
	float *fr_err;		/* same layout, standard error [1/sr] */
	float *fr_rgb;		/* [3][n_ti][n_to][n_phi] linear sRGB diffuse BRDF [1/sr] */
	double *albedo;		/* [n_wl][n_ti] directional-hemispherical diffuse albedo [-] */
	double *albedo_rgb;	/* [3][n_ti] */
	double *rgb_from_wl;	/* [3][n_wl] linear sRGB = rgb_from_wl . spectral values */
	double ior;		/* refractive index of the top surface (sebum if present) [-] */
	double roughness;	/* microfacet roughness alpha (GGX) of the top surface [-] */
	struct specular_stack *stack;	/* [n_wl] clear top stack for the specular Fresnel */
	double *sss_radius_cm;	/* [n_wl] mean exit radius of the diffuse light at normal incidence [cm] */
	double sss_radius_rgb_cm[3];
	int n_r;		/* radial bins of rd_r_rgb (0: the manifest has no profile) */
	double dr_cm;		/* their width [cm] */
	double *rd_r_rgb;	/* [3][n_r] linear sRGB Rd(r) at the first incidence node [1/cm^2], or NULL */
};

struct bake_spec;
struct bake_result;

/* What the writer needs besides the spec and the result. */
struct bake_meta {
	const char *preset;		/* preset name or file */
	double ior;			/* top-surface index for the analytic specular [-] */
	double roughness;		/* GGX alpha of the top surface [-] */
	const double *rgb_from_wl;	/* [3][n_wl] spectral -> linear sRGB weights */
	const char *rgb_note;		/* how wavelengths map to RGB, for the manifest */
	const char *command;		/* command line, for the manifest */
};

/* A bake directory, for base/outdir.h: manifest.json of format
 * "skinbake-bake" and the tables. */
extern const struct outdir_kind bake_outdir_kind;

/* Write the bake directory DIR (created if needed) through base/outdir.h:
 * the complete new set replaces the old one in one swap, or nothing
 * changes; -1 and *cause (also when DIR is not a bake directory, or is
 * being written by another process). */
int bake_write(const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m, char **cause);
/* The files of a bake, written straight into the existing directory DIR
 * (a staging directory: outdir_path, or a family member's in the family's
 * staging); -1 and *cause. */
int bake_write_files(const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m, char **cause);

/* Load DIR; NULL with *cause (caller frees) when a file is missing or corrupt. */
struct bake *bake_load(const char *dir, char **cause);
void bake_free(struct bake *b);

/* Diffuse BRDF per wavelength [1/sr] and its standard error, interpolated
 * (linear in each angle, clamped at the axis ends) at theta_i, theta_o in
 * [0, pi/2] and delta_phi in [0, pi] (values outside are folded/clamped).
 * f and err have n_wl entries; err may be NULL. */
void bake_eval_diffuse(const struct bake *b, double theta_i, double theta_o, double dphi, double *f, double *err);
/* Analytic surface specular BRDF per wavelength [1/sr]. */
void bake_eval_specular(const struct bake *b, double theta_i, double theta_o, double dphi, double *f);
/* Total (diffuse + specular) BRDF in linear sRGB [1/sr]. */
void bake_eval_rgb(const struct bake *b, double theta_i, double theta_o, double dphi, double rgb[3]);
#endif
