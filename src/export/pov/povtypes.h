/* povtypes: the types the POV-Ray files (povfiles.h and its parts
 * povinc.h, povscene.h) are written with besides the scene: each skin's
 * table, stand-ins and bump map, the export's options, and the report of
 * what was written. */
#ifndef SKINBAKE_POVTYPES_H
#define SKINBAKE_POVTYPES_H
#include "export/pov/littable.h"
#include "export/pov/povfar.h"
#include "export/pov/povsplit.h"
#include "export/pov/povsss.h"
#include "scene/scene.h"

/* Everything the exporter knows about one skin of the scene. */
struct pov_maps;
struct pov_skin {
	struct pov_brdf brdf;
	double albedo_rgb[3];	/* diffuse albedo at normal incidence (lambert/phong stand-ins) [-] */
	double ior;		/* top-surface index for reflection { fresnel } [-] */
	const char *height_png;	/* height map file name inside the output directory, or NULL */
	const char *cavity_png;	/* the relief's cavity map there (meshes only), or NULL */
	double bump_size;	/* POV bump_size [-] */
	double tile_units;	/* tile edge [scene units] */
	const struct pov_maps *maps;	/* a family blended by maps (export/pov/pov_maps.h), or NULL */
	int maps_uv;		/* the maps follow the mesh UVs (else a planar projection) */
	struct pov_sss sss;	/* translucent mode: the subsurface layer under the remainder (povsss.h) */
	struct pov_far far;	/* the relief below a pixel as a blended table (povfar.h) */
	/* The split (povsplit.h): diffuse part under the height map blurred by Rd(r). */
	const char *diffuse_png;	/* the blurred height map's file name, or NULL: no split */
	double diffuse_bump_size;	/* its POV bump_size [-] */
	struct pov_brdf diffuse, specular;	/* brdf's parts (maps: per member instead) */
	struct povsplit_spec spec;		/* specular's context */
	double spec_alpha;		/* its GGX alpha, relief below the map added [-] */
	int fill;			/* the scene's fill is added as albedo(theta_o) x fill */
	int n_albedo;			/* the fill's albedo curve (maps: per member) */
	const double *theta_albedo;	/* [n_albedo] [rad], ascending */
	const double *albedo_curve;	/* [3][n_albedo] linear sRGB [-] */
};

struct pov_options {
	const char *base;	/* output base name: BASE.inc, BASE.pov, BASE.ini */
	int n_theta;		/* key-table nodes in theta_i and theta_o */
	int n_gamma;		/* gamma-axis nodes where gamma varies */
	int n_mix;		/* mixture-table nodes per axis */
	int write_scene;	/* 0: only the include (no objects) */
	const char *shapes_inc;	/* file name of the shape macros in the output dir, or NULL */
	int sss_samples;	/* translucent skins: POV-Ray's subsurface samples (0: no translucent skin) */
};

/* What povfiles_write decided and measured, for the CLI to print. */
struct pov_report {
	enum scene_strategy strategy;	/* resolved (never AUTO) */
	int n_gamma_used;		/* max gamma nodes over the key tables (1 = 2-D) */
	double mix_gamma_spread;	/* mixture: gamma variation not in the table [rad] */
	double sep_rms;			/* separable: worst rms fit error over skins [-] */
	double sep_mean;		/* separable: worst mean fit error over skins [-] */
	int layered;			/* passes summed in one run as per-light layers */
	double mix_error;		/* auto with two lights: the mixture's estimated error [-], else -1 */
	int n_bump_triangles;		/* mesh triangles with their own bump map */
	int n_files;
	char *files[8 + SCENE_MAX_OBJECTS];	/* written file names (caller frees via povfiles_report_free) */
};
#endif
