/* source: what an exporter needs from a bake, and nothing of how it is
 * stored: the BRDF to evaluate (total in linear sRGB; per wavelength the
 * diffuse part with its error and the surface specular), the table's own
 * nodes, the diffuse albedo curve, the specular parameters, the subsurface
 * radius and the detail maps of a texture directory.  An exporter (one
 * folder under src/export/, e.g. export/blender) reads only this, so a test
 * can hand it an analytic BRDF and a new exporter needs no bake code.
 *
 * Angles are radians: theta_i, theta_o in [0, pi/2], delta_phi in [0, pi]
 * with 0 back toward the light and pi the mirror side. */
#ifndef SKINBAKE_SOURCE_H
#define SKINBAKE_SOURCE_H
#include "bake/bakefile.h"
#include "geom/texdir.h"

/* Total BRDF (diffuse + surface specular) in linear sRGB [1/sr]. */
typedef void (*brdf_rgb_fn)(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3]);

struct brdf_source {
	brdf_rgb_fn f_rgb;		/* required */
	void *ctx;			/* passed to the functions */
	/* Spectral parts, when the source has wavelengths (n_wl > 0; else NULL). */
	int n_wl;
	const double *wl_nm;		/* [n_wl] [nm] */
	void (*f_diffuse)(void *ctx, double theta_i, double theta_o, double dphi, double *f, double *err);
					/* diffuse BRDF and its standard error per wavelength [1/sr]; err may be NULL */
	void (*f_specular)(void *ctx, double theta_i, double theta_o, double dphi, double *f);
					/* analytic surface specular per wavelength [1/sr] */
	/* The source table's nodes (0 / NULL for an analytic BRDF): exporters
	 * that tabulate put their rows on them to follow its interpolation. */
	int n_ti, n_to;
	const double *theta_i;		/* [n_ti] incidence nodes [rad], ascending */
	const double *theta_o;		/* [n_to] exit bin centres, or nodes of point values [rad], ascending */
	/* Directional-hemispherical diffuse albedo a(theta_i) at nodes. */
	int n_albedo;			/* >= 1 */
	const double *theta_albedo;	/* [n_albedo] [rad], ascending */
	const double *albedo_rgb;	/* [3][n_albedo] linear sRGB [-]; albedo_rgb[c * n_albedo] is
					 * the value at the first node (normal incidence in a bake) */
	double ior;			/* refractive index of the top surface [-] */
	double roughness;		/* GGX alpha of the top surface [-] */
	double sss_radius_cm[3];	/* mean exit radius of the diffuse light per R, G, B [cm] */
	const char *source;		/* bake directory or model name, for metadata */
	const char *preset;		/* preset name or NULL */
	const struct texdir *detail;	/* height and normal maps, or NULL (flat) */
	/* Owned by a source made by brdf_source_open (NULL otherwise). */
	struct bake *bake;
	struct texdir *textures;
};

/* A source from the bake directory BAKE_DIR; NULL and *cause (caller frees)
 * when it cannot be read.  Free with brdf_source_free. */
struct brdf_source *brdf_source_open(const char *bake_dir, char **cause);
/* A source over a bake in memory (e.g. a family interpolated at a point,
 * family_bake_at); with own, brdf_source_free frees b too. */
struct brdf_source *brdf_source_of_bake(struct bake *b, int own);
/* Add the detail maps of texture directory TEX_DIR (height.png and
 * normal.png, texdir_load); -1 and *cause when they cannot be read. */
int brdf_source_add_textures(struct brdf_source *s, const char *tex_dir, char **cause);
void brdf_source_free(struct brdf_source *s);	/* NULL is a no-op */
#endif
