/* mesh2: a placed triangle mesh as a POV-Ray `mesh2` (vertex, normal and uv
 * vectors, so it shades smoothly and carries its UVs), optionally with a
 * bump map that follows the mesh's UVs in tangent space.
 *
 * POV-Ray 3.7 applies `uv_mapping` bump perturbations as if u and v were
 * world x and y (measured in /work/shared/notes/pov.md), so bumps are not
 * uv-mapped here.  Instead each triangle gets its own planar bump map whose
 * matrix maps texture x, y onto the triangle's UV directions (the affine map
 * of its UVs, so the map is continuous across the triangles of one UV
 * island) and texture z onto the inward normal times the tile size.  POV-Ray
 * moves a bump normal into texture space by the matrix's transpose, perturbs
 * it there (its frame for a texture-space normal along -z is the planar map's
 * own, which is right) and moves it back by the inverse transpose, which
 * takes texture-space gradients to surface gradients: the tilt is the
 * relief's physical slope whatever the triangle's shape, size or
 * orientation. */
#ifndef SKINBAKE_MESH2_H
#define SKINBAKE_MESH2_H
#include <stdio.h>

#include "scene/scene.h"
#include "geom/mesh.h"

/* How the UVs map to the tile: per UV island (triangles connected through
 * shared vertices; libassimp splits vertices at UV seams) the scale that
 * keeps its area, sqrt(surface area / UV area), so the relief has its
 * physical size wherever the UV layout gives a region more or less room. */
struct mesh2_uvmap {
	int n_islands;
	int *island;		/* [n_triangles] island of each triangle */
	double *scale;		/* [n_islands] scene units per UV unit */
};
/* NULL-free: a mesh without UVs gets no islands (n_islands 0). */
void mesh2_uvmap_make(const struct mesh *m, struct mesh2_uvmap *u);
void mesh2_uvmap_free(struct mesh2_uvmap *u);

/* The rows of triangle t's bump-map matrix (T, B, N, origin: 12 numbers) for
 * a tile of tile_units scene units; -1 when its UVs or its area are
 * degenerate. */
int mesh2_bump_matrix(const struct mesh *m, const struct mesh2_uvmap *u, int t, double tile_units, double out[12]);

/* Which triangles the camera can see (inside the view frustum, grown by a
 * tenth, and facing it): only they need a bump map. */
void mesh2_visible(const struct mesh *m, const struct scene_camera *c, double aspect, unsigned char *on);

/* Per-triangle textures: bump triangles get PRE " matrix <...>" POST, the
 * others (and degenerate ones) PLAIN. */
struct mesh2_textures {
	const char *pre, *post, *plain;	/* a bumped triangle: pre MATRIX post */
	const char *mid;		/* or NULL; else pre MATRIX mid MATRIX post (two normals) */
	double tile_units;
	const struct mesh2_uvmap *uv;
	const unsigned char *on;	/* [n_triangles] 1 = bump, or NULL: every triangle */
	/* The relief's cavity map (file name in the output directory) or NULL:
	 * each bumped triangle's texture becomes the pattern of that map (by
	 * the triangle's bump matrix, so it lies on the bump map) blending
	 * SKIN_CavityBlack at 0 with the texture at 1, i.e. the texture's
	 * light times the cavity (docs/relief.md). */
	const char *cavity_png;
};
/* The declaration of that black (guarded: every file that uses it has it). */
#define MESH2_CAVITY_BLACK "#ifndef (SKIN_CavityBlack)\n#declare SKIN_CavityBlack = texture { " \
	"pigment { rgb 0 } finish { ambient 0 diffuse 0 emission 0 specular 0 } }\n#end\n"

/* `#declare NAME = mesh2 { ... }` with every vertex moved by -inset along its
 * normal (inner copies for the per-light layers); with tex, a texture list.
 * Returns the number of bump-mapped triangles. */
int mesh2_write(FILE *fp, const char *name, const struct mesh *m, double inset, const struct mesh2_textures *tex);
#endif
