/* White Monte Carlo Rd(r) (engine/wmc.h) against its independent
 * references: the same walk's plain radial tally (a variant without extra
 * absorption scores exactly what the walk scores), plain Monte Carlo of
 * each variant on its own random streams (mean exit radius and ring powers
 * within 4 combined standard errors), and adding-doubling's Rd of each
 * variant (the profile's integral, conservation); the same with far
 * roulette (engine/transport.h) played well inside the profile. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/ad.h"
#include "engine/tally.h"
#include "engine/transport.h"
#include "engine/wmc.h"

enum { NS = SLAB_MAX_LAYERS + 2, NV = 4, NR = 200 };
#define DR 0.005	/* [cm]: the profile reaches 1 cm, where these slabs leave under 1e-6 */

/* The paper preset's stack at 550 nm (sebum, epidermis, dermis), with the
 * epidermis and dermis mu_a of each variant [1/cm]. */
static const double mua[NV][2] = { { 50, 7 }, { 120, 7 }, { 50, 20 }, { 120, 20 } };

static void mkslab(struct slab *s, double mua_epi, double mua_derm)
{
	char *cause = NULL;
	const struct layer L[3] = { { 0.001, 1.5, 0, 0, 0, 0 }, { 0.01, 1.43, mua_epi, 185, 0.8, 0 },
		{ 0.25, 1.43, mua_derm, 185, 0.8, 0 } };
	slab_init(s, 1.0, 1.43);
	for (int i = 0; i < 3; i++)
		assert_int_equal(slab_add(s, &L[i], &cause), 0);
	if (slab_check(s, &cause))
		fail_msg("%s", cause);
	slab_prepare(s);
}

static void variants(struct slab *vs, struct slab *ref, double *dmua)
{
	for (int v = 0; v < NV; v++)
		mkslab(&vs[v], mua[v][0], mua[v][1]);
	for (int v = 1; v < NV; v++)
		assert_true(wmc_same_scattering(&vs[0], &vs[v]));
	wmc_reference(vs, NV, ref, dmua);
	assert_true(ref->layer[2].mu_a == 50 && ref->layer[3].mu_a == 7);
}

/* A variant without extra absorption scores what the walk's own radial tally does, bit for bit. */
static void test_zero_variant_is_the_walk(void **state)
{
	(void)state;
	struct slab vs[NV], ref;
	double dmua[NV * NS];
	variants(vs, &ref, dmua);
	struct transport_opts o;
	transport_opts_default(&o);
	struct tally_variants var = { .n = NV, .dmua = dmua };
	struct tally_grid g = { .n_theta = 1, .n_phi = 1, .n_r = NR, .dr = DR, .var = &var };
	struct launch ln;
	transport_launch(&ref, 0.0, o.fresnel, &ln);
	struct tally t;
	tally_alloc(&t, &g);
	transport_run(&ref, &ln, &o, &g, NULL, 7, 0, 0, 20000, &t);
	assert_memory_equal(t.radial, t.radial_var, sizeof(double) * NR);
	double s0 = 0.0, s1 = 0.0;
	for (int i = 0; i < NR; i++) {
		s0 += t.radial_var[i];
		s1 += t.radial_var[3 * NR + i];
	}
	assert_true(s1 > 0.0 && s1 < 0.8 * s0);	/* the absorbing variant keeps less */
	tally_free(&t);
}

/* Mean radius and its error of profile k of w [cm]. */
static void radius(const struct wmc_radial *w, int k, double *m, double *e)
{
	*m = tally_mean_radius(w->rd_r + k * NR, NR, DR);
	*e = tally_mean_radius_err(w->rd_r + k * NR, w->rd_r_err + k * NR, NR, DR);
}

/* Power on bins [i0, i1) of profile k, with its error (bins independent). */
static void ring(const struct wmc_radial *w, int k, int i0, int i1, double *p, double *e)
{
	double v = 0.0;
	*p = 0.0;
	for (int i = i0; i < i1; i++) {
		double a = tally_annulus_area(DR, i);
		*p += w->rd_r[k * NR + i] * a;
		v += pow(w->rd_r_err[k * NR + i] * a, 2);
	}
	*e = sqrt(v);
}

/* The white run, with far roulette beyond far_cm (0: none; engine/transport.h),
 * against plain Monte Carlo without it and adding-doubling. */
static void against_plain_mc_and_ad(double far_cm)
{
	struct slab vs[NV], ref;
	double dmua[NV * NS], zero[NS] = { 0 };
	variants(vs, &ref, dmua);
	struct transport_opts o, of;
	transport_opts_default(&o);
	of = o;
	of.far_cm = far_cm;
	struct wmc_radial w;
	wmc_radial_run(&ref, dmua, NV, 0.0, &of, NR, DR, 64000, 16, 11, 0, 1, &w);
	static const int edges[] = { 0, 2, 5, 10, 20, 40, NR };
	for (int v = 0; v < NV; v++) {
		struct wmc_radial p;
		wmc_radial_run(&vs[v], zero, 1, 0.0, &o, NR, DR, 64000, 16, 12, (uint32_t)(1 + v), 1, &p);
		double m1, e1, m2, e2;
		radius(&w, v, &m1, &e1);
		radius(&p, 0, &m2, &e2);
		printf("# variant %d: mean radius %.5f +- %.5f cm (white) vs %.5f +- %.5f cm (plain)\n", v, m1, e1, m2, e2);
		assert_true(fabs(m1 - m2) <= 4.0 * hypot(e1, e2));
		assert_true(e1 < 0.05 * m1);	/* the comparison means something */
		for (int r = 0; r + 1 < (int)(sizeof edges / sizeof edges[0]); r++) {
			double p1, pe1, p2, pe2;
			ring(&w, v, edges[r], edges[r + 1], &p1, &pe1);
			ring(&p, 0, edges[r], edges[r + 1], &p2, &pe2);
			if (fabs(p1 - p2) > 4.0 * hypot(pe1, pe2))
				fail_msg("variant %d ring %d: %g +- %g vs %g +- %g", v, r, p1, pe1, p2, pe2);
		}
		/* Conservation: the profile's integral is adding-doubling's Rd. */
		struct ad_opts ao;
		struct ad_result ar;
		char *cause = NULL;
		double th = 0.0;
		ad_opts_default(&ao);
		ao.tol = 1e-5;
		if (ad_solve(&vs[v], o.fresnel, &th, 1, &ao, &ar, &cause))
			fail_msg("ad_solve: %s", cause);
		double pi, pie;
		ring(&w, v, 0, NR, &pi, &pie);
		double rd = ar.beam[0].rd.v - ar.beam[0].rd_unscat, tol = 4.0 * pie + ar.beam[0].rd.err + 1e-6;
		printf("# variant %d: integral %.5f +- %.5f, adding-doubling Rd %.5f +- %.1g\n", v, pi, pie, rd,
		    ar.beam[0].rd.err);
		assert_true(fabs(pi - rd) <= tol);
		ad_result_free(&ar);
		wmc_radial_free(&p);
	}
	wmc_radial_free(&w);
}

static void test_against_plain_mc_and_ad(void **state)
{
	(void)state;
	against_plain_mc_and_ad(0.0);
}

/* Far roulette is unbiased: played from 0.08 cm on (3-8 times the variants'
 * mean radii, the far tail of the profile behind it), the white run still
 * agrees with plain Monte Carlo without it and with adding-doubling's Rd. */
static void test_far_roulette_unbiased(void **state)
{
	(void)state;
	against_plain_mc_and_ad(0.08);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_zero_variant_is_the_walk),
		cmocka_unit_test(test_against_plain_mc_and_ad),
		cmocka_unit_test(test_far_roulette_unbiased),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
