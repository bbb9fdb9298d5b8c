/* The stack of turbid layers and Fresnel boundaries for one Fourier order:
 * adding from the bottom up, and the order-0 sweep down for the fluxes
 * (formulas and sources in ad_stack.h). */
#include "config.h"
#include "engine/ad_stack.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "engine/ad_lapack.h"

static double cos_in(double s, double n)
{
	return sqrt(fmax(0.0, (n - s) * (n + s))) / n;
}

void ad_bnd_rt(enum optics_fresnel model, const double *nl, int cnt, double s, double *r, double *t)
{
	int above = s < nl[0], below = s < nl[cnt - 1];
	double ct;
	*t = 0.0;
	if (!above && !below)
		*r = 0.0;
	else if (!above || !below)
		*r = 1.0;
	else {
		*r = optics_stack_reflectance(model, nl, cnt, cos_in(s, nl[0]), &ct);
		*t = 1.0 - *r;
	}
}

void ad_bnd_fill(struct ad_bnd *b, enum optics_fresnel model, const double *nl, int cnt,
    const double *s, int N, const double *se, int E)
{
	for (int i = 0; i < N; i++)
		ad_bnd_rt(model, nl, cnt, s[i], &b->r[i], &b->t[i]);
	for (int e = 0; e < E; e++)
		ad_bnd_rt(model, nl, cnt, se[e], &b->re[e], &b->te[e]);
}

size_t ad_stack_work(int N, int E)
{
	return (size_t)N * (size_t)N + 2 * (size_t)N * (size_t)(N + E) + (size_t)N + 2 * (size_t)E;
}

static void gemm(int m, int n, int k, const double *A, int lda, const double *B, int ldb,
    double beta, double *C, int ldc)
{
	cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, m, n, k, 1.0, A, lda, B, ldb, beta,
	    C, ldc);
}

/* V <- (I - Pm)^-1 V for all N + E columns, Pm the first N columns of P. */
static int solve_i_minus(int N, int E, const double *P, double *V, double *A, int *piv)
{
	for (int j = 0; j < N; j++)
		for (int i = 0; i < N; i++)
			A[i + (size_t)N * j] = (i == j) - P[i + (size_t)N * j];
	return ad_dgesv_checked(N, N + E, A, N, piv, V, N) == 0 ? 0 : -1;
}

/* Un = reflection of layer (Rl, Tl) above the stack Ub. */
static int add_layer(int N, int E, const struct ad_op *Rl, const struct ad_op *Tl,
    const struct ad_op *Ub, struct ad_op *Un, double *w)
{
	const int nc = N + E;
	double *P = w, *V = P + (size_t)N * nc, *A = V + (size_t)N * nc, *vd = A + (size_t)N * N;
	int *piv = (int *)(vd + E);
	gemm(N, nc, N, Ub->a, N, Rl->a, N, 0.0, P, N);	/* P = U R_l (R_l.d = 0) */
	gemm(N, nc, N, Ub->a, N, Tl->a, N, 0.0, V, N);	/* Z = U T_l */
	for (int e = 0; e < E; e++) {
		vd[e] = Ub->d[e] * Tl->d[e];	/* 1 - P.d = 1 */
		double *zc = V + (size_t)N * (N + e);
		const double *uc = Ub->a + (size_t)N * (N + e), *pc = P + (size_t)N * (N + e);
		for (int i = 0; i < N; i++)
			zc[i] += uc[i] * Tl->d[e] + pc[i] * vd[e];
	}
	if (solve_i_minus(N, E, P, V, A, piv))
		return -1;
	memcpy(Un->a, Rl->a, sizeof(double) * (size_t)N * nc);
	gemm(N, nc, N, Tl->a, N, V, N, 1.0, Un->a, N);
	for (int e = 0; e < E; e++) {
		double *uc = Un->a + (size_t)N * (N + e);
		const double *tc = Tl->a + (size_t)N * (N + e);
		for (int i = 0; i < N; i++)
			uc[i] += tc[i] * vd[e];
		Un->d[e] = Tl->d[e] * vd[e];
	}
	return 0;
}

/* Un = reflection of the full element x above the stack Ub (add_bnd with
 * matrices for the diagonals). */
static int add_elem(int N, int E, const struct ad_elem *x, const struct ad_op *Ub, struct ad_op *Un,
    double *w)
{
	const int nc = N + E;
	double *P = w, *V = P + (size_t)N * nc, *A = V + (size_t)N * nc, *vd = A + (size_t)N * N;
	int *piv = (int *)(vd + E);
	gemm(N, N, N, Ub->a, N, x->rb, N, 0.0, P, N);	/* U Rb */
	gemm(N, nc, N, Ub->a, N, x->td, N, 0.0, V, N);	/* U Td */
	for (int e = 0; e < E; e++) {
		double zd = Ub->d[e] * x->td_d[e];
		vd[e] = zd == 0.0 ? 0.0 : zd / (1.0 - Ub->d[e] * x->rb_d[e]);
		double *zc = V + (size_t)N * (N + e), *pc = P + (size_t)N * (N + e);
		const double *uc = Ub->a + (size_t)N * (N + e);
		for (int i = 0; i < N; i++) {
			pc[i] = uc[i] * x->rb_d[e];
			zc[i] += uc[i] * x->td_d[e] + pc[i] * vd[e];
		}
	}
	if (solve_i_minus(N, E, P, V, A, piv))
		return -1;
	memcpy(Un->a, x->rt, sizeof(double) * (size_t)N * nc);
	gemm(N, nc, N, x->tu, N, V, N, 1.0, Un->a, N);
	for (int e = 0; e < E; e++)
		Un->d[e] = x->rt_d[e] + x->tu_d[e] * vd[e];
	return 0;
}

/* Un = reflection of boundary b above the stack Ub. */
static int add_bnd(int N, int E, const struct ad_bnd *b, const struct ad_op *Ub, struct ad_op *Un,
    double *w)
{
	const int nc = N + E;
	double *P = w, *V = P + (size_t)N * nc, *A = V + (size_t)N * nc, *vd = A + (size_t)N * N;
	int *piv = (int *)(vd + E);
	if (b->x)
		return add_elem(N, E, b->x, Ub, Un, w);
	for (int j = 0; j < nc; j++) {
		double rj = j < N ? b->r[j] : b->re[j - N], tj = j < N ? b->t[j] : b->te[j - N];
		const double *u = Ub->a + (size_t)N * j;
		for (int i = 0; i < N; i++) {
			P[i + (size_t)N * j] = u[i] * rj;
			V[i + (size_t)N * j] = u[i] * tj;
		}
	}
	for (int e = 0; e < E; e++) {
		double zd = Ub->d[e] * b->te[e];
		vd[e] = zd == 0.0 ? 0.0 : zd / (1.0 - Ub->d[e] * b->re[e]);
		double *zc = V + (size_t)N * (N + e);
		const double *pc = P + (size_t)N * (N + e);
		for (int i = 0; i < N; i++)
			zc[i] += pc[i] * vd[e];
	}
	if (solve_i_minus(N, E, P, V, A, piv))
		return -1;
	for (int j = 0; j < nc; j++)
		for (int i = 0; i < N; i++)
			Un->a[i + (size_t)N * j] = b->t[i] * V[i + (size_t)N * j]
			    + (i == j ? b->r[i] : 0.0);
	for (int e = 0; e < E; e++)
		Un->d[e] = b->re[e] + b->te[e] * vd[e];
	return 0;
}

int ad_stack_reflect(int N, int E, int K, const struct ad_bnd *bnd, const struct ad_op *R,
    const struct ad_op *T, struct ad_op *U, double *work, char **cause)
{
	const int nc = N + E;
	struct ad_op *u = &U[2 * K];
	memset(u->a, 0, sizeof(double) * (size_t)N * nc);
	for (int i = 0; i < N; i++)
		u->a[i + (size_t)N * i] = bnd[K].r[i];
	memcpy(u->d, bnd[K].re, sizeof(double) * (size_t)E);
	for (int k = K - 1; k >= 0; k--) {
		if (add_layer(N, E, &R[k], &T[k], &U[2 * k + 2], &U[2 * k + 1], work) ||
		    add_bnd(N, E, &bnd[k], &U[2 * k + 1], &U[2 * k], work)) {
			*cause = xasprintf("adding-doubling: adding failed (singular I - U R, "
			    "LAPACK dgesv)");
			return -1;
		}
	}
	return 0;
}

/* Power of a field (node part v [N x E], collimated part d [E]) for beam e. */
static double field_flux(int N, const double *sqW, const double *v, const double *d, int e)
{
	double f = d[e];
	for (int i = 0; i < N; i++)
		f += sqW[i] * v[i + (size_t)N * e];
	return f;
}

/* out = X v: X an operator, v a field (v [N x E], vd [E]); out [N x E], od [E]. */
static void apply(int N, int E, const struct ad_op *X, const double *v, const double *vd,
    double *out, double *od)
{
	gemm(N, E, N, X->a, N, v, N, 0.0, out, N);
	for (int e = 0; e < E; e++) {
		const double *xc = X->a + (size_t)N * (N + e);
		for (int i = 0; i < N; i++)
			out[i + (size_t)N * e] += xc[i] * vd[e];
		od[e] = X->d[e] * vd[e];
	}
}

/* Power absorbed by layer (Rl, Tl) from field (v, vd), per beam, added to
 * a: what enters minus what the layer's own R and T send out. */
static void absorbed(int N, int E, const struct ad_op *Rl, const struct ad_op *Tl,
    const double *sqW, const double *v, const double *vd, double *a)
{
	for (int j = 0; j < N + E; j++) {
		/* Loss per unit input of column j. */
		double c = j < N ? sqW[j] : 1.0 - Tl->d[j - N];
		for (int l = 0; l < N; l++)
			c -= sqW[l] * (Rl->a[l + (size_t)N * j] + Tl->a[l + (size_t)N * j]);
		if (j >= N) {
			a[j - N] += c * vd[j - N];
			continue;
		}
		for (int e = 0; e < E; e++)
			a[e] += c * v[j + (size_t)N * e];
	}
}

/* step_down through a full element x: D' = (I - Rb U_below)^-1 Td D. */
static int step_down_elem(int N, int E, const struct ad_elem *x, const struct ad_op *Ub,
    const double *D, const double *Dd, double *Dn, double *Dnd, double *w)
{
	const int nc = N + E;
	double *Q = w, *A = Q + (size_t)N * nc;
	int *piv = (int *)(A + (size_t)N * N);
	gemm(N, E, N, x->td, N, D, N, 0.0, Dn, N);
	for (int e = 0; e < E; e++) {
		const double *tc = x->td + (size_t)N * (N + e);
		for (int i = 0; i < N; i++)
			Dn[i + (size_t)N * e] += tc[i] * Dd[e];
		Dnd[e] = x->td_d[e] * Dd[e];
	}
	if (!Ub)
		return 0;
	gemm(N, nc, N, x->rb, N, Ub->a, N, 0.0, Q, N);
	for (int e = 0; e < E; e++) {
		double qd = x->rb_d[e] * Ub->d[e];
		Dnd[e] = Dnd[e] == 0.0 ? 0.0 : Dnd[e] / (1.0 - qd);
		for (int i = 0; i < N; i++)
			Dn[i + (size_t)N * e] += Q[i + (size_t)N * (N + e)] * Dnd[e];
	}
	for (int j = 0; j < N; j++)
		for (int i = 0; i < N; i++)
			A[i + (size_t)N * j] = (i == j) - Q[i + (size_t)N * j];
	return ad_dgesv_checked(N, E, A, N, piv, Dn, N) == 0 ? 0 : -1;
}

/* One step down: the field below element j from the field above it,
 * D' = (I - R_j U_below)^-1 T_j D; Ub == NULL when nothing is below. */
static int step_down(int N, int E, const struct ad_bnd *b, const struct ad_op *Rl,
    const struct ad_op *Tl, const struct ad_op *Ub, const double *D, const double *Dd, double *Dn,
    double *Dnd, double *w)
{
	const int nc = N + E;
	double *Q = w, *A = Q + (size_t)N * nc;
	int *piv = (int *)(A + (size_t)N * N);
	if (b && b->x)
		return step_down_elem(N, E, b->x, Ub, D, Dd, Dn, Dnd, w);
	if (b) {
		for (int e = 0; e < E; e++) {
			for (int i = 0; i < N; i++)
				Dn[i + (size_t)N * e] = b->t[i] * D[i + (size_t)N * e];
			Dnd[e] = b->te[e] * Dd[e];
		}
	} else
		apply(N, E, Tl, D, Dd, Dn, Dnd);
	if (!Ub)
		return 0;
	/* Q = R_j U_below: its node part and beam columns. */
	if (b) {
		for (int j = 0; j < nc; j++)
			for (int i = 0; i < N; i++)
				Q[i + (size_t)N * j] = b->r[i] * Ub->a[i + (size_t)N * j];
	} else {
		gemm(N, nc, N, Rl->a, N, Ub->a, N, 0.0, Q, N);
		for (int e = 0; e < E; e++)
			for (int i = 0; i < N; i++) {
				size_t q = i + (size_t)N * (N + e);
				Q[q] += Rl->a[q] * Ub->d[e];
			}
	}
	for (int e = 0; e < E; e++) {
		double qd = b ? b->re[e] * Ub->d[e] : 0.0;
		Dnd[e] = Dnd[e] == 0.0 ? 0.0 : Dnd[e] / (1.0 - qd);
		for (int i = 0; i < N; i++)
			Dn[i + (size_t)N * e] += Q[i + (size_t)N * (N + e)] * Dnd[e];
	}
	for (int j = 0; j < N; j++)
		for (int i = 0; i < N; i++)
			A[i + (size_t)N * j] = (i == j) - Q[i + (size_t)N * j];
	return ad_dgesv_checked(N, E, A, N, piv, Dn, N) == 0 ? 0 : -1;
}

/* A rough top's reflection of beam e, collimated and diffuse (order 0). */
static double top_reflect(int N, int E, const struct ad_elem *x, const double *sqW, int e)
{
	(void)E;
	return field_flux(N, sqW, x->rt + (size_t)N * N, x->rt_d, e);
}

int ad_stack_flux(int N, int E, int K, const struct ad_bnd *bnd, const struct ad_op *R,
    const struct ad_op *T, const struct ad_op *U, const double *sqW, struct ad_flux *fx,
    double *work, char **cause)
{
	const int ne = 2 * K + 1;	/* elements */
	const size_t fs = (size_t)N * E + E;	/* one field: node part then collimated part */
	/* dn[j]: field going down onto element j (j = ne: into the ambient below);
	 * up[j]: field going up from element j's top. */
	double *dn = xcalloc((size_t)(ne + 1) * fs, sizeof(double));
	double *up = xcalloc((size_t)(ne + 1) * fs, sizeof(double));
	for (int e = 0; e < E; e++)
		dn[(size_t)N * E + e] = 1.0;
	for (int j = 0; j < ne; j++) {
		double *D = dn + j * fs, *Dn = dn + (j + 1) * fs;
		apply(N, E, &U[j], D, D + (size_t)N * E, up + j * fs, up + j * fs + (size_t)N * E);
		int lay = j & 1, k = j >> 1;	/* element j: boundary k, or layer k (odd j) */
		if (step_down(N, E, lay ? NULL : &bnd[k], lay ? &R[k] : NULL, lay ? &T[k] : NULL,
		    j + 1 < ne ? &U[j + 1] : NULL, D, D + (size_t)N * E, Dn, Dn + (size_t)N * E,
		    work)) {
			free(dn);
			free(up);
			*cause = xasprintf("adding-doubling: flux sweep failed (singular I - R U, "
			    "LAPACK dgesv)");
			return -1;
		}
	}
	memset(fx->a, 0, sizeof(double) * (size_t)K * E);
	for (int e = 0; e < E; e++) {
		const double *u0 = up, *bot = dn + ne * fs;
		fx->rsp[e] = bnd[0].x ? top_reflect(N, E, bnd[0].x, sqW, e) : bnd[0].re[e];
		fx->rd[e] = field_flux(N, sqW, u0, u0 + (size_t)N * E, e) - u0[(size_t)N * E + e];
		if (bnd[0].x)
			/* the diffuse part of rsp */
			fx->rd[e] -= fx->rsp[e] - bnd[0].x->rt_d[e];
		fx->rd_d[e] = u0[(size_t)N * E + e] - (bnd[0].x ? bnd[0].x->rt_d[e] : fx->rsp[e]);
		fx->tt_d[e] = bot[(size_t)N * E + e];
		fx->tt[e] = field_flux(N, sqW, bot, bot + (size_t)N * E, e) - fx->tt_d[e];
	}
	for (int k = 0; k < K; k++) {
		int j = 2 * k + 1;
		double *D = dn + j * fs, *Uf = up + (j + 1) * fs;
		absorbed(N, E, &R[k], &T[k], sqW, D, D + (size_t)N * E, fx->a + (size_t)k * E);
		absorbed(N, E, &R[k], &T[k], sqW, Uf, Uf + (size_t)N * E, fx->a + (size_t)k * E);
	}
	free(dn);
	free(up);
	return 0;
}
