/* bakedir: a bake directory in memory (struct bake, as bakefile.h loads
 * it and manifest.h reads its manifest into it) and what its writer needs
 * besides the spec and the result (struct bake_meta).  The layout on disk
 * is in bakefile.h. */
#ifndef SKINBAKE_BAKEDIR_H
#define SKINBAKE_BAKEDIR_H
#include "engine/microfacet_ms.h"
#include "engine/specular.h"

struct bake {
	char *dir;		/* the bake directory */
	char *preset;		/* preset name */
	int n_wl;		/* wavelengths */
	double *wl_nm;		/* [n_wl] wavelengths [nm] */
	int n_ti, n_to, n_phi;	/* table axes */
	double *theta_i;	/* [n_ti] incidence nodes [rad], ascending */
	double *theta_o;	/* [n_to] outgoing bin centres [rad] (of Monte Carlo wavelengths) */
	double *phi;		/* [n_phi] delta_phi bin centres [rad] */
	float *fr;		/* [n_wl][n_ti][n_to][n_phi] diffuse BRDF [1/sr] */
	float *fr_err;		/* same layout, standard error [1/sr] */
	float *fr_rgb;		/* [3][n_ti][n_to][n_phi] linear sRGB diffuse BRDF [1/sr] */
	double *albedo;		/* [n_wl][n_ti] directional-hemispherical diffuse albedo [-] */
	double *albedo_rgb;	/* [3][n_ti] */
	double *rgb_from_wl;	/* [3][n_wl] linear sRGB = rgb_from_wl . spectral values */
	double ior;		/* refractive index of the top surface (sebum if present) [-] */
	double roughness;	/* microfacet roughness alpha (GGX) of the top surface [-] */
	int rough_top;		/* 1: the transport's top boundary is rough at some wavelength
				 * (manifest layers[].layers[0].rough_top > 0): the diffuse BRDF
				 * keeps a finite value at grazing instead of going to 0 */
	double macro_slope;	/* RMS slope of the mm-scale relief over the whole BRDF [-];
				 * 0 = none */
	struct macro_rule *macro;	/* its quadrature (engine/macro.h), NULL when
					 * macro_slope == 0 */
	struct specular_stack *stack;	/* [n_wl] clear top stack for the specular Fresnel */
	struct microfacet_ms *ms;	/* [n_wl] the lobe of what the separable lobe does not
					 * reflect (engine/microfacet_ms.h), NULL unless the
					 * manifest's specular.multiple_scattering is 1 */
	double *sss_radius_cm;	/* [n_wl] mean exit radius of the diffuse light at normal incidence [cm] */
	double sss_radius_rgb_cm[3];
	int n_r;		/* radial bins of rd_r_rgb (0: the manifest has no profile) */
	double dr_cm;		/* their width [cm] */
	double *rd_r_rgb;	/* [3][n_r] linear sRGB Rd(r) at the first incidence node [1/cm^2], or NULL */
	/* Point values (NULL in bakes of bin means only; bakefile.h). */
	int *points;		/* [n_wl] 1: the wavelength's values are at the nodes below, 0: bin means */
	double *theta_o_nodes;	/* [n_to] exit nodes of point values [rad] */
	double *phi_nodes;	/* [n_phi] delta_phi nodes of point values [rad] */
	struct bake_series *interp;	/* the series through them (bakeinterp.h) */
};

struct bake_spec;
struct bake_result;

/* What the writer needs besides the spec and the result. */
struct bake_meta {
	const char *preset;		/* preset name or file */
	double ior;			/* top-surface index for the analytic specular [-] */
	double roughness;		/* GGX alpha of the top surface [-] */
	double macro_slope;		/* RMS slope of the mm-scale relief [-] (0: none) */
	const double *rgb_from_wl;	/* [3][n_wl] spectral -> linear sRGB weights */
	const char *rgb_note;		/* how wavelengths map to RGB, for the manifest */
	const char *command;		/* command line, for the manifest */
};

/* Free B and everything it holds (NULL is a no-op). */
void bake_free(struct bake *b);
#endif
