/* meshray: a uniform grid over a mesh's triangles and rays through it by
 * cell walking (Amanatides and Woo 1987), Moller-Trumbore triangle tests. */
#include "config.h"
#include "export/pov/meshray.h"

#include <math.h>
#include <stdlib.h>

#include "base/util.h"
#include "export/pov/vec3.h"

static int clampi(int v, int lo, int hi)
{
	return v < lo ? lo : v > hi ? hi : v;
}

/* The cells [c0, c1] a box [lo, hi] overlaps. */
static void cell_range(const struct meshray *g, const double lo[3], const double hi[3], int c0[3],
    int c1[3])
{
	for (int i = 0; i < 3; i++) {
		c0[i] = clampi((int)floor((lo[i] - g->lo[i]) / g->cell[i]), 0, g->n[i] - 1);
		c1[i] = clampi((int)floor((hi[i] - g->lo[i]) / g->cell[i]), 0, g->n[i] - 1);
	}
}

static void tri_box(const struct mesh *m, int t, double lo[3], double hi[3])
{
	for (int i = 0; i < 3; i++) {
		lo[i] = INFINITY;
		hi[i] = -INFINITY;
	}
	for (int j = 0; j < 3; j++)
		for (int i = 0; i < 3; i++) {
			lo[i] = fmin(lo[i], m->position[m->triangle[t][j]][i]);
			hi[i] = fmax(hi[i], m->position[m->triangle[t][j]][i]);
		}
}

static int cell_index(const struct meshray *g, int x, int y, int z)
{
	return (z * g->n[1] + y) * g->n[0] + x;
}

/* Call 0: count the triangles per cell into start; 1: fill tri. */
static void bin(struct meshray *g, int fill, int *next)
{
	for (int t = 0; t < g->m->n_triangles; t++) {
		double lo[3], hi[3];
		int c0[3], c1[3];
		tri_box(g->m, t, lo, hi);
		cell_range(g, lo, hi, c0, c1);
		for (int z = c0[2]; z <= c1[2]; z++)
			for (int y = c0[1]; y <= c1[1]; y++)
				for (int x = c0[0]; x <= c1[0]; x++) {
					int c = cell_index(g, x, y, z);
					if (fill)
						g->tri[next[c]++] = t;
					else
						g->start[c + 1]++;
				}
	}
}

void meshray_make(struct meshray *g, const struct mesh *m)
{
	g->m = m;
	mesh_bounds(m, g->lo, g->hi);
	double ext[3], vol = 1, pad = 0;
	for (int i = 0; i < 3; i++)
		pad = fmax(pad, g->hi[i] - g->lo[i]);
	pad = 1e-6 * pad + 1e-12;
	for (int i = 0; i < 3; i++) {
		g->lo[i] -= pad;
		g->hi[i] += pad;
		ext[i] = g->hi[i] - g->lo[i];
		vol *= ext[i];
	}
	/* About half as many cells as triangles, cubes as far as they go. */
	double side = cbrt(vol / fmax(0.5 * m->n_triangles, 1));
	int total = 1;
	for (int i = 0; i < 3; i++) {
		g->n[i] = clampi((int)ceil(ext[i] / side), 1, 256);
		g->cell[i] = ext[i] / g->n[i];
		total *= g->n[i];
	}
	g->start = xcalloc((size_t)total + 1, sizeof(int));
	bin(g, 0, NULL);
	for (int c = 0; c < total; c++)
		g->start[c + 1] += g->start[c];
	g->tri = xmalloc(sizeof(int) * ((size_t)g->start[total] + 1));
	int *next = xmalloc(sizeof(int) * (size_t)total);
	for (int c = 0; c < total; c++)
		next[c] = g->start[c];
	bin(g, 1, next);
	free(next);
}

void meshray_free(struct meshray *g)
{
	free(g->start);
	free(g->tri);
	g->start = NULL;
	g->tri = NULL;
}

/* Moller-Trumbore: 1 and t, b1, b2 when the ray hits triangle T. */
static int hit_tri(const struct mesh *m, int t, const double o[3], const double d[3], double *tt,
    double *b1, double *b2)
{
	const double *p0 = m->position[m->triangle[t][0]];
	const double *p1 = m->position[m->triangle[t][1]];
	const double *p2 = m->position[m->triangle[t][2]];
	double e1[3], e2[3], s[3], pv[3], qv[3];
	for (int i = 0; i < 3; i++) {
		e1[i] = p1[i] - p0[i];
		e2[i] = p2[i] - p0[i];
		s[i] = o[i] - p0[i];
	}
	vec3_cross(d, e2, pv);
	double det = vec3_dot(e1, pv);
	if (det == 0)
		return 0;
	double inv = 1 / det;
	double u = vec3_dot(s, pv) * inv;
	if (u < 0 || u > 1)
		return 0;
	vec3_cross(s, e1, qv);
	double v = vec3_dot(d, qv) * inv;
	if (v < 0 || u + v > 1)
		return 0;
	*tt = vec3_dot(e2, qv) * inv;
	*b1 = u;
	*b2 = v;
	return 1;
}

/* The ray's span inside the grid's box: 0 when it misses it. */
static int clip(const struct meshray *g, const double o[3], const double d[3], double *t0,
    double *t1)
{
	for (int i = 0; i < 3; i++) {
		if (d[i] == 0) {
			if (o[i] < g->lo[i] || o[i] > g->hi[i])
				return 0;
			continue;
		}
		double a = (g->lo[i] - o[i]) / d[i], b = (g->hi[i] - o[i]) / d[i];
		*t0 = fmax(*t0, fmin(a, b));
		*t1 = fmin(*t1, fmax(a, b));
	}
	return *t0 <= *t1;
}

int meshray_cast(const struct meshray *g, const double o[3], const double d[3], double tmin,
    double tmax, int any, struct meshray_hit *h)
{
	double t0 = tmin, t1 = tmax;
	if (!clip(g, o, d, &t0, &t1))
		return 0;
	int c[3], step[3];
	double next[3], delta[3];
	for (int i = 0; i < 3; i++) {
		double p = o[i] + t0 * d[i];
		c[i] = clampi((int)floor((p - g->lo[i]) / g->cell[i]), 0, g->n[i] - 1);
		step[i] = d[i] > 0 ? 1 : -1;
		if (d[i] == 0) {
			next[i] = INFINITY;
			delta[i] = INFINITY;
			continue;
		}
		next[i] = (g->lo[i] + (c[i] + (d[i] > 0)) * g->cell[i] - o[i]) / d[i];
		delta[i] = g->cell[i] / fabs(d[i]);
	}
	int found = 0;
	h->t = tmax;
	for (;;) {
		int ci = cell_index(g, c[0], c[1], c[2]);
		for (int k = g->start[ci]; k < g->start[ci + 1]; k++) {
			double t, b1, b2;
			if (!hit_tri(g->m, g->tri[k], o, d, &t, &b1, &b2) || t <= tmin || t >= h->t)
				continue;
			h->t = t;
			h->tri = g->tri[k];
			h->b1 = b1;
			h->b2 = b2;
			found = 1;
			if (any)
				return 1;
		}
		int a = 0;
		if (next[1] < next[a])
			a = 1;
		if (next[2] < next[a])
			a = 2;
		if (h->t <= next[a] || next[a] > t1)
			return found;
		c[a] += step[a];
		if (c[a] < 0 || c[a] >= g->n[a])
			return found;
		next[a] += delta[a];
	}
}
