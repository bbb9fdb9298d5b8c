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
	double lo[3], cell;		/* bucket grid origin and cell size (CIELAB units) */
	int dim[3];
	int *start, *item;		/* CSR: bucket b holds item[start[b] .. start[b + 1]) */
};

static double axis_coord(const struct family_axis *a, double v)
{
	return a->log_coord ? log(v) : v;
}

/* Parameter values at grid coordinates g (continuous, in grid units). */
static void grid_params(const struct lut *t, const double *g, double *x)
{
	for (int a = 0; a < t->k; a++) {
		double c = t->c0[a] + (t->c1[a] - t->c0[a]) * g[a] / (t->g[a] - 1);
		x[a] = t->f->axis[a].log_coord ? exp(c) : c;
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
			t->c0[a] = axis_coord(ax, ax->node[0]);
			t->c1[a] = axis_coord(ax, ax->node[ax->n - 1]);
		}
		t->n *= t->g[a];
	}
	t->lab = xmalloc(sizeof(double) * 3 * (size_t)t->n);
#pragma omp parallel for schedule(static) num_threads(threads)
	for (int i = 0; i < t->n; i++) {
		double g[FAMILY_MAX_AXES] = { i % t->g[0], (i / t->g[0]) % t->g[1], i / (t->g[0] * t->g[1]) }, x[3];
		grid_params(t, g, x);
		params_lab(f, x, t->lab + 3 * (size_t)i);
	}
	/* Buckets of 1 CIELAB unit (coarser if there would be more than 4M). */
	double hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (int c = 0; c < 3; c++)
		t->lo[c] = INFINITY;
	for (int i = 0; i < t->n; i++)
		for (int c = 0; c < 3; c++) {
			t->lo[c] = fmin(t->lo[c], t->lab[3 * i + c]);
			hi[c] = fmax(hi[c], t->lab[3 * i + c]);
		}
	t->cell = 1.0;
	double vol = 1.0;
	for (int c = 0; c < 3; c++)
		vol *= (hi[c] - t->lo[c]) / t->cell + 1.0;
	if (vol > 4e6)
		t->cell *= cbrt(vol / 4e6);
	size_t nb = 1;
	for (int c = 0; c < 3; c++) {
		t->dim[c] = (int)floor((hi[c] - t->lo[c]) / t->cell) + 1;
		nb *= (size_t)t->dim[c];
	}
	t->start = xcalloc(nb + 1, sizeof(int));
	t->item = xmalloc(sizeof(int) * (size_t)t->n);
	int *bi = xmalloc(sizeof(int) * (size_t)t->n);
	for (int i = 0; i < t->n; i++) {
		int b[3];
		for (int c = 0; c < 3; c++) {
			b[c] = (int)floor((t->lab[3 * i + c] - t->lo[c]) / t->cell);
			b[c] = b[c] < 0 ? 0 : b[c] >= t->dim[c] ? t->dim[c] - 1 : b[c];
		}
		bi[i] = (b[2] * t->dim[1] + b[1]) * t->dim[0] + b[0];
		t->start[bi[i] + 1]++;
	}
	for (size_t b = 0; b < nb; b++)
		t->start[b + 1] += t->start[b];
	int *fill = xmalloc(sizeof(int) * nb);
	memcpy(fill, t->start, sizeof(int) * nb);
	for (int i = 0; i < t->n; i++)
		t->item[fill[bi[i]]++] = i;
	free(fill);
	free(bi);
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

/* The grid point nearest to lab in CIELAB: buckets shell by shell around
 * lab's bucket until no closer point can remain; all points past 40 shells. */
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
			for (int i = 0; i < t->n; i++) {
				double d = d2(t->lab + 3 * (size_t)i, lab);
				if (d < bd)
					bd = d, best = i;
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
						if (d < bd || (d == bd && t->item[j] < best))
							bd = d, best = t->item[j];
					}
				}
		/* A point in shell s + 1 or beyond is at least s cells away. */
		if (best >= 0 && bd <= (s * t->cell) * (s * t->cell))
			return best;
	}
	return best;
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
			m[c][j] = m[p][j], m[p][j] = x;
		}
		double x = b[c];
		b[c] = b[p], b[p] = x;
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

/* Damped Gauss-Newton (Levenberg-Marquardt) from g, inside the grid. */
static void refine(const struct lut *t, double *g, const double *target)
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
}

void maps_texel_linear(const struct image *im, size_t i, int input_linear, double rgb[3])
{
	for (int c = 0; c < 3; c++) {
		double v = image_get(im, i, c);
		rgb[c] = input_linear ? v : srgb_decode(v);
	}
}

/* Distinct colours: texels sorted by the bits of their three values. */
struct key {
	uint32_t v[3];
	int texel;
};

static int key_cmp(const void *a, const void *b)
{
	const struct key *x = a, *y = b;
	for (int c = 0; c < 3; c++)
		if (x->v[c] != y->v[c])
			return x->v[c] < y->v[c] ? -1 : 1;
	return x->texel < y->texel ? -1 : x->texel > y->texel;
}

static void texel_key(const struct image *im, size_t i, struct key *k)
{
	for (int c = 0; c < 3; c++) {
		float v = image_get(im, i, c);
		memcpy(&k->v[c], &v, sizeof v);
	}
	k->texel = (int)i;
}

/* Median, 95th percentile and maximum of the errors over fitted texels. */
static void error_stats(const struct mapset *m, struct maps_fit_summary *s)
{
	enum { NB = 100000 };	/* 0.001 bins up to 100 */
	long *h = xcalloc(NB + 1, sizeof(long));
	size_t n = (size_t)m->w * m->h;
	s->de_max = 0.0;
	for (size_t i = 0; i < n; i++) {
		if (m->status[i] == MAPS_NOT_FITTED)
			continue;
		double d = m->de2000[i];
		s->de_max = fmax(s->de_max, d);
		long b = lround(d * 1000.0);
		h[b > NB ? NB : b]++;
	}
	long cum = 0;
	s->de_median = s->de_p95 = -1.0;
	for (long b = 0; b <= NB && s->fitted > 0; b++) {
		cum += h[b];
		if (s->de_median < 0 && 2 * cum >= s->fitted)
			s->de_median = b / 1000.0;
		if (s->de_p95 < 0 && 100 * cum >= 95 * s->fitted)
			s->de_p95 = b / 1000.0;
	}
	if (s->fitted == 0)
		s->de_median = s->de_p95 = 0.0;
	free(h);
}

int maps_fit(struct family *f, const struct image *albedo, const struct image *mask, const struct maps_fit_opts *o,
    struct mapset **out, struct maps_fit_summary *sum, char **cause)
{
	if (mask && (mask->w != albedo->w || mask->h != albedo->h)) {
		*cause = xasprintf("the mask is %d x %d texels, the albedo %d x %d", mask->w, mask->h, albedo->w, albedo->h);
		return -1;
	}
	double t0 = util_now();
	int threads = n_threads(o->threads);
	family_albedo_prepare(f);
	struct lut t;
	lut_build(&t, f, threads);
	struct mapset *m = mapset_new(f, albedo->w, albedo->h, NULL);
	size_t n = (size_t)albedo->w * albedo->h;
	m->de2000 = xcalloc(n, sizeof(float));
	m->status = xmalloc(n);
	memset(sum, 0, sizeof *sum);
	sum->texels = (long)n;
	struct key *keys = xmalloc(sizeof *keys * (n > 0 ? n : 1));
	for (size_t i = 0; i < n; i++) {
		int in = image_get(albedo, i, 3) >= 0.5f && (mask == NULL || image_get(mask, i, 0) >= 0.5f);
		m->status[i] = in ? MAPS_MATCHED : MAPS_NOT_FITTED;
		if (in)
			texel_key(albedo, i, &keys[sum->fitted++]);
	}
	qsort(keys, (size_t)sum->fitted, sizeof *keys, key_cmp);
	/* The first texel of each run of equal colours. */
	long *first = xmalloc(sizeof(long) * (size_t)(sum->fitted + 1));
	for (long i = 0; i < sum->fitted; i++)
		if (i == 0 || memcmp(keys[i].v, keys[i - 1].v, sizeof keys[i].v) != 0)
			first[sum->unique++] = i;
	first[sum->unique] = sum->fitted;
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads)
	for (long u = 0; u < sum->unique; u++) {
		double rgb[3], target[3], g[FAMILY_MAX_AXES], x[FAMILY_MAX_AXES], lab[3];
		maps_texel_linear(albedo, (size_t)keys[first[u]].texel, o->input_linear, rgb);
		colour_linear_srgb_to_lab(rgb, target);
		int nb = lut_nearest(&t, target);
		for (int a = 0; a < t.k; a++)
			g[a] = (nb / (a == 0 ? 1 : a == 1 ? t.g[0] : t.g[0] * t.g[1])) % t.g[a];
		refine(&t, g, target);
		grid_params(&t, g, x);
		params_lab(f, x, lab);
		double de = colour_de2000(target, lab);
		for (long j = first[u]; j < first[u + 1]; j++) {
			size_t i = (size_t)keys[j].texel;
			for (int a = 0; a < t.k; a++)
				m->p[a].v[i] = (float)x[a];
			m->de2000[i] = (float)de;
			m->status[i] = de <= o->max_de ? MAPS_MATCHED : MAPS_UNMATCHED;
		}
	}
	for (size_t i = 0; i < n; i++)
		sum->unmatched += m->status[i] == MAPS_UNMATCHED;
	sum->matched = sum->fitted - sum->unmatched;
	error_stats(m, sum);
	free(first);
	free(keys);
	lut_free(&t);
	sum->seconds = util_now() - t0;
	*out = m;
	return 0;
}

char *maps_fit_summary_json(const struct maps_fit_summary *s, const struct maps_fit_opts *o, const char *albedo)
{
	json_object *j = json_object_new_object();
	json_object_object_add(j, "albedo", json_object_new_string(albedo));
	json_object_object_add(j, "input", json_object_new_string(o->input_linear ? "linear sRGB" : "sRGB-encoded"));
	json_object_object_add(j, "max_de2000", json_object_new_double(o->max_de));
	json_object_object_add(j, "texels", json_object_new_int64(s->texels));
	json_object_object_add(j, "fitted", json_object_new_int64(s->fitted));
	json_object_object_add(j, "matched", json_object_new_int64(s->matched));
	json_object_object_add(j, "unmatched", json_object_new_int64(s->unmatched));
	json_object_object_add(j, "not_fitted", json_object_new_int64(s->texels - s->fitted));
	json_object_object_add(j, "distinct_colours", json_object_new_int64(s->unique));
	json_object_object_add(j, "de2000_median", json_object_new_double(s->de_median));
	json_object_object_add(j, "de2000_p95", json_object_new_double(s->de_p95));
	json_object_object_add(j, "de2000_max", json_object_new_double(s->de_max));
	json_object_object_add(j, "seconds", json_object_new_double(s->seconds));
	char *text = xstrdup(json_object_to_json_string_ext(j, JSON_C_TO_STRING_PLAIN | JSON_C_TO_STRING_NOSLASHESCAPE));
	json_object_put(j);
	return text;
}
