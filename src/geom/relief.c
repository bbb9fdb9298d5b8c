/* relief: periodic height field of skin micro-relief (pores and Delaunay
 * furrows).  Features are placed once (serial, from the seed) in tile units;
 * rendering bins them into square blocks of pixels, each feature once per
 * tile shift that reaches the window, so features that cross the tile border
 * reappear on the other side and the map is periodic by construction.
 * Blocks are independent, so OpenMP over blocks gives the same result for
 * any thread count.  Profiles are smooth polynomials with zero slope at
 * their rim, so the height is continuous with a continuous slope except at
 * the bottom of a furrow (a V groove) and where two grooves meet. */
#include "config.h"

#include "geom/relief.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/delaunay.h"
#include "base/rng.h"
#include "base/util.h"

#define MAX_PORES 2000000
#define MAX_LEVEL_POINTS 1000000
#define BLOCK 64

/* Random streams under one seed: every feature family has its own, so
 * changing one parameter does not reshuffle the others. */
enum { STREAM_PORE_POS = 1, STREAM_PORE_SHAPE = 2, STREAM_JUNCTION = 3, STREAM_LEVEL = 16 };

struct bbox {
	double x0, x1, y0, y1;	/* extent [tiles] */
};

struct pore {
	double x, y;	/* centre [tiles] */
	double a, b;	/* semi-axes [cm] */
	double c, s;	/* cosine, sine of the long axis angle [1] */
	double depth;	/* [cm] */
};

struct furrow {
	double x0, y0, x1, y1;	/* ends [tiles]; (x1, y1) may lie in a neighbour tile */
	double half;	/* half width [cm] */
	double depth;	/* [cm] */
};

struct plateau {
	double x[3], y[3];	/* vertices [tiles], counter-clockwise */
	double inv2a;	/* 1 / twice the area [1/tiles^2] */
	double ridge;	/* dome height [cm] */
};

struct level {
	struct relief_level_info info;
	struct delaunay *del;
	double *xy;	/* junctions [tiles] */
	int n_furrows, n_plateaus;
	struct furrow *furrows;
	struct plateau *plateaus;
	struct bbox *fbox, *pbox;
};

struct relief {
	struct relief_params p;
	int n_pores;
	struct pore *pores;
	struct bbox *pore_box;
	int n_levels;
	struct level level[RELIEF_MAX_LEVELS];
};

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

/* Features binned by pixel block, as compressed rows: the entries of block
 * b are entry[start[b] .. start[b+1]). */
struct bin_entry {
	int id;	/* feature */
	int sx, sy;	/* tile shift that brings it into the window [tiles] */
};

struct bins {
	int *start;
	struct bin_entry *entry;
};

struct window {
	int n;	/* pixels per edge */
	int nb;	/* blocks per edge */
	double x0, y0;	/* lower-left corner [tiles], in [0, 1) */
};

/* Pixel range [lo, hi] of the feature extent shifted by s, clipped to the
 * window; empty when lo > hi.  Column c samples x0 + (c + 0.5) / n; row r
 * samples y0 + (n - r - 0.5) / n. */
static void col_range(const struct window *w, double a, double b, int *lo, int *hi)
{
	*lo = (int)fmax(0, ceil((a - w->x0) * w->n - 0.5));
	*hi = (int)fmin(w->n - 1, floor((b - w->x0) * w->n - 0.5));
}

static void row_range(const struct window *w, double a, double b, int *lo, int *hi)
{
	*lo = (int)fmax(0, ceil(w->n - 0.5 - (b - w->y0) * w->n));
	*hi = (int)fmin(w->n - 1, floor(w->n - 0.5 - (a - w->y0) * w->n));
}

/* Visit every (feature shift, block) pair whose pixels the feature reaches.
 * Called twice: first to count (entry == NULL), then to fill. */
static void bin_pass(const struct window *w, int nf, const struct bbox *box, int *count,
    struct bin_entry *entry)
{
	for (int f = 0; f < nf; f++) {
		const struct bbox *b = &box[f];
		int sx0 = (int)floor(w->x0 - b->x1), sx1 = (int)ceil(w->x0 + 1 - b->x0);
		int sy0 = (int)floor(w->y0 - b->y1), sy1 = (int)ceil(w->y0 + 1 - b->y0);
		for (int sy = sy0; sy <= sy1; sy++) {
			int r0, r1;
			row_range(w, b->y0 + sy, b->y1 + sy, &r0, &r1);
			if (r0 > r1)
				continue;
			for (int sx = sx0; sx <= sx1; sx++) {
				int c0, c1;
				col_range(w, b->x0 + sx, b->x1 + sx, &c0, &c1);
				if (c0 > c1)
					continue;
				for (int br = r0 / BLOCK; br <= r1 / BLOCK; br++)
					for (int bc = c0 / BLOCK; bc <= c1 / BLOCK; bc++) {
						int blk = br * w->nb + bc;
						if (entry)
							entry[count[blk]++] = (struct bin_entry){ f, sx, sy };
						else
							count[blk + 1]++;
					}
			}
		}
	}
}

static struct bins bin_features(const struct window *w, int nf, const struct bbox *box)
{
	int nblk = w->nb * w->nb;
	struct bins b;
	b.start = xcalloc((size_t)nblk + 1, sizeof *b.start);
	bin_pass(w, nf, box, b.start, NULL);
	for (int k = 0; k < nblk; k++)
		b.start[k + 1] += b.start[k];
	b.entry = xmalloc(sizeof *b.entry * (size_t)(b.start[nblk] > 0 ? b.start[nblk] : 1));
	int *fill = xmalloc(sizeof *fill * (size_t)nblk);
	memcpy(fill, b.start, sizeof *fill * (size_t)nblk);
	bin_pass(w, nf, box, fill, b.entry);
	free(fill);
	return b;
}

static void bins_free(struct bins *b)
{
	free(b->start);
	free(b->entry);
}

/* Pixel rectangle of one block. */
struct rect {
	int r0, r1, c0, c1;	/* inclusive rows and columns */
};

static double px_x(const struct window *w, int c)
{
	return w->x0 + (c + 0.5) / w->n;
}

static double px_y(const struct window *w, int r)
{
	return w->y0 + (w->n - r - 0.5) / w->n;
}

/* Clip a shifted extent to the block; 0 if nothing is left. */
static int clip(const struct window *w, const struct rect *k, const struct bbox *b, int sx, int sy,
    struct rect *out)
{
	col_range(w, b->x0 + sx, b->x1 + sx, &out->c0, &out->c1);
	row_range(w, b->y0 + sy, b->y1 + sy, &out->r0, &out->r1);
	out->c0 = out->c0 > k->c0 ? out->c0 : k->c0;
	out->c1 = out->c1 < k->c1 ? out->c1 : k->c1;
	out->r0 = out->r0 > k->r0 ? out->r0 : k->r0;
	out->r1 = out->r1 < k->r1 ? out->r1 : k->r1;
	return out->c0 <= out->c1 && out->r0 <= out->r1;
}

/* Pore dimple: -depth (1 - s^2)^2 inside the ellipse (s < 1), zero slope at
 * the centre and at the rim.  Overlapping pores take the deeper value. */
static void draw_pores(const struct relief *r, const struct window *w, const struct bins *bn, int blk,
    const struct rect *k, float *buf)
{
	double T = r->p.tile;
	for (int e = bn->start[blk]; e < bn->start[blk + 1]; e++) {
		const struct bin_entry *be = &bn->entry[e];
		const struct pore *q = &r->pores[be->id];
		struct rect c;
		if (!clip(w, k, &r->pore_box[be->id], be->sx, be->sy, &c))
			continue;
		double ia2 = 1 / (q->a * q->a), ib2 = 1 / (q->b * q->b);
		for (int row = c.r0; row <= c.r1; row++) {
			double dy = (px_y(w, row) - (q->y + be->sy)) * T;
			float *o = buf + (row - k->r0) * BLOCK;
			for (int col = c.c0; col <= c.c1; col++) {
				double dx = (px_x(w, col) - (q->x + be->sx)) * T;
				double u = q->c * dx + q->s * dy, v = -q->s * dx + q->c * dy;
				double s2 = u * u * ia2 + v * v * ib2;
				if (s2 >= 1)
					continue;
				float h = (float)(-q->depth * (1 - s2) * (1 - s2));
				if (h < o[col - k->c0])
					o[col - k->c0] = h;
			}
		}
	}
}

/* Furrow groove along a segment: -depth (1 - t^2)^2 with t = distance /
 * half width; grooves of one level combine by their minimum. */
static void draw_furrows(const struct level *l, double T, const struct window *w,
    const struct bins *bn, int blk, const struct rect *k, float *buf)
{
	for (int e = bn->start[blk]; e < bn->start[blk + 1]; e++) {
		const struct bin_entry *be = &bn->entry[e];
		const struct furrow *f = &l->furrows[be->id];
		struct rect c;
		if (!clip(w, k, &l->fbox[be->id], be->sx, be->sy, &c))
			continue;
		double ax = (f->x0 + be->sx) * T, ay = (f->y0 + be->sy) * T;
		double ex = (f->x1 - f->x0) * T, ey = (f->y1 - f->y0) * T;
		double il2 = 1 / (ex * ex + ey * ey), ih2 = 1 / (f->half * f->half);
		for (int row = c.r0; row <= c.r1; row++) {
			double py = px_y(w, row) * T - ay;
			float *o = buf + (row - k->r0) * BLOCK;
			for (int col = c.c0; col <= c.c1; col++) {
				double px = px_x(w, col) * T - ax;
				double t = (px * ex + py * ey) * il2;
				t = t < 0 ? 0 : t > 1 ? 1 : t;
				double dx = px - t * ex, dy = py - t * ey;
				double s2 = (dx * dx + dy * dy) * ih2;
				if (s2 >= 1)
					continue;
				float h = (float)(-f->depth * (1 - s2) * (1 - s2));
				if (h < o[col - k->c0])
					o[col - k->c0] = h;
			}
		}
	}
}

/* Plateau dome: ridge * 27 b0 b1 b2 (barycentric bubble), 1 at the
 * centroid and 0 on the edges, so neighbouring triangles join continuously. */
static void draw_plateaus(const struct level *l, const struct window *w, const struct bins *bn,
    int blk, const struct rect *k, float *buf)
{
	for (int e = bn->start[blk]; e < bn->start[blk + 1]; e++) {
		const struct bin_entry *be = &bn->entry[e];
		const struct plateau *q = &l->plateaus[be->id];
		struct rect c;
		if (q->ridge <= 0 || !clip(w, k, &l->pbox[be->id], be->sx, be->sy, &c))
			continue;
		double x0 = q->x[0] + be->sx, y0 = q->y[0] + be->sy;
		double x1 = q->x[1] + be->sx, y1 = q->y[1] + be->sy;
		double x2 = q->x[2] + be->sx, y2 = q->y[2] + be->sy;
		for (int row = c.r0; row <= c.r1; row++) {
			double py = px_y(w, row);
			float *o = buf + (row - k->r0) * BLOCK;
			for (int col = c.c0; col <= c.c1; col++) {
				double px = px_x(w, col);
				double b1 = ((px - x0) * (y2 - y0) - (py - y0) * (x2 - x0)) * q->inv2a;
				double b2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) * q->inv2a;
				double b0 = 1 - b1 - b2;
				if (b0 < 0 || b1 < 0 || b2 < 0)
					continue;
				o[col - k->c0] = (float)(q->ridge * 27 * b0 * b1 * b2);
			}
		}
	}
}

void relief_render(const struct relief *r, int n, double x0, double y0, float *pores, float *furrows)
{
	struct window w = { n, (n + BLOCK - 1) / BLOCK, x0 - floor(x0), y0 - floor(y0) };
	struct bins pb = { 0 }, fb[RELIEF_MAX_LEVELS], tb[RELIEF_MAX_LEVELS];
	if (pores)
		pb = bin_features(&w, r->n_pores, r->pore_box);
	for (int k = 0; furrows && k < r->n_levels; k++) {
		fb[k] = bin_features(&w, r->level[k].n_furrows, r->level[k].fbox);
		tb[k] = bin_features(&w, r->level[k].n_plateaus, r->level[k].pbox);
	}
	int nblk = w.nb * w.nb;
#pragma omp parallel for schedule(dynamic, 4)
	for (int blk = 0; blk < nblk; blk++) {
		float acc[BLOCK * BLOCK], groove[BLOCK * BLOCK], dome[BLOCK * BLOCK];
		struct rect k;
		k.r0 = blk / w.nb * BLOCK;
		k.c0 = blk % w.nb * BLOCK;
		k.r1 = k.r0 + BLOCK - 1 < n - 1 ? k.r0 + BLOCK - 1 : n - 1;
		k.c1 = k.c0 + BLOCK - 1 < n - 1 ? k.c0 + BLOCK - 1 : n - 1;
		if (pores) {
			memset(acc, 0, sizeof acc);
			draw_pores(r, &w, &pb, blk, &k, acc);
			for (int row = k.r0; row <= k.r1; row++)
				memcpy(pores + (size_t)row * n + k.c0, acc + (row - k.r0) * BLOCK,
				    sizeof(float) * (size_t)(k.c1 - k.c0 + 1));
		}
		if (furrows) {
			memset(acc, 0, sizeof acc);
			for (int lv = 0; lv < r->n_levels; lv++) {
				memset(groove, 0, sizeof groove);
				memset(dome, 0, sizeof dome);
				draw_furrows(&r->level[lv], r->p.tile, &w, &fb[lv], blk, &k, groove);
				draw_plateaus(&r->level[lv], &w, &tb[lv], blk, &k, dome);
				for (int q = 0; q < BLOCK * BLOCK; q++)
					acc[q] += groove[q] + dome[q];
			}
			for (int row = k.r0; row <= k.r1; row++)
				memcpy(furrows + (size_t)row * n + k.c0, acc + (row - k.r0) * BLOCK,
				    sizeof(float) * (size_t)(k.c1 - k.c0 + 1));
		}
	}
	if (pores)
		bins_free(&pb);
	for (int k = 0; furrows && k < r->n_levels; k++) {
		bins_free(&fb[k]);
		bins_free(&tb[k]);
	}
}

void relief_normals(int n, double pitch, const float *h, float *nx, float *ny, float *nz)
{
	double inv = 1 / (2 * pitch);
#pragma omp parallel for schedule(static)
	for (int row = 0; row < n; row++) {
		const float *up = h + (size_t)((row + n - 1) % n) * n;
		const float *dn = h + (size_t)((row + 1) % n) * n;
		const float *cur = h + (size_t)row * n;
		size_t o = (size_t)row * n;
		for (int c = 0; c < n; c++) {
			int l = c ? c - 1 : n - 1, rr = c + 1 < n ? c + 1 : 0;
			/* Row index grows downward, so dh/dy (y up) is up - down. */
			double hx = ((double)cur[rr] - cur[l]) * inv;
			double hy = ((double)up[c] - dn[c]) * inv;
			double norm = 1 / sqrt(hx * hx + hy * hy + 1);
			nx[o + c] = (float)(-hx * norm);
			ny[o + c] = (float)(-hy * norm);
			nz[o + c] = (float)norm;
		}
	}
}
