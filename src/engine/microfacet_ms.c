/* microfacet_ms: the albedo-based lobe for what the separable
 * single-scattering lobe does not reflect (microfacet_ms.h). */
#include "config.h"

#include <math.h>

#include "engine/microfacet_ms.h"
#include "base/rng.h"

#define RULE_N 160	/* facet rule: RULE_N x RULE_N points per incidence */
#define MS_SEED 0x6d735f6c6f6265ULL	/* fixed streams of the later bounces */

static double uniform_of(void *r)
{
	return rng_uniform(r);
}

/* R_sep and R_hc at cos_i: the reflectance F D G (wi.m) / cos_i over the
 * facet normals m, in the measure D cos_m domega_m (GGX: cos^2 theta_m =
 * (1 - x) / (1 + (alpha^2 - 1) x), x uniform), midpoints in x and phi. */
static void first_bounce(const struct microfacet *m, double n_i, double n_t, double cos_i,
    double *r_sep, double *r_hc)
{
	double wi[3] = { sqrt(fmax(0.0, 1.0 - cos_i * cos_i)), 0.0, cos_i };
	double a2 = m->alpha * m->alpha, li = microfacet_lambda(m, cos_i), s = 0.0, h = 0.0;
	for (int i = 0; i < RULE_N; i++) {
		double x = (i + 0.5) / RULE_N, c2 = (1.0 - x) / (1.0 + (a2 - 1.0) * x);
		double cm = sqrt(c2), sm = sqrt(fmax(0.0, 1.0 - c2));
		for (int j = 0; j < RULE_N; j++) {
			double ph = 2.0 * M_PI * (j + 0.5) / RULE_N;
			double mn[3] = { sm * cos(ph), sm * sin(ph), cm }, ct;
			double im = wi[0] * mn[0] + wi[1] * mn[1] + wi[2] * mn[2];
			if (im <= 0.0)
				continue;
			double wo_z = 2.0 * im * mn[2] - wi[2];
			if (wo_z <= 0.0)
				continue;
			double F = optics_fresnel(m->fresnel, n_i, n_t, im, &ct);
			double lo = microfacet_lambda(m, wo_z), w = F * im / (cos_i * cm);
			s += w / ((1.0 + li) * (1.0 + lo));
			h += w / (1.0 + li + lo);
		}
	}
	*r_sep = s / (RULE_N * RULE_N);
	*r_hc = h / (RULE_N * RULE_N);
}

void microfacet_ms_init(struct microfacet_ms *c, double alpha, double n_i, double n_t,
    enum optics_fresnel fresnel, int walks)
{
	struct microfacet m = { MICROFACET_GGX, alpha, fresnel };
	c->alpha = alpha;
	c->n_i = n_i;
	c->n_t = n_t;
	c->e = 0.0;
	walks = walks > 0 ? walks : MICROFACET_MS_WALKS;
	for (int k = 0; k < MICROFACET_MS_NMU; k++) {
		c->mu[k] = (k + 0.5) / MICROFACET_MS_NMU;
		c->r_sep[k] = c->r_hc[k] = c->r_2[k] = c->r_2_err[k] = c->dr[k] = 0.0;
	}
	if (alpha <= 0.0 || n_i == n_t)
		return;
	for (int k = 0; k < MICROFACET_MS_NMU; k++) {
		double mu = c->mu[k], wi[3] = { sqrt(1.0 - mu * mu), 0.0, mu }, s = 0.0;
		first_bounce(&m, n_i, n_t, mu, &c->r_sep[k], &c->r_hc[k]);
		for (int p = 0; p < walks; p++) {
			struct rng r;
			double wo[3];
			int order = 0;
			rng_seed(&r, MS_SEED, (uint32_t)k, (uint64_t)p);
			double w = microfacet_sample_ms(&m, n_i, n_t, wi, uniform_of, &r, wo,
			    &order);
			if (wo[2] > 0.0 && order >= 2)
				s += w;
		}
		c->r_2[k] = s / walks;
		c->r_2_err[k] = sqrt(c->r_2[k] * (1.0 - c->r_2[k]) / walks);
		c->dr[k] = fmax(0.0, c->r_hc[k] - c->r_sep[k] + c->r_2[k]);
	}
	/* E = 2 int dR(mu) mu dmu of the interpolant (midpoints, 4096). */
	double e = 0.0;
	for (int i = 0; i < 4096; i++) {
		double mu = (i + 0.5) / 4096.0;
		e += microfacet_ms_missing(c, mu) * mu;
	}
	c->e = 2.0 * e / 4096.0;
}

double microfacet_ms_missing(const struct microfacet_ms *c, double cos_i)
{
	const int n = MICROFACET_MS_NMU;
	double x = cos_i * n - 0.5;
	if (x <= 0.0)
		return c->dr[0];
	if (x >= n - 1)
		return c->dr[n - 1];
	int k = (int)x;
	double t = x - k;
	return (1.0 - t) * c->dr[k] + t * c->dr[k + 1];
}

double microfacet_ms_eval(const struct microfacet_ms *c, double cos_i, double cos_o)
{
	if (c->e <= 0.0 || cos_i <= 0.0 || cos_o <= 0.0)
		return 0.0;
	return microfacet_ms_missing(c, cos_i) * microfacet_ms_missing(c, cos_o) / (M_PI * c->e);
}
