/* The adding-doubling solver's values and error estimates from its solves
 * at N, N/2 and N/4 nodes (definitions in ad_err.h). */
#include "config.h"
#include "engine/ad_err.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

/* Relative size of differences that are rounding, not convergence. */
#define AD_ERR_ROUNDING 1e-10

int ad_err_kept_orders(const struct ad_series *sr)
{
	return sr->lv.complete || sr->lv.M <= 2 ? sr->lv.M : sr->lv.M - 2;
}

double ad_err_tail_factor(const struct ad_series *sr)
{
	/* rho: the decay of the order sizes over the last two pairs (pairs, as
	 * the odd orders vanish at normal incidence); sum rho^k = 1/(1 - rho). */
	const struct ad_level *lv = &sr->lv;
	int M = lv->M;
	if (lv->complete || M < 5)
		return 1.0;
	const double *s = lv->order_size;
	double a = s[M - 1] + s[M - 2], b = s[M - 3] + s[M - 4];
	double rho = b > 0.0 ? a / b : 1.0;
	return rho < 0.999 ? 1.0 / (1.0 - rho) : 1000.0;
}

/* A series' table at the result's grid: the full values, and (main solve)
 * the last two orders alone. */
struct tabs {
	double *fr, *az, *last;
};

static void tabs_make(const struct ad_series *sr, const struct ad_result *r, int main_solve, struct tabs *t)
{
	const int E = sr->lv.E, nt = r->n_to, np = r->n_phi;
	size_t nb = (size_t)nt * np;
	t->fr = xcalloc((size_t)E * nb, sizeof(double));
	t->last = xcalloc((size_t)E * nb, sizeof(double));
	t->az = xcalloc((size_t)E * nt, sizeof(double));
	int mk = main_solve ? ad_err_kept_orders(sr) : 0;
	ad_series_table(sr, nt, np, mk, t->fr, t->az, mk > 0 && mk < sr->lv.M ? t->last : NULL);
	for (size_t j = 0; j < (size_t)E * nb; j++)
		t->fr[j] += t->last[j];
}

static void tabs_free(struct tabs *t)
{
	free(t->fr);
	free(t->az);
	free(t->last);
}

static double total(const struct ad_level *l, int e, int which)
{
	return which ? l->tt[e] + l->tt_d[e] : l->rd[e] + l->rd_d[e];
}

/* F from the three solves (see ad_err.h). */
static double conv_factor(const struct ad_series *hi, const struct ad_series *lo, const struct ad_series *lo2,
    const struct tabs *th, const struct tabs *tl, const struct tabs *tl2, const struct ad_result *r)
{
	if (!lo || !lo2)
		return 1.0;
	const int E = hi->lv.E, nt = r->n_to, np = r->n_phi;
	double d1 = 0.0, d2 = 0.0, s1 = 0.0, s2 = 0.0, sum = 0.0;
	for (int e = 0; e < E; e++) {
		for (int it = 0; it < nt; it++) {
			double w = cos(it * 0.5 * M_PI / nt) - cos((it + 1) * 0.5 * M_PI / nt);
			for (int ip = 0; ip < np; ip++) {
				size_t j = ((size_t)e * nt + it) * np + ip;
				double v = fabs(th->fr[j]);
				if (v > 0.0) {
					d1 += w * pow((th->fr[j] - tl->fr[j]) / v, 2);
					d2 += w * pow((tl->fr[j] - tl2->fr[j]) / v, 2);
				}
			}
		}
		for (int q = 0; q < 2; q++) {
			s1 += fabs(total(&hi->lv, e, q) - total(&lo->lv, e, q));
			s2 += fabs(total(&lo->lv, e, q) - total(&lo2->lv, e, q));
			sum += fabs(total(&hi->lv, e, q));
		}
	}
	double q = 0.0;
	if (d1 > 0.0)
		q = d2 > 0.0 ? sqrt(d1 / d2) : 1.0;
	/* Totals converged to rounding (thin layers at normal incidence: 1e-13)
	 * say nothing about the rate: their ratio is noise. */
	if (s1 > AD_ERR_ROUNDING * sum)
		q = fmax(q, s2 > 0.0 ? s1 / s2 : 1.0);
	return q <= 0.5 ? 1.0 : (q >= 0.9 ? 9.0 : q / (1.0 - q));
}

static void assemble_tables(const struct ad_series *hi, const struct tabs *th, const struct tabs *tl, double F,
    struct ad_result *r)
{
	const int E = hi->lv.E, nt = r->n_to, np = r->n_phi, nb = nt * np;
	double tf = ad_err_tail_factor(hi), e2 = 0.0;
	for (int k = 0; k < E; k++) {
		struct ad_beam *b = &r->beam[k];
		double num = 0.0, den = 0.0;
		for (int it = 0; it < nt; it++) {
			double w = cos(it * 0.5 * M_PI / nt) - cos((it + 1) * 0.5 * M_PI / nt);
			size_t ja = (size_t)k * nt + it;
			b->fr_az[it] = th->az[ja];
			b->fr_az_err[it] = tl ? F * fabs(th->az[ja] - tl->az[ja]) : 0.0;
			for (int ip = 0; ip < np; ip++) {
				size_t j = (size_t)k * nb + it * np + ip;
				double v = th->fr[j];
				double err = tf * fabs(th->last[j]) + (tl ? F * fabs(v - tl->fr[j]) : 0.0);
				b->fr[it * np + ip] = v;
				b->fr_err[it * np + ip] = err;
				double rel = v > 0.0 ? err / v : (err > 0.0 ? 1.0 : 0.0);
				num += w * rel * rel;
				den += w;
			}
		}
		b->rms_rel_err = sqrt(num / den);
		e2 += b->rms_rel_err * b->rms_rel_err;
	}
	r->rms_rel_err = sqrt(e2 / E);
}

static void assemble_totals(const struct ad_series *hi, const struct ad_series *lo, double F, struct ad_result *r)
{
	const struct ad_level *h = &hi->lv, *l = lo ? &lo->lv : NULL;
	const int E = h->E, K = hi->md.K;
	for (int e = 0; e < E; e++) {
		struct ad_beam *b = &r->beam[e];
		b->rsp = h->rsp[e];
		b->rd.v = total(h, e, 0);
		b->rd_unscat = h->rd_d[e];
		b->tt.v = total(h, e, 1);
		b->tt_unscat = h->tt_d[e];
		double drop = h->t_drop;
		b->rd.err = drop + (l ? F * fabs(b->rd.v - total(l, e, 0)) : 0.0);
		b->tt.err = drop + (l ? F * fabs(b->tt.v - total(l, e, 1)) : 0.0);
		double sum = b->rsp + b->rd.v + b->tt.v;
		for (int k = 0; k < K; k++) {
			struct ad_value *a = &b->a[hi->md.slab_layer[k]];
			a->v = h->a[(size_t)k * E + e];
			a->err = drop + (l ? F * fabs(a->v - l->a[(size_t)k * E + e]) : 0.0);
			sum += a->v;
		}
		b->balance = sum - 1.0;
		int rough = 0;
		for (int k = 0; k <= K; k++)
			rough |= hi->md.brough[k];
		if (rough) {
			/* What the fluxes leave is the facets' single-scattering loss:
			 * balance then checks nothing (see ad.h). */
			b->facet_loss.v = -b->balance;
			b->facet_loss.err = b->rd.err + b->tt.err;
			for (int k = 0; k < K; k++)
				b->facet_loss.err += b->a[hi->md.slab_layer[k]].err;
			b->balance = 0.0;
		}
	}
	r->n_nodes = h->N;
	r->n_orders = ad_err_kept_orders(hi);
	r->series_complete = h->complete;
	r->delta_m_f = h->f_max;
	r->norm_max = h->norm_max;
}

void ad_err_assemble(const struct ad_series *hi, const struct ad_series *lo, const struct ad_series *lo2,
    struct ad_result *r)
{
	struct tabs th, tl, tl2;
	tabs_make(hi, r, 1, &th);
	if (lo)
		tabs_make(lo, r, 0, &tl);
	if (lo && lo2)
		tabs_make(lo2, r, 0, &tl2);
	double F = conv_factor(hi, lo, lo2, &th, &tl, &tl2, r);
	r->conv_factor = F;
	assemble_totals(hi, lo, F, r);
	assemble_tables(hi, &th, lo ? &tl : NULL, F, r);
	tabs_free(&th);
	if (lo)
		tabs_free(&tl);
	if (lo && lo2)
		tabs_free(&tl2);
}

int ad_err_meets(const struct ad_result *r, double tol)
{
	if (r->rms_rel_err > tol)
		return 0;
	for (int k = 0; k < r->n_beams; k++) {
		const struct ad_beam *b = &r->beam[k];
		if (b->rd.err > tol * b->rd.v + 1e-9 || b->tt.err > tol * b->tt.v + 1e-9)
			return 0;
	}
	return 1;
}
