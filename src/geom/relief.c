/* relief: place the features of a periodic skin micro-relief (pores at
 * Poisson-disk positions, furrows along periodic Delaunay nets) once,
 * serially from the seed, in tile units; relief_render.c draws them. */
#include "config.h"

#include "geom/relief.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/delaunay.h"
#include "geom/relief_impl.h"
#include "base/rng.h"
#include "base/util.h"

#define MAX_PORES 2000000
#define MAX_LEVEL_POINTS 1000000

/* Random streams under one seed: every feature family has its own, so
 * changing one parameter does not reshuffle the others. */
enum { STREAM_PORE_POS = 1, STREAM_PORE_SHAPE = 2, STREAM_JUNCTION = 3, STREAM_LEVEL = 16 };

/* A standard normal deviate (Box-Muller), clamped to +-2.5 sigma so that
 * one draw cannot make a pore or furrow absurdly large. */
static double normal(struct rng *r)
{
	double u1 = rng_uniform(r), u2 = rng_uniform(r);
	double z = sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
	return fmax(-2.5, fmin(2.5, z));
}

static double wrap(double d)
{
	return d - nearbyint(d);
}

/* The area-preserving metric that makes Delaunay cells `stretch` times
 * longer along angle th than across: R(th) diag(1/sqrt(s), sqrt(s)) R(-th). */
static void stretch_metric(double stretch, double th, double m[4])
{
	double c = cos(th), s = sin(th), k1 = 1 / sqrt(stretch), k2 = sqrt(stretch);
	m[0] = k1 * c * c + k2 * s * s;
	m[1] = m[2] = (k1 - k2) * c * s;
	m[3] = k1 * s * s + k2 * c * c;
}

/* Dart throwing on the torus: add points to xy[0 .. nfixed) until there are
 * `target`, none closer than dmin to another in the metric m (distances
 * measured in m applied to the nearest periodic image).  After 40 misses per
 * wanted point the rest are placed without the distance test, so the count
 * is always met.  A grid of cells no smaller than the tile-space reach of
 * dmin keeps the test to the 3x3 neighbouring cells. */
static void poisson(struct rng *r, int target, int nfixed, double dmin, const double m[4], double *xy)
{
	/* Largest tile-space length of a metric vector of length dmin:
	 * dmin / (smallest singular value of m). */
	double a = m[0] * m[0] + m[2] * m[2], b = m[0] * m[1] + m[2] * m[3];
	double c = m[1] * m[1] + m[3] * m[3];
	double lmin = 0.5 * (a + c - sqrt((a - c) * (a - c) + 4 * b * b));
	double reach = dmin / sqrt(fmax(lmin, 1e-300));
	int g = reach > 0 ? (int)fmin(1024.0, floor(1 / reach)) : 1024;
	if (g < 3)
		g = 1;
	int *head = xmalloc(sizeof *head * (size_t)g * (size_t)g);
	int *next = xmalloc(sizeof *next * (size_t)(target > 0 ? target : 1));
	for (int k = 0; k < g * g; k++)
		head[k] = -1;
	int n = 0;
	double d2min = dmin * dmin;
#define CELL(v) ((int)fmin((double)g - 1, floor((v) * g)))
	for (; n < nfixed; n++) {
		int cell = CELL(xy[2 * n + 1]) * g + CELL(xy[2 * n]);
		next[n] = head[cell];
		head[cell] = n;
	}
	long misses = 0, budget = 40L * target;
	while (n < target) {
		double x = rng_uniform(r), y = rng_uniform(r);
		int ok = 1;
		if (misses < budget && dmin > 0) {
			int cx = CELL(x), cy = CELL(y);
			int span = g >= 3 ? 1 : 0;
			for (int dy = -span; dy <= span && ok; dy++)
				for (int dx = -span; dx <= span && ok; dx++) {
					int cell = ((cy + dy + g) % g) * g + (cx + dx + g) % g;
					for (int q = head[cell]; q >= 0 && ok; q = next[q]) {
						double ex = wrap(x - xy[2 * q]), ey = wrap(y - xy[2 * q + 1]);
						double mx = m[0] * ex + m[1] * ey, my = m[2] * ex + m[3] * ey;
						if (mx * mx + my * my < d2min)
							ok = 0;
					}
				}
			if (!ok) {
				misses++;
				continue;
			}
		}
		xy[2 * n] = x;
		xy[2 * n + 1] = y;
		int cell = CELL(y) * g + CELL(x);
		next[n] = head[cell];
		head[cell] = n;
		n++;
	}
#undef CELL
	free(head);
	free(next);
}

static struct relief_level_info level_info(const struct relief_params *p, int k)
{
	struct relief_level_info li;
	li.cell = p->furrow_cell * pow(p->level_scale, k);
	li.points = (int)fmin(2e9, nearbyint((p->tile / li.cell) * (p->tile / li.cell)));
	/* Finer levels are narrower, by sqrt(scale) per level so that they stay
	 * a few pixels wide, but never wider than half their cell. */
	li.width = fmin(p->furrow_width * pow(p->level_scale, 0.5 * k), 0.5 * li.cell);
	li.depth = p->furrow_depth * pow(p->level_gain, k);
	li.ridge = p->ridge_height * pow(p->level_gain, k);
	return li;
}

int relief_params_check(const struct relief_params *p, char **cause)
{
#define NEED(cond, ...) do { if (!(cond)) { *cause = xasprintf(__VA_ARGS__); return -1; } } while (0)
	NEED(p->tile > 0 && isfinite(p->tile), "tile size %g cm must be positive", p->tile);
	NEED(p->pore_density >= 0 && isfinite(p->pore_density), "pore density %g /cm^2 must be >= 0",
	    p->pore_density);
	double npores = p->pore_density * p->tile * p->tile;
	NEED(npores <= MAX_PORES, "%.3g pores per tile exceed the limit %d (pore density %g /mm^2 "
	    "on a %g mm tile)", npores, MAX_PORES, p->pore_density / 100, p->tile * 10);
	NEED(p->pore_radius > 0 && p->pore_radius < p->tile / 4, "pore radius %g um must be in "
	    "(0, tile/4 = %g um)", p->pore_radius * 1e4, p->tile / 4 * 1e4);
	NEED(p->pore_depth >= 0, "pore depth %g um must be >= 0", p->pore_depth * 1e4);
	NEED(p->pore_radius_sd >= 0 && p->pore_depth_sd >= 0, "pore log-normal sigmas must be >= 0");
	NEED(p->pore_aspect >= 1, "pore aspect %g must be >= 1", p->pore_aspect);
	NEED(p->pore_junction >= 0 && p->pore_junction <= 1, "pore junction fraction %g must be "
	    "in [0, 1]", p->pore_junction);
	NEED(p->pore_regularity >= 0 && p->pore_regularity <= 0.8, "pore regularity %g must be in "
	    "[0, 0.8]", p->pore_regularity);
	NEED(p->levels >= 0 && p->levels <= RELIEF_MAX_LEVELS, "furrow levels %d must be in [0, %d]",
	    p->levels, RELIEF_MAX_LEVELS);
	if (p->levels == 0)
		return 0;
	NEED(p->furrow_cell > 0 && p->furrow_cell <= p->tile / 2, "furrow cell %g mm must be in "
	    "(0, tile/2 = %g mm]", p->furrow_cell * 10, p->tile * 5);
	NEED(p->furrow_width > 0, "furrow width %g um must be > 0", p->furrow_width * 1e4);
	NEED(p->furrow_depth >= 0 && p->ridge_height >= 0 && p->furrow_depth_sd >= 0,
	    "furrow depth, ridge height and depth sigma must be >= 0");
	NEED(p->level_scale > 0 && p->level_scale < 1, "level scale %g must be in (0, 1)",
	    p->level_scale);
	NEED(p->level_gain >= 0 && p->level_gain <= 1, "level gain %g must be in [0, 1]",
	    p->level_gain);
	NEED(p->stretch >= 1 && p->stretch <= 10, "stretch %g must be in [1, 10]", p->stretch);
	NEED(isfinite(p->orientation), "orientation must be finite");
	NEED(p->furrow_regularity >= 0 && p->furrow_regularity <= 0.8, "furrow regularity %g must "
	    "be in [0, 0.8]", p->furrow_regularity);
	for (int k = 0; k < p->levels; k++) {
		struct relief_level_info li = level_info(p, k);
		NEED(li.points <= MAX_LEVEL_POINTS, "furrow level %d has %d junctions per tile, more "
		    "than %d (cell %g mm on a %g mm tile); use fewer levels or a larger cell", k + 1,
		    li.points, MAX_LEVEL_POINTS, li.cell * 10, p->tile * 10);
	}
	return 0;
#undef NEED
}

static void pore_place(struct relief *r, uint64_t seed)
{
	const struct relief_params *p = &r->p;
	int n = (int)nearbyint(p->pore_density * p->tile * p->tile);
	r->n_pores = n;
	if (n == 0)
		return;
	double *xy = xmalloc(sizeof *xy * 2 * (size_t)n);
	struct rng rg;
	int nfix = 0;
	/* Hair follicles sit on furrow junctions on most body skin: put that
	 * fraction of the pores on randomly chosen primary junctions. */
	if (r->n_levels > 0 && p->pore_junction > 0) {
		const struct level *l0 = &r->level[0];
		int nj = l0->info.points;
		nfix = (int)fmin(nj, nearbyint(p->pore_junction * n));
		int *perm = xmalloc(sizeof *perm * (size_t)nj);
		for (int k = 0; k < nj; k++)
			perm[k] = k;
		rng_seed(&rg, seed, STREAM_JUNCTION, 0);
		for (int k = 0; k < nfix; k++) {
			int j = k + (int)(rng_uniform(&rg) * (nj - k));
			int t = perm[k];
			perm[k] = perm[j];
			perm[j] = t;
			xy[2 * k] = l0->xy[2 * perm[k]];
			xy[2 * k + 1] = l0->xy[2 * perm[k] + 1];
		}
		free(perm);
	}
	static const double id[4] = { 1, 0, 0, 1 };
	rng_seed(&rg, seed, STREAM_PORE_POS, 0);
	poisson(&rg, n, nfix, p->pore_regularity / sqrt((double)n), id, xy);

	r->pores = xmalloc(sizeof *r->pores * (size_t)n);
	r->pore_box = xmalloc(sizeof *r->pore_box * (size_t)n);
	rng_seed(&rg, seed, STREAM_PORE_SHAPE, 0);
	double sa = sqrt(p->pore_aspect);
	for (int k = 0; k < n; k++) {
		struct pore *q = &r->pores[k];
		double rad = p->pore_radius * exp(p->pore_radius_sd * normal(&rg));
		/* Larger openings are deeper: depth scales with the radius. */
		q->depth = p->pore_depth * (rad / p->pore_radius) * exp(p->pore_depth_sd * normal(&rg));
		double phi = M_PI * rng_uniform(&rg);
		q->x = xy[2 * k];
		q->y = xy[2 * k + 1];
		q->a = rad * sa;
		q->b = rad / sa;
		q->c = cos(phi);
		q->s = sin(phi);
		double e = q->a / p->tile;
		r->pore_box[k] = (struct bbox){ q->x - e, q->x + e, q->y - e, q->y + e };
	}
	free(xy);
}

static int level_place(struct relief *r, int k, uint64_t seed, char **cause)
{
	const struct relief_params *p = &r->p;
	struct level *l = &r->level[k];
	l->info = level_info(p, k);
	int n = l->info.points;
	double m[4];
	stretch_metric(p->stretch, p->orientation, m);
	struct rng rg;
	rng_seed(&rg, seed, STREAM_LEVEL + 2 * (uint32_t)k, 0);
	l->xy = xmalloc(sizeof *l->xy * 2 * (size_t)n);
	poisson(&rg, n, 0, p->furrow_regularity / sqrt((double)n), m, l->xy);
	l->del = delaunay_periodic(n, l->xy, m, cause);
	if (l->del == NULL)
		return -1;

	const struct delaunay *d = l->del;
	double T = p->tile;
	rng_seed(&rg, seed, STREAM_LEVEL + 2 * (uint32_t)k + 1, 0);
	l->n_furrows = d->n_edges;
	l->furrows = xmalloc(sizeof *l->furrows * (size_t)d->n_edges);
	l->fbox = xmalloc(sizeof *l->fbox * (size_t)d->n_edges);
	for (int e = 0; e < d->n_edges; e++) {
		const struct delaunay_edge *de = &d->edges[e];
		struct furrow *f = &l->furrows[e];
		f->x0 = l->xy[2 * de->i];
		f->y0 = l->xy[2 * de->i + 1];
		f->x1 = l->xy[2 * de->j] + de->sx;
		f->y1 = l->xy[2 * de->j + 1] + de->sy;
		double z = normal(&rg);
		double rel = exp(p->furrow_depth_sd * z);
		/* A deeper furrow is also wider (constant flank slope would give
		 * width ~ depth; the square root keeps shallow ones visible). */
		f->depth = l->info.depth * rel;
		f->half = 0.5 * l->info.width * sqrt(rel);
		double e2 = f->half / T;
		l->fbox[e] = (struct bbox){ fmin(f->x0, f->x1) - e2, fmax(f->x0, f->x1) + e2,
			fmin(f->y0, f->y1) - e2, fmax(f->y0, f->y1) + e2 };
	}
	l->n_plateaus = d->n_tris;
	l->plateaus = xmalloc(sizeof *l->plateaus * (size_t)d->n_tris);
	l->pbox = xmalloc(sizeof *l->pbox * (size_t)d->n_tris);
	for (int t = 0; t < d->n_tris; t++) {
		struct plateau *q = &l->plateaus[t];
		struct bbox *b = &l->pbox[t];
		*b = (struct bbox){ INFINITY, -INFINITY, INFINITY, -INFINITY };
		for (int v = 0; v < 3; v++) {
			q->x[v] = l->xy[2 * d->tris[t].v[v]] + d->tris[t].sx[v];
			q->y[v] = l->xy[2 * d->tris[t].v[v] + 1] + d->tris[t].sy[v];
			b->x0 = fmin(b->x0, q->x[v]);
			b->x1 = fmax(b->x1, q->x[v]);
			b->y0 = fmin(b->y0, q->y[v]);
			b->y1 = fmax(b->y1, q->y[v]);
		}
		double a2 = (q->x[1] - q->x[0]) * (q->y[2] - q->y[0])
		    - (q->y[1] - q->y[0]) * (q->x[2] - q->x[0]);
		q->inv2a = 1 / a2;
		q->ridge = l->info.ridge;
	}
	return 0;
}

struct relief *relief_new(const struct relief_params *p, uint64_t seed, char **cause)
{
	if (relief_params_check(p, cause) != 0)
		return NULL;
	struct relief *r = xcalloc(1, sizeof *r);
	r->p = *p;
	r->n_levels = p->levels;
	for (int k = 0; k < p->levels; k++)
		if (level_place(r, k, seed, cause) != 0) {
			relief_free(r);
			return NULL;
		}
	pore_place(r, seed);
	return r;
}

void relief_free(struct relief *r)
{
	if (r == NULL)
		return;
	free(r->pores);
	free(r->pore_box);
	for (int k = 0; k < RELIEF_MAX_LEVELS; k++) {
		struct level *l = &r->level[k];
		delaunay_free(l->del);
		free(l->xy);
		free(l->furrows);
		free(l->plateaus);
		free(l->fbox);
		free(l->pbox);
	}
	free(r);
}

int relief_n_pores(const struct relief *r)
{
	return r->n_pores;
}

struct relief_level_info relief_level(const struct relief *r, int k)
{
	if (k < 0 || k >= r->n_levels)
		return (struct relief_level_info){ 0 };
	return r->level[k].info;
}
