/* bakeinterp: series through a bake table's point values, and the linear
 * reconstruction of its bin means (method and errors in bakeinterp.h). */
#include "config.h"
#include "bake/bakeinterp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakedir.h"
#include "base/check.h"
#include "base/util.h"

/* The series of the point-value wavelengths. */
struct bake_series {
	int sym;		/* 1: square grid in (theta_i, theta_o), both axes as series */
	int NI, N, P;		/* rows over theta_i (terms when sym, else incidence nodes), terms in theta_o, dphi */
	size_t len;		/* NI * N * P */
	double *c;		/* [n_wl + 3][len] coefficients per wavelength (points only), then R, G, B */
	double *ce;		/* [n_wl][len] those of fr_err */
	double *ca;		/* [n_wl][len] the antisymmetric part in (theta_i, theta_o) (sym) */
	int rgb;		/* 1: every wavelength has point values (R, G, B series in c) */
};

/* Values at n nodes cos-spaced in t (t_j = j pi / (n - 1)) -> coefficients
 * of cos(k t), k < n (the DCT-I): along v[0], v[stride], ... */
static void dct1(double *v, int n, size_t stride, double *tmp)
{
	if (n < 2)
		return;
	for (int k = 0; k < n; k++) {
		double s = 0.0;
		for (int j = 0; j < n; j++)
			s += (j == 0 || j == n - 1 ? 0.5 : 1.0) * v[(size_t)j * stride] * cos(M_PI * k * j / (n - 1));
		tmp[k] = 2.0 * s / (n - 1);
	}
	tmp[0] *= 0.5;
	tmp[n - 1] *= 0.5;
	for (int k = 0; k < n; k++)
		v[(size_t)k * stride] = tmp[k];
}

/* The square grid's row theta_i = 90 deg (row N - 1 of c) by reciprocity,
 * f(90, b) = f(b, 90): the table's grazing-exit column.  That column is 0
 * under a smooth top (no transmittance at grazing), so the row is 0 as the
 * BRDF's limit says; under a rough top it is not (the facets a grazing
 * direction sees are tilted toward it: ad_eval.c exit_weights), and a row
 * of 0 there made the series wiggle by -6..+7 % at exit 60-85 deg along
 * theta_i = 0 (docs/grazing.md, "Rough tops").  The corner f(90, 90), which
 * no node holds, is the quadratic through the column's last three nodes
 * (0.8 deg beyond the last at the default 18 exit nodes). */
static void grazing_row(const struct bake *b, const struct bake_series *s, double *c)
{
	const int N = s->N, P = s->P;
	const double *t = b->theta_o_nodes;
	double *row = c + (size_t)(N - 1) * N * P;
	for (int k = 0; k < N - 1; k++)
		for (int m = 0; m < P; m++)
			row[(size_t)k * P + m] = c[((size_t)k * N + N - 1) * P + m];
	if (N < 4)
		return;
	double x = 0.5 * M_PI, l[3];
	for (int j = 0; j < 3; j++) {
		l[j] = 1.0;
		for (int q = 0; q < 3; q++)
			if (q != j)
				l[j] *= (x - t[N - 4 + q]) / (t[N - 4 + j] - t[N - 4 + q]);
	}
	for (int m = 0; m < P; m++) {
		double v = 0.0;
		for (int j = 0; j < 3; j++)
			v += l[j] * c[((size_t)(N - 4 + j) * N + N - 1) * P + m];
		row[(size_t)(N - 1) * P + m] = v;
	}
}

/* One plane [n_ti][n_to][n_phi] of floats -> coefficients c[len]. */
static void plane_series(const struct bake *b, const struct bake_series *s, const float *plane, double *c)
{
	const int N = s->N, P = s->P;
	memset(c, 0, sizeof(double) * s->len);
	for (int a = 0; a < b->n_ti; a++)
		for (int k = 0; k < N * P; k++)
			c[(size_t)a * N * P + k] = plane[(size_t)a * N * P + k];
	if (s->sym)
		grazing_row(b, s, c);
	double *tmp = xmalloc(sizeof(double) * (size_t)(s->NI > N ? (s->NI > P ? s->NI : P) : (N > P ? N : P)));
	for (int a = 0; a < s->NI; a++)
		for (int k = 0; k < N; k++)
			dct1(c + ((size_t)a * N + k) * P, P, 1, tmp);
	for (int a = 0; a < s->NI; a++)
		for (int m = 0; m < P; m++)
			dct1(c + (size_t)a * N * P + m, N, (size_t)P, tmp);
	if (s->sym)
		for (int k = 0; k < N * P; k++)
			dct1(c + k, s->NI, (size_t)N * P, tmp);
	free(tmp);
}

/* Split c into its symmetric part (in c) and antisymmetric part (in ca). */
static void symmetrise(const struct bake_series *s, double *c, double *ca)
{
	const int N = s->N, P = s->P;
	memset(ca, 0, sizeof(double) * s->len);
	for (int j = 0; j < N; j++)
		for (int k = j + 1; k < N; k++)
			for (int m = 0; m < P; m++) {
				double *x = c + ((size_t)j * N + k) * P + m, *y = c + ((size_t)k * N + j) * P + m;
				double sy = 0.5 * (*x + *y), an = 0.5 * (*x - *y);
				*x = *y = sy;
				ca[((size_t)j * N + k) * P + m] = an;
				ca[((size_t)k * N + j) * P + m] = -an;
			}
}

/* Whether theta_i are the exit nodes below 90 deg (the default of a bake). */
static int square_nodes(const struct bake *b)
{
	if (b->n_ti != b->n_to - 1)
		return 0;
	for (int a = 0; a < b->n_ti; a++)
		if (fabs(b->theta_i[a] - b->theta_o_nodes[a]) > 1e-9)
			return 0;
	return fabs(b->theta_o_nodes[b->n_to - 1] - 0.5 * M_PI) < 1e-9;
}

void bake_interp_build(struct bake *b)
{
	int any = 0, all = 1;
	for (int w = 0; b->points && w < b->n_wl; w++) {
		any |= b->points[w];
		all &= b->points[w];
	}
	if (!any || !b->theta_o_nodes || !b->phi_nodes)
		return;
	/* One allocation (bake_free frees it without knowing its layout). */
	int sym = square_nodes(b), NI = sym ? b->n_to : b->n_ti;
	size_t len = (size_t)NI * b->n_to * b->n_phi, nd = len * (size_t)(3 * b->n_wl + 3);
	struct bake_series *s = xcalloc(1, sizeof *s + sizeof(double) * nd);
	s->sym = sym;
	s->N = b->n_to;
	s->P = b->n_phi;
	s->NI = NI;
	s->len = len;
	s->rgb = all;
	s->c = (double *)(s + 1);
	s->ce = s->c + len * (size_t)(b->n_wl + 3);
	s->ca = s->ce + len * (size_t)b->n_wl;
	size_t npx = (size_t)b->n_ti * b->n_to * b->n_phi;
	for (int w = 0; w < b->n_wl; w++) {
		if (!b->points[w])
			continue;
		plane_series(b, s, b->fr + w * npx, s->c + w * s->len);
		plane_series(b, s, b->fr_err + w * npx, s->ce + w * s->len);
		if (s->sym)
			symmetrise(s, s->c + w * s->len, s->ca + w * s->len);
	}
	for (int c = 0; all && c < 3; c++) {
		double *dst = s->c + (size_t)(b->n_wl + c) * s->len, *junk = xcalloc(s->len, sizeof(double));
		plane_series(b, s, b->fr_rgb + c * npx, dst);
		if (s->sym)
			symmetrise(s, dst, junk);
		free(junk);
	}
	b->interp = s;
}

void bake_interp_free(struct bake *b)
{
	free(b->interp);
	b->interp = NULL;
}

/* u of Chebyshev-Lobatto nodes in theta over [0, pi/2]. */
static double cheb_u(double theta)
{
	double x = 1.0 - 4.0 * theta / M_PI;
	return acos(fmax(-1.0, fmin(1.0, x)));
}

static void basis(double u, int n, double *out)
{
	for (int k = 0; k < n; k++)
		out[k] = cos(k * u);
}

/* sum over rows j (weights bi, NI of them), k, m of c * bi * bo * bp, and
 * the same over the first half of the terms of every axis into *half
 * (rows: only when halve_rows). */
static double series_sum(const double *c, const struct bake_series *s, int nrow, const double *bi, int halve_rows,
    const double *bo, const double *bp, double *half)
{
	const int N = s->N, P = s->P, hn = (N + 1) / 2, hp = (P + 1) / 2, hi = halve_rows ? (nrow + 1) / 2 : nrow;
	double f = 0.0, fh = 0.0;
	for (int j = 0; j < nrow; j++) {
		if (bi[j] == 0.0)
			continue;
		for (int k = 0; k < N; k++) {
			const double *ck = c + ((size_t)j * N + k) * P;
			double v = 0.0, vh = 0.0;
			for (int m = 0; m < P; m++) {
				double x = ck[m] * bp[m];
				v += x;
				if (m < hp)
					vh += x;
			}
			f += bi[j] * bo[k] * v;
			if (j < hi && k < hn)
				fh += bi[j] * bo[k] * vh;
		}
	}
	if (half)
		*half = fh;
	return f;
}

/* Incidence weights over the rows: sym: the Chebyshev basis; else linear
 * between nodes, to 0 at 90 deg past the last, held below the first;
 * *t and the two rows for the linear step's error. */
static void incidence_weights(const struct bake *b, const struct bake_series *s, double ti, double *bi, int *a0,
    int *a1, double *t)
{
	memset(bi, 0, sizeof(double) * (size_t)s->NI);
	*a0 = *a1 = -1;
	*t = 0.0;
	if (s->sym) {
		basis(cheb_u(ti), s->NI, bi);
		return;
	}
	int n = b->n_ti;
	if (ti <= b->theta_i[0]) {
		bi[0] = 1.0;
		return;
	}
	if (ti >= b->theta_i[n - 1]) {
		double end = 0.5 * M_PI - b->theta_i[n - 1];
		*t = end > 0.0 ? fmin(1.0, (ti - b->theta_i[n - 1]) / end) : 0.0;
		bi[n - 1] = 1.0 - *t;
		*a0 = n - 1;
		return;
	}
	int lo = 0;
	while (lo + 1 < n - 1 && b->theta_i[lo + 1] <= ti)
		lo++;
	*t = (ti - b->theta_i[lo]) / (b->theta_i[lo + 1] - b->theta_i[lo]);
	bi[lo] = 1.0 - *t;
	bi[lo + 1] = *t;
	*a0 = lo;
	*a1 = lo + 1;
}

/* Other incidence nodes, past the last one: the value at theta_i = 90 deg
 * that the linear step goes to, f(90, to) = f(to, 90) by reciprocity: the
 * table's grazing-exit column, linear in theta_i at to (held past the last
 * node).  0 under a smooth top; under a rough top the BRDF's finite limit
 * (grazing_row).  Its first-half series into *half. */
static double grazing_end(const struct bake *b, const struct bake_series *s, const double *c,
    double to, const double *bp, double *half)
{
	double *bj = xcalloc((size_t)s->NI + (size_t)s->N, sizeof(double)), *b90 = bj + s->NI;
	int a0, a1;
	double t;
	incidence_weights(b, s, fmin(to, b->theta_i[b->n_ti - 1]), bj, &a0, &a1, &t);
	basis(cheb_u(0.5 * M_PI), s->N, b90);
	double f = series_sum(c, s, s->NI, bj, 0, b90, bp, half);
	free(bj);
	return f;
}

/* Point-value wavelength w (c: its coefficients) at the angles. */
static double points_eval(const struct bake *b, const double *c, const double *ce, const double *ca, double ti,
    double to, double ph, double *err)
{
	const struct bake_series *s = b->interp;
	double *buf = xmalloc(sizeof(double) * (size_t)(s->NI + s->N + s->P + 2 * s->NI));
	double *bi = buf, *bo = bi + s->NI, *bp = bo + s->N, *bone = bp + s->P;
	int a0, a1;
	double t, half, fend = 0.0, fend_half = 0.0;
	incidence_weights(b, s, ti, bi, &a0, &a1, &t);
	basis(cheb_u(to), s->N, bo);
	basis(ph, s->P, bp);
	double f = series_sum(c, s, s->NI, bi, s->sym, bo, bp, &half);
	if (!s->sym && a0 >= 0 && a1 < 0 && t > 0.0) {
		fend = grazing_end(b, s, c, to, bp, &fend_half);
		f += t * fend;
		half += t * fend_half;
	}
	if (err) {
		double e = fabs(series_sum(ce, s, s->NI, bi, s->sym, bo, bp, NULL)) + fabs(f - half);
		if (s->sym)
			e += fabs(series_sum(ca, s, s->NI, bi, 1, bo, bp, NULL));
		else if (a0 >= 0) {
			/* the linear step in theta_i: t (1 - t) |f(a0) - f(a1)| (past the
			 * last node f(a1) = grazing_end) */
			double fa[2] = { 0.0, fend };
			for (int q = 0; q < 2; q++) {
				int a = q ? a1 : a0;
				if (a < 0)
					continue;
				memset(bone, 0, sizeof(double) * (size_t)s->NI);
				bone[a] = 1.0;
				fa[q] = series_sum(c, s, s->NI, bone, 0, bo, bp, NULL);
			}
			e += t * (1.0 - t) * fabs(fa[0] - fa[1]);
		}
		*err = e;
	}
	free(buf);
	return f;
}

/* ---- bin means ---- */

/* Linear weights on an ascending axis: value = (1 - t) v[i0] + t v[i1];
 * i1 = -1 stands for 0 at 90 deg past the last node (the BRDF's limit
 * under a smooth top), held below the first node; hold: held past the last
 * too (a rough top, whose BRDF keeps a finite value at grazing). */
static void axis_weights(const double *ax, int n, double x, int hold, int *i0, int *i1, double *t)
{
	*t = 0.0;
	if (x <= ax[0] || (n == 1 && ax[0] >= 0.5 * M_PI)) {
		*i0 = *i1 = 0;
		return;
	}
	if (x >= ax[n - 1] && hold) {
		*i0 = *i1 = n - 1;
		return;
	}
	if (x >= ax[n - 1]) {
		double end = 0.5 * M_PI - ax[n - 1];
		*i0 = n - 1;
		*i1 = -1;
		*t = end > 0.0 ? fmin(1.0, (x - ax[n - 1]) / end) : 0.0;
		return;
	}
	int lo = 0, hi = n - 1;
	while (hi - lo > 1) {
		int mid = (lo + hi) / 2;
		if (ax[mid] <= x)
			lo = mid;
		else
			hi = mid;
	}
	*i0 = lo;
	*i1 = lo + 1;
	*t = (x - ax[lo]) / (ax[lo + 1] - ax[lo]);
}

/* Linear in dphi between bin centres, held at the ends. */
static void phi_weights(const double *ax, int n, double x, int *i0, int *i1, double *t)
{
	*t = 0.0;
	*i0 = *i1 = x <= ax[0] ? 0 : n - 1;
	if (x <= ax[0] || x >= ax[n - 1])
		return;
	int lo = 0;
	while (lo + 1 < n - 1 && ax[lo + 1] <= x)
		lo++;
	*i0 = lo;
	*i1 = lo + 1;
	*t = (x - ax[lo]) / (ax[lo + 1] - ax[lo]);
}

static double bins_eval(const struct bake *b, const float *plane, double ti, double to, double ph);

/* A rough top's value at theta_i = 90 deg for the linear step past the
 * last incidence node: f(90, to) = f(to, 90) by reciprocity, the last
 * theta_o bin held (incidence held at the last node past it). */
static double bins_grazing_end(const struct bake *b, const float *plane, double to, double ph)
{
	return bins_eval(b, plane, fmin(to, b->theta_i[b->n_ti - 1]), 0.5 * M_PI, ph);
}

static double bins_eval(const struct bake *b, const float *plane, double ti, double to, double ph)
{
	int ia[2], ib[2], ic[2];
	double ta, tb, tc;
	axis_weights(b->theta_i, b->n_ti, ti, 0, &ia[0], &ia[1], &ta);
	axis_weights(b->theta_o, b->n_to, to, b->rough_top, &ib[0], &ib[1], &tb);
	phi_weights(b->phi, b->n_phi, ph, &ic[0], &ic[1], &tc);
	double wa[2] = { 1 - ta, ta }, wb[2] = { 1 - tb, tb }, wc[2] = { 1 - tc, tc }, v = 0.0;
	for (int x = 0; x < 2; x++)
		for (int y = 0; y < 2; y++)
			for (int z = 0; z < 2; z++) {
				if (ia[x] < 0 || ib[y] < 0 || wa[x] * wb[y] * wc[z] == 0.0)
					continue;
				size_t k = ((size_t)ia[x] * b->n_to + (size_t)ib[y]) * b->n_phi + (size_t)ic[z];
				v += wa[x] * wb[y] * wc[z] * (double)plane[k];
			}
	if (b->rough_top && ia[1] < 0 && ta > 0.0)
		v += ta * bins_grazing_end(b, plane, to, ph);
	return v;
}

/* The reconstruction's error estimate below is second order (the
 * curvature from neighbouring values); this factor covers the higher
 * orders (tests/test_grazing: at 1 it covers the actual error at 91 % of a
 * dense grid, at 2 at more than 99 %). */
#define BINS_ERR_SAFETY 2.0

/* The second derivative at node i of values v[k * stride] at ascending ax[n]
 * (divided differences; the end nodes take their neighbour's; 0 below 3
 * nodes).  zero_end: a further node at 90 deg where the value is 0 (the
 * BRDF's limit at grazing). */
static double axis_d2(const float *v, size_t stride, const double *ax, int n, int i, int zero_end)
{
	int m = n + (zero_end != 0);
	if (m < 3)
		return 0.0;
	i = i < 1 ? 1 : i > m - 2 ? m - 2 : i;
	double x[3], y[3];
	for (int k = 0; k < 3; k++) {
		int j = i - 1 + k;
		x[k] = j < n ? ax[j] : 0.5 * M_PI;
		y[k] = j < n ? v[(size_t)j * stride] : 0.0;
	}
	double s0 = (y[1] - y[0]) / (x[1] - x[0]), s1 = (y[2] - y[1]) / (x[2] - x[1]);
	return 2.0 * (s1 - s0) / (x[2] - x[0]);
}

/* The width of bin i of centres ax[n] on [0, end]. */
static double bin_width(const double *ax, int n, int i, double end)
{
	if (n == 1)
		return end;
	if (i == 0)
		return 2.0 * ax[0];
	if (i == n - 1)
		return 2.0 * (end - ax[n - 1]);
	return 0.5 * (ax[i + 1] - ax[i - 1]);
}

/* The error of the linear reconstruction along one axis at x: |f''| times
 * (h^2 / 24, the offset of a bin's mean from its centre value, when means)
 * + (x - a)(b - x) / 2 between nodes a and b (to 90 deg past the last when
 * zero_end) or (x - a)^2 / 2 where the end value is held (f' = 0 there:
 * the delta_phi axis; theta_o below its first centre adds |f'| (a - x),
 * and past the last with slope_end, a rough top's held end, |f'| (x - a),
 * f' from the last two nodes), f'' from axis_d2 at the nodes beside x. */
static double axis_err(const float *v, size_t stride, const double *ax, int n, double end,
    int means, int zero_end, int slope_end, double x)
{
	int i0 = 0;
	while (i0 + 1 < n && ax[i0 + 1] <= x)
		i0++;
	double d2 = fabs(axis_d2(v, stride, ax, n, i0, zero_end)), h = bin_width(ax, n, i0, end);
	double step, held = 0.0;
	if (x < ax[0]) {
		step = 0.5 * (ax[0] - x) * (ax[0] - x);
		if ((zero_end || slope_end) && n > 1)
			held = fabs(v[stride] - v[0]) / (ax[1] - ax[0]) * (ax[0] - x);
	} else if (i0 + 1 < n || zero_end) {
		double b = i0 + 1 < n ? ax[i0 + 1] : 0.5 * M_PI;
		if (i0 + 1 < n)
			d2 = fmax(d2, fabs(axis_d2(v, stride, ax, n, i0 + 1, zero_end)));
		step = 0.5 * (x - ax[i0]) * (b - x);
	} else {
		step = 0.5 * (x - ax[i0]) * (x - ax[i0]);
		if (slope_end && n > 1)
			held = fabs(v[(size_t)(n - 1) * stride] - v[(size_t)(n - 2) * stride])
			    / (ax[n - 1] - ax[n - 2]) * (x - ax[n - 1]);
	}
	return BINS_ERR_SAFETY * (d2 * ((means ? h * h / 24.0 : 0.0) + step) + held);
}

/* The error of bins_eval's reconstruction of the plane's bin means at the
 * angles: at each corner of the cell that bins_eval weighs, axis_err along
 * theta_o (means, to 0 at 90 deg) and along delta_phi (means, held at the
 * ends), weighted as the values; and along theta_i (point values at the
 * nodes, to 0 at 90 deg) on the values interpolated in the other two. */
static double bins_interp_err(const struct bake *b, const float *plane, double ti, double to,
    double ph)
{
	int ia[2], ib[2], ic[2];
	double ta, tb, tc;
	axis_weights(b->theta_i, b->n_ti, ti, 0, &ia[0], &ia[1], &ta);
	axis_weights(b->theta_o, b->n_to, to, b->rough_top, &ib[0], &ib[1], &tb);
	phi_weights(b->phi, b->n_phi, ph, &ic[0], &ic[1], &tc);
	double wa[2] = { 1 - ta, ta }, wb[2] = { 1 - tb, tb }, wc[2] = { 1 - tc, tc }, e = 0.0;
	const int rough = b->rough_top;
	size_t P = (size_t)b->n_phi, row = (size_t)b->n_to * P;
	float *col = xmalloc(sizeof(float) * (size_t)b->n_ti);
	for (int a = 0; a < b->n_ti; a++) {
		const float *r = plane + (size_t)a * row;
		double v = 0.0;
		for (int y = 0; y < 2; y++)
			for (int z = 0; z < 2; z++)
				if (ib[y] >= 0)
					v += wb[y] * wc[z] * r[(size_t)ib[y] * P + (size_t)ic[z]];
		col[a] = (float)v;
		double w = a == ia[0] ? wa[0] : 0.0;
		if (a == ia[1] && ia[1] != ia[0])
			w += wa[1];
		if (w == 0.0)
			continue;
		for (int z = 0; z < 2; z++)
			e += w * wc[z] * axis_err(r + ic[z], P, b->theta_o, b->n_to, 0.5 * M_PI,
			    1, !rough, rough, to);
		for (int y = 0; y < 2; y++)
			if (ib[y] >= 0)
				e += w * wb[y] * axis_err(r + (size_t)ib[y] * P, 1, b->phi,
				    b->n_phi, M_PI, 1, 0, 0, ph);
	}
	if (rough && ia[1] < 0 && ta > 0.0) {
		/* past the last incidence node, linear to bins_grazing_end: the
		 * step's t (1 - t) |f(a) - f_end| and f_end's own error */
		double tl = fmin(to, b->theta_i[b->n_ti - 1]);
		e += BINS_ERR_SAFETY * ta * (1.0 - ta)
		    * fabs(col[b->n_ti - 1] - bins_grazing_end(b, plane, to, ph))
		    + ta * bins_interp_err(b, plane, tl, 0.5 * M_PI, ph);
		/* f_end held in incidence from the last node to `to`: the slope
		 * there taken by reciprocity from the last two theta_o bins of
		 * the last node's row, over that distance */
		if (to > tl && b->n_to > 1) {
			const double *c = b->theta_o;
			int n = b->n_to;
			double d = bins_eval(b, plane, tl, c[n - 1], ph)
			    - bins_eval(b, plane, tl, c[n - 2], ph);
			e += BINS_ERR_SAFETY * ta * fabs(d) / (c[n - 1] - c[n - 2]) * (to - tl);
		}
	} else {
		e += axis_err(col, 1, b->theta_i, b->n_ti, 0.5 * M_PI, 0, !rough, 0, ti);
	}
	free(col);
	return e;
}

double bake_interp_eval(const struct bake *b, int w, double theta_i, double theta_o, double dphi, double *err)
{
	size_t npx = (size_t)b->n_ti * b->n_to * b->n_phi;
	if (b->interp && b->points && b->points[w]) {
		const struct bake_series *s = b->interp;
		return points_eval(b, s->c + w * s->len, s->ce + w * s->len, s->ca + w * s->len, theta_i, theta_o, dphi,
		    err);
	}
	if (err)
		*err = bins_eval(b, b->fr_err + w * npx, theta_i, theta_o, dphi)
		    + bins_interp_err(b, b->fr + w * npx, theta_i, theta_o, dphi);
	return bins_eval(b, b->fr + w * npx, theta_i, theta_o, dphi);
}

int bake_interp_rgb(const struct bake *b, int c, double theta_i, double theta_o, double dphi, double *v)
{
	size_t npx = (size_t)b->n_ti * b->n_to * b->n_phi;
	const struct bake_series *s = b->interp;
	if (!s) {
		*v = bins_eval(b, b->fr_rgb + c * npx, theta_i, theta_o, dphi);
		return 0;
	}
	if (!s->rgb)
		return -1;
	*v = points_eval(b, s->c + (size_t)(b->n_wl + c) * s->len, NULL, NULL, theta_i, theta_o, dphi, NULL);
	return 0;
}
