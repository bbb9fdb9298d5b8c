/* relief_lines: join the edges of the primary furrow net into long lines.
 * Skin's primary lines run on across several junctions and cross there
 * (an X, with a pore in the crossing), while the cracks of a glaze or of
 * leather meet in Y and T junctions and stop; the Delaunay net alone is
 * the latter.  At every junction the incident edges are paired greedily by
 * how straight they continue (the pair closest to 180 degrees first, up to
 * LINE_MAX_TURN off), pairs are chained into lines, and each line gets one
 * log-normal depth factor, so that some long lines are deep and others
 * faint; a line's free ends fade out. */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "geom/relief_impl.h"
#include "base/rng.h"
#include "base/util.h"

/* Largest turn between two edges that continue one line [rad]. */
#define LINE_MAX_TURN (40 * M_PI / 180)

struct end {
	int edge, side;	/* edge index, 0 at its point i, 1 at its point j */
	double angle;	/* direction from the junction along the edge [rad] */
};

struct pair {
	int a, b;	/* indices into the ends */
	double turn;	/* deviation from straight [rad] */
};

static int pair_cmp(const void *x, const void *y)
{
	const struct pair *p = x, *q = y;
	if (p->turn != q->turn)
		return p->turn < q->turn ? -1 : 1;
	return p->a != q->a ? p->a - q->a : p->b - q->b;
}

static int find(int *parent, int x)
{
	while (parent[x] != x) {
		parent[x] = parent[parent[x]];
		x = parent[x];
	}
	return x;
}

void relief_lines_factors(const struct delaunay *d, const double *xy, double sd, double end_factor,
    struct rng *rg, double *factor)
{
	int ne = d->n_edges, np = d->n_points;
	int *start = xcalloc((size_t)np + 1, sizeof *start);
	struct end *ends = xmalloc(sizeof *ends * 2 * (size_t)(ne > 0 ? ne : 1));
	for (int e = 0; e < ne; e++) {
		start[d->edges[e].i + 1]++;
		start[d->edges[e].j + 1]++;
	}
	for (int k = 0; k < np; k++)
		start[k + 1] += start[k];
	int *fill = xmalloc(sizeof *fill * (size_t)(np > 0 ? np : 1));
	for (int k = 0; k < np; k++)
		fill[k] = start[k];
	for (int e = 0; e < ne; e++) {
		const struct delaunay_edge *de = &d->edges[e];
		double dx = xy[2 * de->j] + de->sx - xy[2 * de->i];
		double dy = xy[2 * de->j + 1] + de->sy - xy[2 * de->i + 1];
		ends[fill[de->i]++] = (struct end){ e, 0, atan2(dy, dx) };
		ends[fill[de->j]++] = (struct end){ e, 1, atan2(-dy, -dx) };
	}
	free(fill);
	int *parent = xmalloc(sizeof *parent * (size_t)(ne > 0 ? ne : 1));
	unsigned char *joined = xcalloc(2 * (size_t)(ne > 0 ? ne : 1), 1);	/* [edge][side] */
	for (int e = 0; e < ne; e++)
		parent[e] = e;
	for (int v = 0; v < np; v++) {
		int k0 = start[v], deg = start[v + 1] - k0, n = 0;
		struct pair *pr = xmalloc(sizeof *pr * (size_t)(deg * deg / 2 + 1));
		for (int a = 0; a < deg; a++)
			for (int b = a + 1; b < deg; b++) {
				double da = ends[k0 + a].angle - ends[k0 + b].angle;
				double t = fabs(remainder(da, 2 * M_PI));
				if (M_PI - t <= LINE_MAX_TURN)
					pr[n++] = (struct pair){ a, b, M_PI - t };
			}
		qsort(pr, (size_t)n, sizeof *pr, pair_cmp);
		for (int q = 0; q < n; q++) {
			const struct end *ea = &ends[k0 + pr[q].a], *eb = &ends[k0 + pr[q].b];
			unsigned char *ja = &joined[2 * ea->edge + ea->side];
			unsigned char *jb = &joined[2 * eb->edge + eb->side];
			if (*ja || *jb)
				continue;
			*ja = *jb = 1;
			int ra = find(parent, ea->edge), rb = find(parent, eb->edge);
			if (ra != rb)
				parent[ra < rb ? rb : ra] = ra < rb ? ra : rb;
		}
		free(pr);
	}
	/* One depth factor per line, drawn in the order of its lowest edge. */
	double *line = xmalloc(sizeof *line * (size_t)(ne > 0 ? ne : 1));
	for (int e = 0; e < ne; e++) {
		int root = find(parent, e);
		if (root == e)
			line[e] = exp(sd * relief_normal(rg));
		factor[2 * e] = line[root] * (joined[2 * e] ? 1 : end_factor);
		factor[2 * e + 1] = line[root] * (joined[2 * e + 1] ? 1 : end_factor);
	}
	free(line);
	free(parent);
	free(joined);
	free(ends);
	free(start);
}
