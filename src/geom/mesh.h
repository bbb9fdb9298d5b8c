/* mesh: triangle meshes read from model files through libassimp (OBJ, PLY,
 * glTF, Collada .dae/.zae and every other format it reads), with the file's
 * node transforms applied, unit vertex normals, the first UV set and unit
 * tangents (from the file, else computed from the UVs).  Coordinates are the
 * file's: right-handed, model units (often metres), usually +y up. */
#ifndef SKINBAKE_MESH_H
#define SKINBAKE_MESH_H
#include <stddef.h>

struct mesh {
	char *source;		/* what was read: "FILE" or "FILE: NAME" */
	int n_vertices;
	int n_triangles;
	double (*position)[3];	/* [n_vertices] model units */
	double (*normal)[3];	/* [n_vertices] unit; smooth ones made from the faces when the file has none */
	double (*uv)[2];	/* [n_vertices] first UV set (v up), or NULL when the file has none */
	double (*tangent)[4];	/* [n_vertices] unit tangent along +u and the handedness w = +-1 (bitangent
				 * along +v = w n x t); NULL without UVs */
	int (*triangle)[3];	/* [n_triangles] vertex indices, counter-clockwise seen from the normal side */
	/* The material of the first mesh read, for parts that are not skin. */
	double diffuse_rgb[3];	/* diffuse colour [-] (0.8 grey when the file has none) */
	double specular;	/* specular strength (mean of the specular colour) [-] */
	double shininess;	/* Phong exponent [-] */
	char *texture_file;	/* diffuse texture file (resolved against the model), or NULL */
	unsigned char *texture;	/* or its bytes when embedded in the model (e.g. a .zae), else NULL */
	size_t texture_size;	/* [bytes] */
	char texture_type[8];	/* file type of the texture: png, jpg, ... */
};

/* Read the meshes of PATH whose mesh or node name is NAME (every mesh when
 * NAME is NULL), triangulated, one mesh.  NULL with *cause (caller frees)
 * when the file is missing, of a format libassimp does not read, corrupt,
 * holds no triangles, or has no mesh NAME (the message lists the names). */
struct mesh *mesh_load(const char *path, const char *name, char **cause);
void mesh_free(struct mesh *m);

/* One level of smooth subdivision: every triangle into four, the new
 * vertex of an edge on the cubic curve that the edge's end normals define
 * (the edge of a PN triangle: Vlachos, Peters, Boyd & Mitchell, "Curved PN
 * triangles", I3D 2001), its normal, UV and tangent the ends' means.  The
 * geometry moves toward the smooth surface the normals describe, which
 * shrinks what coarse meshes show: faceted silhouettes and shadow
 * terminators that follow triangle edges.  Vertices split at UV seams get
 * the same new positions on both sides (they depend on positions and
 * normals only). */
void mesh_subdivide(struct mesh *m);

/* Axis-aligned bounds [model units]. */
void mesh_bounds(const struct mesh *m, double lo[3], double hi[3]);
/* Surface area [model units^2]; with uv, the area in UV space [-]. */
double mesh_area(const struct mesh *m);
double mesh_uv_area(const struct mesh *m);
#endif
