/* manifest: manifest.json of a bake directory, written and read (the
 * directory's layout is in bakefile.h, which uses these).  The manifest holds
 * everything but the tables: axes, RGB weights, the specular model and its
 * stacks, the layers per wavelength, the radial profiles and subsurface
 * radii, the settings, and per entry the totals and the error. */
#ifndef SKINBAKE_MANIFEST_H
#define SKINBAKE_MANIFEST_H
#include "bake/bake.h"
#include "bake/bakefile.h"

#define BAKE_FORMAT_VERSION 1

/* The manifest of a bake (pretty-printed JSON, caller frees). */
char *bake_manifest_text(const struct bake_spec *s, const struct bake_result *r, const struct bake_meta *m);

/* Read DIR/manifest.json into b: preset, axes (radians), rgb_from_wl,
 * ior, roughness, stacks and subsurface radii; not the tables.  -1 and
 * *cause (caller frees) when it is missing, corrupt or of another format. */
int bake_manifest_read(const char *dir, struct bake *b, char **cause);
#endif
