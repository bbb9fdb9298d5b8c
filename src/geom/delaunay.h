/* delaunay: Delaunay triangulation of points on the unit torus (a square
 * tile that repeats in x and y), through libqhull_r.  The points are
 * replicated into a border band around the tile (or into the full 3x3 or
 * 5x5 neighbourhood), triangulated once, and every edge and triangle is
 * mapped back to (point index, tile shift).  A triangulation of a torus has
 * exactly E = 3N edges and F = 2N triangles (Euler characteristic 0); the
 * result is checked against that, and the band widened until it holds. */
#ifndef SKINBAKE_DELAUNAY_H
#define SKINBAKE_DELAUNAY_H

/* Edge from point i to the copy of point j shifted by (sx, sy) whole tiles. */
struct delaunay_edge {
	int i, j;	/* point indices, i <= j */
	int sx, sy;	/* tile shift of j's end relative to i's [tiles] */
};

/* Triangle whose vertex k is point v[k] shifted by (sx[k], sy[k]) tiles.
 * The shifts place the centroid inside [0, 1)^2; vertices are counter-
 * clockwise in tile coordinates (x right, y up). */
struct delaunay_tri {
	int v[3];	/* point indices */
	int sx[3], sy[3];	/* tile shifts [tiles] */
};

struct delaunay {
	int n_points;	/* N */
	int n_edges;	/* 3N */
	int n_tris;	/* 2N */
	struct delaunay_edge *edges;	/* sorted by (i, j, sx, sy) */
	struct delaunay_tri *tris;	/* sorted by their first vertex */
	double band;	/* border band that sufficed [tiles]; >= 1 means the full 3x3, 2 means 5x5 */
};

/* Triangulate n >= 3 points xy[2k], xy[2k+1] in [0, 1)^2 (tile units) on the
 * torus.  metric (row-major 2x2, may be NULL for the identity) maps tile
 * coordinates to the space in which the triangulation is Delaunay; a metric
 * that squeezes a direction makes triangles long along it.  It must be
 * non-singular.  Returns NULL and *cause (caller frees) when qhull fails or
 * the counts cannot be met (duplicate or cocircular points on a lattice).
 * Caller frees with delaunay_free. */
struct delaunay *delaunay_periodic(int n, const double *xy, const double *metric, char **cause);
void delaunay_free(struct delaunay *d);
#endif
