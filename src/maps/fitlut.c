/* fitlut: the per-colour solver of maps fit (method in fit.h): the dense
 * CIELAB table of a family, its bucket grid, the nearest node and the
 * Levenberg-Marquardt refinement on the table's multilinear interpolant. */
#include "config.h"
#include "maps/fitlut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "skin/colour.h"

/* The pull toward the axis middle, CIELAB units per unit of normalised coordinate. */
#define REG 0.01

/* Parameter values at grid coordinates g (continuous, in grid units). */
void fit_lut_params(const struct fit_lut *t, const double *g, double *x)
{
	for (int a = 0; a < t->k; a++) {
		double c = t->c0[a] + (t->c1[a] - t->c0[a]) * g[a] / (t->g[a] - 1);
		x[a] = family_axis_value(&t->f->axis[a], c);
		/* keep the ends exact (exp(log(v)) may differ in the last bit) */
		const struct family_axis *ax = &t->f->axis[a];
		x[a] = fmin(fmax(x[a], ax->node[0]), ax->node[ax->n - 1]);
	}
}

void fit_lut_lab(const struct family *f, const double *x, double lab[3])
{
	double rgb[3];
	family_albedo(f, x, NULL, rgb, NULL);
	colour_linear_srgb_to_lab(rgb, lab);
}

void fit_lut_build(struct fit_lut *t, const struct family *f, int threads)
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
		double g[FAMILY_MAX_AXES] = { i % t->g[0], (i / t->g[0]) % t->g[1],
		    i / (t->g[0] * t->g[1]) }, x[3];
		fit_lut_params(t, g, x);
		fit_lut_lab(f, x, t->lab + 3 * (size_t)i);
	}
	/* Buckets of 2 CIELAB units over a coarse subset of the grid (the
	 * refinement walks the fine grid from the coarse point found). */
	static const int step[FAMILY_MAX_AXES + 1] = { 1, 16, 4, 4 };
	int *coarse = xmalloc(sizeof(int) * (size_t)t->n);
	t->n_coarse = 0;
	for (int i = 0; i < t->n; i++) {
		int q[FAMILY_MAX_AXES] = { i % t->g[0], (i / t->g[0]) % t->g[1],
		    i / (t->g[0] * t->g[1]) }, in = 1;
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

void fit_lut_free(struct fit_lut *t)
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
static int lut_nearest(const struct fit_lut *t, const double lab[3])
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
static void lut_eval2(const struct fit_lut *t, const int *i0, const double *fr, double lab[3],
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
static void lut_eval(const struct fit_lut *t, const double *g, double lab[3],
    double jac[3][FAMILY_MAX_AXES])
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

static double cost(const struct fit_lut *t, const double *g, const double *target, double lab[3],
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
static double refine(const struct fit_lut *t, double *g, const double *target)
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

/* One colour's parameters (grid coordinates g, warm-started from g when
 * warm), by the coarse nearest point and the refinement; a warm start that
 * reaches an exact match (within 0.02 CIELAB) is taken as it is. */
void fit_lut_solve(const struct fit_lut *t, const double target[3], double *g, int warm)
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

