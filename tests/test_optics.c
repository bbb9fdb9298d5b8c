/* Fresnel and Snell against closed forms. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>

#include "engine/optics.h"
#include "engine/specular.h"

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

/* The microfacet pieces: Schlick's end points and its agreement with the
 * Schlick model of optics_fresnel, D normalised over the hemisphere of
 * half vectors, G1 = 1 at normal view and equal to the tangent form, and
 * specular_ggx built from them for a single interface. */
static void test_microfacet_pieces(void **state)
{
	(void)state;
	double n = 1.44, r0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1)), ct;
	assert_float_equal(specular_schlick(1.0, n), r0, 1e-15);
	assert_float_equal(specular_schlick(0.0, n), 1.0, 1e-15);
	for (double c = 0.05; c < 1; c += 0.1)
		assert_float_equal(specular_schlick(c, n), optics_fresnel(OPTICS_FRESNEL_SCHLICK, 1.0, n, c, &ct), 1e-14);
	for (double a = 0.1; a < 1; a += 0.2) {
		/* int D(h) cos(h) d(omega_h) = 1, midpoint rule in cos(h). */
		double a2 = a * a, sum = 0.0;
		enum { N = 200000 };
		for (int i = 0; i < N; i++) {
			double mu = (i + 0.5) / N;
			sum += specular_ggx_d(mu, a2) * mu * 2 * M_PI / N;
		}
		assert_float_equal(sum, 1.0, 1e-4);
		assert_float_equal(specular_smith_g1(1.0, a2), 1.0, 1e-15);
		for (double c = 0.05; c < 1; c += 0.1) {
			double t2 = (1 - c * c) / (c * c);
			assert_float_equal(specular_smith_g1(c, a2), 2 / (1 + sqrt(1 + a2 * t2)), 1e-14);
		}
	}
	struct specular_stack st = { .n = 2, .n_list = { 1.0, n }, .model = OPTICS_FRESNEL_SCHLICK };
	double ti = 0.4, to = 0.7, dphi = 2.5, a = 0.3;
	double wi[3] = { sin(ti), 0, cos(ti) }, wo[3] = { sin(to) * cos(dphi), sin(to) * sin(dphi), cos(to) };
	double h[3] = { wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2] }, hn = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
	double ch = h[2] / hn, cd = (wi[0] * h[0] + wi[2] * h[2]) / hn;
	double want = specular_schlick(cd, n) * specular_ggx_d(ch, a * a) * specular_smith_g1(cos(ti), a * a) *
	    specular_smith_g1(cos(to), a * a) / (4 * cos(ti) * cos(to));
	assert_float_equal(specular_ggx(&st, a, ti, to, dphi), want, 1e-12 * want);
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
		cmocka_unit_test(test_microfacet_pieces),
	};
	return cmocka_run_group_tests_name("optics", tests, NULL, NULL);
}
