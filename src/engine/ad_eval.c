/* The diffuse BRDF from the solver's Fourier series: at a point and as the
 * bake table's bin means (interpolation and integration in ad_eval.h). */
#include "config.h"
#include "engine/ad_eval.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine/ad_stack.h"
#include "base/util.h"

/* Top boundary transmittance at exit s. */
static double top_t(const struct ad_series *sr, double s)
{
	double r, t;
	if (sr->md.brough[0])
		return 1.0;
	ad_bnd_rt(sr->md.fresnel, sr->md.bn[0], sr->md.bcnt[0], s, &r, &t);
	return t;
}

/* Weights on piece k's nodes for the value at its grazing end (theta* =
 * pi/2) under a rough top: the least-squares line in theta* through the
 * last AD_EVAL_GRAZING_NODES nodes, not the piece's interpolating
 * polynomial.  The last nodes' values are uneven by about 1 % (fair-oily
 * at alpha 0.3, theta_i 0, 550 nm, 64 nodes: the last three read 4.375,
 * 4.320, 4.360e-2 /sr; not the facet rule's share past the last node,
 * which moves them by 1e-5; cause not found); the polynomial's weights at
 * the end alternate with sizes up to 1.6 and amplify that (5.48, 4.41,
 * 4.32, 4.30e-2 at 32, 64, 128, 256 nodes), the line's are small (4.81,
 * 4.33, 4.31, 4.30e-2).  Its own error, the curvature over the
 * last nodes' span, falls as the square of the spacing. */
static void grazing_line(const struct ad_quad *q, int k, double *wt)
{
	int f = q->first[k], nk = q->first[k + 1] - f;
	int K = nk < AD_EVAL_GRAZING_NODES ? nk : AD_EVAL_GRAZING_NODES, j0 = nk - K;
	double end = asin(fmin(1.0, q->sigma[k + 1] / q->nstar[k]));
	double xm = 0.0, sxx = 0.0;
	memset(wt, 0, sizeof(double) * (size_t)nk);
	for (int j = j0; j < nk; j++)
		xm += (q->th[f + j] - end) / K;
	for (int j = j0; j < nk; j++)
		sxx += pow(q->th[f + j] - end - xm, 2);
	for (int j = j0; j < nk; j++)
		wt[j] = 1.0 / K - (sxx > 0.0 ? xm * (q->th[f + j] - end - xm) / sxx : 0.0);
}

/* Between piece k's last node and its grazing end (Gauss variable t):
 * linear from the last node's value to grazing_line's end value, so the
 * values join the interpolant at the last node. */
static void grazing_end(const struct ad_quad *q, int k, double t, double *wt)
{
	int f = q->first[k], nk = q->first[k + 1] - f;
	double end = asin(fmin(1.0, q->sigma[k + 1] / q->nstar[k])), tl = q->th[f + nk - 1];
	double u = end > tl ? fmin(1.0, (t - tl) / (end - tl)) : 1.0;
	grazing_line(q, k, wt);
	for (int j = 0; j < nk; j++)
		wt[j] *= u;
	wt[nk - 1] += 1.0 - u;
}

/* Interpolation weights over all exit nodes (zero outside s's piece) for
 * exit s, times the top transmittance; 0 if no light leaves there.  Grazing
 * exit (s = n_above) is 0 under a smooth top (its transmittance), but not
 * under a rough one: the facets the exit direction sees are tilted toward
 * it, so the BRDF keeps a finite limit there (e.g. 0.040 /sr at theta_i 0 on
 * docs/grazing.md's medium), the end value of the exit piece's interpolant
 * (n_above is a piece edge, ad.c model_pieces). */
static int exit_weights(const struct ad_series *sr, double s, double *wt)
{
	const struct ad_level *lv = &sr->lv;
	const int rough = sr->md.brough[0];
	memset(wt, 0, sizeof(double) * (size_t)lv->na);
	if (rough && s >= sr->md.n_above)
		s = sr->md.n_above;
	if (lv->na == 0 || s >= lv->q.sigma[lv->q.n_iv] || (!rough && s >= sr->md.n_above))
		return 0;
	int k = ad_quad_piece(&lv->q, s);
	if (rough && s == sr->md.n_above && k > 0 && s <= lv->q.sigma[k])
		k--;	/* grazing: the end of the piece below the edge n_above */
	if (lv->q.first[k] >= lv->na)
		return 0;
	double t = top_t(sr, s);
	if (t <= 0.0)
		return 0;
	int f = lv->q.first[k], nk = lv->q.first[k + 1] - f;
	double tk = asin(fmin(1.0, s / lv->q.nstar[k]));
	if (rough && sr->md.n_above == lv->q.sigma[k + 1] && tk > lv->q.th[f + nk - 1])
		grazing_end(&lv->q, k, tk, wt + f);
	else
		ad_quad_interp(&lv->q, k, s, wt + f);
	/* G = F / t at the nodes, so a weight on F_i is wt_i t(s) / t_i. */
	for (int j = 0; j < nk; j++)
		wt[f + j] = lv->t_air[f + j] > 0.0 ? wt[f + j] * t / lv->t_air[f + j] : 0.0;
	return 1;
}

double ad_series_point(const struct ad_series *sr, int e, double theta_o, double dphi, int m_max)
{
	const struct ad_level *lv = &sr->lv;
	int M = m_max > 0 && m_max < lv->M ? m_max : lv->M, na = lv->na;
	double *wt = xcalloc((size_t)na + 1, sizeof(double));
	double f = 0.0;
	if (exit_weights(sr, sr->md.n_above * sin(theta_o), wt))
		for (int m = 0; m < M; m++) {
			const double *Fm = lv->F + ((size_t)m * lv->E + e) * na;
			double v = 0.0;
			for (int i = 0; i < na; i++)
				v += wt[i] * Fm[i];
			f += (m & 1 ? -1.0 : 1.0) * cos(m * dphi) * v;
		}
	free(wt);
	return f;
}

int ad_series_fourier(const struct ad_series *sr, int e, double theta_o, double *coef, int max)
{
	const struct ad_level *lv = &sr->lv;
	int M = max < lv->M ? max : lv->M, na = lv->na;
	double *wt = xcalloc((size_t)na + 1, sizeof(double));
	int on = exit_weights(sr, sr->md.n_above * sin(theta_o), wt);
	for (int m = 0; m < M; m++) {
		const double *Fm = lv->F + ((size_t)m * lv->E + e) * na;
		double v = 0.0;
		for (int i = 0; on && i < na; i++)
			v += wt[i] * Fm[i];
		coef[m] = m & 1 ? -v : v;
	}
	free(wt);
	return M;
}

/* B[it * na + i]: the theta_o bin mean of F_m is sum_i B F_m(i). */
static void theta_means(const struct ad_series *sr, int n_to, double *B)
{
	const struct ad_level *lv = &sr->lv;
	const int na = lv->na;
	const double dth = 0.5 * M_PI / n_to, n0 = sr->md.n_above;
	double *wt = xcalloc((size_t)na + 1, sizeof(double));
	memset(B, 0, sizeof(double) * (size_t)n_to * na);
	for (int it = 0; it < n_to; it++) {
		double t0 = it * dth, t1 = (it + 1) * dth;
		/* Split at the exit angles of the pieces' edges (critical angles). */
		double cut[AD_MAX_IV + 2];
		int nc = 0;
		cut[nc++] = t0;
		for (int k = 1; k <= lv->q.n_iv; k++) {
			double sk = lv->q.sigma[k];
			if (sk < n0) {
				double tk = asin(sk / n0);
				if (tk > t0 && tk < t1)
					cut[nc++] = tk;
			}
		}
		cut[nc++] = t1;
		double s0 = sin(t0), s1 = sin(t1), den = 0.5 * (s1 * s1 - s0 * s0);
		for (int c = 0; c + 1 < nc; c++) {
			double x[AD_EVAL_POINTS], w[AD_EVAL_POINTS];
			ad_gauss_legendre(AD_EVAL_POINTS, cut[c], cut[c + 1], x, w);
			for (int p = 0; p < AD_EVAL_POINTS; p++) {
				if (!exit_weights(sr, n0 * sin(x[p]), wt))
					continue;
				double g = w[p] * cos(x[p]) * sin(x[p]) / den;
				for (int i = 0; i < na; i++)
					B[(size_t)it * na + i] += g * wt[i];
			}
		}
	}
	free(wt);
}

void ad_series_table(const struct ad_series *sr, int n_to, int n_phi, int m_max, double *fr, double *fr_az,
    double *last)
{
	const struct ad_level *lv = &sr->lv;
	const int na = lv->na, E = lv->E, nb = n_to * n_phi;
	int M = m_max > 0 && m_max < lv->M ? m_max : lv->M;
	double *B = xcalloc((size_t)n_to * na + 1, sizeof(double));
	double *th = xcalloc((size_t)n_to, sizeof(double));
	theta_means(sr, n_to, B);
	memset(fr, 0, sizeof(double) * (size_t)E * nb);
	if (last)
		memset(last, 0, sizeof(double) * (size_t)E * nb);
	const double dph = M_PI / n_phi;
	for (int m = 0; m < lv->M; m++) {
		double *out = m < M ? fr : last;
		if (!out)
			break;
		for (int e = 0; e < E; e++) {
			const double *Fm = lv->F + ((size_t)m * E + e) * na;
			for (int it = 0; it < n_to; it++) {
				double v = 0.0;
				for (int i = 0; i < na; i++)
					v += B[(size_t)it * na + i] * Fm[i];
				th[it] = v;
				if (m == 0)
					fr_az[(size_t)e * n_to + it] = v;
			}
			for (int ip = 0; ip < n_phi; ip++) {
				double p0 = ip * dph, p1 = (ip + 1) * dph;
				double cm = m == 0 ? 1.0 : (sin(m * p1) - sin(m * p0)) / (m * dph);
				if (m & 1)
					cm = -cm;
				for (int it = 0; it < n_to; it++)
					out[(size_t)e * nb + it * n_phi + ip] += cm * th[it];
			}
		}
	}
	free(B);
	free(th);
}
