/* meshray: rays against one triangle mesh through a uniform grid (the
 * back light's thickness and shadows, povback.h). */
#ifndef SKINBAKE_MESHRAY_H
#define SKINBAKE_MESHRAY_H
#include "geom/mesh.h"

struct meshray {
	const struct mesh *m;
	double lo[3], hi[3];	/* the grid's box, the mesh's bounds grown a little [units] */
	double cell[3];		/* cell size [units] */
	int n[3];		/* cells per axis */
	int *start;		/* [n0 n1 n2 + 1] first entry of each cell in tri */
	int *tri;		/* triangle indices per cell */
};

/* The grid of M (about two triangles per cell); M must outlive it. */
void meshray_make(struct meshray *g, const struct mesh *m);
void meshray_free(struct meshray *g);

struct meshray_hit {
	double t;		/* distance along the unit direction [units] */
	int tri;		/* the triangle hit */
	double b1, b2;		/* its barycentric weights of vertices 1 and 2 */
};

/* The nearest hit of the ray O + t D (D unit) with TMIN < t < TMAX; with
 * ANY the first found.  1 and *h, or 0 when it hits nothing. */
int meshray_cast(const struct meshray *g, const double o[3], const double d[3], double tmin,
    double tmax, int any, struct meshray_hit *h);
#endif
