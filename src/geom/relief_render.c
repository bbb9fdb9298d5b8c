/* relief_render: rasterise a placed relief (relief.c) onto pixels, and the
 * normals of a height map.  Features are binned into square blocks of
 * pixels, each feature once per tile shift that reaches the window, so
 * features that cross the tile border reappear on the other side and the map
 * is periodic by construction.  Blocks are independent, so OpenMP over blocks
 * gives the same result for any thread count.  Profiles are piecewise
 * polynomials with zero slope at their rim (a pore is a funnel, a furrow a V
 * with a rounded bottom and rim), so the height is continuous with a
 * continuous slope except where two grooves or pores meet. */
#include "config.h"

#include "geom/relief.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/relief_impl.h"
#include "base/util.h"

#define BLOCK 64

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

/* The funnel of a pore opening at s = distance / radius in [0, 1): (1 -
 * s)^2 / (1 - b) outside a rounded bottom of radius b, a parabola inside it
 * with the same value and slope at b; 1 at the centre, 0 with zero slope at
 * the rim.  A follicle's mouth is a funnel that narrows into the canal (steep
 * walls near the centre, a rim that rolls into the plateau), not a shallow
 * dish: its wall slope is 2 depth / radius at the bottom's edge. */
static double funnel(double s)
{
	const double b = RELIEF_PORE_BOTTOM;
	return s < b ? 1 - s * s / b : (1 - s) * (1 - s) / (1 - b);
}

/* Pore funnel: -depth funnel(s) inside the ellipse (s < 1).  Overlapping
 * pores take the deeper value. */
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
				float h = (float)(-q->depth * funnel(sqrt(s2)));
				if (h < o[col - k->c0])
					o[col - k->c0] = h;
			}
		}
	}
}

/* The V of a furrow at s = distance / half width in [0, 1): straight
 * flanks between a rounded bottom (a parabola out to b) and a rounded rim
 * (a parabola over the last c), each joined with the same slope; 1 at the
 * centre, 0 with zero slope at the rim.  Replicas show furrows as V-shaped
 * grooves, not as the bell of a smooth bump. */
static double vgroove(double s)
{
	const double b = RELIEF_GROOVE_BOTTOM, c = RELIEF_GROOVE_RIM;
	double f0 = 1 - 0.5 * c - 0.5 * b, f;
	if (s < b)
		f = 1 - 0.5 * c - 0.5 * (s * s + b * b) / b;
	else if (s <= 1 - c)
		f = 1 - s - 0.5 * c;
	else
		f = 0.5 * (1 - s) * (1 - s) / c;
	return f / f0;
}

/* The meander's displacement [cm] of every pixel of block k into wxy (x, y
 * interleaved, BLOCK per row): cos(a + b) = cos a cos b - sin a sin b with a
 * from the column and b from the row. */
static void block_warp(const struct relief *r, const struct window *w, const struct rect *k,
    float *wxy)
{
	int nw = r->n_warp, nc = k->c1 - k->c0 + 1;
	double cc[2][RELIEF_WARP_WAVES][BLOCK], sc[2][RELIEF_WARP_WAVES][BLOCK];
	for (int d = 0; d < 2; d++)
		for (int q = 0; q < nw; q++)
			for (int c = 0; c < nc; c++) {
				double a = 2 * M_PI * r->warp[d][q].kx * px_x(w, k->c0 + c);
				cc[d][q][c] = cos(a);
				sc[d][q][c] = sin(a);
			}
	for (int row = k->r0; row <= k->r1; row++) {
		double rc[2][RELIEF_WARP_WAVES], rs[2][RELIEF_WARP_WAVES];
		for (int d = 0; d < 2; d++)
			for (int q = 0; q < nw; q++) {
				const struct wave *wv = &r->warp[d][q];
				double b = 2 * M_PI * wv->ky * px_y(w, row) + wv->phase;
				rc[d][q] = wv->amp * cos(b);
				rs[d][q] = wv->amp * sin(b);
			}
		float *o = wxy + 2 * (row - k->r0) * BLOCK;
		for (int c = 0; c < nc; c++)
			for (int d = 0; d < 2; d++) {
				double sum = 0;
				for (int q = 0; q < nw; q++)
					sum += cc[d][q][c] * rc[d][q] - sc[d][q][c] * rs[d][q];
				o[2 * c + d] = (float)sum;
			}
	}
}

/* Furrow groove along a segment: -depth (1 - k) vgroove(s) inside, s =
 * distance / half width (from the pixel moved by the meander wxy [cm], when
 * not NULL), in buf, and its shoulder -depth k g(s / W), g(s) = (1 - s^2)^2,
 * in sh, k and W the shoulder's depth and width (relief_impl.h):
 * a narrow groove in a broad shallow valley; the depth linear from one end
 * to the other along the segment.  Grooves of one level combine by their
 * minimum (a crossing is no deeper than its deeper line), shoulders by their
 * sum (smooth: a minimum of broad valleys would crease along the lines where
 * two are equal, which shows as facets). */
static void draw_furrows(const struct level *l, double T, const struct window *w,
    const struct bins *bn, int blk, const struct rect *k, const float *wxy, float *buf, float *sh)
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
		const double sk = RELIEF_SHOULDER_DEPTH;
		const double iw2 = 1 / (RELIEF_SHOULDER_WIDTH * RELIEF_SHOULDER_WIDTH);
		for (int row = c.r0; row <= c.r1; row++) {
			double py0 = px_y(w, row) * T - ay;
			float *o = buf + (row - k->r0) * BLOCK, *os = sh + (row - k->r0) * BLOCK;
			const float *wr = wxy ? wxy + 2 * (row - k->r0) * BLOCK : NULL;
			for (int col = c.c0; col <= c.c1; col++) {
				int q = col - k->c0;
				double px = px_x(w, col) * T - ax, py = py0;
				if (wr) {
					px += wr[2 * q];
					py += wr[2 * q + 1];
				}
				double t = (px * ex + py * ey) * il2;
				t = t < 0 ? 0 : t > 1 ? 1 : t;
				double dx = px - t * ex, dy = py - t * ey;
				double s2 = (dx * dx + dy * dy) * ih2, w2 = s2 * iw2;
				if (w2 >= 1)
					continue;
				double d = f->depth + t * (f->depth1 - f->depth);
				os[q] -= (float)(d * sk * (1 - w2) * (1 - w2));
				if (s2 >= 1)
					continue;
				float h = (float)(-d * (1 - sk) * vgroove(sqrt(s2)));
				if (h < o[q])
					o[q] = h;
			}
		}
	}
}

/* Plateau dome: ridge * (27 b0 b1 b2)^2 (a squared barycentric bubble), 1
 * at the centroid, 0 with zero slope on the edges, so neighbouring
 * triangles join smoothly and a bent furrow leaves no crease along the
 * straight edge. */
static void draw_plateaus(const struct level *l, double T, const struct window *w,
    const struct bins *bn, int blk, const struct rect *k, const float *wxy, float *buf)
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
			double py0 = px_y(w, row);
			float *o = buf + (row - k->r0) * BLOCK;
			const float *wr = wxy ? wxy + 2 * (row - k->r0) * BLOCK : NULL;
			for (int col = c.c0; col <= c.c1; col++) {
				double px = px_x(w, col) - x0, py = py0 - y0;
				if (wr) {
					px += wr[2 * (col - k->c0)] / T;
					py += wr[2 * (col - k->c0) + 1] / T;
				}
				double b1 = (px * (y2 - y0) - py * (x2 - x0)) * q->inv2a;
				double b2 = ((x1 - x0) * py - (y1 - y0) * px) * q->inv2a;
				double b0 = 1 - b1 - b2;
				if (b0 < 0 || b1 < 0 || b2 < 0)
					continue;
				double bub = 27 * b0 * b1 * b2;
				o[col - k->c0] = (float)(q->ridge * bub * bub);
			}
		}
	}
}

/* Add the plateau waves to out: cos(a + b) = cos a cos b - sin a sin b
 * with a from the column and b from the row, so each pixel costs two
 * products per wave. */
static void add_waves(const struct relief *r, const struct window *w, float *out)
{
	int n = w->n, nw = r->n_waves;
	/* Column terms stored column by column, so the inner loop over the
	 * waves reads contiguous memory. */
	size_t nterms = (size_t)nw * (size_t)n;
	double *ca = xmalloc(sizeof *ca * nterms), *sa = xmalloc(sizeof *sa * nterms);
	for (int c = 0; c < n; c++)
		for (int q = 0; q < nw; q++) {
			double a = 2 * M_PI * r->waves[q].kx * px_x(w, c);
			ca[(size_t)c * nw + q] = cos(a);
			sa[(size_t)c * nw + q] = sin(a);
		}
#pragma omp parallel for schedule(static)
	for (int row = 0; row < n; row++) {
		double rc[RELIEF_WAVES], rs[RELIEF_WAVES];
		for (int q = 0; q < nw; q++) {
			double b = 2 * M_PI * r->waves[q].ky * px_y(w, row) + r->waves[q].phase;
			rc[q] = r->waves[q].amp * cos(b);
			rs[q] = r->waves[q].amp * sin(b);
		}
		for (int c = 0; c < n; c++) {
			const double *cc = ca + (size_t)c * nw, *sc = sa + (size_t)c * nw;
			double sum = 0;
			/* Vectorised; the order is fixed by the compiler, not the threads. */
#pragma omp simd reduction(+:sum)
			for (int q = 0; q < nw; q++)
				sum += cc[q] * rc[q] - sc[q] * rs[q];
			out[(size_t)row * n + c] += (float)sum;
		}
	}
	free(ca);
	free(sa);
}

void relief_render(const struct relief *r, int n, double x0, double y0, float *pores,
    float *furrows)
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
		float acc[BLOCK * BLOCK], groove[BLOCK * BLOCK];
		float dome[BLOCK * BLOCK], sh[BLOCK * BLOCK];
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
			float wxy[2 * BLOCK * BLOCK], *wp = NULL;
			if (r->n_warp > 0) {
				block_warp(r, &w, &k, wxy);
				wp = wxy;
			}
			memset(acc, 0, sizeof acc);
			for (int lv = 0; lv < r->n_levels; lv++) {
				memset(groove, 0, sizeof groove);
				memset(dome, 0, sizeof dome);
				memset(sh, 0, sizeof sh);
				const struct level *l = &r->level[lv];
				draw_furrows(l, r->p.tile, &w, &fb[lv], blk, &k, wp, groove, sh);
				draw_plateaus(l, r->p.tile, &w, &tb[lv], blk, &k, wp, dome);
				/* Shoulders add up where lines cross; saturate the sum
				 * smoothly at c so that a crossing of many lines is not
				 * a deep bowl that swallows its pore. */
				double c = RELIEF_SHOULDER_CAP * RELIEF_SHOULDER_DEPTH;
				c *= l->info.depth;
				for (int q = 0; q < BLOCK * BLOCK; q++) {
					double s = c > 0 ? -c * (1 - exp(sh[q] / c)) : 0;
					acc[q] += groove[q] + (float)s + dome[q];
				}
			}
			for (int row = k.r0; row <= k.r1; row++)
				memcpy(furrows + (size_t)row * n + k.c0, acc + (row - k.r0) * BLOCK,
				    sizeof(float) * (size_t)(k.c1 - k.c0 + 1));
		}
	}
	if (furrows && r->n_waves > 0)
		add_waves(r, &w, furrows);
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
