/* A rough interface's reflection and transmission per Fourier order, from
 * a facet rule over the GGX visible normals (see ad_rough.h). */
#include "config.h"
#include "engine/ad_rough.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine/microfacet.h"
#include "base/rng.h"
#include "base/util.h"

/* One facet's outgoing light before it is spread: w0 to node i, w1 to
 * node i + 1, at travel azimuth difference phi [rad]. */
struct pt {
	int i;
	double w0, w1, phi;
};

/* Azimuth points of a point-value column: Gauss-Legendre, AD_ROUGH_GPTS
 * per interval, the intervals halving toward phi = 0, where lobes are
 * narrow (grazing directions). */
#define AD_ROUGH_GPTS 8
static const double phi_edges[AD_ROUGH_GIV + 1] = {
	0.0, M_PI / 128, M_PI / 64, M_PI / 32, M_PI / 16, M_PI / 8, M_PI / 4, M_PI / 2, M_PI
};

static void gauss_phi(double *phi, double *w)
{
	for (int k = 0; k < AD_ROUGH_GIV; k++)
		ad_gauss_legendre(AD_ROUGH_GPTS, phi_edges[k], phi_edges[k + 1],
		    phi + AD_ROUGH_GPTS * k, w + AD_ROUGH_GPTS * k);
}

int ad_rough_nu(double density)
{
	(void)density;
	return AD_ROUGH_NU;
}

/* Shares of the direction with s between the two nodes around it, linear
 * in the piece's Gauss variable; one node near a piece's ends.  Returns 0
 * when s is past the quadrature (lost). */
static int share(const struct ad_quad *q, double s, double w, struct pt *p)
{
	if (!(s < q->sigma[q->n_iv]))
		return 0;
	int k = ad_quad_piece(q, s), f = q->first[k], l = q->first[k + 1] - 1;
	double t = asin(fmin(1.0, s / q->nstar[k]));
	p->w1 = 0.0;
	p->w0 = w;
	if (t <= q->th[f] || f == l) {
		p->i = f;
		return 1;
	}
	if (t >= q->th[l]) {
		p->i = l;
		return 1;
	}
	int lo = f, hi = l;	/* th[lo] < t <= th[hi] */
	while (hi - lo > 1) {
		int mid = (lo + hi) / 2;
		if (q->th[mid] < t)
			lo = mid;
		else
			hi = mid;
	}
	double a = (t - q->th[lo]) / (q->th[hi] - q->th[lo]);
	p->i = lo;
	p->w0 = w * (1.0 - a);
	p->w1 = w * a;
	return 1;
}

/* s of direction v (unit, z the normal) in a medium of index n. */
static double s_of(const double v[3], double n)
{
	return n * sqrt(fmax(0.0, v[0] * v[0] + v[1] * v[1]));
}

/* Spread weight w at azimuth phi over the azimuth points of node row a:
 * 4-point Lagrange weights, folded at 0 and pi. */
static void spread_phi(float *a, double phi, double w)
{
	const int np = AD_ROUGH_NPHI;
	const double h = M_PI / (np - 1);
	double x = fabs(phi) / h;
	int b = (int)floor(x);
	if (b > np - 2)
		b = np - 2;
	double t = x - b, l[4];
	l[0] = -t * (t - 1.0) * (t - 2.0) / 6.0;
	l[1] = (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0;
	l[2] = -(t + 1.0) * t * (t - 2.0) / 2.0;
	l[3] = (t + 1.0) * t * (t - 1.0) / 6.0;
	for (int k = 0; k < 4; k++) {
		int j = b - 1 + k;
		if (j < 0)
			j = -j;
		if (j > np - 1)
			j = 2 * (np - 1) - j;
		a[j] += (float)(w * l[k]);
	}
}

/* Power of the facet points and their spread: in nodes (the weighted
 * standard deviation of the node index, fractional between two nodes) and
 * in the azimuth (the weighted RMS of phi, whose mean is 0) [rad]. */
static double spread(const struct pt *p, int n, double *sd, double *sd_phi)
{
	double s0 = 0.0, s1 = 0.0, s2 = 0.0, p2 = 0.0;
	for (int j = 0; j < n; j++) {
		double w = p[j].w0 + p[j].w1;
		if (w == 0.0)
			continue;
		double x = p[j].i + p[j].w1 / w;
		s0 += w;
		s1 += w * x;
		s2 += w * x * x;
		p2 += w * p[j].phi * p[j].phi;
	}
	*sd = s0 > 0.0 ? sqrt(fmax(0.0, s2 / s0 - (s1 / s0) * (s1 / s0))) : 0.0;
	*sd_phi = s0 > 0.0 ? sqrt(p2 / s0) : 0.0;
	return s0;
}

/* The outgoing directions, one side of the interface, of one incoming one. */
struct side {
	const struct ad_quad *q;
	const struct microfacet *mf;
	double n_i, n_t;	/* incident medium, other medium */
	const double *wi;	/* incoming direction (toward where the light comes from) */
	int up;			/* 1: reflection (into n_i), 0: transmission (into n_t) */
	int hc;			/* 1: height-correlated Smith terms (the walk's first order) */
};

/* The height-correlated Smith term of the uniform-height microsurface over
 * the separable one G1(wi) G1(wo) (Heitz 2014; the first order of
 * microfacet_sample_ms, tests/test_microfacet): reflection
 * 1 / (1 + Li + Lo), refraction B(1 + Li, 1 + Lo). */
static double hc_factor(const struct microfacet *mf, double cos_i, double cos_o, int up)
{
	double li = microfacet_lambda(mf, cos_i), lo = microfacet_lambda(mf, cos_o);
	double g2 = up ? 1.0 / (1.0 + li + lo)
	    : exp(lgamma(1.0 + li) + lgamma(1.0 + lo) - lgamma(2.0 + li + lo));
	return g2 * (1.0 + li) * (1.0 + lo);
}

/* Column c by point values of the BSDF at the nodes (Gauss points in the
 * azimuth): exact to the quadrature's (spectral) error where the lobe
 * spans several nodes, so not scaled to the facet rule's power (whose own
 * error, about 5e-4 at 64 x 64 facets, is larger there). */
static void point_col(const struct side *sd, struct ad_rough_col *c)
{
	const struct ad_quad *q = sd->q;
	const double n_o = sd->up ? sd->n_i : sd->n_t;
	double phi[AD_ROUGH_GNP], w[AD_ROUGH_GNP];
	gauss_phi(phi, w);
	c->point = 1;
	c->lo = 0;
	c->cnt = ad_quad_count(q, n_o);
	c->a = xcalloc((size_t)c->cnt * AD_ROUGH_GNP + 1, sizeof(float));
	for (int i = 0; i < c->cnt; i++) {
		double st = q->s[i] / n_o, mu = ad_quad_mu(q, i, n_o), f = q->W[i] / (n_o * n_o);
		for (int b = 0; b < AD_ROUGH_GNP; b++) {
			double wo[3] = { st * cos(phi[b]), st * sin(phi[b]), sd->up ? mu : -mu };
			double v = 2.0 * w[b] * f
			    * microfacet_bsdf(sd->mf, sd->n_i, sd->n_t, sd->wi, wo);
			if (sd->hc && v != 0.0)
				v *= hc_factor(sd->mf, sd->wi[2], mu, sd->up);
			c->a[(size_t)i * AD_ROUGH_GNP + b] = (float)v;
		}
	}
}

/* The facet points p[0 .. n-1] into column c: by the facets themselves
 * when the lobe is narrow, by point values when it spans AD_ROUGH_WIDE
 * nodes or more and AD_ROUGH_WIDE_PHI in the azimuth (near grazing a lobe
 * can be wide in nodes, which crowd there, but too narrow in the azimuth
 * for the point values' azimuth rule: alpha 0.05 put 3 % too much power
 * into one column). */
static void gather(const struct pt *p, int n, const struct side *sd, struct ad_rough_col *c)
{
	double width, width_phi, total = spread(p, n, &width, &width_phi);
	if (total > 0.0 && width >= AD_ROUGH_WIDE && width_phi >= AD_ROUGH_WIDE_PHI) {
		point_col(sd, c);
		return;
	}
	int lo = -1, hi = -1;
	for (int j = 0; j < n; j++) {
		if (p[j].w0 == 0.0 && p[j].w1 == 0.0)
			continue;
		int top = p[j].w1 != 0.0 ? p[j].i + 1 : p[j].i;
		if (lo < 0 || p[j].i < lo)
			lo = p[j].i;
		if (top > hi)
			hi = top;
	}
	c->lo = lo < 0 ? 0 : lo;
	c->cnt = lo < 0 ? 0 : hi - lo + 1;
	c->a = xcalloc((size_t)c->cnt * AD_ROUGH_NPHI + 1, sizeof(float));
	for (int j = 0; j < n; j++) {
		float *row = c->a + (size_t)(p[j].i - c->lo) * AD_ROUGH_NPHI;
		if (p[j].w0 != 0.0)
			spread_phi(row, p[j].phi, p[j].w0);
		if (p[j].w1 != 0.0)
			spread_phi(row + AD_ROUGH_NPHI, p[j].phi, p[j].w1);
	}
}

/* The facet rule and its scratch, shared by the columns of one interface. */
struct rule {
	const struct ad_quad *q;
	const struct microfacet *mf;
	int n_u;
	const double *gx, *gw;	/* Gauss-Legendre points and weights in u1 */
	struct pt *pr, *pt;	/* n_u^2 points each */
	int walks;		/* multiple scattering: 1 = the first order height-correlated */
};

static double uni(void *r)
{
	return rng_uniform(r);
}

/* Orders >= 2 of the multiple-scattering walk (microfacet_sample_ms, Heitz
 * et al. 2016) from incoming cosine mu_i in n_i: AD_ROUGH_MS_WALKS walks on
 * a fixed stream, their Fourier orders f_m = int f cos(m dphi) dphi
 * binned on AD_ROUGH_MS_NB cosine bins of each side, into
 * t[side][bin][m] (side 0 reflected, 1 transmitted).  Returns the power
 * of the orders >= 2. */
static double walk_row(const struct microfacet *mf, double n_i, double n_t, double mu_i,
    uint32_t stream, double *t)
{
	const int nb = AD_ROUGH_MS_NB, M = AD_ROUGH_MS_M, W = AD_ROUGH_MS_WALKS;
	const double wi[3] = { -sqrt(fmax(0.0, 1.0 - mu_i * mu_i)), 0.0, mu_i };
	struct rng g;
	rng_seed(&g, AD_ROUGH_MS_SEED, stream, 0);
	double power = 0.0;
	for (int k = 0; k < W; k++) {
		double wo[3];
		int order = 0;
		if (microfacet_sample_ms(mf, n_i, n_t, wi, uni, &g, wo, &order) == 0.0 || order < 2)
			continue;
		int side = wo[2] < 0.0, b = (int)(fabs(wo[2]) * nb);
		if (b > nb - 1)
			b = nb - 1;
		double phi = atan2(wo[1], wo[0]), lo = (double)b / nb, hi = (b + 1.0) / nb;
		double w = 1.0 / (W * 0.5 * (hi * hi - lo * lo));
		double *row = t + ((size_t)side * nb + b) * (M + 1);
		for (int m = 0; m <= M; m++)
			row[m] += w * cos(m * phi);
		power += 1.0 / W;
	}
	return power;
}

/* The table of one side of incidence: AD_ROUGH_MS_NI incoming cosines. */
static void walk_table(const struct microfacet *mf, double n_i, double n_t, uint32_t stream0,
    double *t)
{
	const size_t row = (size_t)2 * AD_ROUGH_MS_NB * (AD_ROUGH_MS_M + 1);
	for (int g = 0; g < AD_ROUGH_MS_NI; g++)
		walk_row(mf, n_i, n_t, (g + 0.5) / AD_ROUGH_MS_NI, stream0 + (uint32_t)g,
		    t + row * g);
}

/* Linear interpolation position of x in [0, 1] on n cells' centres. */
static int cell(double x, int n, double *a)
{
	double u = x * n - 0.5;
	if (u <= 0.0) {
		*a = 0.0;
		return 0;
	}
	if (u >= n - 1) {
		*a = 1.0;
		return n - 2;
	}
	int k = (int)u;
	*a = u - k;
	return k;
}

/* f_m of the higher orders from mu_i to mu_o on side `side` of table t. */
static double ms_fm(const double *t, double mu_i, double mu_o, int side, int m)
{
	const int nb = AD_ROUGH_MS_NB, M1 = AD_ROUGH_MS_M + 1;
	const size_t row = (size_t)2 * nb * M1;
	double a, b;
	int g = cell(mu_i, AD_ROUGH_MS_NI, &a), k = cell(mu_o, nb, &b);
	const double *t0 = t + row * g + (size_t)side * nb * M1, *t1 = t0 + row;
	double v0 = (1.0 - b) * t0[(size_t)k * M1 + m] + b * t0[(size_t)(k + 1) * M1 + m];
	double v1 = (1.0 - b) * t1[(size_t)k * M1 + m] + b * t1[(size_t)(k + 1) * M1 + m];
	return (1.0 - a) * v0 + a * v1;
}

/* The facets of one incoming direction (cosine mu_i in medium n_i, s) into
 * cr (reflected, into n_i) and ct (transmitted, into n_t), with the
 * height-correlated Smith terms under multiple scattering (its first
 * order); returns the power lost off the quadrature. */
static double column(struct rule *ru, double n_i, double n_t, double s, double mu_i,
    struct ad_rough_col *cr, struct ad_rough_col *ct)
{
	const int n_u = ru->n_u, ns = n_u * n_u, hc = ru->walks > 0;
	const struct microfacet *mf = ru->mf;
	struct pt *pr = ru->pr, *pt = ru->pt;
	double lost = 0.0;
	const double wi[3] = { -s / n_i, 0.0, mu_i };
	memset(pr, 0, sizeof *pr * (size_t)ns);
	memset(pt, 0, sizeof *pt * (size_t)ns);
	if (mu_i > 0.0) {
		for (int a = 0; a < n_u; a++)
			for (int b = 0; b < n_u; b++) {
				double wr[3], wt[3], gr, gt;
				microfacet_sample_split(mf, n_i, n_t, wi, ru->gx[a],
				    (b + 0.5) / n_u, wr, &gr, wt, &gt);
				int j = a * n_u + b;
				gr *= ru->gw[a] / n_u;
				gt *= ru->gw[a] / n_u;
				if (hc && gr > 0.0)
					gr *= hc_factor(mf, mu_i, wr[2], 1);
				if (hc && gt > 0.0)
					gt *= hc_factor(mf, mu_i, -wt[2], 0);
				if (gr > 0.0) {
					pr[j].phi = atan2(wr[1], wr[0]);
					if (!share(ru->q, s_of(wr, n_i), gr, &pr[j]))
						lost += gr;
				}
				if (gt > 0.0) {
					pt[j].phi = atan2(wt[1], wt[0]);
					if (!share(ru->q, s_of(wt, n_t), gt, &pt[j]))
						lost += gt;
				}
			}
	}
	struct side sr = { ru->q, mf, n_i, n_t, wi, 1, hc };
	struct side st = { ru->q, mf, n_i, n_t, wi, 0, hc };
	gather(pr, ns, &sr, cr);
	gather(pt, ns, &st, ct);
	return lost;
}

static double cos_of_s(double s, double n)
{
	return s < n ? sqrt((n - s) * (n + s)) / n : 0.0;
}

static void ms_norm(struct ad_rough *r, const struct ad_quad *q);

void ad_rough_init(struct ad_rough *r, const struct ad_quad *q, double n_above, double n_below,
    double alpha, enum optics_fresnel model, const double *se, int E, int n_u, int walks)
{
	const int N = q->n;
	const struct microfacet mf = { MICROFACET_GGX, alpha, model };
	memset(r, 0, sizeof *r);
	r->N = N;
	r->E = E;
	r->top_r = xcalloc((size_t)(N + E), sizeof *r->top_r);
	r->top_t = xcalloc((size_t)(N + E), sizeof *r->top_t);
	r->bot_r = xcalloc((size_t)N + 1, sizeof *r->bot_r);
	r->bot_t = xcalloc((size_t)N + 1, sizeof *r->bot_t);
	if (walks > 0) {
		const size_t tn = (size_t)AD_ROUGH_MS_NI * 2 * AD_ROUGH_MS_NB * (AD_ROUGH_MS_M + 1);
		r->ms_top = xcalloc(tn, sizeof(double));
		r->ms_bot = xcalloc(tn, sizeof(double));
		walk_table(&mf, n_above, n_below, 0, r->ms_top);
		walk_table(&mf, n_below, n_above, AD_ROUGH_MS_NI, r->ms_bot);
		r->mu_a = xcalloc((size_t)(N + E), sizeof(double));
		r->mu_b = xcalloc((size_t)(N + E), sizeof(double));
		for (int j = 0; j < N + E; j++) {
			double s = j < N ? q->s[j] : se[j - N];
			r->mu_a[j] = j < N ? (s < n_above ? ad_quad_mu(q, j, n_above) : 0.0)
			    : cos_of_s(s, n_above);
			r->mu_b[j] = j < N && s < n_below ? ad_quad_mu(q, j, n_below) : 0.0;
		}
		r->n_above = n_above;
		r->n_below = n_below;
	}
	/* Gauss-Legendre in u1 (the visible-normal map has a square-root edge
	 * there: the midpoint rule was 2.5e-3 off the albedo at alpha 0.05,
	 * this 4e-4), midpoints in the periodic u2. */
	double *gx = xcalloc((size_t)n_u, sizeof(double));
	double *gw = xcalloc((size_t)n_u, sizeof(double));
	ad_gauss_legendre(n_u, 0.0, 1.0, gx, gw);
	struct rule ru = { q, &mf, n_u, gx, gw, NULL, NULL, walks > 0 };
	ru.pr = xcalloc((size_t)n_u * n_u, sizeof *ru.pr);
	ru.pt = xcalloc((size_t)n_u * n_u, sizeof *ru.pt);
	for (int j = 0; j < N + E; j++) {
		double s = j < N ? q->s[j] : se[j - N];
		double mu = j < N ? (s < n_above ? ad_quad_mu(q, j, n_above) : 0.0)
		    : cos_of_s(s, n_above);
		double l = column(&ru, n_above, n_below, s, mu, &r->top_r[j], &r->top_t[j]);
		r->lost_max = fmax(r->lost_max, l);
	}
	for (int j = 0; j < N; j++) {
		double s = q->s[j], mu = s < n_below ? ad_quad_mu(q, j, n_below) : 0.0;
		double l = column(&ru, n_below, n_above, s, mu, &r->bot_r[j], &r->bot_t[j]);
		r->lost_max = fmax(r->lost_max, l);
	}
	if (walks > 0)
		ms_norm(r, q);
	free(ru.pr);
	free(ru.pt);
	free(gx);
	free(gw);
}

/* The power of column c (order 0 of its azimuth points). */
static double col_power(const struct ad_rough_col *c)
{
	const int np = c->point ? AD_ROUGH_GNP : AD_ROUGH_NPHI;
	double p = 0.0;
	for (size_t k = 0; k < (size_t)c->cnt * np; k++)
		p += c->a[k];
	return p;
}

/* The walk tables' power from cosine mu_i (light from below: from = 1)
 * into the quadrature's nodes, both sides. */
static double ms_power(const struct ad_rough *r, const struct ad_quad *q, int from, double mu_i)
{
	double p = 0.0;
	for (int side = 0; side < 2; side++) {
		const double *mo = (from == side) ? r->mu_a : r->mu_b;
		double n_o = (from == side) ? r->n_above : r->n_below;
		for (int i = 0; i < r->N; i++)
			if (mo[i] > 0.0)
				p += q->W[i]
				    * ms_fm(from ? r->ms_bot : r->ms_top, mu_i, mo[i], side, 0)
				    / (n_o * n_o);
	}
	return p;
}

/* Scale each column's higher orders so that it keeps all its power: the
 * walk loses nothing, and the tables' interpolation between incoming
 * cosines (coarse near grazing) is what is off otherwise. */
static void ms_norm(struct ad_rough *r, const struct ad_quad *q)
{
	const int N = r->N, E = r->E;
	r->ms_scale_a = xcalloc((size_t)(N + E), sizeof(double));
	r->ms_scale_b = xcalloc((size_t)N + 1, sizeof(double));
	for (int from = 0; from < 2; from++)
		for (int j = 0; j < (from ? N : N + E); j++) {
			double mu = from ? r->mu_b[j] : r->mu_a[j];
			if (!(mu > 0.0))
				continue;
			double p1 = from ? col_power(&r->bot_r[j]) + col_power(&r->bot_t[j])
			    : col_power(&r->top_r[j]) + col_power(&r->top_t[j]);
			double pm = ms_power(r, q, from, mu), want = fmax(0.0, 1.0 - p1);
			(from ? r->ms_scale_b : r->ms_scale_a)[j] = pm > 0.0 ? want / pm : 0.0;
		}
}

/* Column out[N] of an operator from c at order m (cm: cos(m phi_b)): the
 * powers, over sqrt(W_i), times in (sqrt(W_j) for a node column), added
 * to out. */
static void order_col(const struct ad_rough_col *c, const double *cm, const double *cg,
    const double *sqW, double in, double *out)
{
	const int np = c->point ? AD_ROUGH_GNP : AD_ROUGH_NPHI;
	const double *cs = c->point ? cg : cm;
	for (int i = 0; i < c->cnt; i++) {
		const float *row = c->a + (size_t)i * np;
		double v = 0.0;
		for (int b = 0; b < np; b++)
			v += row[b] * cs[b];
		out[c->lo + i] += v * in / sqW[c->lo + i];
	}
}

/* The walk's higher orders added to order m's columns: node i's power
 * P_m(i | j) = W_i f_m(j -> i) / n_o^2 (the point-value limit, ad_rough.h),
 * f_m interpolated in the tables. */
static void ms_order(const struct ad_rough *r, int m, const double *sqW, struct ad_elem *x)
{
	const int N = r->N, E = r->E;
	for (int from = 0; from < 2; from++)
		for (int j = 0; j < (from ? N : N + E); j++) {
			const double *t = from ? r->ms_bot : r->ms_top;
			double mu_i = from ? r->mu_b[j] : r->mu_a[j];
			if (!(mu_i > 0.0))
				continue;
			double in = (j < N ? sqW[j] : 1.0)
			    * (from ? r->ms_scale_b : r->ms_scale_a)[j];
			double *xr = (from ? x->rb : x->rt) + (size_t)N * j;
			double *xt = (from ? x->tu : x->td) + (size_t)N * j;
			for (int side = 0; side < 2; side++) {
				const double *mo = (from == side) ? r->mu_a : r->mu_b;
				double n_o = (from == side) ? r->n_above : r->n_below;
				double *out = side ? xt : xr;
				for (int i = 0; i < N; i++)
					if (mo[i] > 0.0)
						out[i] += sqW[i] * ms_fm(t, mu_i, mo[i], side, m)
						    / (n_o * n_o) * in;
			}
		}
}

void ad_rough_order(const struct ad_rough *r, int m, const double *sqW, struct ad_elem *x)
{
	const int N = r->N, E = r->E;
	double cm[AD_ROUGH_NPHI], cg[AD_ROUGH_GNP], phi[AD_ROUGH_GNP], w[AD_ROUGH_GNP];
	for (int b = 0; b < AD_ROUGH_NPHI; b++)
		cm[b] = cos(m * (M_PI * b / (AD_ROUGH_NPHI - 1)));
	gauss_phi(phi, w);
	for (int b = 0; b < AD_ROUGH_GNP; b++)
		cg[b] = cos(m * phi[b]);
	memset(x->rt, 0, sizeof(double) * ad_elem_size(N, E));
	for (int j = 0; j < N + E; j++) {
		double in = j < N ? sqW[j] : 1.0;
		order_col(&r->top_r[j], cm, cg, sqW, in, x->rt + (size_t)N * j);
		order_col(&r->top_t[j], cm, cg, sqW, in, x->td + (size_t)N * j);
	}
	for (int j = 0; j < N; j++) {
		order_col(&r->bot_r[j], cm, cg, sqW, sqW[j], x->rb + (size_t)N * j);
		order_col(&r->bot_t[j], cm, cg, sqW, sqW[j], x->tu + (size_t)N * j);
	}
	if (r->ms_top && m <= AD_ROUGH_MS_M)
		ms_order(r, m, sqW, x);
}

static void cols_free(struct ad_rough_col *c, int n)
{
	for (int j = 0; c && j < n; j++)
		free(c[j].a);
	free(c);
}

void ad_rough_free(struct ad_rough *r)
{
	cols_free(r->top_r, r->N + r->E);
	cols_free(r->top_t, r->N + r->E);
	cols_free(r->bot_r, r->N);
	cols_free(r->bot_t, r->N);
	free(r->ms_top);
	free(r->ms_bot);
	free(r->mu_a);
	free(r->mu_b);
	free(r->ms_scale_a);
	free(r->ms_scale_b);
	memset(r, 0, sizeof *r);
}
