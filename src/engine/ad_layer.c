/* One homogeneous layer for one Fourier order: diamond start and doubling
 * (formulas and sources in ad_layer.h).  Internally the layer works in the
 * cosine-symmetric form v_i = flux_i / sqrt(mu_i w_i); its node matrices are
 * the same as in the solver's form (the two differ by a factor n per
 * vector), its beam columns are divided by n on the way out. */
#include "config.h"
#include "engine/ad_layer.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "engine/ad_lapack.h"

/* Transmittance below which a layer counts as opaque: its T is set to 0. */
#define AD_T_NEGLIGIBLE 1e-14
#define AD_MAX_DOUBLINGS 200

size_t ad_layer_work(int n, int ne)
{
	size_t nn = (size_t)n * (size_t)(n + ne);
	return (size_t)n * (size_t)n + 4 * nn + 3 * (size_t)n + (size_t)ne;
}

/* The last n doubles of the workspace: sqrt(mu_i w_i), the flux weights of
 * max_transmittance, set once per layer (the rest is scratch). */
static double *flux_weights(int n, int ne, double *work)
{
	return work + ad_layer_work(n, ne) - (size_t)n;
}

/* The diamond start for optical thickness dt: R, T and the beams' columns
 * (in the symmetric form) and the beams' Pade attenuation d. */
static int diamond(const struct ad_layer_in *in, double dt, double *R, double *T, double *d, double *work)
{
	const int n = in->n, ne = in->ne, nc = n + ne;
	const double h = 0.5 * dt, om = in->omega;
	double *A1 = work, *A2 = A1 + (size_t)n * n, *Y1 = A2 + (size_t)n * n, *Y2 = Y1 + (size_t)n * nc;
	double *q = Y2 + (size_t)n * nc;
	int *piv = (int *)(q + n);	/* n ints fit in n doubles */
	for (int i = 0; i < n; i++)
		q[i] = sqrt(in->w[i] / in->mu[i]);
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++) {
			size_t k = (size_t)i + (size_t)n * j;
			double a = -om * q[i] * in->Hpp[k] * q[j], b = om * q[i] * in->Hpm[k] * q[j];
			if (i == j)
				a += 1.0 / in->mu[i];
			A1[k] = (i == j) + h * (a - b);
			A2[k] = (i == j) + h * (a + b);
			Y1[k] = Y2[k] = i == j;
		}
	for (int e = 0; e < ne; e++) {
		double me = in->mu_e[e];
		double *y1 = Y1 + (size_t)n * (n + e), *y2 = Y2 + (size_t)n * (n + e);
		if (me <= 0.0) {
			d[e] = 0.0;
			memset(y1, 0, sizeof(double) * n);
			memset(y2, 0, sizeof(double) * n);
			continue;
		}
		double x = h * in->ext_e[e] / me;
		d[e] = (1.0 - x) / (1.0 + x);
		/* Trapezoidal source of the beam: values 1 and d at the two faces. */
		double k0 = h * om * (1.0 + d[e]) / me;
		for (int i = 0; i < n; i++) {
			size_t k = (size_t)i + (size_t)n * (n + e);
			double sp = k0 * q[i] * in->Hpp[k], sm = k0 * q[i] * in->Hpm[k];
			y1[i] = sp + sm;
			y2[i] = sp - sm;
		}
	}
	if (ad_dgesv(n, nc, A1, n, piv, Y1, n) != 0 ||
	    ad_dgesv(n, nc, A2, n, piv, Y2, n) != 0)
		return -1;
	/* Y1 = X1 [I | s+ + s-] = [T + R + I | x + y]/..., see ad_layer.h. */
	for (int j = 0; j < nc; j++)
		for (int i = 0; i < n; i++) {
			size_t k = (size_t)i + (size_t)n * j;
			if (j < n) {
				R[k] = Y1[k] - Y2[k];
				T[k] = Y1[k] + Y2[k] - (i == j);
			} else {
				T[k] = 0.5 * (Y1[k] + Y2[k]);
				R[k] = 0.5 * (Y1[k] - Y2[k]);
			}
		}
	return 0;
}

/* out = base + sign * T (I -+ R)^-1 [T | v]: Cholesky of A = I -+ R, an LU
 * factorization if that fails.  Y, A, piv are scratch.  (Unchecked LAPACK
 * calls, engine/ad_lapack.h: a NaN scan of every input was 2 % of a solve.) */
static int half_step(int n, int nc, const double *R, const double *T, double sign, double *Y, double *A,
    int *piv, double *out)
{
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++)
			A[i + (size_t)n * j] = (i == j) - sign * R[i + (size_t)n * j];
	if (ad_dpotrf_lower(n, A, n) == 0) {
		/* T (L L^T)^-1 Y = (L^-1 T)^T (L^-1 Y), T symmetric. */
		cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, n, nc, 1.0, A, n, Y, n);
		cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, n, nc, n, sign, Y, n, Y, n, 1.0, out, n);
		return 0;
	}
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++)
			A[i + (size_t)n * j] = (i == j) - sign * R[i + (size_t)n * j];
	if (ad_dgesv(n, nc, A, n, piv, Y, n) != 0)
		return -1;
	cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, nc, n, sign, T, n, Y, n, 1.0, out, n);
	return 0;
}

/* One doubling of (R, T, d) in place. */
static int double_once(int n, int ne, double *R, double *T, double *d, double *work)
{
	const int nc = n + ne;
	double *A = work, *Y = A + (size_t)n * n, *S = Y + (size_t)n * nc, *D = S + (size_t)n * nc;
	int *piv = (int *)(D + (size_t)n * nc);
	size_t nn = (size_t)n * n;
	/* S' = R + T (I - R)^-1 T; beams: R_e + T_e d + T (I - R)^-1 (T_e + R_e d). */
	memcpy(Y, T, sizeof(double) * nn);
	memcpy(S, R, sizeof(double) * nn);
	for (int e = 0; e < ne; e++)
		for (int i = 0; i < n; i++) {
			size_t k = nn + (size_t)n * e + i;
			Y[k] = T[k] + R[k] * d[e];
			S[k] = R[k] + T[k] * d[e];
		}
	if (half_step(n, nc, R, T, 1.0, Y, A, piv, S))
		return -1;
	/* D' = R - T (I + R)^-1 T; beams: R_e - T_e d + T (I + R)^-1 (R_e d - T_e). */
	memcpy(Y, T, sizeof(double) * nn);
	memcpy(D, R, sizeof(double) * nn);
	for (int e = 0; e < ne; e++)
		for (int i = 0; i < n; i++) {
			size_t k = nn + (size_t)n * e + i;
			Y[k] = T[k] - R[k] * d[e];	/* half_step subtracts T (I + R)^-1 Y */
			D[k] = R[k] - T[k] * d[e];
		}
	if (half_step(n, nc, R, T, -1.0, Y, A, piv, D))
		return -1;
	for (size_t k = 0; k < (size_t)n * nc; k++) {
		R[k] = 0.5 * (S[k] + D[k]);
		T[k] = 0.5 * (S[k] - D[k]);
	}
	for (int e = 0; e < ne; e++)
		d[e] *= d[e];
	return 0;
}

/* Largest transmittance of any node or beam (flux per incident flux); a
 * holds sqrt(mu_i w_i). */
static double max_transmittance(const struct ad_layer_in *in, const double *a, const double *T, const double *d)
{
	const int n = in->n;
	double m = 0.0;
	for (int j = 0; j < n + in->ne; j++) {
		double sum = 0.0;
		const double *tj = T + (size_t)n * j;
		for (int i = 0; i < n; i++)
			sum += a[i] * fabs(tj[i]);
		m = fmax(m, j < n ? sum / a[j] : sum + fabs(d[j - n]));
	}
	return m;
}

int ad_layer_solve(const struct ad_layer_in *in, struct ad_layer_out *out, double *work, char **cause)
{
	const int n = in->n, ne = in->ne;
	double *R = out->R, *T = out->T, *d = out->dT;
	int steps = 0, semi = isinf(in->tau);
	double dt = in->dtau_max;
	if (!semi) {
		double r = in->tau / in->dtau_max;
		steps = r > 1.0 ? (int)ceil(log2(r)) : 0;
		dt = ldexp(in->tau, -steps);
	}
	out->doublings = 0;
	out->t_drop = 0.0;
	double *a = flux_weights(n, ne, work);
	for (int i = 0; i < n; i++)
		a[i] = sqrt(in->mu[i] * in->w[i]);
	if (diamond(in, dt, R, T, d, work)) {
		*cause = xasprintf("adding-doubling: the starting layer's matrix is singular (LAPACK dgesv)");
		return -1;
	}
	for (int k = 0; semi || k < steps; k++) {
		double tmax = max_transmittance(in, a, T, d);
		if (tmax < AD_T_NEGLIGIBLE) {
			/* Opaque: further doublings change R by O(T^2). */
			out->t_drop = tmax;
			memset(T, 0, sizeof(double) * (size_t)n * (size_t)(n + ne));
			memset(d, 0, sizeof(double) * (size_t)ne);
			break;
		}
		if (out->doublings >= AD_MAX_DOUBLINGS) {
			*cause = xasprintf("adding-doubling: a half space did not converge in %d doublings "
			    "(transmittance still %.3g)", AD_MAX_DOUBLINGS, tmax);
			return -1;
		}
		if (double_once(n, ne, R, T, d, work)) {
			*cause = xasprintf("adding-doubling: doubling failed (singular I -+ R, LAPACK)");
			return -1;
		}
		out->doublings++;
	}
	/* Beams' columns: symmetric form -> the solver's form. */
	for (int e = 0; e < ne; e++)
		for (int i = 0; i < n; i++) {
			size_t k = (size_t)n * (n + e) + i;
			R[k] /= in->n_index;
			T[k] /= in->n_index;
		}
	return 0;
}
