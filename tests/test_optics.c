/* Fresnel and Snell against closed forms. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>

#include "engine/optics.h"

static void test_normal_incidence(void **state)
{
	(void)state;
	double pairs[][2] = { { 1.0, 1.5 }, { 1.5, 1.0 }, { 1.0, 1.4 }, { 1.4, 1.5 }, { 1.0, 2.5 } };
	for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
		double n1 = pairs[i][0], n2 = pairs[i][1], ct;
		double r0 = (n1 - n2) / (n1 + n2);
		r0 *= r0;
		assert_float_equal(optics_fresnel(OPTICS_FRESNEL_EXACT, n1, n2, 1.0, &ct), r0, 1e-15);
		assert_float_equal(ct, 1.0, 1e-15);
		assert_float_equal(optics_fresnel(OPTICS_FRESNEL_SCHLICK, n1, n2, 1.0, &ct), r0, 1e-15);
	}
	double ct;
	/* The sebum value of the references: air/1.5 gives 0.04 exactly. */
	assert_float_equal(optics_fresnel(OPTICS_FRESNEL_EXACT, 1.0, 1.5, 1.0, &ct), 0.04, 1e-15);
}

static void test_equal_indices(void **state)
{
	(void)state;
	for (double c = 0.0; c <= 1.0; c += 0.01) {
		double ct;
		assert_true(optics_fresnel(OPTICS_FRESNEL_EXACT, 1.4, 1.4, c, &ct) == 0.0);
		assert_true(ct == c);
		assert_true(optics_fresnel(OPTICS_FRESNEL_SCHLICK, 1.4, 1.4, c, &ct) == 0.0);
	}
}

static void test_critical_angle(void **state)
{
	(void)state;
	double n1 = 1.4, n2 = 1.0;
	double cc = optics_cos_critical(n1, n2);
	assert_float_equal(cc, sqrt(1.0 - 1.0 / (1.4 * 1.4)), 1e-15);
	assert_float_equal(asin(n2 / n1), acos(cc), 1e-12);
	double ct;
	/* Beyond the critical angle: total reflection. */
	assert_true(optics_fresnel(OPTICS_FRESNEL_EXACT, n1, n2, cc * 0.999, &ct) == 1.0);
	assert_true(optics_fresnel(OPTICS_FRESNEL_SCHLICK, n1, n2, cc * 0.999, &ct) == 1.0);
	/* Continuous at it: R -> 1 from inside. */
	assert_true(optics_fresnel(OPTICS_FRESNEL_EXACT, n1, n2, cc * (1 + 1e-9), &ct) > 0.999);
	assert_true(optics_fresnel(OPTICS_FRESNEL_SCHLICK, n1, n2, cc * (1 + 1e-9), &ct) > 0.999);
	assert_true(optics_cos_critical(1.0, 1.4) == 0.0);
	/* Grazing incidence from the thin side reflects everything. */
	assert_float_equal(optics_fresnel(OPTICS_FRESNEL_EXACT, 1.0, 1.4, 0.0, &ct), 1.0, 1e-12);
}

static void test_snell(void **state)
{
	(void)state;
	double pairs[][2] = { { 1.0, 1.5 }, { 1.5, 1.0 }, { 1.33, 1.4 }, { 2.5, 1.0 } };
	for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++)
		for (double c = 0.005; c <= 1.0; c += 0.01) {
			double n1 = pairs[i][0], n2 = pairs[i][1];
			double ct = optics_cos_t(n1, n2, c);
			if (ct < 0) {
				assert_true(n1 * sqrt(1 - c * c) > n2);
				continue;
			}
			assert_float_equal(n1 * sqrt(1 - c * c), n2 * sqrt(1 - ct * ct), 1e-12);
		}
}

/* Exact Fresnel against the textbook trigonometric form. */
static void test_against_trig_form(void **state)
{
	(void)state;
	double n1 = 1.0, n2 = 1.43;
	for (double th = 0.01; th < M_PI / 2; th += 0.05) {
		double tt = asin(n1 * sin(th) / n2), ct;
		double rs = sin(th - tt) / sin(th + tt), rp = tan(th - tt) / tan(th + tt);
		double ref = 0.5 * (rs * rs + rp * rp);
		assert_float_equal(optics_fresnel(OPTICS_FRESNEL_EXACT, n1, n2, cos(th), &ct), ref, 1e-12);
	}
}

/* Reciprocity: the reflectance is the same seen from either side, R(n1 -> n2,
 * theta_i) = R(n2 -> n1, theta_t), for both models; and the dense side
 * below its critical angle matches the trigonometric form too. */
static void test_reciprocity(void **state)
{
	(void)state;
	double pairs[][2] = { { 1.0, 1.4 }, { 1.0, 1.5 }, { 1.4, 1.5 }, { 1.0, 2.5 } };
	for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++)
		for (double c = 0.01; c <= 1.0; c += 0.01) {
			double n1 = pairs[i][0], n2 = pairs[i][1], ct, cb;
			for (int m = 0; m < 2; m++) {
				enum optics_fresnel model = m ? OPTICS_FRESNEL_SCHLICK : OPTICS_FRESNEL_EXACT;
				double r12 = optics_fresnel(model, n1, n2, c, &ct);
				double r21 = optics_fresnel(model, n2, n1, ct, &cb);
				assert_float_equal(r12, r21, 1e-12);
				assert_float_equal(cb, c, 1e-12);
				assert_true(r12 >= 0.0 && r12 <= 1.0);
			}
			double th = acos(ct), ti = acos(c);
			double rs = sin(th - ti) / sin(th + ti), rp = tan(th - ti) / tan(th + ti);
			if (c < 1.0)
				assert_float_equal(optics_fresnel(OPTICS_FRESNEL_EXACT, n2, n1, ct, &cb),
				    0.5 * (rs * rs + rp * rp), 1e-12);
		}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_normal_incidence),
		cmocka_unit_test(test_equal_indices),
		cmocka_unit_test(test_critical_angle),
		cmocka_unit_test(test_snell),
		cmocka_unit_test(test_against_trig_form),
		cmocka_unit_test(test_reciprocity),
	};
	return cmocka_run_group_tests_name("optics", tests, NULL, NULL);
}
