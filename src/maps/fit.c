/* fit: parameters per texel from an albedo colour (method in fit.h): the
 * dense CIELAB table of the family, its bucket grid, the nearest node and
 * the Gauss-Newton refinement, distinct colours, the summary. */
#include "config.h"
#include "maps/fit.h"

#include <json-c/json.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/check.h"
#include "base/srgb.h"
#include "base/util.h"
#include "io/json.h"
#include "skin/colour.h"

#define REG 0.01	/* pull toward the axis middle, CIELAB units per unit of normalised coordinate */

static int n_threads(int t)
{
#ifdef _OPENMP
	return t > 0 ? t : omp_get_max_threads();
#else
	(void)t;
	return 1;
#endif
}

/* The family's CIELAB on a dense grid, and buckets over CIELAB. */
struct lut {
	const struct family *f;
	int k;				/* axes */
	int g[FAMILY_MAX_AXES];		/* grid points per axis */
	double c0[FAMILY_MAX_AXES], c1[FAMILY_MAX_AXES];	/* axis coordinate at the grid's ends */
	int n;				/* grid points */
	double *lab;			/* [n][3] */
	int n_coarse;			/* grid points in the buckets: every step-th per axis and the last */
	double lo[3], cell;		/* bucket grid origin and cell size (CIELAB units) */
	int dim[3];
	int *start, *item;		/* CSR: bucket b holds item[start[b] .. start[b + 1]) */
};

/* Parameter values at grid coordinates g (continuous, in grid units). */
static void grid_params(const struct lut *t, const double *g, double *x)
{
	for (int a = 0; a < t->k; a++) {
		double c = t->c0[a] + (t->c1[a] - t->c0[a]) * g[a] / (t->g[a] - 1);
		x[a] = family_axis_value(&t->f->axis[a], c);
		/* keep the ends exact (exp(log(v)) may differ in the last bit) */
		const struct family_axis *ax = &t->f->axis[a];
		x[a] = fmin(fmax(x[a], ax->node[0]), ax->node[ax->n - 1]);
	}
}

static void params_lab(const struct family *f, const double *x, double lab[3])
{
	double rgb[3];
	family_albedo(f, x, NULL, rgb, NULL);
	colour_linear_srgb_to_lab(rgb, lab);
}

static void lut_build(struct lut *t, const struct family *f, int threads)
{
	memset(t, 0, sizeof *t);
	t->f = f;
	t->k = f->n_axes;
	static const int per_axis[FAMILY_MAX_AXES + 1] = { 0, 2048, 160, 48 };
	t->n = 1;
	for (int a = 0; a < FAMILY_MAX_AXES; a++) {
		t->g[a] = a < t->k ? per_axis[t->k] : 1;
		if (a < t->k) {
			const struct family_axis *ax = &f->axis[a];
			t->c0[a] = family_axis_coord(ax, ax->node[0]);
			t->c1[a] = family_axis_coord(ax, ax->node[ax->n - 1]);
		}
		t->n *= t->g[a];
	}
	t->lab = xmalloc(sizeof(double) * 3 * (size_t)t->n);
	(void)threads; /* only OpenMP's pragma reads it */
#pragma omp parallel for schedule(static) num_threads(threads)
	for (int i = 0; i < t->n; i++) {
		double g[FAMILY_MAX_AXES] = { i % t->g[0], (i / t->g[0]) % t->g[1], i / (t->g[0] * t->g[1]) }, x[3];
		grid_params(t, g, x);
		params_lab(f, x, t->lab + 3 * (size_t)i);
	}
	/* Buckets of 2 CIELAB units over a coarse subset of the grid (the
	 * refinement walks the fine grid from the coarse point found). */
	static const int step[FAMILY_MAX_AXES + 1] = { 1, 16, 4, 4 };
	int *coarse = xmalloc(sizeof(int) * (size_t)t->n);
	t->n_coarse = 0;
	for (int i = 0; i < t->n; i++) {
		int q[FAMILY_MAX_AXES] = { i % t->g[0], (i / t->g[0]) % t->g[1], i / (t->g[0] * t->g[1]) }, in = 1;
		for (int a = 0; a < t->k; a++)
			in = in && (q[a] % step[t->k] == 0 || q[a] == t->g[a] - 1);
		if (in)
			coarse[t->n_coarse++] = i;
	}
	double hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (int c = 0; c < 3; c++)
		t->lo[c] = INFINITY;
	for (int j = 0; j < t->n_coarse; j++)
		for (int c = 0; c < 3; c++) {
			t->lo[c] = fmin(t->lo[c], t->lab[3 * (size_t)coarse[j] + c]);
			hi[c] = fmax(hi[c], t->lab[3 * (size_t)coarse[j] + c]);
		}
	t->cell = 2.0;
	double vol = 1.0;
	for (int c = 0; c < 3; c++)
		vol *= (hi[c] - t->lo[c]) / t->cell + 1.0;
	if (vol > 1e6)
		t->cell *= cbrt(vol / 1e6);
	size_t nb = 1;
	for (int c = 0; c < 3; c++) {
		t->dim[c] = (int)floor((hi[c] - t->lo[c]) / t->cell) + 1;
		nb *= (size_t)t->dim[c];
	}
	t->start = xcalloc(nb + 1, sizeof(int));
	t->item = xmalloc(sizeof(int) * (size_t)t->n_coarse);
	int *bi = xmalloc(sizeof(int) * (size_t)t->n_coarse);
	for (int j = 0; j < t->n_coarse; j++) {
		int b[3];
		for (int c = 0; c < 3; c++) {
			b[c] = (int)floor((t->lab[3 * (size_t)coarse[j] + c] - t->lo[c]) / t->cell);
			b[c] = b[c] < 0 ? 0 : b[c] >= t->dim[c] ? t->dim[c] - 1 : b[c];
		}
		bi[j] = (b[2] * t->dim[1] + b[1]) * t->dim[0] + b[0];
		t->start[bi[j] + 1]++;
	}
	for (size_t b = 0; b < nb; b++)
		t->start[b + 1] += t->start[b];
	int *fill = xmalloc(sizeof(int) * nb);
	memcpy(fill, t->start, sizeof(int) * nb);
	for (int j = 0; j < t->n_coarse; j++)
		t->item[fill[bi[j]]++] = coarse[j];
	free(fill);
	free(bi);
	free(coarse);
}

static void lut_free(struct lut *t)
{
	free(t->lab);
	free(t->start);
	free(t->item);
}

static double d2(const double *a, const double *b)
{
	double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
	return x * x + y * y + z * z;
}

/* The coarse grid point nearest to lab in CIELAB: buckets shell by shell
 * around lab's bucket until no closer point can remain; all coarse points
 * past 40 shells. */
static int lut_nearest(const struct lut *t, const double lab[3])
{
	int tc[3], best = -1;
	double bd = INFINITY;
	for (int c = 0; c < 3; c++)
		tc[c] = (int)floor((lab[c] - t->lo[c]) / t->cell);
	int s0 = 0;	/* shells before the box */
	for (int c = 0; c < 3; c++) {
		int out = tc[c] < 0 ? -tc[c] : tc[c] >= t->dim[c] ? tc[c] - t->dim[c] + 1 : 0;
		s0 = out > s0 ? out : s0;
	}
	int smax = t->dim[0] + t->dim[1] + t->dim[2] + s0;
	for (int s = s0; s <= smax; s++) {
		if (s > s0 + 40) {
			for (int j = 0; j < t->n_coarse; j++) {
				double d = d2(t->lab + 3 * (size_t)t->item[j], lab);
				if (d < bd || (d == bd && t->item[j] < best)) {
					bd = d;
					best = t->item[j];
				}
			}
			return best;
		}
		int lo[3], hi[3];
		for (int c = 0; c < 3; c++) {
			lo[c] = tc[c] - s < 0 ? 0 : tc[c] - s;
			hi[c] = tc[c] + s >= t->dim[c] ? t->dim[c] - 1 : tc[c] + s;
		}
		for (int z = lo[2]; z <= hi[2]; z++)
			for (int y = lo[1]; y <= hi[1]; y++)
				for (int x = lo[0]; x <= hi[0]; x++) {
					int cheb = abs(x - tc[0]);
					cheb = abs(y - tc[1]) > cheb ? abs(y - tc[1]) : cheb;
					cheb = abs(z - tc[2]) > cheb ? abs(z - tc[2]) : cheb;
					if (cheb != s)
						continue;
					int b = (z * t->dim[1] + y) * t->dim[0] + x;
					for (int j = t->start[b]; j < t->start[b + 1]; j++) {
						double d = d2(t->lab + 3 * (size_t)t->item[j], lab);
						if (d < bd || (d == bd && t->item[j] < best)) {
							bd = d;
							best = t->item[j];
						}
					}
				}
		/* A point in shell s + 1 or beyond is at least s cells away. */
		if (best >= 0 && bd <= (s * t->cell) * (s * t->cell))
			return best;
	}
	return best;
}

/* lut_eval for two axes: the same operations in the same order (so the
 * same bits), unrolled; the general loop spends most of its time on
 * indexing and branches. */
static void lut_eval2(const struct lut *t, const int *i0, const double *fr, double lab[3],
    double jac[3][FAMILY_MAX_AXES])
{
	const double f0 = fr[0], f1 = fr[1], e0 = 1.0 - fr[0], e1 = 1.0 - fr[1];
	const double w[4] = { e0 * e1, f0 * e1, e0 * f1, f0 * f1 };
	const double d0[4] = { -1.0 * e1, 1.0 * e1, -1.0 * f1, 1.0 * f1 };
	const double d1[4] = { e0 * -1.0, f0 * -1.0, e0 * 1.0, f0 * 1.0 };
	const int base = i0[0] + i0[1] * t->g[0];
	const int off[4] = { base, base + 1, base + t->g[0], base + t->g[0] + 1 };
	for (int c = 0; c < 3; c++) {
		lab[c] = 0.0;
		jac[c][0] = 0.0;
		jac[c][1] = 0.0;
	}
	for (int corner = 0; corner < 4; corner++) {
		const double *L = t->lab + 3 * (size_t)off[corner];
		for (int c = 0; c < 3; c++) {
			lab[c] += w[corner] * L[c];
			jac[c][0] += d0[corner] * L[c];
			jac[c][1] += d1[corner] * L[c];
		}
	}
}

/* The multilinear interpolant of the grid at g and its Jacobian. */
static void lut_eval(const struct lut *t, const double *g, double lab[3], double jac[3][FAMILY_MAX_AXES])
{
	int i0[FAMILY_MAX_AXES];
	double fr[FAMILY_MAX_AXES];
	for (int a = 0; a < t->k; a++) {
		i0[a] = (int)floor(g[a]);
		if (i0[a] > t->g[a] - 2)
			i0[a] = t->g[a] - 2;
		if (i0[a] < 0)
			i0[a] = 0;
		fr[a] = g[a] - i0[a];
	}
	if (t->k == 2) {
		lut_eval2(t, i0, fr, lab, jac);
		return;
	}
	for (int c = 0; c < 3; c++) {
		lab[c] = 0.0;
		for (int a = 0; a < t->k; a++)
			jac[c][a] = 0.0;
	}
	for (int corner = 0; corner < (1 << t->k); corner++) {
		int idx = 0, mul = 1;
		double w = 1.0, dw[FAMILY_MAX_AXES];
		for (int a = 0; a < t->k; a++) {
			int bit = (corner >> a) & 1;
			idx += (i0[a] + bit) * mul;
			mul *= t->g[a];
			w *= bit ? fr[a] : 1.0 - fr[a];
		}
		for (int a = 0; a < t->k; a++) {
			dw[a] = 1.0;
			for (int b = 0; b < t->k; b++) {
				int bit = (corner >> b) & 1;
				dw[a] *= b == a ? (bit ? 1.0 : -1.0) : (bit ? fr[b] : 1.0 - fr[b]);
			}
		}
		const double *L = t->lab + 3 * (size_t)idx;
		for (int c = 0; c < 3; c++) {
			lab[c] += w * L[c];
			for (int a = 0; a < t->k; a++)
				jac[c][a] += dw[a] * L[c];
		}
	}
}

static double cost(const struct lut *t, const double *g, const double *target, double lab[3],
    double jac[3][FAMILY_MAX_AXES])
{
	lut_eval(t, g, lab, jac);
	double s = d2(lab, target);
	for (int a = 0; a < t->k; a++) {
		double r = REG * (g[a] / (t->g[a] - 1) - 0.5);
		s += r * r;
	}
	return s;
}

/* Solve the k x k system m x = b (k <= 3) by Gaussian elimination with
 * pivoting; 0 when singular. */
static int solve(int k, double m[3][3], double *b)
{
	for (int c = 0; c < k; c++) {
		int p = c;
		for (int r = c + 1; r < k; r++)
			if (fabs(m[r][c]) > fabs(m[p][c]))
				p = r;
		if (fabs(m[p][c]) < 1e-300)
			return 0;
		for (int j = 0; j < k; j++) {
			double x = m[c][j];
			m[c][j] = m[p][j];
			m[p][j] = x;
		}
		double x = b[c];
		b[c] = b[p];
		b[p] = x;
		for (int r = c + 1; r < k; r++) {
			double q = m[r][c] / m[c][c];
			for (int j = c; j < k; j++)
				m[r][j] -= q * m[c][j];
			b[r] -= q * b[c];
		}
	}
	for (int c = k - 1; c >= 0; c--) {
		for (int j = c + 1; j < k; j++)
			b[c] -= m[c][j] * b[j];
		b[c] /= m[c][c];
	}
	return 1;
}

/* Damped Gauss-Newton (Levenberg-Marquardt) from g, inside the grid; the
 * CIELAB distance reached. */
static double refine(const struct lut *t, double *g, const double *target)
{
	double lab[3], jac[3][FAMILY_MAX_AXES], lambda = 1e-3;
	double c = cost(t, g, target, lab, jac);
	for (int it = 0; it < 50; it++) {
		double m[3][3] = { { 0 } }, b[3] = { 0 }, gn[FAMILY_MAX_AXES];
		for (int a = 0; a < t->k; a++) {
			double ra = REG / (t->g[a] - 1), r = REG * (g[a] / (t->g[a] - 1) - 0.5);
			for (int bb = 0; bb < t->k; bb++)
				for (int q = 0; q < 3; q++)
					m[a][bb] += jac[q][a] * jac[q][bb];
			m[a][a] += ra * ra;
			for (int q = 0; q < 3; q++)
				b[a] -= jac[q][a] * (lab[q] - target[q]);
			b[a] -= ra * r;
		}
		for (int a = 0; a < t->k; a++)
			m[a][a] *= 1.0 + lambda;
		if (!solve(t->k, m, b))
			break;
		double step = 0.0;
		for (int a = 0; a < t->k; a++) {
			gn[a] = fmin(fmax(g[a] + b[a], 0.0), t->g[a] - 1.0);
			step = fmax(step, fabs(gn[a] - g[a]));
		}
		double labn[3], jacn[3][FAMILY_MAX_AXES], cn = cost(t, gn, target, labn, jacn);
		if (cn <= c) {
			memcpy(g, gn, sizeof(double) * (size_t)t->k);
			memcpy(lab, labn, sizeof lab);
			memcpy(jac, jacn, sizeof jac);
			lambda = fmax(lambda / 3.0, 1e-9);
			int done = step < 1e-7 || c - cn < 1e-14;
			c = cn;
			if (done)
				break;
		} else {
			lambda *= 10.0;
			if (lambda > 1e8)
				break;
		}
	}
	return sqrt(d2(lab, target));
}

void maps_texel_linear(const struct image *im, size_t i, int input_linear, double rgb[3])
{
	for (int c = 0; c < 3; c++) {
		double v = image_get(im, i, c);
		rgb[c] = input_linear ? v : srgb_decode(v);
	}
}

/* Distinct colours: a hash of the bits of the three values, ids in the
 * order of first appearance (raster order, so neighbouring ids are mostly
 * neighbouring texels of similar colour).  The table grows with the
 * colours found, so a texture streamed in bands needs memory for its
 * distinct colours only: per colour its key (12 bytes), 8 to 16 bytes of
 * 4-byte hash slots and its result (4 bytes per axis and the error). */
struct colours {
	long n;			/* distinct colours */
	uint32_t (*key)[3];	/* [n] the bits of the texel's three float values */
	size_t kcap;		/* keys allocated */
	int32_t *slot;		/* [cap] colour id or -1 */
	size_t cap;		/* 2^bits, at least 2 n */
	int bits;
};

static void texel_bits(const struct image *im, size_t i, uint32_t k[3])
{
	for (int c = 0; c < 3; c++) {
		float v = image_get(im, i, c);
		memcpy(&k[c], &v, sizeof v);
	}
}

/* Multiplicative hashing: the top bits of a product mix every key bit
 * (the low bits of a product see only the key's low bits). */
static size_t key_hash(const uint32_t k[3], int bits)
{
	uint64_t h = ((((uint64_t)k[0] * 0x9E3779B97F4A7C15ULL) ^ k[1]) * 0xC2B2AE3D27D4EB4FULL ^ k[2]) *
	    0x165667B19E3779F9ULL;
	return (size_t)(h >> (64 - bits));
}

static void colours_init(struct colours *cl)
{
	memset(cl, 0, sizeof *cl);
	cl->cap = 1024;
	cl->bits = 10;
	cl->slot = xmalloc(sizeof(int32_t) * cl->cap);
	for (size_t i = 0; i < cl->cap; i++)
		cl->slot[i] = -1;
}

/* The slot of key k: its colour's, or the empty one where it goes. */
static size_t colours_slot(const struct colours *cl, const uint32_t k[3])
{
	size_t j = key_hash(k, cl->bits);
	for (;;) {
		int32_t id = cl->slot[j];
		if (id < 0)
			return j;
		const uint32_t *q = cl->key[id];
		if (q[0] == k[0] && q[1] == k[1] && q[2] == k[2])
			return j;
		j = (j + 1) & (cl->cap - 1);
	}
}

/* The id of colour k, added if new. */
static int32_t colours_add(struct colours *cl, const uint32_t k[3])
{
	size_t j = colours_slot(cl, k);
	if (cl->slot[j] >= 0)
		return cl->slot[j];
	CHECK(cl->n < INT32_MAX);
	if ((size_t)cl->n == cl->kcap) {
		cl->kcap = cl->kcap ? 2 * cl->kcap : 1024;
		cl->key = xreallocarray(cl->key, cl->kcap, sizeof *cl->key);
	}
	memcpy(cl->key[cl->n], k, sizeof(uint32_t) * 3);
	cl->slot[j] = (int32_t)cl->n++;
	if (2 * (size_t)cl->n > cl->cap) {
		/* grow: the ids stay, only their slots move */
		free(cl->slot);
		cl->cap *= 2;
		cl->bits++;
		cl->slot = xmalloc(sizeof(int32_t) * cl->cap);
		for (size_t i = 0; i < cl->cap; i++)
			cl->slot[i] = -1;
		for (long u = 0; u < cl->n; u++)
			cl->slot[colours_slot(cl, cl->key[u])] = (int32_t)u;
	}
	return (int32_t)cl->n - 1;
}

/* The id of colour k, or -1 if it was not added. */
static int32_t colours_id(const struct colours *cl, const uint32_t k[3])
{
	return cl->slot[colours_slot(cl, k)];
}

/* The texel values a colour's key holds (as image_get returned them). */
static void key_values(const uint32_t k[3], float v[3])
{
	for (int c = 0; c < 3; c++)
		memcpy(&v[c], &k[c], sizeof v[c]);
}

static void colours_free(struct colours *cl)
{
	free(cl->key);
	free(cl->slot);
}

/* One colour's parameters (grid coordinates g, warm-started from g when
 * warm), by the coarse nearest point and the refinement; a warm start that
 * reaches an exact match (within 0.02 CIELAB) is taken as it is. */
static void solve_colour(const struct lut *t, const double target[3], double *g, int warm)
{
	double gw[FAMILY_MAX_AXES], rw = INFINITY;
	if (warm) {
		memcpy(gw, g, sizeof gw);
		rw = refine(t, gw, target);
		if (rw < 0.02) {
			memcpy(g, gw, sizeof gw);
			return;
		}
	}
	int nb = lut_nearest(t, target);
	for (int a = 0; a < t->k; a++)
		g[a] = (nb / (a == 0 ? 1 : a == 1 ? t->g[0] : t->g[0] * t->g[1])) % t->g[a];
	if (refine(t, g, target) > rw)
		memcpy(g, gw, sizeof gw);
}

/* The errors over fitted texels, in 0.001 bins up to 100, for the median
 * and 95th percentile; their maximum. */
struct de_hist {
	long *h;
	double max;
};
enum { DE_BINS = 100000 };

static void hist_add(struct de_hist *dh, double d)
{
	dh->max = fmax(dh->max, d);
	long b = lround(d * 1000.0);
	dh->h[b > DE_BINS ? DE_BINS : b]++;
}

static void hist_stats(const struct de_hist *dh, struct maps_fit_summary *s)
{
	long cum = 0;
	s->de_max = dh->max;
	s->de_median = s->de_p95 = -1.0;
	for (long b = 0; b <= DE_BINS && s->fitted > 0; b++) {
		cum += dh->h[b];
		if (s->de_median < 0 && 2 * cum >= s->fitted)
			s->de_median = b / 1000.0;
		if (s->de_p95 < 0 && 100 * cum >= 95 * s->fitted)
			s->de_p95 = b / 1000.0;
	}
	if (s->fitted == 0)
		s->de_median = s->de_p95 = 0.0;
}

/* The fit's state between its passes: the table, the colours and their
 * results (nr floats each: the parameters and the error). */
struct fitter {
	struct family *f;
	const struct maps_fit_opts *o;
	int threads;
	struct lut t;
	struct colours cl;
	int nr;
	float *res;
	struct de_hist dh;
};

static void fitter_init(struct fitter *F, struct family *f, const struct maps_fit_opts *o)
{
	memset(F, 0, sizeof *F);
	F->f = f;
	F->o = o;
	F->threads = n_threads(o->threads);
	family_albedo_prepare(f);
	colours_init(&F->cl);
	F->dh.h = xcalloc(DE_BINS + 1, sizeof(long));
}

static void fitter_free(struct fitter *F)
{
	if (F->res)
		lut_free(&F->t);
	colours_free(&F->cl);
	free(F->res);
	free(F->dh.h);
}

/* Whether texel i of a band is fitted (opaque, inside the mask). */
static int texel_in(const struct image *albedo, const struct image *mask, size_t i)
{
	return image_get(albedo, i, 3) >= 0.5f && (mask == NULL || image_get(mask, i, 0) >= 0.5f);
}

/* Pass 1 over a band: its fitted texels' colours, in raster order; ids
 * (NULL or one per texel of the band) gets each texel's colour, -1 when
 * it is not fitted. */
static void fitter_scan(struct fitter *F, const struct image *albedo, const struct image *mask, int nrows,
    int32_t *ids, struct maps_fit_summary *sum)
{
	size_t n = (size_t)albedo->w * (size_t)nrows;
	uint32_t prev[3] = { 0 };
	int32_t prev_id = -1;	/* the id of colour prev, -1 none yet */
	for (size_t i = 0; i < n; i++) {
		int32_t id = -1;
		if (texel_in(albedo, mask, i)) {
			sum->fitted++;
			uint32_t k[3];
			texel_bits(albedo, i, k);
			/* runs of one colour: no hash */
			id = prev_id >= 0 && memcmp(k, prev, sizeof k) == 0 ? prev_id : colours_add(&F->cl, k);
			memcpy(prev, k, sizeof k);
			prev_id = id;
		}
		if (ids)
			ids[i] = id;
	}
	sum->texels += (long)n;
}

/* Solve every colour: fixed chunks, each solved in order with warm starts,
 * so the result does not depend on the threads. */
static void fitter_solve(struct fitter *F)
{
	const struct colours *cl = &F->cl;
	lut_build(&F->t, F->f, F->threads);
	const struct lut *t = &F->t;
	enum { CHUNK = 512 };
	const int nr = F->nr = t->k + 1;
	F->res = xmalloc(sizeof(float) * (size_t)(cl->n > 0 ? cl->n : 1) * (size_t)nr);
	float *res = F->res;
	const struct maps_fit_opts *o = F->o;
	struct family *f = F->f;
	long n_chunks = (cl->n + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(dynamic, 1) num_threads(F->threads)
	for (long ch = 0; ch < n_chunks; ch++) {
		double g[FAMILY_MAX_AXES] = { 0 };
		for (long u = ch * CHUNK; u < cl->n && u < (ch + 1) * CHUNK; u++) {
			double rgb[3], target[3], x[FAMILY_MAX_AXES], lab[3];
			float v[3];
			key_values(cl->key[u], v);
			for (int c = 0; c < 3; c++)
				rgb[c] = o->input_linear ? v[c] : srgb_decode(v[c]);
			colour_linear_srgb_to_lab(rgb, target);
			solve_colour(t, target, g, u > ch * CHUNK);
			grid_params(t, g, x);
			params_lab(f, x, lab);
			float *r = res + (size_t)u * (size_t)nr;
			for (int a = 0; a < t->k; a++)
				r[a] = (float)x[a];
			r[t->k] = (float)colour_de2000(target, lab);
		}
	}
}

/* Pass 2 over a band: each texel's maps from its colour's result, the
 * colour from ids (pass 1's) or else from the albedo and mask; not fitted
 * texels keep the values v[a] and de2000 hold, and status 128.  -1 when a
 * colour was not seen by pass 1 (the file changed). */
static int fitter_apply(struct fitter *F, const int32_t *ids, const struct image *albedo, const struct image *mask,
    long n, float *const *v, float *de2000, unsigned char *status, struct maps_fit_summary *sum)
{
	long unmatched = 0, unseen = 0;
	const int k = F->t.k, nr = F->nr;
	const double max_de = F->o->max_de;
#pragma omp parallel num_threads(F->threads) reduction(+ : unmatched, unseen)
	{
	uint32_t prev[3] = { 0 };
	int32_t prev_id = -1;	/* the id of colour prev, -1 none yet */
#pragma omp for schedule(static)
	for (long i = 0; i < n; i++) {
		int32_t id;
		if (ids)
			id = ids[i];
		else if (!texel_in(albedo, mask, (size_t)i))
			id = -1;
		else {
			uint32_t key[3];
			texel_bits(albedo, (size_t)i, key);
			id = prev_id >= 0 && memcmp(key, prev, sizeof key) == 0 ? prev_id : colours_id(&F->cl, key);
			memcpy(prev, key, sizeof key);
			prev_id = id;
			unseen += id < 0;
		}
		if (id < 0) {
			status[i] = MAPS_NOT_FITTED;
			continue;
		}
		const float *r = F->res + (size_t)id * (size_t)nr;
		for (int a = 0; a < k; a++)
			v[a][i] = r[a];
		de2000[i] = r[k];
		status[i] = r[k] <= max_de ? MAPS_MATCHED : MAPS_UNMATCHED;
		unmatched += status[i] == MAPS_UNMATCHED;
	}
	}
	for (long i = 0; i < n; i++)
		if (status[i] != MAPS_NOT_FITTED)
			hist_add(&F->dh, de2000[i]);
	sum->unmatched += unmatched;
	return unseen ? -1 : 0;
}

int maps_fit(struct family *f, const struct image *albedo, const struct image *mask, const struct maps_fit_opts *o,
    struct mapset **out, struct maps_fit_summary *sum, char **cause)
{
	if (mask && (mask->w != albedo->w || mask->h != albedo->h)) {
		*cause = xasprintf("the mask is %d x %d texels, the albedo %d x %d", mask->w, mask->h, albedo->w, albedo->h);
		return -1;
	}
	double t0 = util_now();
	struct fitter F;
	fitter_init(&F, f, o);
	memset(sum, 0, sizeof *sum);
	fitter_scan(&F, albedo, mask, albedo->h, NULL, sum);
	sum->unique = F.cl.n;
	fitter_solve(&F);
	struct mapset *m = mapset_new(f, albedo->w, albedo->h, NULL);
	size_t n = (size_t)albedo->w * albedo->h;
	m->de2000 = xcalloc(n, sizeof(float));
	m->status = xmalloc(n);
	float *v[FAMILY_MAX_AXES];
	for (int a = 0; a < m->n; a++)
		v[a] = m->p[a].v;
	CHECK(fitter_apply(&F, NULL, albedo, mask, (long)n, v, m->de2000, m->status, sum) == 0);
	sum->matched = sum->fitted - sum->unmatched;
	hist_stats(&F.dh, sum);
	fitter_free(&F);
	sum->seconds = util_now() - t0;
	*out = m;
	return 0;
}

/* Open the albedo (and mask) streams; -1 and *cause. */
static int open_inputs(const char *albedo, const char *mask, struct image_stream **sa, struct image_stream **sm,
    struct image **ba, struct image **bm, int band, int *w, int *h, char **cause)
{
	int nch, bits, mw, mh, mch, mbits;
	*sa = image_stream_open(albedo, w, h, &nch, &bits, cause);
	if (*sa == NULL)
		return -1;
	*ba = image_new(*w, band, nch, bits);
	if (mask) {
		*sm = image_stream_open(mask, &mw, &mh, &mch, &mbits, cause);
		if (*sm == NULL)
			return -1;
		if (mw != *w || mh != *h) {
			*cause = xasprintf("the mask is %d x %d texels, the albedo %d x %d", mw, mh, *w, *h);
			return -1;
		}
		*bm = image_new(*w, band, mch, mbits);
	}
	return 0;
}

static void close_inputs(struct image_stream **sa, struct image_stream **sm, struct image **ba, struct image **bm)
{
	image_stream_close(*sa);
	image_stream_close(*sm);
	image_free(*ba);
	image_free(*bm);
	*sa = *sm = NULL;
	*ba = *bm = NULL;
}

int maps_fit_files(struct family *f, const char *albedo, const char *mask, const struct maps_fit_opts *o,
    const char *out, int exr, const char *command, struct maps_fit_summary *sum, int *input_error, char **cause)
{
	enum { BAND = 64 };
	double t0 = util_now();
	struct image_stream *sa = NULL, *sm = NULL;
	struct image *ba = NULL, *bm = NULL;
	struct mapset_writer *wr = NULL;
	struct mapset *m = NULL;
	float *v[FAMILY_MAX_AXES] = { NULL }, *de = NULL;
	unsigned char *st = NULL;
	int32_t *ids = NULL;	/* pass 1's colour per texel, or NULL: read again */
	int w, h, rc = -1;
	struct fitter F;
	fitter_init(&F, f, o);
	memset(sum, 0, sizeof *sum);
	*input_error = 1;
	/* Pass 1: the distinct colours, and each texel's when they fit in
	 * MAPS_FIT_IDS_MAX (pass 2 then needs no second reading). */
	if (open_inputs(albedo, mask, &sa, &sm, &ba, &bm, BAND, &w, &h, cause) != 0)
		goto out;
	if (!o->reread && (double)w * h * sizeof(int32_t) <= MAPS_FIT_IDS_MAX)
		ids = xmalloc(sizeof(int32_t) * (size_t)w * (size_t)h);
	for (int y = 0; y < h; y += BAND) {
		int nr = h - y < BAND ? h - y : BAND;
		if (image_stream_rows(sa, ba, nr, cause) != 0 || (sm && image_stream_rows(sm, bm, nr, cause) != 0))
			goto out;
		fitter_scan(&F, ba, bm, nr, ids ? ids + (size_t)y * (size_t)w : NULL, sum);
	}
	close_inputs(&sa, &sm, &ba, &bm);
	sum->unique = F.cl.n;
	fitter_solve(&F);
	/* Pass 2: the maps, band by band, straight to the files. */
	m = mapset_new(f, 1, 1, NULL);
	m->w = w;
	m->h = h;
	m->exr = exr;
	size_t nb = (size_t)w * BAND;
	for (int a = 0; a < m->n; a++) {
		v[a] = xmalloc(sizeof(float) * nb);
		for (size_t i = 0; i < nb; i++)
			v[a][i] = m->p[a].v[0];	/* the not fitted texels' value */
	}
	de = xcalloc(nb, sizeof(float));
	st = xmalloc(nb);
	if (ids == NULL && open_inputs(albedo, mask, &sa, &sm, &ba, &bm, BAND, &w, &h, cause) != 0)
		goto out;
	if (w != m->w || h != m->h) {
		*cause = xasprintf("%s: changed while it was read", albedo);
		goto out;
	}
	*input_error = 0;
	if ((wr = mapset_writer_begin(out, m, 1, F.threads, cause)) == NULL)
		goto out;
	for (int y = 0; y < h; y += BAND) {
		int nr = h - y < BAND ? h - y : BAND;
		*input_error = 1;
		if (ids == NULL && (image_stream_rows(sa, ba, nr, cause) != 0 ||
		    (sm && image_stream_rows(sm, bm, nr, cause) != 0)))
			goto out;
		if (fitter_apply(&F, ids ? ids + (size_t)y * (size_t)w : NULL, ba, bm, (long)w * nr, v, de, st, sum) != 0) {
			*cause = xasprintf("%s: changed while it was read (a colour the first reading did not have)", albedo);
			goto out;
		}
		*input_error = 0;
		for (size_t i = 0; i < (size_t)w * nr; i++)
			if (st[i] == MAPS_NOT_FITTED) {
				for (int a = 0; a < m->n; a++)
					v[a][i] = m->p[a].v[0];
				de[i] = 0.0f;
			}
		int fail = mapset_writer_rows(wr, nr, (const float *const *)v, de, st, cause) != 0;
		if (fail) {
			wr = NULL;	/* freed by its failure */
			goto out;
		}
	}
	sum->matched = sum->fitted - sum->unmatched;
	hist_stats(&F.dh, sum);
	sum->seconds = util_now() - t0;
	m->fit = maps_fit_summary_json(sum, o, albedo);
	mapset_add_history(m, command);
	rc = mapset_writer_end(wr, m, cause);
	wr = NULL;
out:
	mapset_writer_abort(wr);
	close_inputs(&sa, &sm, &ba, &bm);
	for (int a = 0; a < FAMILY_MAX_AXES; a++)
		free(v[a]);
	free(de);
	free(st);
	free(ids);
	mapset_free(m);
	fitter_free(&F);
	return rc;
}

char *maps_fit_summary_json(const struct maps_fit_summary *s, const struct maps_fit_opts *o, const char *albedo)
{
	json_object *j = json_object_new_object();
	json_object_object_add(j, "albedo", json_object_new_string(albedo));
	json_object_object_add(j, "input", json_object_new_string(o->input_linear ? "linear sRGB" : "sRGB-encoded"));
	json_object_object_add(j, "max_de2000", json_num(o->max_de));
	json_object_object_add(j, "texels", json_object_new_int64(s->texels));
	json_object_object_add(j, "fitted", json_object_new_int64(s->fitted));
	json_object_object_add(j, "matched", json_object_new_int64(s->matched));
	json_object_object_add(j, "unmatched", json_object_new_int64(s->unmatched));
	json_object_object_add(j, "not_fitted", json_object_new_int64(s->texels - s->fitted));
	json_object_object_add(j, "distinct_colours", json_object_new_int64(s->unique));
	json_object_object_add(j, "de2000_median", json_num(s->de_median));
	json_object_object_add(j, "de2000_p95", json_num(s->de_p95));
	json_object_object_add(j, "de2000_max", json_num(s->de_max));
	json_object_object_add(j, "seconds", json_num(s->seconds));
	char *text = json_text(j, JSON_PLAIN);
	json_object_put(j);
	return text;
}
