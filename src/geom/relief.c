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
enum {
	STREAM_PORE_POS = 1,
	STREAM_PORE_SHAPE = 2,
	STREAM_JUNCTION = 3,
	STREAM_WAVES = 4,
	STREAM_REGION = 5,
	STREAM_LINES = 6,
	STREAM_WARP = 7,
	STREAM_LEVEL = 16
};

/* Segments per bent furrow. */
#define BEND_SEGMENTS 4

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

/* The preferred furrow direction at (x, y) [tiles]: the direction map's
 * pixel there, or the orientation. */
static double direction_at(const struct relief_params *p, double x, double y)
{
	if (p->direction == NULL)
		return p->orientation;
	int n = p->direction_n;
	int c = (int)floor((x - floor(x)) * n), r = (int)floor((1 - (y - floor(y))) * n);
	c = c < 0 ? 0 : c >= n ? n - 1 : c;
	r = r < 0 ? 0 : r >= n ? n - 1 : r;
	return p->direction[(size_t)r * n + c];
}

/* Depth factor of a furrow at angle phi where the preferred direction is
 * theta: gain^(cos 2 (phi - theta) / 2), so along / across = gain. */
static double align_gain(double gain, double phi, double theta)
{
	return pow(gain, 0.5 * cos(2 * (phi - theta)));
}

/* Dart throwing on the torus: add points to xy[0 .. nfixed) until there are
 * `target`, none closer than dmin to another in the metric m (distances
 * measured in m applied to the nearest periodic image).  After 40 misses per
 * wanted point the rest are placed without the distance test, so the count
 * is always met.  A grid of cells no smaller than the tile-space reach of
 * dmin keeps the test to the 3x3 neighbouring cells.  With LOCAL's direction
 * map the metric of each candidate's place replaces m0. */
static void poisson(struct rng *r, int target, int nfixed, double dmin, const double m0[4],
    const struct relief_params *local, double *xy)
{
	const double *m = m0;
	double ml[4];
	/* Largest tile-space length of a metric vector of length dmin:
	 * dmin / (smallest singular value of m). */
	double a = m0[0] * m0[0] + m0[2] * m0[2], b = m0[0] * m0[1] + m0[2] * m0[3];
	double c = m0[1] * m0[1] + m0[3] * m0[3];
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
		/* With a direction map, each candidate is spaced in the metric of
		 * its own place (same stretch, so the same reach). */
		if (local != NULL && local->direction != NULL) {
			stretch_metric(local->stretch, direction_at(local, x, y), ml);
			m = ml;
		}
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
	li.furrows = (int)fmin(2e9, 3.0 * li.points);
	if (k == 1 && p->hierarchy) {
		/* Stars in the 2 N primary triangles: N junctions + 2 N centres +
		 * up to 3 N arm ends on the 3 N primary edges; up to 3 arms per
		 * triangle (star_place records the number drawn). */
		double n0 = nearbyint((p->tile / p->furrow_cell) * (p->tile / p->furrow_cell));
		li.points = (int)fmin(2e9, 6 * n0);
		li.furrows = (int)fmin(2e9, 6 * n0);
		li.cell = p->tile / sqrt(6 * n0);
	}
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
	NEED(p->plateau_roughness >= 0 && isfinite(p->plateau_roughness),
	    "plateau roughness %g um must be >= 0", p->plateau_roughness * 1e4);
	NEED(p->plateau_roughness == 0 || (p->plateau_scale > 0 && p->plateau_scale <= p->tile / 2),
	    "plateau scale %g um must be in (0, tile/2 = %g um]", p->plateau_scale * 1e4,
	    p->tile / 2 * 1e4);
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
	NEED(p->hierarchy == 0 || p->hierarchy == 1, "hierarchy %d must be 0 or 1", p->hierarchy);
	NEED(p->bend >= 0 && p->bend <= 0.3, "bend %g must be in [0, 0.3]", p->bend);
	NEED(p->furrow_fade >= 0 && p->furrow_fade <= 1.5, "furrow fade %g must be in [0, 1.5]",
	    p->furrow_fade);
	NEED(p->region_sd >= 0 && p->region_sd <= 1, "region sigma %g must be in [0, 1]",
	    p->region_sd);
	NEED(p->direction_gain >= 1 && p->direction_gain <= 10,
	    "direction gain %g must be in [1, 10]", p->direction_gain);
	NEED(p->direction == NULL || p->direction_n >= 1, "direction map needs a positive size");
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
	poisson(&rg, n, nfix, p->pore_regularity / sqrt((double)n), id, NULL, xy);

	r->pores = xmalloc(sizeof *r->pores * (size_t)n);
	r->pore_box = xmalloc(sizeof *r->pore_box * (size_t)n);
	rng_seed(&rg, seed, STREAM_PORE_SHAPE, 0);
	double sa = sqrt(p->pore_aspect);
	for (int k = 0; k < n; k++) {
		struct pore *q = &r->pores[k];
		double rad = p->pore_radius * exp(p->pore_radius_sd * relief_normal(&rg));
		/* Larger openings are deeper: depth scales with the radius. */
		double zd = relief_normal(&rg);
		q->depth = p->pore_depth * (rad / p->pore_radius) * exp(p->pore_depth_sd * zd);
		q->x = xy[2 * k];
		q->y = xy[2 * k + 1];
		/* Pore openings are elongated along the tension lines where there
		 * is a preferred direction, randomly elsewhere. */
		double phi = M_PI * rng_uniform(&rg);
		if (p->direction != NULL || p->stretch > 1 || p->direction_gain > 1)
			phi = direction_at(p, q->x, q->y) + 0.35 * relief_normal(&rg);
		q->a = rad * sa;
		q->b = rad / sa;
		q->c = cos(phi);
		q->s = sin(phi);
		double e = q->a / p->tile;
		r->pore_box[k] = (struct bbox){ q->x - e, q->x + e, q->y - e, q->y + e };
	}
	free(xy);
}

/* splitmix64's finaliser: random numbers of an edge that both of its
 * triangles can recompute. */
static uint64_t mix64(uint64_t z)
{
	z += 0x9e3779b97f4a7c15ULL;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

/* A furrow from point i to point j shifted by (sx, sy) tiles. */
struct side {
	int i, j, sx, sy;
};

/* The side from point i (tile shift si) to point j (shift sj) in canonical
 * form: from the lower index, or for i == j toward a positive shift; *flip
 * is 1 when the canonical side runs from j to i. */
static struct side canonical(int i, int six, int siy, int j, int sjx, int sjy, int *flip)
{
	struct side e = { i, j, sjx - six, sjy - siy };
	*flip = i > j || (i == j && (e.sx < 0 || (e.sx == 0 && e.sy < 0)));
	if (*flip)
		e = (struct side){ j, i, six - sjx, siy - sjy };
	return e;
}

/* Sideways amplitudes [1 of the length] of the bend of canonical side e of
 * level k, from the seed and the side alone. */
static void side_bend(const struct relief_params *p, uint64_t seed, int k, struct side e,
    double w[2])
{
	uint64_t h = mix64(seed ^ mix64(((uint64_t)(uint32_t)k << 32) | (uint32_t)e.i));
	uint64_t shift = ((uint64_t)(uint16_t)e.sx << 16) ^ (uint16_t)e.sy;
	h = mix64(h ^ ((uint64_t)(uint32_t)e.j << 32) ^ shift);
	double u1 = ((h >> 11) + 0.5) * 0x1.0p-53, u2 = ((mix64(h) >> 11) + 0.5) * 0x1.0p-53;
	double rad = sqrt(-2 * log(u1));
	w[0] = 0.2 * p->bend * fmax(-2.5, fmin(2.5, rad * cos(2 * M_PI * u2)));
	w[1] = 0.2 * p->bend * fmax(-2.5, fmin(2.5, rad * sin(2 * M_PI * u2)));
}

/* The point at t in [0, 1] of the furrow from a to b [tiles] bent by w:
 * the chord plus (w0 sin(pi t) + w1 sin(2 pi t)) times its normal. */
static void bent_point(const double a[2], const double b[2], const double w[2], double t,
    double out[2])
{
	double dx = b[0] - a[0], dy = b[1] - a[1];
	double off = w[0] * sin(M_PI * t) + w[1] * sin(2 * M_PI * t);
	out[0] = a[0] + t * dx - dy * off;
	out[1] = a[1] + t * dy + dx * off;
}

/* Append the furrow a-b bent by w as BEND_SEGMENTS straight grooves (one
 * when straight); l->furrows and l->fbox have room.  The depth is depth *
 * fa at a and depth * fb at b (the junctions; 1 where a line goes on) and
 * exp(-fade |z|), z standard normal, times the linear value in between at
 * the inner joints, linear along each piece, so a line fades in and out
 * without getting deeper than at its ends.  The box includes the groove's
 * shoulder (relief_render.c). */
static void emit(struct level *l, double T, const double a[2], const double b[2], const double w[2],
    double depth, const double fab[2], double half, double fade, struct rng *rg)
{
	int segs = w[0] == 0 && w[1] == 0 ? 1 : BEND_SEGMENTS;
	double p0[2] = { a[0], a[1] }, d0 = depth * fab[0], e2 = RELIEF_SHOULDER_WIDTH * half / T;
	for (int s = 1; s <= segs; s++) {
		double t = (double)s / segs, lin = depth * (fab[0] + t * (fab[1] - fab[0]));
		double p1[2], d1 = s == segs ? lin : lin * exp(-fade * fabs(relief_normal(rg)));
		bent_point(a, b, w, (double)s / segs, p1);
		struct furrow f = { p0[0], p0[1], p1[0], p1[1], half, d0, d1 };
		l->furrows[l->n_furrows] = f;
		l->fbox[l->n_furrows] = (struct bbox){ fmin(p0[0], p1[0]) - e2,
			fmax(p0[0], p1[0]) + e2, fmin(p0[1], p1[1]) - e2, fmax(p0[1], p1[1]) + e2 };
		l->n_furrows++;
		p0[0] = p1[0];
		p0[1] = p1[1];
		d0 = d1;
	}
}

/* Depth and half width of one furrow of level li at angle phi where the
 * preferred direction is theta and the regional factor is region:
 * log-normal, deeper along the direction, and
 * a deeper furrow is also wider (constant flank slope would give width ~
 * depth; the square root keeps shallow ones visible). */
static void furrow_size(const struct relief_params *p, const struct relief_level_info *li,
    struct rng *rg, double sd, double phi, double theta, double region, double *depth, double *half)
{
	double rel = exp(sd * relief_normal(rg));
	rel *= align_gain(p->direction_gain, phi, theta) * region;
	*depth = li->depth * rel;
	*half = 0.5 * li->width * sqrt(rel);
}

static void level_alloc(struct level *l, int n)
{
	l->furrows = xmalloc(sizeof *l->furrows * (size_t)n * BEND_SEGMENTS);
	l->fbox = xmalloc(sizeof *l->fbox * (size_t)n * BEND_SEGMENTS);
}

/* Secondary level k in the triangles of level k - 1: two or three arms
 * from an interior point (near the centroid) to a point of the sides of
 * the triangle, on the bent furrow of that side, so every secondary line
 * ends on a primary one. */
static void star_place(struct relief *r, int k, uint64_t seed)
{
	const struct relief_params *p = &r->p;
	const struct level *pl = &r->level[k - 1];
	struct level *l = &r->level[k];
	const struct delaunay *d = pl->del;
	struct rng rg;
	rng_seed(&rg, seed, STREAM_LEVEL + 2 * (uint32_t)k + 1, 0);
	level_alloc(l, 3 * d->n_tris);
	int arms = 0;
	static const double full[2] = { 1, 1 };
	for (int t = 0; t < d->n_tris; t++) {
		const struct delaunay_tri *tr = &d->tris[t];
		double v[3][2], bw[3], sum = 0, c[2] = { 0, 0 };
		for (int i = 0; i < 3; i++) {
			v[i][0] = pl->xy[2 * tr->v[i]] + tr->sx[i];
			v[i][1] = pl->xy[2 * tr->v[i] + 1] + tr->sy[i];
			bw[i] = exp(0.35 * relief_normal(&rg));
			sum += bw[i];
		}
		for (int i = 0; i < 3; i++) {
			c[0] += bw[i] / sum * v[i][0];
			c[1] += bw[i] / sum * v[i][1];
		}
		/* Three arms (a star) in 2 of 5 triangles, two (a bent chord from
		 * side to side) in the others, so that the cells are not all
		 * split alike. */
		int skip = rng_uniform(&rg) < 0.4 ? -1 : (int)(3 * rng_uniform(&rg));
		for (int i = 0; i < 3; i++) {
			if (i == skip)
				continue;
			int i1 = (i + 1) % 3, flip;
			struct side e = canonical(tr->v[i], tr->sx[i], tr->sy[i],
			    tr->v[i1], tr->sx[i1], tr->sy[i1], &flip);
			double w[2], q[2], aw[2], depth, half;
			side_bend(p, seed, k - 1, e, w);
			double u = 0.3 + 0.4 * rng_uniform(&rg);
			const double *from = flip ? v[i1] : v[i], *to = flip ? v[i] : v[i1];
			bent_point(from, to, w, flip ? 1 - u : u, q);
			aw[0] = 0.2 * p->bend * relief_normal(&rg);
			aw[1] = 0.2 * p->bend * relief_normal(&rg);
			double phi = atan2(q[1] - c[1], q[0] - c[0]);
			double mx = 0.5 * (c[0] + q[0]), my = 0.5 * (c[1] + q[1]);
			double th = direction_at(p, mx, my);
			double reg = relief_region_at(r, mx, my);
			furrow_size(p, &l->info, &rg, p->furrow_depth_sd, phi, th, reg, &depth, &half);
			emit(l, p->tile, c, q, aw, depth, full, half, p->furrow_fade, &rg);
			arms++;
		}
	}
	l->info.furrows = arms;
}

static int level_place(struct relief *r, int k, uint64_t seed, char **cause)
{
	const struct relief_params *p = &r->p;
	struct level *l = &r->level[k];
	l->info = level_info(p, k);
	if (k == 1 && p->hierarchy) {
		star_place(r, k, seed);
		return 0;
	}
	int n = l->info.points;
	double m[4];
	stretch_metric(p->stretch, p->orientation, m);
	struct rng rg;
	rng_seed(&rg, seed, STREAM_LEVEL + 2 * (uint32_t)k, 0);
	l->xy = xmalloc(sizeof *l->xy * 2 * (size_t)n);
	poisson(&rg, n, 0, p->furrow_regularity / sqrt((double)n), m, p, l->xy);
	/* With a direction map the spacing already varies; no global metric. */
	l->del = delaunay_periodic(n, l->xy, p->direction ? NULL : m, cause);
	if (l->del == NULL)
		return -1;

	const struct delaunay *d = l->del;
	/* The primary net as long lines (relief_lines.c): the depth sigma is
	 * the lines', a third of it is left to each edge. */
	double *fab = xmalloc(sizeof *fab * 2 * (size_t)d->n_edges), esd = p->furrow_depth_sd;
	for (int e = 0; e < 2 * d->n_edges; e++)
		fab[e] = 1;
	if (k == 0) {
		rng_seed(&rg, seed, STREAM_LINES, 0);
		relief_lines_factors(d, l->xy, esd, exp(-2 * p->furrow_fade), &rg, fab);
		esd /= 3;
	}
	rng_seed(&rg, seed, STREAM_LEVEL + 2 * (uint32_t)k + 1, 0);
	level_alloc(l, d->n_edges);
	for (int e = 0; e < d->n_edges; e++) {
		const struct delaunay_edge *de = &d->edges[e];
		int flip;
		struct side sd = canonical(de->i, 0, 0, de->j, de->sx, de->sy, &flip);
		double a[2] = { l->xy[2 * sd.i], l->xy[2 * sd.i + 1] };
		double b[2] = { l->xy[2 * sd.j] + sd.sx, l->xy[2 * sd.j + 1] + sd.sy };
		double w[2], depth, half;
		side_bend(p, seed, k, sd, w);
		double phi = atan2(b[1] - a[1], b[0] - a[0]);
		double mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
		double th = direction_at(p, mx, my);
		double reg = relief_region_at(r, mx, my);
		furrow_size(p, &l->info, &rg, esd, phi, th, reg, &depth, &half);
		double f2[2] = { fab[2 * e + flip], fab[2 * e + 1 - flip] };
		emit(l, p->tile, a, b, w, depth, f2, half, p->furrow_fade, &rg);
	}
	free(fab);
	l->n_plateaus = d->n_tris;
	l->plateaus = xmalloc(sizeof *l->plateaus * (size_t)d->n_tris);
	l->pbox = xmalloc(sizeof *l->pbox * (size_t)d->n_tris);
	for (int t = 0; t < d->n_tris; t++) {
		struct plateau *q = &l->plateaus[t];
		struct bbox *bb = &l->pbox[t];
		*bb = (struct bbox){ INFINITY, -INFINITY, INFINITY, -INFINITY };
		for (int v = 0; v < 3; v++) {
			q->x[v] = l->xy[2 * d->tris[t].v[v]] + d->tris[t].sx[v];
			q->y[v] = l->xy[2 * d->tris[t].v[v] + 1] + d->tris[t].sy[v];
			bb->x0 = fmin(bb->x0, q->x[v]);
			bb->x1 = fmax(bb->x1, q->x[v]);
			bb->y0 = fmin(bb->y0, q->y[v]);
			bb->y1 = fmax(bb->y1, q->y[v]);
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
	relief_region_place(r, seed, STREAM_REGION);
	relief_warp_place(r, seed, STREAM_WARP);
	for (int k = 0; k < p->levels; k++)
		if (level_place(r, k, seed, cause) != 0) {
			relief_free(r);
			return NULL;
		}
	/* The meander moves the point where a pixel looks up furrows and
	 * plateaus by at most the sum of its amplitudes: widen their boxes. */
	double reach = 0;
	for (int q = 0; q < r->n_warp; q++)
		reach += fmax(fabs(r->warp[0][q].amp), fabs(r->warp[1][q].amp));
	reach /= p->tile;
	for (int k = 0; reach > 0 && k < p->levels; k++) {
		struct level *l = &r->level[k];
		for (int f = 0; f < l->n_furrows; f++)
			l->fbox[f] = (struct bbox){ l->fbox[f].x0 - reach, l->fbox[f].x1 + reach,
				l->fbox[f].y0 - reach, l->fbox[f].y1 + reach };
		for (int t = 0; t < l->n_plateaus; t++)
			l->pbox[t] = (struct bbox){ l->pbox[t].x0 - reach, l->pbox[t].x1 + reach,
				l->pbox[t].y0 - reach, l->pbox[t].y1 + reach };
	}
	pore_place(r, seed);
	relief_waves_place(r, seed, STREAM_WAVES);
	return r;
}

void relief_free(struct relief *r)
{
	if (r == NULL)
		return;
	free(r->pores);
	free(r->pore_box);
	free(r->waves);
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
