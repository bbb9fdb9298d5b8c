/* One adding-doubling solve at one quadrature, order by order in the
 * azimuth (see ad_order.h): media and boundaries set up once, then each
 * Fourier order's phase matrices, layers and adding. */
#include "config.h"
#include "engine/ad_order.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "engine/ad_cache.h"
#include "engine/ad_layer.h"
#include "engine/ad_phase.h"
#include "engine/ad_rough.h"
#include "engine/ad_stack.h"
#include "base/util.h"

/* A turbid layer at this quadrature. */
struct medium {
	int n;			/* nodes that exist in it */
	double *x;		/* [n + E] node cosines, then beam cosines (0 = beam absent) */
	double *w;		/* [n] cosine weights */
	struct ad_hg hg;
	double tau, omega;	/* delta-M scaled */
	double dtau_max;	/* thickest starting layer */
	double *corr;		/* [n] correction of h_m's diagonal (forward
				 * scattering), from order 0 */
	double *ext;		/* [E] beams' extinction factor */
	double *bscale;		/* [E] factor on a beam's backward column (g < 0) */
};

/* What every order shares. */
struct ctx {
	const struct ad_model *md;
	const struct ad_level_opts *o;
	struct ad_level *lv;
	struct medium med[SLAB_MAX_LAYERS];
	struct ad_bnd bnd[SLAB_MAX_LAYERS + 1];
	double *sqW;		/* [N] */
	const double *se;	/* [E] */
	int max_m;		/* orders that can be nonzero */
	/* boundary k's interface j, if rough */
	struct ad_rough rough[SLAB_MAX_LAYERS + 1][SLAB_MAX_LAYERS + 1];
};

/* Per-thread scratch for one order. */
struct ws {
	double *Hpp, *Hpm, *hgw, *lR, *lT, *ldT, *lwork, *swork;
	struct ad_op R[SLAB_MAX_LAYERS], T[SLAB_MAX_LAYERS], U[2 * SLAB_MAX_LAYERS + 1];
	double *block;	/* one allocation behind the ops */
	struct ad_elem xb[SLAB_MAX_LAYERS + 1], xi;	/* rough boundaries for the
							 * order; one interface */
	double *eblock, *ework;	/* behind them; NULL when all boundaries are smooth */
};

static void ws_alloc(struct ws *w, const struct ctx *c)
{
	const int N = c->lv->N, E = c->lv->E, K = c->md->K;
	size_t op = (size_t)N * (N + E) + E, lmax = 2;
	for (int k = 0; k < K; k++)
		if ((size_t)c->med[k].hg.L > lmax)
			lmax = (size_t)c->med[k].hg.L;
	w->Hpp = xcalloc((size_t)N * (N + E), sizeof(double));
	w->Hpm = xcalloc((size_t)N * (N + E), sizeof(double));
	w->hgw = xcalloc(2 * (size_t)(N + E + 1) * lmax, sizeof(double));
	w->lR = xcalloc((size_t)N * (N + E), sizeof(double));
	w->lT = xcalloc((size_t)N * (N + E), sizeof(double));
	w->ldT = xcalloc((size_t)E + 1, sizeof(double));
	w->lwork = xcalloc(ad_layer_work(N, E), sizeof(double));
	w->swork = xcalloc(ad_stack_work(N, E), sizeof(double));
	w->block = xcalloc(op * (size_t)(4 * K + 1), sizeof(double));
	struct ad_op *all[4 * SLAB_MAX_LAYERS + 1];
	int n = 0;
	for (int k = 0; k < K; k++)
		all[n++] = &w->R[k], all[n++] = &w->T[k];
	for (int j = 0; j < 2 * K + 1; j++)
		all[n++] = &w->U[j];
	for (int j = 0; j < n; j++) {
		all[j]->a = w->block + op * (size_t)j;
		all[j]->d = all[j]->a + (size_t)N * (N + E);
	}
	int nr = 0;
	for (int k = 0; k <= K; k++)
		nr += c->md->brough[k];
	if (nr == 0)
		return;
	size_t es = ad_elem_size(N, E);
	w->eblock = xcalloc(es * (size_t)(K + 2), sizeof(double));
	w->ework = xcalloc(ad_elem_work(N, E), sizeof(double));
	for (int k = 0; k <= K; k++)
		ad_elem_bind(&w->xb[k], w->eblock + es * (size_t)k, N, E);
	ad_elem_bind(&w->xi, w->eblock + es * (size_t)(K + 1), N, E);
}

static void ws_free(struct ws *w)
{
	free(w->Hpp);
	free(w->Hpm);
	free(w->hgw);
	free(w->lR);
	free(w->lT);
	free(w->ldT);
	free(w->lwork);
	free(w->swork);
	free(w->block);
	free(w->eblock);
	free(w->ework);
}

/* Interface j of boundary k at order mo into x. */
static void interface_order(const struct ctx *c, int k, int j, int mo, struct ad_elem *x)
{
	const struct ad_level *lv = c->lv;
	const double *nl = c->md->bn[k];
	if (c->md->balpha[k][j] > 0.0)
		ad_rough_order(&c->rough[k][j], mo, c->sqW, x);
	else
		ad_elem_smooth(x, lv->N, lv->E, c->md->fresnel, nl[j], nl[j + 1], lv->q.s, c->se);
}

/* Rough boundary k at order mo: its interfaces added from the bottom up. */
static int rough_boundary(const struct ctx *c, int k, int mo, struct ws *w, char **cause)
{
	const int cnt = c->md->bcnt[k];
	interface_order(c, k, cnt - 2, mo, &w->xb[k]);
	for (int j = cnt - 3; j >= 0; j--) {
		interface_order(c, k, j, mo, &w->xi);
		if (ad_elem_add(c->lv->N, c->lv->E, &w->xi, &w->xb[k], &w->xb[k], w->ework)) {
			*cause = xasprintf("adding-doubling: adding a rough boundary's interfaces "
			    "failed (LAPACK dgesv)");
			return -1;
		}
	}
	return 0;
}

/* Order 0: the discrete normalization of h_0 over the nodes.  Where the
 * quadrature misses part of the phase function's peak, the missing part is
 * put back where the peak is: on the diagonal of h(mu, mu) for a forward
 * peak (forward scattering, the same in every order, like a delta-M
 * remainder; a beam keeps it in its unscattered part), on the diagonal of
 * h(mu, -mu) for a backward one (g < 0: exact reversal, (-1)^m in order m,
 * with the delta-M fraction there too; a beam's backward column is scaled
 * to carry it, the beam has no collimated reflection). */
static void normalize(struct ctx *c, struct medium *m, const double *Hpp, const double *Hpm)
{
	const int n = m->n, E = c->lv->E;
	/* For g < 0 the retro-reflected fraction f is part of the sum (exactly). */
	double fb = m->hg.g < 0.0 ? m->hg.f : 0.0;
	for (int i = 0; i < n; i++) {
		double s = fb;
		for (int j = 0; j < n; j++)
			s += (1.0 - fb) * m->w[j]
			    * (Hpp[j + (size_t)n * i] + Hpm[j + (size_t)n * i]);
		m->corr[i] = (1.0 - s) / m->w[i];
		c->lv->norm_max = fmax(c->lv->norm_max, fabs(1.0 - s));
		m->corr[i] += fb / m->w[i];
	}
	for (int e = 0; e < E; e++) {
		double sp = 0.0, sm = 0.0;
		for (int j = 0; j < n; j++) {
			sp += (1.0 - fb) * m->w[j] * Hpp[j + (size_t)n * (n + e)];
			sm += (1.0 - fb) * m->w[j] * Hpm[j + (size_t)n * (n + e)];
		}
		int present = m->x[n + e] > 0.0;
		m->bscale[e] = 1.0;
		m->ext[e] = 1.0;
		if (present && m->hg.g < 0.0 && sm > 0.0)
			m->bscale[e] = (1.0 - sp) / sm;
		else if (present)
			m->ext[e] = 1.0 - m->omega * (1.0 - sp - sm);
	}
}

/* Layer k's operators for order mo into w->R[k], w->T[k] (full size). */
static int layer_order(struct ctx *c, int k, int mo, struct ws *w, char **cause)
{
	struct medium *m = &c->med[k];
	const int n = m->n, N = c->lv->N, E = c->lv->E, nc = N + E;
	ad_hg_fourier(&m->hg, mo, m->x, n, n + E, w->Hpp, w->Hpm, w->hgw);
	if (mo == 0)
		normalize(c, m, w->Hpp, w->Hpm);
	if (m->hg.g >= 0.0)
		for (int i = 0; i < n; i++)
			w->Hpp[i + (size_t)n * i] += m->corr[i];
	else {
		/* p = (1 - f) p* + f (retro-reflection); the beam columns carry f by bscale. */
		double keep = 1.0 - m->hg.f;
		for (size_t j = 0; j < (size_t)n * (n + E); j++) {
			w->Hpp[j] *= keep;
			w->Hpm[j] *= keep;
		}
		for (int i = 0; i < n; i++)
			w->Hpm[i + (size_t)n * i] += (mo & 1 ? -1.0 : 1.0) * m->corr[i];
		for (int e = 0; e < E; e++)
			for (int i = 0; i < n; i++)
				w->Hpm[i + (size_t)n * (n + e)] *= m->bscale[e];
	}
	struct ad_layer_in in = {
		.n = n, .ne = E, .mu = m->x, .w = m->w, .mu_e = m->x + n, .ext_e = m->ext,
		.Hpp = w->Hpp, .Hpm = w->Hpm, .tau = m->tau, .omega = m->omega,
		.dtau_max = m->dtau_max, .n_index = c->md->n[k],
		.doubling_only = c->o->doubling_only,
	};
	struct ad_layer_out out = { .R = w->lR, .T = w->lT, .dT = w->ldT };
	if (c->o->cache == NULL || !ad_cache_get(c->o->cache, &in, &out)) {
		if (ad_layer_solve(&in, &out, w->lwork, cause))
			return -1;
		if (c->o->cache)
			ad_cache_put(c->o->cache, &in, &out);
	}
	struct ad_op *R = &w->R[k], *T = &w->T[k];
	memset(R->a, 0, sizeof(double) * ((size_t)N * nc + E));
	memset(T->a, 0, sizeof(double) * ((size_t)N * nc + E));
	for (int j = 0; j < n + E; j++) {
		int J = j < n ? j : N + j - n;
		memcpy(R->a + (size_t)N * J, w->lR + (size_t)n * j, sizeof(double) * n);
		memcpy(T->a + (size_t)N * J, w->lT + (size_t)n * j, sizeof(double) * n);
	}
	memcpy(T->d, w->ldT, sizeof(double) * E);
#pragma omp atomic
	c->lv->doublings += out.doublings;
	if (out.t_drop > 0.0) {
#pragma omp critical(ad_tdrop)
		c->lv->t_drop = fmax(c->lv->t_drop, out.t_drop);
	}
	return 0;
}

/* Order mo of the whole stack; its exit coefficients into lv->F. */
static int solve_order(struct ctx *c, int mo, struct ws *w, char **cause)
{
	struct ad_level *lv = c->lv;
	const int N = lv->N, E = lv->E, K = c->md->K, na = lv->na;
	struct ad_bnd bnd[SLAB_MAX_LAYERS + 1];
	for (int k = 0; k < K; k++)
		if (layer_order(c, k, mo, w, cause))
			return -1;
	for (int k = 0; k <= K; k++) {
		bnd[k] = c->bnd[k];
		if (c->md->brough[k]) {
			if (rough_boundary(c, k, mo, w, cause))
				return -1;
			bnd[k].x = &w->xb[k];
		}
	}
	if (ad_stack_reflect(N, E, K, bnd, w->R, w->T, w->U, w->swork, cause))
		return -1;
	/* A rough top's own reflection of the beams is rsp, not the diffuse
	 * BRDF (the analytic specular lobe stands for it): take it out. */
	const double *top = bnd[0].x ? bnd[0].x->rt + (size_t)N * N : NULL;
	/* BRDF coefficient: flux per unit beam flux over kappa_m a_i, kappa_0 =
	 * 2 pi, kappa_m = pi, a_i = W_i / n_above^2 (see ad_layer.h). */
	double kap = mo == 0 ? 2.0 * M_PI : M_PI, n2 = c->md->n_above * c->md->n_above;
	for (int e = 0; e < E; e++)
		for (int i = 0; i < na; i++)
			lv->F[((size_t)mo * E + e) * na + i] = n2 *
			    (w->U[0].a[i + (size_t)N * (N + e)]
			    - (top ? top[i + (size_t)N * e] : 0.0)) / (kap * c->sqW[i]);
	if (mo > 0)
		return 0;
	struct ad_flux fx = {
		.rsp = lv->rsp, .rd = lv->rd, .rd_d = lv->rd_d, .tt = lv->tt, .tt_d = lv->tt_d, .a = lv->a
	};
	return ad_stack_flux(N, E, K, bnd, w->R, w->T, w->U, c->sqW, &fx, w->swork, cause);
}

static double cos_of_s(double s, double n)
{
	return s < n ? sqrt((n - s) * (n + s)) / n : 0.0;
}

/* Media, boundaries and result arrays for the quadrature. */
static void setup(struct ctx *c, const double *se)
{
	const struct ad_model *md = c->md;
	struct ad_level *lv = c->lv;
	const int N = lv->N, E = lv->E, K = md->K;
	c->sqW = xcalloc((size_t)N, sizeof(double));
	for (int i = 0; i < N; i++)
		c->sqW[i] = sqrt(lv->q.W[i]);
	c->max_m = 1;
	for (int k = 0; k < K; k++) {
		struct medium *m = &c->med[k];
		double nk = md->n[k];
		m->n = ad_quad_count(&lv->q, nk);
		m->x = xcalloc((size_t)(m->n + E), sizeof(double));
		m->w = xcalloc((size_t)m->n + 1, sizeof(double));
		m->corr = xcalloc((size_t)m->n + 1, sizeof(double));
		m->ext = xcalloc((size_t)E + 1, sizeof(double));
		m->bscale = xcalloc((size_t)E + 1, sizeof(double));
		double mu_min = 1.0;
		for (int i = 0; i < m->n; i++) {
			m->x[i] = ad_quad_mu(&lv->q, i, nk);
			m->w[i] = lv->q.W[i] / (nk * nk * m->x[i]);
			mu_min = fmin(mu_min, m->x[i]);
		}
		for (int e = 0; e < E; e++) {
			m->x[m->n + e] = cos_of_s(se[e], nk);
			if (m->x[m->n + e] > 0.0)
				mu_min = fmin(mu_min, m->x[m->n + e]);
		}
		int lmax = (int)(c->o->dm_terms * m->n);
		ad_hg_init(&m->hg, md->g[k], lmax < 2 ? 2 : lmax);
		/* retro-reflection stays scattering */
		double f = md->g[k] > 0.0 ? m->hg.f : 0.0, om = md->omega[k];
		m->tau = md->tau[k] * (1.0 - om * f);
		m->omega = om * (1.0 - f) / (1.0 - om * f);
		m->dtau_max = c->o->dtau_frac * mu_min;
		lv->f_max = fmax(lv->f_max, m->hg.f);
		if (m->hg.L > c->max_m)
			c->max_m = m->hg.L;
	}
	if (c->max_m > c->o->max_orders)
		c->max_m = c->o->max_orders;
	for (int k = 0; k <= K; k++) {
		struct ad_bnd *b = &c->bnd[k];
		b->r = xcalloc((size_t)N, sizeof(double));
		b->t = xcalloc((size_t)N, sizeof(double));
		b->re = xcalloc((size_t)E + 1, sizeof(double));
		b->te = xcalloc((size_t)E + 1, sizeof(double));
		ad_bnd_fill(b, md->fresnel, md->bn[k], md->bcnt[k], lv->q.s, N, se, E);
	}
	for (int k = 0; k <= K; k++)
		for (int j = 0; md->brough[k] && j + 1 < md->bcnt[k]; j++)
			if (md->balpha[k][j] > 0.0) {
				struct ad_rough *r = &c->rough[k][j];
				ad_rough_init(r, &lv->q, md->bn[k][j], md->bn[k][j + 1],
				    md->balpha[k][j], md->fresnel, se, E,
				    md->rough_nu > 0 ? md->rough_nu : ad_rough_nu(c->o->density),
				    md->rough_walks);
				lv->rough_lost = fmax(lv->rough_lost, r->lost_max);
			}
	lv->t_air = xcalloc((size_t)lv->na + 1, sizeof(double));
	for (int i = 0; i < lv->na; i++)
		lv->t_air[i] = md->brough[0] ? 1.0 : c->bnd[0].t[i];
	double **fl[] = { &lv->rsp, &lv->rd, &lv->rd_d, &lv->tt, &lv->tt_d };
	for (size_t j = 0; j < sizeof fl / sizeof fl[0]; j++)
		*fl[j] = xcalloc((size_t)E, sizeof(double));
	lv->a = xcalloc((size_t)K * E, sizeof(double));
	lv->F = xcalloc((size_t)c->max_m * E * (lv->na + 1), sizeof(double));
	lv->order_size = xcalloc((size_t)c->max_m, sizeof(double));
}

static void teardown(struct ctx *c)
{
	for (int k = 0; k < c->md->K; k++) {
		free(c->med[k].x);
		free(c->med[k].w);
		free(c->med[k].corr);
		free(c->med[k].ext);
		free(c->med[k].bscale);
		ad_hg_free(&c->med[k].hg);
	}
	for (int k = 0; k <= c->md->K; k++) {
		free(c->bnd[k].r);
		free(c->bnd[k].t);
		free(c->bnd[k].re);
		free(c->bnd[k].te);
		for (int j = 0; j + 1 < c->md->bcnt[k]; j++)
			if (c->md->balpha[k][j] > 0.0)
				ad_rough_free(&c->rough[k][j]);
	}
	free(c->sqW);
}

/* Largest |F_m| relative to the largest F_0, over beams. */
static double order_size(const struct ad_level *lv, int mo)
{
	double s = 0.0;
	for (int e = 0; e < lv->E; e++) {
		double f0 = 0.0, fm = 0.0;
		for (int i = 0; i < lv->na; i++) {
			f0 = fmax(f0, fabs(lv->F[(size_t)e * lv->na + i]));
			fm = fmax(fm, fabs(lv->F[((size_t)mo * lv->E + e) * lv->na + i]));
		}
		s = fmax(s, f0 > 0.0 ? fm / f0 : fm);
	}
	return s;
}

int ad_level_solve(const struct ad_model *md, const double *se, int E,
    const struct ad_level_opts *o, struct ad_level *lv, char **cause)
{
	memset(lv, 0, sizeof *lv);
	if (ad_quad_build(&lv->q, md->sigma, md->nstar, md->n_iv, o->density, o->n_min, cause))
		return -1;
	lv->N = lv->q.n;
	lv->E = E;
	lv->na = ad_quad_count(&lv->q, md->n_above);
	struct ctx c = { .md = md, .o = o, .lv = lv, .se = se };
	setup(&c, se);
	int nt = o->threads > 0 ? o->threads : 1, rc = 0;
	struct ws *w = xcalloc((size_t)nt, sizeof *w);
	for (int t = 0; t < nt; t++)
		ws_alloc(&w[t], &c);
	rc = solve_order(&c, 0, &w[0], cause);
	lv->M = 1;
	lv->order_size[0] = 1.0;
	/* Orders in blocks, spread over the threads; stop after two small ones.
	 * A block of 4 orders per thread keeps the barriers few (waiting
	 * threads spin) and wastes at most a block past the stopping order. */
	int done = c.max_m <= 1, block = nt > 1 ? 4 * nt : 1;
	while (!rc && !done) {
		int m0 = lv->M, m1 = m0 + block < c.max_m ? m0 + block : c.max_m, fail = 0;
		char *why = NULL;
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt) if (nt > 1)
		for (int mo = m0; mo < m1; mo++) {
			int t = 0;
#ifdef _OPENMP
			t = omp_get_thread_num();
#endif
			char *cz = NULL;
			if (solve_order(&c, mo, &w[t], &cz)) {
#pragma omp critical(ad_fail)
				{
					if (!fail)
						why = cz;
					else
						free(cz);
					fail = 1;
				}
			}
		}
		if (fail) {
			*cause = why;
			rc = -1;
			break;
		}
		for (int mo = m0; mo < m1 && !done; mo++) {
			lv->order_size[mo] = order_size(lv, mo);
			lv->M = mo + 1;
			if (mo >= 2 && lv->order_size[mo] < o->tol_f &&
			    lv->order_size[mo - 1] < o->tol_f)
				done = 1;
		}
		if (lv->M >= c.max_m)
			done = 1;
	}
	lv->complete = lv->M >= c.max_m;
	for (int t = 0; t < nt; t++)
		ws_free(&w[t]);
	free(w);
	teardown(&c);
	return rc;
}

void ad_level_free(struct ad_level *lv)
{
	ad_quad_free(&lv->q);
	free(lv->F);
	free(lv->t_air);
	free(lv->order_size);
	free(lv->rsp);
	free(lv->rd);
	free(lv->rd_d);
	free(lv->tt);
	free(lv->tt_d);
	free(lv->a);
	memset(lv, 0, sizeof *lv);
}
