/* The angular quadrature of the adding-doubling solver: Gauss-Legendre
 * pieces in s = n sin(theta), split at the critical angles (see ad_quad.h). */
#include "config.h"
#include "engine/ad_quad.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "engine/ad_lapack.h"

int ad_gauss_legendre(int n, double a, double b, double *x, double *w)
{
	/* Golub & Welsch (Math. Comp. 23, 1969): the nodes are the eigenvalues
	 * of the symmetric tridiagonal Jacobi matrix of the Legendre recurrence,
	 * the weights 2 v0^2 from the eigenvectors' first components. */
	double *e = xcalloc((size_t)n + 1, sizeof(double));
	double *z = xcalloc((size_t)n * (size_t)n, sizeof(double));
	for (int k = 0; k < n; k++)
		x[k] = 0.0;
	for (int k = 1; k < n; k++)
		e[k - 1] = k / sqrt(4.0 * k * k - 1.0);
	int info = ad_dstev(n, x, e, z, n);
	if (info == 0) {
		double h = 0.5 * (b - a), m = 0.5 * (b + a);
		for (int k = 0; k < n; k++) {
			w[k] = 2.0 * z[(size_t)k * (size_t)n] * z[(size_t)k * (size_t)n] * h;
			x[k] = m + h * x[k];
		}
	}
	free(e);
	free(z);
	return info == 0 ? 0 : -1;
}

/* Angle in a medium of index nm of the direction with s (s <= nm). */
static double theta_of_s(double s, double nm)
{
	return asin(fmin(1.0, s / nm));
}

int ad_quad_build(struct ad_quad *q, const double *sigma, const double *nstar, int n_iv, double density,
    int n_min, char **cause)
{
	memset(q, 0, sizeof *q);
	q->n_iv = n_iv;
	int cnt[AD_MAX_IV];
	for (int k = 0; k < n_iv; k++) {
		q->sigma[k] = sigma[k];
		q->nstar[k] = nstar[k];
		/* The piece's share of a quarter turn, in angle or in cosine,
		 * whichever is larger (pieces near grazing are short in angle). */
		double t0 = theta_of_s(sigma[k], nstar[k]), t1 = theta_of_s(sigma[k + 1], nstar[k]);
		double len = fmax((t1 - t0) / (0.5 * M_PI), cos(t0) - cos(t1));
		int c = (int)ceil(density * len - 1e-9);
		cnt[k] = c < n_min ? n_min : c;
		q->first[k] = q->n;
		q->n += cnt[k];
	}
	q->sigma[n_iv] = sigma[n_iv];
	q->first[n_iv] = q->n;
	q->s = xcalloc((size_t)q->n, sizeof(double));
	q->th = xcalloc((size_t)q->n, sizeof(double));
	q->W = xcalloc((size_t)q->n, sizeof(double));
	q->bary = xcalloc((size_t)q->n, sizeof(double));
	double x[1024], w[1024];
	for (int k = 0; k < n_iv; k++) {
		double ns = nstar[k], tlo = theta_of_s(sigma[k], ns), thi = theta_of_s(sigma[k + 1], ns);
		if (cnt[k] > 1024 || ad_gauss_legendre(cnt[k], tlo, thi, x, w)) {
			*cause = xasprintf("adding-doubling: no Gauss-Legendre rule of %d nodes (LAPACK dstev failed)",
			    cnt[k]);
			ad_quad_free(q);
			return -1;
		}
		for (int j = 0; j < cnt[k]; j++) {
			int i = q->first[k] + j;
			q->th[i] = x[j];
			q->s[i] = ns * sin(x[j]);
			q->W[i] = ns * ns * sin(x[j]) * cos(x[j]) * w[j];	/* s ds */
		}
		/* Barycentric weights 1 / prod (t_j - t_l) on the piece mapped to
		 * [-1, 1]; their common factor cancels in the formula. */
		double mid = 0.5 * (thi + tlo), half = 0.5 * (thi - tlo);
		for (int j = 0; j < cnt[k]; j++) {
			int i = q->first[k] + j;
			double tj = (q->th[i] - mid) / half, p = 1.0;
			for (int l = 0; l < cnt[k]; l++)
				if (l != j)
					p *= tj - (q->th[q->first[k] + l] - mid) / half;
			q->bary[i] = 1.0 / p;
		}
	}
	return 0;
}

void ad_quad_free(struct ad_quad *q)
{
	free(q->s);
	free(q->th);
	free(q->W);
	free(q->bary);
	memset(q, 0, sizeof *q);
}

int ad_quad_count(const struct ad_quad *q, double n_medium)
{
	int c = 0;
	while (c < q->n && q->s[c] < n_medium)
		c++;
	return c;
}

double ad_quad_mu(const struct ad_quad *q, int i, double n_medium)
{
	int k = 0;
	while (i >= q->first[k + 1])
		k++;
	double ns = q->nstar[k], c = cos(q->th[i]), sn = sin(q->th[i]);
	if (n_medium == ns)
		return c;
	return sqrt(c * c + (n_medium - ns) * (n_medium + ns) / (n_medium * n_medium) * sn * sn);
}

int ad_quad_piece(const struct ad_quad *q, double s)
{
	int k = 0;
	while (k < q->n_iv - 1 && s >= q->sigma[k + 1])
		k++;
	return k;
}

void ad_quad_interp(const struct ad_quad *q, int k, double s, double *wt)
{
	int f = q->first[k], nk = q->first[k + 1] - f;
	double ns = q->nstar[k];
	double tlo = theta_of_s(q->sigma[k], ns), thi = theta_of_s(q->sigma[k + 1], ns);
	double mid = 0.5 * (thi + tlo), half = 0.5 * (thi - tlo);
	double t = (theta_of_s(fmin(s, ns), ns) - mid) / half, sum = 0.0;
	for (int j = 0; j < nk; j++) {
		double d = t - (q->th[f + j] - mid) / half;
		if (d == 0.0) {
			for (int l = 0; l < nk; l++)
				wt[l] = l == j;
			return;
		}
		wt[j] = q->bary[f + j] / d;
		sum += wt[j];
	}
	for (int j = 0; j < nk; j++)
		wt[j] /= sum;
}
