/* Henyey-Greenstein sampling against its density: mean cosine and a
 * chi-square test, for g near 0 (both signs) and near 1. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>

#include "engine/phase.h"
#include "base/rng.h"

static const double gs[] = { -0.9, -1e-7, 0.0, 1e-7, 0.5, 0.99, 0.9999 };

/* HG CDF of cos: P(cos <= c). */
static double hg_cdf(double g, double c)
{
	if (fabs(g) < 1e-12)
		return 0.5 * (c + 1.0);
	double a = 1.0 + g * g - 2.0 * g * c;
	return (1.0 - g * g) / (2.0 * g) * (1.0 / sqrt(a) - 1.0 / (1.0 + g));
}

static void test_mean_cosine(void **state)
{
	(void)state;
	const long n = 2000000;
	for (size_t k = 0; k < sizeof gs / sizeof gs[0]; k++) {
		double g = gs[k], s = 0.0, s2 = 0.0;
		struct rng r;
		rng_seed(&r, 12345, (uint32_t)k, 0);
		for (long i = 0; i < n; i++) {
			double c = hg_sample_cos(g, rng_uniform(&r));
			assert_true(c >= -1.0 && c <= 1.0);
			s += c;
			s2 += c * c;
		}
		double mean = s / n, var = s2 / n - mean * mean;
		double se = sqrt(var / n);
		/* 4 sigma, plus a floor for the nearly deterministic g = 0.9999. */
		if (fabs(mean - g) > 4.0 * se + 1e-9)
			fail_msg("g = %g: mean cosine %.8f, expected %g +- %.2g", g, mean, g, 4 * se);
	}
}

/* Chi-square of the sampled cos against HG in 50 bins equiprobable under the
 * exact CDF; critical value for 49 dof at p = 0.001 is 85.4. */
static void test_chi_square(void **state)
{
	(void)state;
	enum { NB = 50 };
	const long n = 500000;
	for (size_t k = 0; k < sizeof gs / sizeof gs[0]; k++) {
		double g = gs[k];
		long cnt[NB] = { 0 };
		struct rng r;
		rng_seed(&r, 777, (uint32_t)k, 0);
		for (long i = 0; i < n; i++) {
			double c = hg_sample_cos(g, rng_uniform(&r));
			int b = (int)(hg_cdf(g, c) * NB);
			cnt[b < 0 ? 0 : (b >= NB ? NB - 1 : b)]++;
		}
		double chi = 0.0, e = (double)n / NB;
		for (int b = 0; b < NB; b++)
			chi += (cnt[b] - e) * (cnt[b] - e) / e;
		if (chi > 85.4)
			fail_msg("g = %g: chi-square %.1f > 85.4", g, chi);
	}
}

/* The density integrates to 1 for every g.  The peak sits at the end
 * cos = sign(g) with width ~(1-|g|)^2, so integrate in the distance x from
 * that end on a logarithmic grid, x = e^t (midpoint rule in t). */
static void test_pdf_normalised(void **state)
{
	(void)state;
	for (size_t k = 0; k < sizeof gs / sizeof gs[0]; k++) {
		double g = gs[k], sign = g < 0 ? -1.0 : 1.0;
		const double x0 = 1e-18, t0 = log(x0), t1 = log(2.0);
		const int m = 200000;
		double dt = (t1 - t0) / m;
		double s = hg_pdf_cos(g, sign) * x0;	/* [0, x0]: constant to 1e-10 */
		for (int i = 0; i < m; i++) {
			double x = exp(t0 + (i + 0.5) * dt);
			s += hg_pdf_cos(g, sign * (1.0 - x)) * x * dt;
		}
		if (fabs(s - 1.0) > 1e-6)
			fail_msg("g = %g: integral of the HG density %.9f, expected 1", g, s);
	}
}

/* Continuity across the switch between the two forms at |g| = 0.5. */
static void test_branch_continuity(void **state)
{
	(void)state;
	for (double u = 0.01; u < 1.0; u += 0.01) {
		double a = hg_sample_cos(0.5 - 1e-12, u), b = hg_sample_cos(0.5, u);
		assert_float_equal(a, b, 1e-9);
		a = hg_sample_cos(-0.5 + 1e-12, u), b = hg_sample_cos(-0.5, u);
		assert_float_equal(a, b, 1e-9);
	}
}

static void test_spin_unit(void **state)
{
	(void)state;
	struct rng r;
	rng_seed(&r, 1, 0, 0);
	double ux = 0.6, uy = 0.0, uz = 0.8;
	for (int i = 0; i < 100000; i++) {
		double ct = hg_sample_cos(0.9, rng_uniform(&r)), psi = 2 * M_PI * rng_uniform(&r);
		double ox = ux, oy = uy, oz = uz;
		spin_dir(&ux, &uy, &uz, ct, cos(psi), sin(psi));
		assert_float_equal(ux * ux + uy * uy + uz * uz, 1.0, 1e-9);
		assert_float_equal(ux * ox + uy * oy + uz * oz, ct, 1e-7);
		double nn = sqrt(ux * ux + uy * uy + uz * uz);
		ux /= nn, uy /= nn, uz /= nn;
	}
}

/* The polynomial azimuth equals libm's cos and sin of 2 pi u, on a fine grid
 * and at the quarter-turn seams where its branches meet. */
static void test_azimuth_sample(void **state)
{
	(void)state;
	double worst = 0.0;
	const int n = 1000000;
	for (int i = 0; i <= n + 8; i++) {
		double u = i <= n ? (i + 0.5) / (n + 1.0) : 0.125 * (i - n) - 0x1.0p-40;
		if (i > n && (u <= 0.0 || u >= 1.0))
			continue;
		double c, s;
		azimuth_sample(u, &c, &s);
		double e = fmax(fabs(c - cos(2 * M_PI * u)), fabs(s - sin(2 * M_PI * u)));
		worst = fmax(worst, e);
		if (!(e < 1e-15 && fabs(c * c + s * s - 1.0) < 1e-15))
			fail_msg("u = %.17g: (%.17g, %.17g) vs libm (%.17g, %.17g)", u, c, s, cos(2 * M_PI * u),
			    sin(2 * M_PI * u));
	}
	print_message("# azimuth_sample: worst difference from libm %.2g\n", worst);
	/* The extreme uniforms rng_uniform can return. */
	double c, s;
	azimuth_sample(0x1.0p-33, &c, &s);
	assert_float_equal(c, 1.0, 1e-15);
	azimuth_sample(1.0 - 0x1.0p-33, &c, &s);
	assert_float_equal(c, 1.0, 1e-15);
	assert_true(s < 0.0);
}

/* spin_dir from straight down and straight up (its pole branch). */
static void test_spin_pole(void **state)
{
	(void)state;
	const double z0[] = { 1.0, -1.0, 0.999995, -0.999995 };
	for (int k = 0; k < 4; k++)
		for (double ct = -1.0; ct <= 1.0; ct += 0.125)
			for (double psi = 0.1; psi < 2 * M_PI; psi += 0.7) {
				double ux = sqrt(1.0 - z0[k] * z0[k]), uy = 0.0, uz = z0[k];
				double ox = ux, oz = uz;
				spin_dir(&ux, &uy, &uz, ct, cos(psi), sin(psi));
				assert_float_equal(ux * ux + uy * uy + uz * uz, 1.0, 1e-9);
				/* The pole branch ignores the tiny sideways part: 3e-3 rad. */
				assert_float_equal(ux * ox + uz * oz, ct, k < 2 ? 1e-12 : 1e-2);
			}
}

static void test_rng_reproducible(void **state)
{
	(void)state;
	struct rng a, b;
	rng_seed(&a, 99, 3, 123456789012ULL);
	rng_seed(&b, 99, 3, 123456789012ULL);
	for (int i = 0; i < 100; i++) {
		double x = rng_uniform(&a);
		assert_true(x > 0.0 && x < 1.0);
		assert_true(x == rng_uniform(&b));
	}
	rng_seed(&b, 99, 4, 123456789012ULL);
	rng_seed(&a, 99, 3, 123456789012ULL);
	assert_true(rng_uniform(&a) != rng_uniform(&b));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_mean_cosine),
		cmocka_unit_test(test_chi_square),
		cmocka_unit_test(test_pdf_normalised),
		cmocka_unit_test(test_branch_continuity),
		cmocka_unit_test(test_spin_unit),
		cmocka_unit_test(test_azimuth_sample),
		cmocka_unit_test(test_spin_pole),
		cmocka_unit_test(test_rng_reproducible),
	};
	return cmocka_run_group_tests_name("phase", tests, NULL, NULL);
}
