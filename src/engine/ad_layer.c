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
/* Doublings from which the eigenvector solution replaces them. */
#ifndef AD_EIGEN_MIN_STEPS
#define AD_EIGEN_MIN_STEPS 1
#endif

/* Doubles and ints of LAPACK workspace for either eigensolver. */
static size_t eig_work(int n)
{
	return ad_dsyevd_work(n) > ad_dsyevr_work(n) ? ad_dsyevd_work(n) : ad_dsyevr_work(n);
}
static size_t eig_iwork(int n)
{
	return ad_dsyevd_iwork(n) > ad_dsyevr_iwork(n) ? ad_dsyevd_iwork(n) : ad_dsyevr_iwork(n);
}

/* Doubles of scratch eigen_layer needs. */
static size_t eigen_work(int n, int ne)
{
	size_t nn = (size_t)n * (size_t)n;
	size_t w = eig_work(n), iw = eig_iwork(n);
	return 8 * nn + 3 * (size_t)n * (size_t)ne + 4 * (size_t)n + w + iw + (size_t)ne;
}

size_t ad_layer_work(int n, int ne)
{
	size_t nn = (size_t)n * (size_t)(n + ne);
	size_t dbl = (size_t)n * (size_t)n + 4 * nn + 3 * (size_t)n + (size_t)ne;
	size_t eig = eigen_work(n, ne);
	return (dbl > eig ? dbl : eig) + (size_t)n;
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

/* Short names for the BLAS calls of eigen_layer (column-major). */
#define TRMM(...) cblas_dtrmm(CblasColMajor, __VA_ARGS__)
#define TRSM(...) cblas_dtrsm(CblasColMajor, __VA_ARGS__)
#define SYRK(...) cblas_dsyrk(CblasColMajor, __VA_ARGS__)
#define SYMM(...) cblas_dsymm(CblasColMajor, __VA_ARGS__)
#define GEMM(...) cblas_dgemm(CblasColMajor, __VA_ARGS__)
#define L_ CblasLeft
#define R_ CblasRight
#define LO CblasLower
#define NT CblasNoTrans
#define TR CblasTrans
#define NU CblasNonUnit

/* eigen_layer's scratch. */
struct eig_ws {
	double *C, *U, *B, *G, *A1, *A2, *X1, *X2;	/* [n x n] */
	double *Zp, *Zm, *Zs;				/* [n x ne] */
	double *lam, *q, *tk, *ck, *ew, *kap;
	int *iw;
};

static void eig_bind(int n, int ne, double *work, struct eig_ws *w)
{
	const size_t nn = (size_t)n * n;
	double **m[] = { &w->C, &w->U, &w->B, &w->G, &w->A1, &w->A2, &w->X1, &w->X2 };
	for (int j = 0; j < 8; j++)
		*m[j] = work + nn * j;
	w->Zp = work + 8 * nn;
	w->Zm = w->Zp + (size_t)n * ne;
	w->Zs = w->Zm + (size_t)n * ne;
	w->lam = w->Zs + (size_t)n * ne;
	w->q = w->lam + n;
	w->tk = w->q + n;
	w->ck = w->tk + n;
	w->ew = w->ck + n;
	w->iw = (int *)(w->ew + eig_work(n));
	w->kap = w->ew + eig_work(n) + eig_iwork(n);
}

/* eigen_layer's beam columns (R and T's node matrices done). */
static int eigen_beams(const struct ad_layer_in *in, double *R, double *T, double *d,
    const struct eig_ws *ws)
{
	const int n = in->n, ne = in->ne, semi = isinf(in->tau);
	const size_t nn = (size_t)n * n;
	const double om = in->omega, tau = in->tau;
	double *C = ws->C, *U = ws->U, *Zp = ws->Zp, *Zm = ws->Zm, *Zs = ws->Zs;
	double *lam = ws->lam, *q = ws->q, *kap = ws->kap;
	/* Beams: sources s+ + s- into Zp, s+ - s- into Zm (per unit tau, the
	 * collimated flux 1 at the top). */
	for (int e = 0; e < ne; e++) {
		double me = in->mu_e[e];
		double *sp = Zp + (size_t)n * e, *sm = Zm + (size_t)n * e;
		if (me <= 0.0) {
			kap[e] = 0.0;
			memset(sp, 0, sizeof(double) * n);
			memset(sm, 0, sizeof(double) * n);
			continue;
		}
		kap[e] = in->ext_e[e] / me;
		for (int k = 0; k < n; k++) {
			double r = fabs(lam[k] - kap[e] * kap[e]);
			if (r < 1e-6 * fmax(lam[k], kap[e] * kap[e]))
				return 1;
		}
		for (int i = 0; i < n; i++) {
			size_t k = (size_t)i + (size_t)n * (n + e);
			double f = om * q[i] / me;
			sp[i] = f * (in->Hpp[k] + in->Hpm[k]);
			sm[i] = f * (in->Hpp[k] - in->Hpm[k]);
		}
	}
	/* p = C^-1 s- (Zm), C^T s+ (Zp); Zs = U^T (C^T s+ + kappa p) / (l^2 - kappa^2). */
	TRSM(L_, LO, NT, NU, n, ne, 1.0, C, n, Zm, n);
	TRMM(L_, LO, TR, NU, n, ne, 1.0, C, n, Zp, n);
	for (int e = 0; e < ne; e++)
		cblas_daxpy(n, kap[e], Zm + (size_t)n * e, 1, Zp + (size_t)n * e, 1);
	GEMM(TR, NT, n, ne, n, 1.0, U, n, Zp, n, 0.0, Zs, n);
	for (int e = 0; e < ne; e++)
		for (int k = 0; k < n; k++) {
			double *z = Zs + k + (size_t)n * e;
			*z = kap[e] > 0.0 ? *z / (lam[k] - kap[e] * kap[e]) : 0.0;
		}
	/* s = U Zs into Zp; t = kappa s + p into Zm; S = C s, D = C^-T t. */
	GEMM(NT, NT, n, ne, n, 1.0, U, n, Zs, n, 0.0, Zp, n);
	for (int e = 0; e < ne; e++)
		cblas_daxpy(n, kap[e], Zp + (size_t)n * e, 1, Zm + (size_t)n * e, 1);
	TRMM(L_, LO, NT, NU, n, ne, 1.0, C, n, Zp, n);
	TRSM(L_, LO, TR, NU, n, ne, 1.0, C, n, Zm, n);
	/* Z+ = (S + D) / 2 into Zp, Z- = (S - D) / 2 into Zm; then d Z- in Zs. */
	for (size_t k = 0; k < (size_t)n * ne; k++) {
		double S = Zp[k], D = Zm[k];
		Zp[k] = 0.5 * (S + D);
		Zm[k] = 0.5 * (S - D);
	}
	for (int e = 0; e < ne; e++) {
		d[e] = semi || kap[e] == 0.0 ? 0.0 : exp(-kap[e] * tau);
		for (int i = 0; i < n; i++)
			Zs[i + (size_t)n * e] = d[e] * Zm[i + (size_t)n * e];
	}
	/* R_e = Z- - R Z+ - T d Z-, T_e = d Z+ - T Z+ - R d Z-. */
	double *Re = R + nn, *Te = T + nn;
	for (int e = 0; e < ne; e++)
		for (int i = 0; i < n; i++) {
			size_t k = i + (size_t)n * e;
			Re[k] = Zm[k];
			Te[k] = d[e] * Zp[k];
		}
	GEMM(NT, NT, n, ne, n, -1.0, R, n, Zp, n, 1.0, Re, n);
	GEMM(NT, NT, n, ne, n, -1.0, R, n, Zs, n, 1.0, Te, n);
	if (!semi) {
		GEMM(NT, NT, n, ne, n, -1.0, T, n, Zs, n, 1.0, Re, n);
		GEMM(NT, NT, n, ne, n, -1.0, T, n, Zp, n, 1.0, Te, n);
	}
	return 0;
}


/* The layer at its full thickness from the eigenvectors of the
 * discrete-ordinate equations (ad_layer.h).  With a and b as in diamond,
 * S = I+ + I- and D = I+ - I- obey S' = -(a + b) D, D' = -(a - b) S.  With
 * a + b = C C^T (Cholesky) and C^T (a - b) C = U diag(l^2) U^T, B = C U
 * turns them into independent modes, cosh and sinh of l tau.  A layer lit
 * equally from both sides has D = 0 at its middle, one lit oppositely S = 0;
 * with h = tau / 2 that gives in closed form
 *   R + T = 2 B (B^T B + diag(l tanh(l h)))^-1 B^T - I,
 *   R - T = 2 B (B^T B + diag(l coth(l h)))^-1 B^T - I,
 *   T = B (B^T B + diag(l tanh))^-1 diag(2 l / sinh(l tau)) (B^T B + diag(l coth))^-1 B^T,
 * the last free of the cancellation R + T - (R - T) has in thick layers;
 * all finite at l = 0 (conservative scattering: l coth(l h) -> 1/h) and for
 * a half space (tanh = coth = 1, T = 0).  A beam (source e^{-kappa tau})
 * has the particular solution S = C s, D = C^-T (kappa s + p) with
 * p = C^-1 s-, (U diag(l^2) U^T - kappa^2) s = C^T s+ + kappa p (s+- the
 * sum and difference of its downward and upward sources); the layer's
 * R and T then take away what that solution sends into it at the faces.
 * Exact in the thickness (no starting layer, the beam's attenuation
 * e^{-kappa tau} exactly); declined (1: the caller doubles) where a
 * factorization fails or a beam's kappa is within 1e-6 of an eigenvalue
 * l (the particular solution's resonance). */
static int eigen_layer(const struct ad_layer_in *in, double *R, double *T, double *d, double *work)
{
	const int n = in->n, ne = in->ne;
	const size_t nn = (size_t)n * n;
	const double om = in->omega, tau = in->tau, h = 0.5 * tau;
	const int semi = isinf(tau);
	struct eig_ws ws;
	eig_bind(n, ne, work, &ws);
	double *C = ws.C, *U = ws.U, *B = ws.B, *G = ws.G, *A1 = ws.A1, *A2 = ws.A2, *X1 = ws.X1;
	double *X2 = ws.X2, *lam = ws.lam, *q = ws.q, *tk = ws.tk, *ck = ws.ck;
	for (int i = 0; i < n; i++)
		q[i] = sqrt(in->w[i] / in->mu[i]);
	/* a + b into C, a - b into U (lower triangles; H is symmetric: the mean
	 * of both triangles). */
	for (int j = 0; j < n; j++)
		for (int i = j; i < n; i++) {
			size_t k = (size_t)i + (size_t)n * j, kt = (size_t)j + (size_t)n * i;
			double hp = 0.5 * (in->Hpp[k] + in->Hpp[kt]);
			double hm = 0.5 * (in->Hpm[k] + in->Hpm[kt]);
			double base = i == j ? 1.0 / in->mu[i] : 0.0, f = om * q[i] * q[j];
			C[k] = base - f * (hp - hm);
			U[k] = base - f * (hp + hm);
			if (i > j) {
				C[kt] = 0.0;
				U[kt] = U[k];
			}
		}
	memcpy(G, U, sizeof(double) * nn);
	if (ad_dpotrf_lower(n, C, n) != 0)
		return 1;
	/* U = C^T (a - b) C, then its eigenvectors. */
	TRMM(R_, LO, NT, NU, n, n, 1.0, C, n, U, n);
	TRMM(L_, LO, TR, NU, n, n, 1.0, C, n, U, n);
#ifdef AD_EIG_DSYEVD
	if (ad_dsyevd(n, U, n, lam, ws.ew, ws.iw) != 0)
		return 1;
#else
	memcpy(X1, U, sizeof(double) * nn);
	if (ad_dsyevr(n, X1, n, lam, U, n, ws.ew, ws.iw) != 0)
		return 1;
#endif
	/* a - b is positive semidefinite (0 only for conservative scattering):
	 * a clearly negative eigenvalue is not rounding. */
	if (lam[0] < -1e-10 * fabs(lam[n - 1]))
		return 1;
	/* B = C U.  The eigenvalues' absolute error is eps times the largest,
	 * 1 / mu_min^2: for the smallest (the slow modes that carry a thick
	 * layer's transmittance, e^{-l tau}) that is 1e-9 relative and more.
	 * Their Rayleigh quotients b^T (a - b) b with b = C u are exact to
	 * first order in the eigenvectors' error and rounded relative to the
	 * mode's own terms: 1e-13 (test_ad test_start_thickness). */
	memcpy(B, U, sizeof(double) * nn);
	TRMM(L_, LO, NT, NU, n, n, 1.0, C, n, B, n);
	SYMM(L_, LO, n, n, 1.0, G, n, B, n, 0.0, X1, n);
	for (int k = 0; k < n; k++)
		lam[k] = cblas_ddot(n, B + (size_t)n * k, 1, X1 + (size_t)n * k, 1);
	for (int k = 0; k < n; k++) {
		double l = sqrt(fmax(lam[k], 0.0)), x = l * h;
		lam[k] = fmax(lam[k], 0.0);
		if (semi)
			tk[k] = ck[k] = l;
		else {
			double th = tanh(x);
			tk[k] = l * th;
			ck[k] = x > 1e-8 ? l / th : 1.0 / h;
		}
	}
	/* G = B^T B; A1 = G + diag(tk), A2 = G + diag(ck). */
	SYRK(LO, TR, n, n, 1.0, B, n, 0.0, G, n);
	memcpy(A1, G, sizeof(double) * nn);
	memcpy(A2, G, sizeof(double) * nn);
	for (int k = 0; k < n; k++) {
		A1[k + (size_t)n * k] += tk[k];
		A2[k + (size_t)n * k] += ck[k];
	}
	if (ad_dpotrf_lower(n, A1, n) != 0 || ad_dpotrf_lower(n, A2, n) != 0)
		return 1;
	/* X = B L^-T: R + T = 2 X1 X1^T - I, R - T = 2 X2 X2^T - I. */
	memcpy(X1, B, sizeof(double) * nn);
	memcpy(X2, B, sizeof(double) * nn);
	TRSM(R_, LO, TR, NU, n, n, 1.0, A1, n, X1, n);
	TRSM(R_, LO, TR, NU, n, n, 1.0, A2, n, X2, n);
	SYRK(LO, NT, n, n, 1.0, X1, n, 0.0, R, n);
	SYRK(LO, NT, n, n, 1.0, X2, n, 1.0, R, n);
	for (int j = 0; j < n; j++) {
		R[j + (size_t)n * j] -= 1.0;
		for (int i = j + 1; i < n; i++)
			R[j + (size_t)n * i] = R[i + (size_t)n * j];
	}
	if (semi)
		memset(T, 0, sizeof(double) * nn);
	else {
		/* F = X L^-1 = B A^-1; T = F1 diag(2 l / sinh(l tau)) F2^T. */
		TRSM(R_, LO, NT, NU, n, n, 1.0, A1, n, X1, n);
		TRSM(R_, LO, NT, NU, n, n, 1.0, A2, n, X2, n);
		for (int k = 0; k < n; k++) {
			double l = sqrt(lam[k]), x = l * tau;
			double dk = x > 1e-8 ? (x < 700.0 ? 2.0 * l / sinh(x) : 0.0) : 2.0 / tau;
			cblas_dscal(n, dk, X1 + (size_t)n * k, 1);
		}
		GEMM(NT, TR, n, n, n, 1.0, X1, n, X2, n, 0.0, T, n);
	}
	return ne > 0 ? eigen_beams(in, R, T, d, &ws) : 0;
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
	out->eigen = 0;
	double *a = flux_weights(n, ne, work);
	for (int i = 0; i < n; i++)
		a[i] = sqrt(in->mu[i] * in->w[i]);
	int try_eigen = !in->doubling_only && (semi || steps >= AD_EIGEN_MIN_STEPS);
	if (try_eigen && eigen_layer(in, R, T, d, work) == 0) {
		out->eigen = 1;
		double tmax = semi ? 0.0 : max_transmittance(in, a, T, d);
		if (!semi && tmax < AD_T_NEGLIGIBLE) {
			/* Opaque, as the doubling would have found it. */
			out->t_drop = tmax;
			memset(T, 0, sizeof(double) * (size_t)n * (size_t)(n + ne));
			memset(d, 0, sizeof(double) * (size_t)ne);
		}
		goto beams;
	}
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
beams:
	/* Beams' columns: symmetric form -> the solver's form. */
	for (int e = 0; e < ne; e++)
		for (int i = 0; i < n; i++) {
			size_t k = (size_t)n * (n + e) + i;
			R[k] /= in->n_index;
			T[k] /= in->n_index;
		}
	return 0;
}
