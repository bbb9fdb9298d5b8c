/* delaunay: periodic Delaunay triangulation through libqhull_r.
 * Method (verified in docs/texture.md and dependencies.md section 5): copy the
 * points into a border band of the neighbouring tiles, triangulate with
 * qhull's "d Qbb Qc Qz Q12 Qt", keep the triangles whose centroid is in the
 * central tile and the edges with an endpoint there, canonicalise each edge
 * to (i, j, shift) and deduplicate.  E = 3N and F = 2N (Euler's formula on
 * the torus) tell whether the band was wide enough. */
#include "config.h"

#include "geom/delaunay.h"

#include <libqhull_r/qhull_ra.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

struct copy {
	int idx;	/* original point */
	int sx, sy;	/* tile shift [tiles] */
};

static int edge_cmp(const void *pa, const void *pb)
{
	const struct delaunay_edge *a = pa, *b = pb;
	if (a->i != b->i)
		return a->i < b->i ? -1 : 1;
	if (a->j != b->j)
		return a->j < b->j ? -1 : 1;
	if (a->sx != b->sx)
		return a->sx < b->sx ? -1 : 1;
	if (a->sy != b->sy)
		return a->sy < b->sy ? -1 : 1;
	return 0;
}

static int tri_cmp(const void *pa, const void *pb)
{
	const struct delaunay_tri *a = pa, *b = pb;
	for (int k = 0; k < 3; k++)
		if (a->v[k] != b->v[k])
			return a->v[k] < b->v[k] ? -1 : 1;
	for (int k = 0; k < 3; k++) {
		if (a->sx[k] != b->sx[k])
			return a->sx[k] < b->sx[k] ? -1 : 1;
		if (a->sy[k] != b->sy[k])
			return a->sy[k] < b->sy[k] ? -1 : 1;
	}
	return 0;
}

/* The edge u-v as (min index, max index, shift of the second end relative
 * to the first); a point joined to its own image takes the shift that is
 * lexicographically positive. */
static struct delaunay_edge canonical(struct copy u, struct copy v)
{
	int dx = v.sx - u.sx, dy = v.sy - u.sy;
	if (u.idx > v.idx || (u.idx == v.idx && (dx < 0 || (dx == 0 && dy < 0))))
		return (struct delaunay_edge){ v.idx, u.idx, -dx, -dy };
	return (struct delaunay_edge){ u.idx, v.idx, dx, dy };
}

/* The edges and triangles gathered from qhull's facets, growing. */
struct net {
	struct delaunay_edge *edges;
	struct delaunay_tri *tris;
	int ne, nt;	/* filled */
	int ecap, tcap;	/* allocated */
};

/* Copies of the points in the (2 ring + 1)^2 tiles around the central one
 * that lie within `band` tiles of it, in the metric m: *cp says which point
 * and shift each is, *pts holds their coordinates for qhull.  Returns the
 * number of copies. */
static int band_copies(int n, const double *xy, const double *m, double band, int ring, struct copy **cp,
    coordT **pts)
{
	int cap = (2 * ring + 1) * (2 * ring + 1) * n, nc = 0;
	*cp = xmalloc(sizeof **cp * (size_t)cap);
	*pts = xmalloc(sizeof **pts * 2 * (size_t)cap);
	for (int a = -ring; a <= ring; a++)
		for (int b = -ring; b <= ring; b++)
			for (int k = 0; k < n; k++) {
				double x = xy[2 * k] + a, y = xy[2 * k + 1] + b;
				if (x < -band || x >= 1 + band || y < -band || y >= 1 + band)
					continue;
				(*cp)[nc] = (struct copy){ k, a, b };
				(*pts)[2 * nc] = m[0] * x + m[1] * y;
				(*pts)[2 * nc + 1] = m[2] * x + m[3] * y;
				nc++;
			}
	return nc;
}

/* The sides of triangle c that have an endpoint in the central tile. */
static void net_add_edges(struct net *t, int n, const struct copy c[3])
{
	for (int e = 0; e < 3; e++) {
		struct copy u = c[e], v = c[(e + 1) % 3];
		if (!(u.sx == 0 && u.sy == 0) && !(v.sx == 0 && v.sy == 0))
			continue;
		if (t->ne == t->ecap) {
			t->ecap = t->ecap ? 2 * t->ecap : 3 * n + 64;
			t->edges = xreallocarray(t->edges, (size_t)t->ecap, sizeof *t->edges);
		}
		t->edges[t->ne++] = canonical(u, v);
	}
}

/* Triangle c if its centroid is in the central tile: counter-clockwise,
 * lowest point index first. */
static void net_add_tri(struct net *t, int n, const double *xy, struct copy c[3])
{
	double px[3], py[3];
	for (int e = 0; e < 3; e++) {
		px[e] = xy[2 * c[e].idx] + c[e].sx;
		py[e] = xy[2 * c[e].idx + 1] + c[e].sy;
	}
	double cx = (px[0] + px[1] + px[2]) / 3, cy = (py[0] + py[1] + py[2]) / 3;
	if (cx < 0 || cx >= 1 || cy < 0 || cy >= 1)
		return;
	double cross = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
	if (cross < 0) {
		struct copy s = c[1];
		c[1] = c[2];
		c[2] = s;
	}
	/* Lowest index first, keeping the orientation. */
	int f = 0;
	for (int e = 1; e < 3; e++)
		if (c[e].idx < c[f].idx)
			f = e;
	if (t->nt == t->tcap) {
		t->tcap = t->tcap ? 2 * t->tcap : 2 * n + 64;
		t->tris = xreallocarray(t->tris, (size_t)t->tcap, sizeof *t->tris);
	}
	for (int e = 0; e < 3; e++) {
		struct copy q = c[(f + e) % 3];
		t->tris[t->nt].v[e] = q.idx;
		t->tris[t->nt].sx[e] = q.sx;
		t->tris[t->nt].sy[e] = q.sy;
	}
	t->nt++;
}

/* Walk the lower Delaunay facets of qhull's hull; each is a triangle of
 * three copies (cp, nc of them). */
static void net_collect(qhT *qh, const struct copy *cp, int nc, int n, const double *xy, struct net *t)
{
	facetT *facet;
	vertexT *vertex, **vertexp;
	FORALLfacets {
		if (facet->upperdelaunay)
			continue;
		struct copy c[3];
		int k = 0, bad = 0;
		FOREACHvertex_(facet->vertices) {
			int id = qh_pointid(qh, vertex->point);
			if (k >= 3 || id < 0 || id >= nc) {
				bad = 1;
				break;
			}
			c[k++] = cp[id];
		}
		if (bad || k != 3)
			continue;
		net_add_edges(t, n, c);
		net_add_tri(t, n, xy, c);
	}
}

/* Sort both lists and drop the edges found twice, then check that the net
 * closes up on the torus: E = 3N, F = 2N, and every side of every triangle
 * one of the edges.  1 when it does. */
static int net_closes(struct net *t, int n)
{
	qsort(t->edges, (size_t)t->ne, sizeof *t->edges, edge_cmp);
	int w = 0;
	for (int e = 0; e < t->ne; e++)
		if (w == 0 || edge_cmp(&t->edges[w - 1], &t->edges[e]) != 0)
			t->edges[w++] = t->edges[e];
	t->ne = w;
	qsort(t->tris, (size_t)t->nt, sizeof *t->tris, tri_cmp);
	if (t->ne != 3 * n || t->nt != 2 * n)
		return 0;
	for (int k = 0; k < t->nt; k++)
		for (int e = 0; e < 3; e++) {
			const struct delaunay_tri *q = &t->tris[k];
			struct copy u = { q->v[e], q->sx[e], q->sy[e] };
			struct copy v = { q->v[(e + 1) % 3], q->sx[(e + 1) % 3], q->sy[(e + 1) % 3] };
			struct delaunay_edge key = canonical(u, v);
			if (bsearch(&key, t->edges, (size_t)t->ne, sizeof *t->edges, edge_cmp) == NULL)
				return 0;
		}
	return 1;
}

/* One attempt with copies within `band` tiles of the central tile, over the
 * (2 ring + 1)^2 neighbourhood.  Returns 0 with *out set, 1 if the counts
 * fail (widen and retry), -1 with *cause if qhull fails. */
static int attempt(int n, const double *xy, const double *m, double band, int ring,
    struct delaunay **out, char **cause)
{
	struct copy *cp;
	coordT *pts;
	int nc = band_copies(n, xy, m, band, ring, &cp, &pts);

	qhT qh_qh, *qh = &qh_qh;
	char *errbuf = NULL;
	size_t errlen = 0;
	FILE *errfp = open_memstream(&errbuf, &errlen);
	char options[] = "qhull d Qbb Qc Qz Q12 Qt";
	int rc = -1;
	struct net t = { 0 };

	QHULL_LIB_CHECK
	qh_zero(qh, errfp);
	int exitcode = qh_new_qhull(qh, 2, nc, pts, False, options, NULL, errfp);
	if (exitcode != 0) {
		fflush(errfp);
		*cause = xasprintf("qhull failed (code %d) on %d points: %.300s", exitcode, nc,
		    errbuf ? errbuf : "");
		goto done;
	}
	net_collect(qh, cp, nc, n, xy, &t);
	rc = 1;
	if (!net_closes(&t, n))
		goto done;
	struct delaunay *d = xcalloc(1, sizeof *d);
	d->n_points = n;
	d->n_edges = t.ne;
	d->n_tris = t.nt;
	d->edges = t.edges;
	d->tris = t.tris;
	d->band = band;
	t.edges = NULL;
	t.tris = NULL;
	*out = d;
	rc = 0;
done:
	qh_freeqhull(qh, !qh_ALL);
	int curlong, totlong;
	qh_memfreeshort(qh, &curlong, &totlong);
	fclose(errfp);
	free(errbuf);
	free(t.edges);
	free(t.tris);
	free(pts);
	free(cp);
	return rc;
}

struct delaunay *delaunay_periodic(int n, const double *xy, const double *metric, char **cause)
{
	static const double identity[4] = { 1, 0, 0, 1 };
	const double *m = metric ? metric : identity;
	if (n < 3) {
		*cause = xasprintf("periodic Delaunay needs at least 3 points, got %d", n);
		return NULL;
	}
	double det = m[0] * m[3] - m[1] * m[2];
	if (!(fabs(det) > 1e-12)) {
		*cause = xasprintf("periodic Delaunay: singular metric (determinant %g)", det);
		return NULL;
	}
	for (int k = 0; k < 2 * n; k++)
		if (!(xy[k] >= 0 && xy[k] < 1)) {
			*cause = xasprintf("periodic Delaunay: point %d has coordinate %g outside [0, 1)",
			    k / 2, xy[k]);
			return NULL;
		}
	/* Circumcircles reach a few mean spacings; in tile units that is longer
	 * by the metric's anisotropy (ratio of its singular values). */
	double a = m[0] * m[0] + m[2] * m[2], b = m[0] * m[1] + m[2] * m[3];
	double c = m[1] * m[1] + m[3] * m[3];
	double disc = sqrt((a - c) * (a - c) + 4 * b * b);
	double aniso = sqrt((a + c + disc) / fmax(a + c - disc, 1e-300));
	double band = fmin(1.0, fmax(0.1, 3.0 * aniso / sqrt((double)n)));
	for (;;) {
		struct delaunay *d = NULL;
		int rc = attempt(n, xy, m, band, 1, &d, cause);
		if (rc <= 0)
			return d;
		if (band >= 1)
			break;
		band = fmin(1.0, 2 * band);
	}
	struct delaunay *d = NULL;
	int rc = attempt(n, xy, m, 2.0, 2, &d, cause);
	if (rc < 0)
		return NULL;
	if (rc > 0) {
		*cause = xasprintf("periodic Delaunay of %d points does not close up (expected %d edges "
		    "and %d triangles); are points duplicated or on a lattice?", n, 3 * n, 2 * n);
		return NULL;
	}
	return d;
}

void delaunay_free(struct delaunay *d)
{
	if (d == NULL)
		return;
	free(d->edges);
	free(d->tris);
	free(d);
}
