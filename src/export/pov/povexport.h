/* povexport: the POV-Ray export as one call: a scene (a file, or lights and
 * a camera from the command line) plus bakes and texture directories bound
 * to its skins, to the files of povfiles.h, or with `plan` the list of
 * incidence angles the scene needs.  Everything is read and checked before
 * anything is written. */
#ifndef SKINBAKE_POVEXPORT_H
#define SKINBAKE_POVEXPORT_H
#include <stdio.h>

#include "scene/scene.h"

#define POVEXPORT_MAX_BIND (SCENE_MAX_SKINS + 1)

/* --mode: auto is translucent for a skin on meshes where that applies
 * (povexport.c, auto_exact), else exact. */
enum { POVEXPORT_EXACT, POVEXPORT_TRANSLUCENT, POVEXPORT_AUTO };

struct povexport_options {
	const char *scene_path;		/* scene file, or NULL: lights and camera below */
	struct scene *cmdline;		/* --light/--camera: lights and camera (scene_path NULL) */
	int have_camera;		/* cmdline has a camera */
	int n_bakes, n_texs;
	const char *bakes[POVEXPORT_MAX_BIND];	/* "[SKIN=]DIR" */
	const char *texs[POVEXPORT_MAX_BIND];	/* "[SKIN=]DIR" */
	const char *out;		/* output directory */
	const char *name;		/* output base name, or NULL */
	const char *data_dir;		/* where skinbake_shapes.inc is, or NULL */
	const char *lights;		/* strategy name overriding the scene's, or NULL */
	int n_theta, n_gamma, n_mix;	/* table nodes */
	int analytic;			/* the analytic BRDF instead of bakes */
	const char *family, *maps;	/* a family and its maps for every skin (pov_maps.h), or NULL */
	int plan;			/* print the plan to `plan_out`, write nothing */
	int bump_filter;		/* box-filter height maps to the pixel footprint */
	int sharp_diffuse;		/* --diffuse-relief sharp: no split (povsplit.h) */
	int width, height;		/* image size [px], 0 = the scene's (320x240 without one) */
	double unit_mm;			/* one scene unit [mm], 0 = the scene's (10 without one) */
	int translucent;		/* --mode: POVEXPORT_EXACT, _TRANSLUCENT or _AUTO */
	int sss_samples;		/* POV-Ray's subsurface samples for it */
	FILE *plan_out;
};

/* Messages for the user, in order (the CLI prefixes each with the command). */
#define POVEXPORT_MAX_MSGS 32
struct povexport_result {
	int n_msgs;
	char *msgs[POVEXPORT_MAX_MSGS];
	int n_files;
	char *files[16];		/* the files written, "OUT/NAME" */
};
void povexport_result_free(struct povexport_result *r);

/* 0 on success; -1 for bad input (nothing written; exit status 2) and -2 for
 * a failure while writing (exit status 1), both with *cause. */
int povexport_run(const struct povexport_options *o, struct povexport_result *r, char **cause);
#endif
