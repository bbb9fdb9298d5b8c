/* povfiles: the POV-Ray files the exporter writes, and only this module
 * writes them: BASE.inc (lights, lit-table pigments, finishes, bump maps,
 * stand-in textures; #declared, guarded, #version 3.7 inside), BASE.pov (the
 * scene), BASE.ini (size, antialiasing, output) and for per-light passes
 * BASE_combine.pov/.ini (POV-Ray's own sum of the .hdr passes). */
#ifndef SKINBAKE_POVFILES_H
#define SKINBAKE_POVFILES_H
#include "base/outdir.h"
#include <stddef.h>

#include "export/pov/littable.h"
#include "scene/scene.h"

/* Everything the exporter knows about one skin of the scene. */
struct pov_maps;
struct pov_skin {
	struct pov_brdf brdf;
	double albedo_rgb[3];	/* diffuse albedo at normal incidence (lambert/phong stand-ins) [-] */
	double ior;		/* top-surface index for reflection { fresnel } [-] */
	const char *height_png;	/* height map file name inside the output directory, or NULL */
	double bump_size;	/* POV bump_size [-] */
	double tile_units;	/* tile edge [scene units] */
	const struct pov_maps *maps;	/* a family blended by maps (export/pov/pov_maps.h), or NULL */
	int maps_uv;		/* the maps follow the mesh UVs (else a planar projection) */
};

struct pov_options {
	const char *base;	/* output base name: BASE.inc, BASE.pov, BASE.ini */
	int n_theta;		/* key-table nodes in theta_i and theta_o */
	int n_gamma;		/* gamma-axis nodes where gamma varies */
	int n_mix;		/* mixture-table nodes per axis */
	int write_scene;	/* 0: only the include (no objects) */
	const char *shapes_inc;	/* file name of the shape macros in the output dir, or NULL */
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
void povfiles_report_free(struct pov_report *r);

/* Write BASE.inc (and with write_scene BASE.pov and BASE.ini; for passes
 * also BASE_combine.pov and BASE_combine.ini) into outdir.  Every file goes
 * through a temporary name and all are renamed into place only when all
 * were written.  -1 and *cause on failure. */
int povfiles_write(const struct scene *s, const struct pov_skin *skins, const struct pov_options *o,
    const char *outdir, struct pov_report *r, char **cause);

/* An export's directory, for base/outdir.h: manifest.json of format
 * "skinbake-pov" listing the files (written by povfiles_write_index). */
extern const struct outdir_kind povfiles_outdir_kind;
/* manifest.json in DIR listing every other entry of DIR (call it last). */
int povfiles_write_index(const char *dir, char **cause);

/* Copy a file, or write bytes to one (through a temporary name). */
int povfiles_copy(const char *src, const char *dst, char **cause);
int povfiles_write_bytes(const char *dst, const unsigned char *data, size_t size, char **cause);
#endif
