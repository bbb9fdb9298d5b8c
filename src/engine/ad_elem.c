/* A boundary with full reflection and transmission matrices, and the
 * adding of two of them (see ad_elem.h). */
#include "config.h"
#include "engine/ad_elem.h"

#include <cblas.h>
#include <math.h>
#include <string.h>

#include "engine/ad_lapack.h"

size_t ad_elem_size(int N, int E)
{
	return 2 * (size_t)N * (size_t)(N + E) + 2 * (size_t)N * (size_t)N + 4 * (size_t)E;
}

void ad_elem_bind(struct ad_elem *e, double *block, int N, int E)
{
	size_t op = (size_t)N * (size_t)(N + E), sq = (size_t)N * (size_t)N;
	e->rt = block;
	e->td = e->rt + op;
	e->rb = e->td + op;
	e->tu = e->rb + sq;
	e->rt_d = e->tu + sq;
	e->td_d = e->rt_d + E;
	e->rb_d = e->td_d + E;
	e->tu_d = e->rb_d + E;
}

/* One smooth interface at s: ad_bnd_rt's rule (ad_stack.h) for two indices
 * (r = 1 where the direction exists on one side only). */
static void smooth_rt(enum optics_fresnel model, const double nl[2], double s, double *r, double *t)
{
	int above = s < nl[0], below = s < nl[1];
	double ct;
	*t = 0.0;
	if (!above && !below)
		*r = 0.0;
	else if (!above || !below)
		*r = 1.0;
	else {
		*r = optics_stack_reflectance(model, nl, 2,
		    sqrt(fmax(0.0, (nl[0] - s) * (nl[0] + s))) / nl[0], &ct);
		*t = 1.0 - *r;
	}
}

void ad_elem_smooth(struct ad_elem *x, int N, int E, enum optics_fresnel model, double n_above,
    double n_below, const double *s, const double *se)
{
	const double nl[2] = { n_above, n_below };
	memset(x->rt, 0, sizeof(double) * ad_elem_size(N, E));
	for (int i = 0; i < N; i++) {
		double r, t;
		smooth_rt(model, nl, s[i], &r, &t);
		x->rt[i + (size_t)N * i] = r;
		x->td[i + (size_t)N * i] = t;
		x->rb[i + (size_t)N * i] = r;
		x->tu[i + (size_t)N * i] = t;
	}
	for (int e = 0; e < E; e++) {
		smooth_rt(model, nl, se[e], &x->rt_d[e], &x->td_d[e]);
		x->rb_d[e] = x->rt_d[e];
		x->tu_d[e] = x->td_d[e];
	}
}

size_t ad_elem_work(int N, int E)
{
	/* o, S and Su [N x (2N + E)], M [N x N], cdn [E], piv [N] (ints). */
	return ad_elem_size(N, E) + 2 * (size_t)N * (size_t)(2 * N + E) + (size_t)N * (size_t)N
	    + (size_t)E + (size_t)N + 1;
}

static void gemm(int m, int n, int k, const double *A, const double *B, double beta, double *C)
{
	cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, m, n, k, 1.0, A, m, B, k, beta,
	    C, m);
}

int ad_elem_add(int N, int E, const struct ad_elem *A, const struct ad_elem *B, struct ad_elem *out,
    double *work)
{
	const int nc = N + E, ncb = 2 * N + E;	/* from above (N + E), then from below (N) */
	struct ad_elem o;
	ad_elem_bind(&o, work, N, E);
	double *S = work + ad_elem_size(N, E);	/* [N x ncb]: the gap's sources, then d */
	double *Su = S + (size_t)N * ncb;	/* [N x ncb]: light going up in
						 * the gap from its sources */
	double *M = Su + (size_t)N * ncb;	/* [N x N]: I - Rb_A Rt_B */
	double *cdn = M + (size_t)N * N;	/* [E] collimated going down in the gap */
	int *piv = (int *)(cdn + E);
	memset(Su, 0, sizeof(double) * (size_t)N * ncb);
	/* From above: A sends Td_A down, and B's response to the collimated
	 * part goes up; from below: B sends Tu_B up. */
	memcpy(S, A->td, sizeof(double) * (size_t)N * nc);
	for (int e = 0; e < E; e++) {
		double den = 1.0 - A->rb_d[e] * B->rt_d[e];
		cdn[e] = A->td_d[e] == 0.0 ? 0.0 : A->td_d[e] / den;
		for (int i = 0; i < N; i++)
			Su[i + (size_t)N * (N + e)] = B->rt[i + (size_t)N * (N + e)] * cdn[e];
	}
	memcpy(Su + (size_t)N * nc, B->tu, sizeof(double) * (size_t)N * N);
	memset(S + (size_t)N * nc, 0, sizeof(double) * (size_t)N * N);
	/* S += Rb_A Su; d = (I - Rb_A Rt_B)^-1 S. */
	gemm(N, ncb, N, A->rb, Su, 1.0, S);
	gemm(N, N, N, A->rb, B->rt, 0.0, M);
	for (size_t j = 0; j < (size_t)N * N; j++)
		M[j] = -M[j];
	for (int i = 0; i < N; i++)
		M[i + (size_t)N * i] += 1.0;
	if (ad_dgesv_checked(N, ncb, M, N, piv, S, N) != 0)
		return -1;
	/* u = Su + Rt_B d (node part of Rt_B only). */
	gemm(N, ncb, N, B->rt, S, 1.0, Su);
	/* From above: Rt = Rt_A + Tu_A u, Td = Td_B d + Td_B's beam columns times cdn. */
	memcpy(o.rt, A->rt, sizeof(double) * (size_t)N * nc);
	gemm(N, nc, N, A->tu, Su, 1.0, o.rt);
	gemm(N, nc, N, B->td, S, 0.0, o.td);
	for (int e = 0; e < E; e++)
		for (int i = 0; i < N; i++)
			o.td[i + (size_t)N * (N + e)] += B->td[i + (size_t)N * (N + e)] * cdn[e];
	/* From below: Rb = Rb_B + Td_B d, Tu = Tu_A u. */
	memcpy(o.rb, B->rb, sizeof(double) * (size_t)N * N);
	gemm(N, N, N, B->td, S + (size_t)N * nc, 1.0, o.rb);
	gemm(N, N, N, A->tu, Su + (size_t)N * nc, 0.0, o.tu);
	for (int e = 0; e < E; e++) {
		double den = 1.0 - A->rb_d[e] * B->rt_d[e];
		o.rt_d[e] = A->rt_d[e] + A->tu_d[e] * B->rt_d[e] * cdn[e];
		o.td_d[e] = B->td_d[e] * cdn[e];
		o.rb_d[e] = B->rb_d[e]
		    + (B->tu_d[e] == 0.0 ? 0.0 : B->td_d[e] * A->rb_d[e] * B->tu_d[e] / den);
		o.tu_d[e] = B->tu_d[e] == 0.0 ? 0.0 : A->tu_d[e] * B->tu_d[e] / den;
	}
	memcpy(out->rt, o.rt, sizeof(double) * ad_elem_size(N, E));
	return 0;
}
