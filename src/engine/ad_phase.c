/* The phase redistribution function (matrix at the nodes: h++ and h+- of
 * the adding-doubling literature) of the Henyey-Greenstein phase function:
 * its Fourier components in azimuth, from its Legendre moments g^l, with
 * delta-M where the series is cut. */
#include "config.h"
#include "engine/ad_phase.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

void ad_hg_init(struct ad_hg *h, double g, int l_max)
{
	memset(h, 0, sizeof *h);
	h->g = g;
	/* Terms until |g|^l < 1e-15 make the series exact in double precision. */
	int L = 2;
	if (fabs(g) > 1e-300)
		L = (int)ceil(log(1e-15) / log(fabs(g))) + 1;
	if (L < 2)
		L = 2;
	h->f = 0.0;
	if (L > l_max) {
		L = l_max & ~1;		/* even: f = g^L = |g|^L > 0 */
		h->f = pow(g, L);
	}
	h->L = L;
	h->cl = xcalloc((size_t)L, sizeof(double));
	double gl = 1.0, sg = g < 0.0 ? -1.0 : 1.0, fl = h->f;
	for (int l = 0; l < L; l++) {
		h->cl[l] = 0.5 * (2 * l + 1) * (gl - fl) / (1.0 - h->f);
		gl *= g;
		fl *= sg;	/* f for a forward peak, f (-1)^l for a backward one */
	}
}

void ad_hg_free(struct ad_hg *h)
{
	free(h->cl);
	memset(h, 0, sizeof *h);
}

/* P[p + np * (l - m)] = L_l^m(x_p) for l = m .. L-1, by the stable
 * three-term recurrence in l (e.g. Press et al., Numerical Recipes, 6.7);
 * ab holds 2 (L - m) doubles for its coefficients. */
static void legendre_table(int m, int L, const double *x, int np, double *P, double *ab)
{
	for (int l = m + 2; l < L; l++) {
		double r = 1.0 / sqrt((double)(l - m) * (l + m));
		ab[2 * (l - m)] = (2.0 * l - 1.0) * r;
		ab[2 * (l - m) + 1] = sqrt((double)(l - 1 - m) * (l - 1 + m)) * r;
	}
	for (int p = 0; p < np; p++) {
		double xx = x[p], sx = sqrt(fmax(0.0, (1.0 - xx) * (1.0 + xx)));
		double pmm = 1.0;
		for (int k = 1; k <= m; k++)
			pmm *= sqrt((2.0 * k - 1.0) / (2.0 * k)) * sx;
		double p0 = pmm, p1 = sqrt(2.0 * m + 1.0) * xx * pmm;
		P[p] = p0;
		if (m + 1 < L)
			P[p + np] = p1;
		for (int l = m + 2; l < L; l++) {
			double pl = ab[2 * (l - m)] * xx * p1 - ab[2 * (l - m) + 1] * p0;
			P[p + (size_t)np * (size_t)(l - m)] = pl;
			p0 = p1;
			p1 = pl;
		}
	}
}

void ad_hg_fourier(const struct ad_hg *h, int m, const double *x, int nr, int np, double *Hpp, double *Hpm,
    double *work)
{
	int nl = h->L - m;
	if (nl <= 0) {
		memset(Hpp, 0, sizeof(double) * (size_t)nr * (size_t)np);
		memset(Hpm, 0, sizeof(double) * (size_t)nr * (size_t)np);
		return;
	}
	double *P = work, *Q = work + (size_t)np * (size_t)nl;
	legendre_table(m, h->L, x, np, P, Q);	/* Q is free until the products */
	/* h_m(x, y) = P D P^T; with y -> -y each term changes by (-1)^(l+m). */
	for (int l = 0; l < nl; l++)
		for (int p = 0; p < np; p++)
			Q[p + (size_t)np * l] = h->cl[m + l] * P[p + (size_t)np * l];
	cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, nr, np, nl, 1.0, P, np, Q, np, 0.0, Hpp, nr);
	for (int l = 1; l < nl; l += 2)
		for (int p = 0; p < np; p++)
			Q[p + (size_t)np * l] = -Q[p + (size_t)np * l];
	cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, nr, np, nl, 1.0, P, np, Q, np, 0.0, Hpm, nr);
}
