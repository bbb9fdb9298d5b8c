/* The lobe of the facets' later reflections (engine/microfacet_ms): its
 * first-bounce rule against microfacet_albedo, the separable lobe plus the
 * missing reflectance against an independent walk (the transport's Rsp),
 * energy of the lobe, reciprocity, alpha -> 0; prints the energy booking
 * (what the single-scattering model loses, what the lobe returns). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>

#include "engine/microfacet_ms.h"
#include "base/rng.h"

static const double alphas[] = { 0.05, 0.2, 0.413, 0.5 };
#define N_ALPHA 4
static struct microfacet_ms tab[N_ALPHA];

static int setup(void **state)
{
	(void)state;
	for (int a = 0; a < N_ALPHA; a++)
		microfacet_ms_init(&tab[a], alphas[a], 1.0, 1.5, OPTICS_FRESNEL_EXACT, 0);
	return 0;
}

/* R_sep of the facet rule (160 x 160 midpoints in the D cos_m measure)
 * against microfacet_albedo's product rule (400 x 400): two quadratures of
 * one integral, measured apart by at most 4.2e-4 at alpha 0.2 and 9.7e-4
 * at 0.05 (both at the most grazing node, mu 0.021; 1.6e-4 and 4.2e-4 at
 * the others): within 5e-4 and 1e-3. */
static void test_first_bounce(void **state)
{
	(void)state;
	struct microfacet m = { MICROFACET_GGX, 0.0, OPTICS_FRESNEL_EXACT };
	for (int a = 0; a < N_ALPHA; a++) {
		m.alpha = alphas[a];
		for (int k = 0; k < MICROFACET_MS_NMU; k++) {
			double R, T;
			microfacet_albedo(&m, 1.0, 1.5, tab[a].mu[k], 400, 400, &R, &T);
			double tol = alphas[a] >= 0.2 ? 5e-4 : 1e-3;
			if (fabs(tab[a].r_sep[k] - R) > tol)
				fail_msg("alpha %g mu %.4f: rule %.6f, albedo %.6f", alphas[a], tab[a].mu[k],
				    tab[a].r_sep[k], R);
			/* the height-correlated term is never below the separable one */
			assert_true(tab[a].r_hc[k] >= tab[a].r_sep[k]);
		}
	}
}

static double uni(void *r)
{
	return rng_uniform(r);
}

/* The separable lobe plus dR is the walk's whole reflectance (what the
 * transport books as Rsp with multiple scattering), against walks on other
 * streams: within 3 standard errors of both plus 2e-4 (the rule); prints
 * the booking per incidence. */
static void test_energy_booking(void **state)
{
	(void)state;
	const int n = 400000;
	for (int a = 1; a < N_ALPHA; a++) {
		struct microfacet m = { MICROFACET_GGX, alphas[a], OPTICS_FRESNEL_EXACT };
		printf("# alpha %g, air into n 1.5: incidence, single-scattering loss 1-R-T, "
		    "walk R, separable lobe R, returned by the lobe dR\n", alphas[a]);
		for (int k = 1; k < MICROFACET_MS_NMU; k += 4) {
			double mu = tab[a].mu[k], wi[3] = { sqrt(1.0 - mu * mu), 0.0, mu }, s = 0.0;
			for (int p = 0; p < n; p++) {
				struct rng r;
				double wo[3];
				rng_seed(&r, 12345, (uint32_t)k, (uint64_t)p);
				if (microfacet_sample_ms(&m, 1.0, 1.5, wi, uni, &r, wo, NULL) > 0.0 && wo[2] > 0.0)
					s += 1.0;
			}
			double rw = s / n, se = sqrt(rw * (1.0 - rw) / n), R, T;
			microfacet_albedo(&m, 1.0, 1.5, mu, 400, 400, &R, &T);
			double got = R + tab[a].dr[k];
			printf("#   %5.1f deg: loss %.4f, walk R %.4f +- %.4f, lobe R %.4f, dR %.4f (%.0f %% of the "
			    "loss)\n", acos(mu) * 180.0 / M_PI, 1.0 - R - T, rw, se, R, tab[a].dr[k],
			    100.0 * tab[a].dr[k] / (1.0 - R - T));
			double tol = 3.0 * sqrt(se * se + tab[a].r_2_err[k] * tab[a].r_2_err[k]) + 2e-4;
			if (fabs(got - rw) > tol)
				fail_msg("alpha %g mu %.4f: lobe + dR %.5f, walk %.5f (tol %.5f)", alphas[a], mu,
				    got, rw, tol);
		}
	}
}

/* int f_ms mu_o domega_o = dR(mu_i), within 1e-6 (midpoints, 20000). */
static void test_lobe_energy(void **state)
{
	(void)state;
	for (int a = 0; a < N_ALPHA; a++)
		for (double mi = 0.05; mi < 1.0; mi += 0.1) {
			double s = 0.0;
			for (int j = 0; j < 20000; j++) {
				double mo = (j + 0.5) / 20000.0;
				s += microfacet_ms_eval(&tab[a], mi, mo) * mo;
			}
			s *= 2.0 * M_PI / 20000.0;
			assert_float_equal(s, microfacet_ms_missing(&tab[a], mi), 1e-6);
		}
}

/* f(i, o) = f(o, i) exactly; f >= 0. */
static void test_reciprocity(void **state)
{
	(void)state;
	for (int a = 0; a < N_ALPHA; a++)
		for (double x = 0.01; x < 1.0; x += 0.07)
			for (double y = 0.02; y < 1.0; y += 0.09) {
				double f = microfacet_ms_eval(&tab[a], x, y);
				assert_true(f >= 0.0 && f == microfacet_ms_eval(&tab[a], y, x));
			}
}

/* alpha -> 0: no lobe at 0 (nor without an interface); dR at mu >= 0.1
 * shrinks with alpha (measured 2.7e-2 at alpha 0.05, 2.2e-3 at 0.01,
 * 1.0e-4 at 0.002: the later bounces of grazing light, which the
 * separable lobe shadows away): below 3e-3 at 0.01 and 2e-4 at 0.002, and
 * the lobe's E with it. */
static void test_smooth_limit(void **state)
{
	(void)state;
	struct microfacet_ms z;
	microfacet_ms_init(&z, 0.0, 1.0, 1.5, OPTICS_FRESNEL_EXACT, 0);
	assert_true(z.e == 0.0 && microfacet_ms_eval(&z, 0.5, 0.5) == 0.0);
	microfacet_ms_init(&z, 0.3, 1.5, 1.5, OPTICS_FRESNEL_EXACT, 100);
	assert_true(z.e == 0.0 && microfacet_ms_eval(&z, 0.2, 0.2) == 0.0);
	const double as[] = { 0.01, 0.002 }, bound[] = { 3e-3, 2e-4 };
	double e_prev = tab[0].e;
	for (int a = 0; a < 2; a++) {
		microfacet_ms_init(&z, as[a], 1.0, 1.5, OPTICS_FRESNEL_EXACT, 0);
		double mx = 0.0;
		for (int k = 0; k < MICROFACET_MS_NMU; k++)
			if (z.mu[k] >= 0.1)
				mx = fmax(mx, z.dr[k]);
		printf("# alpha %g: largest dR at mu >= 0.1 %.2e, E %.2e\n", as[a], mx, z.e);
		assert_true(mx < bound[a] && z.e < e_prev);
		e_prev = z.e;
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_first_bounce),
		cmocka_unit_test(test_energy_booking),
		cmocka_unit_test(test_lobe_energy),
		cmocka_unit_test(test_reciprocity),
		cmocka_unit_test(test_smooth_limit),
	};
	return cmocka_run_group_tests(tests, setup, NULL);
}
