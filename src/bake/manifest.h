/* manifest: manifest.json of a bake directory, written and read (the
 * directory's layout is in bakefile.h, which uses these; the types are bakedir.h).  The manifest holds
 * everything but the tables: axes, RGB weights, the specular model and its
 * stacks, the layers per wavelength, the radial profiles and subsurface
 * radii, the settings, and per entry the totals and the error. */
#ifndef SKINBAKE_MANIFEST_H
#define SKINBAKE_MANIFEST_H
#include "bake/bake.h"
#include "bake/bakedir.h"

#define BAKE_FORMAT_VERSION 1

/* The manifest of a bake (pretty-printed JSON, caller frees). */
char *bake_manifest_text(const struct bake_spec *s, const struct bake_result *r, const struct bake_meta *m);

/* Read DIR/manifest.json into b: preset, axes (radians), rgb_from_wl,
 * ior, roughness, stacks and subsurface radii; not the tables.  -1 and
 * *cause (caller frees) when it is missing, corrupt or of another format. */
int bake_manifest_read(const char *dir, struct bake *b, char **cause);

/* How a bake's table was made, for re-computing its cells (bake/verify.h):
 * the layer stack per wavelength, the boundary model, and per entry the
 * method and the Monte Carlo batches behind its standard errors. */
struct bake_provenance {
	int n_wl, n_ti;
	struct slab *slab;		/* [n_wl] checked and prepared */
	enum optics_fresnel fresnel;
	char solver[16];		/* the manifest's solver.name ("mc" before there was a choice) */
	int *entry_mc;			/* [n_wl * n_ti] 1 when Monte Carlo made the entry */
	long *entry_batches;		/* [n_wl * n_ti] its batches (0 when unknown or not Monte Carlo) */
	uint64_t seed;			/* the bake's Monte Carlo seed */
};

/* Read DIR/manifest.json into p; -1 and *cause when it is missing, corrupt
 * or its layers do not make a valid stack.  Free with bake_provenance_free. */
int bake_provenance_read(const char *dir, struct bake_provenance *p, char **cause);
void bake_provenance_free(struct bake_provenance *p);
#endif
