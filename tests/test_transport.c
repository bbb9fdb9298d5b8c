/* Transport kernel and simulation driver: hard cases, exact weight
 * bookkeeping, reproducibility across threads, and consistency checks that
 * have a closed form (Fresnel, Beer-Lambert, BRDF integral).  The published
 * and adding-doubling references are in test_refs.c.
 *
 * Statistical comparisons use the run's own standard error (spread between
 * batches) and a fixed seed, so each test is deterministic; a failure at
 * "n sigma" means a real bias unless n is near the limit. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/sim.h"
#include "engine/slab.h"
#include "engine/transport.h"

/* Unpolarized Fresnel reflectance from the trigonometric textbook form (Born
 * & Wolf), independent of optics.c; theta in radians from n1 into n2. */
static double fresnel_trig(double n1, double n2, double th)
{
	if (n1 == n2)
		return 0.0;
	double st = n1 * sin(th) / n2;
	if (st >= 1.0)
		return 1.0;
	if (th == 0.0) {
		double r = (n1 - n2) / (n1 + n2);
		return r * r;
	}
	double tt = asin(st);
	double rs = sin(th - tt) / sin(th + tt), rp = tan(th - tt) / tan(th + tt);
	return 0.5 * (rs * rs + rp * rp);
}

static void cfg_init(struct sim_config *c, double n_above, double n_below, long photons)
{
	sim_config_default(c);
	slab_init(&c->slab, n_above, n_below);
	c->photons = photons;
	c->seed = 20240601;
	c->threads = 0;
}

static void cfg_layer(struct sim_config *c, double d, double n, double mu_a, double mu_s, double g)
{
	struct layer l = { .d = d, .n = n, .mu_a = mu_a, .mu_s = mu_s, .g = g };
	char *cause = NULL;
	if (slab_add(&c->slab, &l, &cause) != 0)
		fail_msg("slab_add: %s", cause);
}

static void cfg_prepare(struct sim_config *c)
{
	char *cause = NULL;
	if (slab_check(&c->slab, &cause) != 0)
		fail_msg("slab_check rejected a valid stack: %s", cause);
	slab_prepare(&c->slab);
}

static int finite_v(struct estimate v)
{
	return isfinite(v.v) && isfinite(v.err) && v.err >= 0.0;
}

static int all_finite(const double *x, int n)
{
	for (int i = 0; i < n; i++)
		if (!isfinite(x[i]))
			return 0;
	return 1;
}

/* What every run must satisfy: finite outputs, fractions in range, and the
 * exact balance Rsp + Rd + Tt + sum(A) + lost = 1 (to 1e-9). */
static void check_run(const char *label, const struct sim_result *r)
{
	print_message("# %-28s Rsp %.6f Rd %.6f+-%.1e Tt %.6f+-%.1e lost %.3g balance %.2e\n", label, r->rsp,
	    r->rd.v, r->rd.err, r->tt.v, r->tt.err, r->lost.v, r->balance);
	if (!(isfinite(r->balance) && fabs(r->balance) < 1e-9))
		fail_msg("%s: balance %g, expected |balance| < 1e-9", label, r->balance);
	if (!(isfinite(r->rsp) && finite_v(r->rd) && finite_v(r->rd_unscat) && finite_v(r->tt)
	    && finite_v(r->tt_unscat) && finite_v(r->lost)))
		fail_msg("%s: a total is not finite", label);
	for (int i = 1; i <= r->n_layers; i++)
		if (!finite_v(r->a[i]))
			fail_msg("%s: A[%d] = %g +- %g is not finite", label, i, r->a[i].v, r->a[i].err);
	const double eps = 1e-12;
	if (!(r->rsp >= 0 && r->rsp <= 1 && r->rd.v >= 0 && r->rd.v <= 1 + eps && r->tt.v >= 0 && r->tt.v <= 1 + eps
	    && r->lost.v >= 0 && r->lost.v <= 1 + eps))
		fail_msg("%s: a fraction is outside [0, 1]", label);
	if (!(r->rd_unscat.v <= r->rd.v + eps && r->tt_unscat.v <= r->tt.v + eps))
		fail_msg("%s: unscattered part exceeds its total", label);
	int ne = r->grid.n_theta * r->grid.n_phi;
	if (!all_finite(r->fr, ne) || !all_finite(r->fr_err, ne) || !all_finite(r->fr_az, r->grid.n_theta)
	    || !all_finite(r->fr_az_err, r->grid.n_theta))
		fail_msg("%s: BRDF not finite", label);
	if (r->grid.n_r > 0 && (!all_finite(r->rd_r, r->grid.n_r) || !all_finite(r->rd_r_err, r->grid.n_r)))
		fail_msg("%s: Rd(r) not finite", label);
}

static void run(const char *label, const struct sim_config *c, struct sim_result *r)
{
	sim_run(c, r, NULL, NULL);
	check_run(label, r);
}

/* |a - b| <= k sigma with sigma = sqrt(ea^2 + eb^2) (+ an absolute floor). */
static void expect_close(const char *label, double a, double ea, double b, double eb, double k, double floor)
{
	double s = sqrt(ea * ea + eb * eb);
	double d = fabs(a - b);
	print_message("# %-40s %.7f vs %.7f  diff %.2e = %.2f sigma\n", label, a, b, a - b, s > 0 ? d / s : 0.0);
	if (!(d <= k * s + floor))
		fail_msg("%s: %.7f vs %.7f differ by %.3g > %g sigma (sigma %.3g, floor %g)", label, a, b, d, k, s, floor);
}

static double sum_a(const struct sim_result *r)
{
	double s = 0.0;
	for (int i = 0; i <= r->n_layers + 1; i++)
		s += r->a[i].v;
	return s;
}

/* ---- hard cases ----------------------------------------------------- */

static void test_hard_g(void **state)
{
	(void)state;
	const double gs[] = { 0.9999, -0.9999, 0.0, 1e-9, -1e-9 };
	for (size_t k = 0; k < sizeof gs / sizeof gs[0]; k++) {
		struct sim_config c;
		struct sim_result r;
		char label[64];
		cfg_init(&c, 1.0, 1.0, 40000);
		cfg_layer(&c, 0.1, 1.4, 1.0, 100.0, gs[k]);
		cfg_prepare(&c);
		snprintf(label, sizeof label, "g = %g", gs[k]);
		run(label, &c, &r);
		assert_true(r.lost.v == 0.0);
		assert_true(r.rd.v > 0.0 && r.tt.v > 0.0 && r.a[1].v > 0.0);
		if (gs[k] > 0.99)
			assert_true(r.tt.v > r.rd.v);	/* forward peaked: most goes through */
		if (gs[k] < -0.99)
			assert_true(r.rd.v > r.tt.v);	/* backward peaked: most comes back */
		sim_result_free(&r);
	}
	/* g = 0 and g = +-1e-9 must agree (same seed, nearly the same walks). */
	double rd[3];
	const double g0[] = { 0.0, 1e-9, -1e-9 };
	for (int k = 0; k < 3; k++) {
		struct sim_config c;
		struct sim_result r;
		cfg_init(&c, 1.0, 1.0, 40000);
		cfg_layer(&c, 0.1, 1.4, 1.0, 100.0, g0[k]);
		cfg_prepare(&c);
		run(k == 0 ? "g = 0 (again)" : k == 1 ? "g = 1e-9 (again)" : "g = -1e-9 (again)", &c, &r);
		rd[k] = r.rd.v;
		if (k > 0)
			expect_close("Rd g=+-1e-9 vs g=0", rd[k], r.rd.err, rd[0], 0.0, 1.0, 1e-12);
		sim_result_free(&r);
	}
}

/* Without absorption nothing is absorbed and roulette never plays (weight
 * never drops).  In a finite slab every photon leaves through a face: the
 * walk ends with probability 1 after ~tau^2 steps.  In a semi-infinite
 * non-absorbing medium the depth is a recurrent random walk: each photon
 * returns to the surface with probability 1, but the expected number of steps
 * is infinite (P(no return after N steps) ~ N^-1/2), so the max_steps guard is
 * what bounds the run; the photons it ends are booked as `lost`. */
static void test_hard_no_absorption(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result r;
	cfg_init(&c, 1.0, 1.0, 20000);
	cfg_layer(&c, 0.1, 1.4, 0.0, 100.0, 0.9);
	cfg_prepare(&c);
	run("mua = 0, finite slab", &c, &r);
	assert_true(r.lost.v == 0.0);
	assert_true(sum_a(&r) == 0.0);
	assert_float_equal(r.rsp + r.rd.v + r.tt.v, 1.0, 1e-12);
	sim_result_free(&r);

	cfg_init(&c, 1.0, 1.4, 10000);
	cfg_layer(&c, INFINITY, 1.4, 0.0, 100.0, 0.0);
	cfg_prepare(&c);
	c.opts.max_steps = 100000;
	run("mua = 0, semi-infinite", &c, &r);
	assert_true(sum_a(&r) == 0.0);
	assert_true(r.tt.v == 0.0);
	assert_float_equal(r.rsp + r.rd.v + r.lost.v, 1.0, 1e-12);
	/* The guard ends a few photons, ~ N^-1/2 = 0.3 % of them. */
	assert_true(r.lost.v > 0.0 && r.lost.v < 0.02);
	sim_result_free(&r);
}

static void test_hard_coefficients(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result r;

	/* mu_a = 1e4: absorbed at the first interaction, ~1 % of weight scatters. */
	cfg_init(&c, 1.0, 1.0, 20000);
	cfg_layer(&c, 0.1, 1.4, 1e4, 100.0, 0.8);
	cfg_prepare(&c);
	run("mua = 1e4", &c, &r);
	assert_true(r.tt.v == 0.0 || r.tt.v < 1e-6);
	assert_true(r.a[1].v > 0.97 * (1.0 - r.rsp));
	sim_result_free(&r);

	/* d = 1e-7 cm: optically negligible; the slab acts as a lossless film
	 * with incoherent reflections: T = (1 - r) / (1 + r). */
	cfg_init(&c, 1.0, 1.0, 100000);
	cfg_layer(&c, 1e-7, 1.4, 10.0, 100.0, 0.9);
	cfg_prepare(&c);
	run("d = 1e-7", &c, &r);
	double r0 = fresnel_trig(1.0, 1.4, 0.0);
	expect_close("d = 1e-7: Tt vs (1-r)/(1+r)", r.tt.v, r.tt.err, (1 - r0) / (1 + r0), 0.0, 4.0, 2e-5);
	assert_true(r.a[1].v < 1e-4);
	sim_result_free(&r);

	/* d = inf: nothing transmitted. */
	cfg_init(&c, 1.0, 1.4, 10000);
	cfg_layer(&c, INFINITY, 1.4, 1.0, 100.0, 0.9);
	cfg_prepare(&c);
	run("d = inf", &c, &r);
	assert_true(r.tt.v == 0.0 && r.lost.v == 0.0);
	assert_float_equal(r.rsp + r.rd.v + r.a[1].v, 1.0, 1e-9);
	sim_result_free(&r);
}

/* mu_s = 0: only unscattered light, so the slab obeys the incoherent
 * thick-plate formulas with t = exp(-mua d) and the normal-incidence Fresnel r:
 *   T = (1-r)^2 t / (1 - r^2 t^2),  R - r = (1-r)^2 r t^2 / (1 - r^2 t^2). */
static void test_hard_no_scattering(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result r;
	cfg_init(&c, 1.0, 1.0, 400000);
	cfg_layer(&c, 0.1, 1.4, 10.0, 0.0, 0.0);
	cfg_prepare(&c);
	run("mus = 0", &c, &r);
	double r0 = fresnel_trig(1.0, 1.4, 0.0), t = exp(-1.0);
	double T = (1 - r0) * (1 - r0) * t / (1 - r0 * r0 * t * t);
	double R = (1 - r0) * (1 - r0) * r0 * t * t / (1 - r0 * r0 * t * t);
	assert_float_equal(r.rsp, r0, 1e-15);
	expect_close("mus = 0: Tt vs plate formula", r.tt.v, r.tt.err, T, 0.0, 4.0, 0.0);
	expect_close("mus = 0: Rd vs plate formula", r.rd.v, r.rd.err, R, 0.0, 4.0, 0.0);
	assert_true(r.tt_unscat.v == r.tt.v && r.rd_unscat.v == r.rd.v);
	assert_true(r.events == 0.0);
	for (int i = 0; i < r.grid.n_theta; i++)
		assert_true(r.fr_az[i] == 0.0);
	sim_result_free(&r);
}

static void test_hard_indices(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result r;

	/* All indices equal: no boundary reflects, so nothing unscattered comes back. */
	cfg_init(&c, 1.4, 1.4, 40000);
	cfg_layer(&c, 0.05, 1.4, 5.0, 100.0, 0.8);
	cfg_layer(&c, 0.05, 1.4, 1.0, 50.0, 0.5);
	cfg_prepare(&c);
	c.theta_in = 30.0 * M_PI / 180.0;
	run("all indices 1.4", &c, &r);
	assert_true(r.rsp == 0.0);
	assert_true(r.rd_unscat.v == 0.0);
	/* Unscattered transmission is Beer-Lambert along the slanted path. */
	double tu = exp(-(105.0 * 0.05 + 51.0 * 0.05) / cos(c.theta_in));
	expect_close("equal n: Tt unscattered vs exp(-tau/cos)", r.tt_unscat.v, r.tt_unscat.err, tu, 0.0, 4.0, 1e-6);
	sim_result_free(&r);

	/* n = 2.5, theta_in = 89.9 deg: nearly everything is reflected specularly. */
	cfg_init(&c, 1.0, 1.0, 40000);
	cfg_layer(&c, 0.1, 2.5, 1.0, 100.0, 0.9);
	cfg_prepare(&c);
	c.theta_in = 89.9 * M_PI / 180.0;
	run("n = 2.5, theta_in = 89.9", &c, &r);
	assert_float_equal(r.rsp, fresnel_trig(1.0, 2.5, c.theta_in), 1e-12);
	assert_true(r.rsp > 0.98);
	sim_result_free(&r);

	/* A denser ambient beyond its critical angle reflects everything. */
	cfg_init(&c, 1.5, 1.0, 1000);
	cfg_layer(&c, 0.1, 1.0, 1.0, 100.0, 0.9);
	cfg_prepare(&c);
	c.theta_in = 60.0 * M_PI / 180.0;
	run("n_above 1.5 > n 1.0 at 60 deg", &c, &r);
	assert_true(r.rsp == 1.0 && r.rd.v == 0.0 && r.tt.v == 0.0);
	sim_result_free(&r);
}

static void test_hard_16_layers(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result r;
	cfg_init(&c, 1.0, 1.33, 20000);
	for (int i = 0; i < SLAB_MAX_LAYERS; i++) {
		/* Alternate indices, a clear layer and a non-absorbing one among them. */
		double n = 1.33 + 0.02 * (i % 5);
		if (i == 3)
			cfg_layer(&c, 0.002, 1.5, 0.0, 0.0, 0.0);
		else if (i == 7)
			cfg_layer(&c, 0.01, n, 0.0, 200.0, 0.9);
		else
			cfg_layer(&c, 0.005 + 0.001 * i, n, 1.0 + i, 100.0 + 10 * i, 0.7 + 0.01 * i);
	}
	cfg_prepare(&c);
	c.theta_in = 45.0 * M_PI / 180.0;
	run("16 layers", &c, &r);
	assert_int_equal(r.n_layers, 16);
	for (int i = 1; i <= 16; i++) {
		if (i == 4 || i == 8) {
			/* No absorption here; roulette's zero-mean booking may show. */
			if (fabs(r.a[i].v) > 3.0 * r.a[i].err + 1e-12)
				fail_msg("non-absorbing layer %d has A = %g +- %g", i, r.a[i].v, r.a[i].err);
		} else if (!(r.a[i].v > 0.0))
			fail_msg("layer %d absorbs nothing", i);
	}
	sim_result_free(&r);

	/* A 17th layer is refused with a message. */
	struct layer l = { .d = 0.1, .n = 1.4, .mu_a = 1, .mu_s = 1, .g = 0 };
	char *cause = NULL;
	assert_int_equal(slab_add(&c.slab, &l, &cause), -1);
	assert_non_null(cause);
	assert_non_null(strstr(cause, "16"));
	free(cause);
}

/* Guards and roulette settings change the walk, never the bookkeeping. */
static void test_guards_and_roulette(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result r, r2;
	cfg_init(&c, 1.0, 1.0, 20000);
	cfg_layer(&c, 0.1, 1.4, 1.0, 100.0, 0.9);
	cfg_prepare(&c);
	c.opts.max_steps = 3;
	run("max_steps = 3", &c, &r);
	assert_true(r.lost.v > 0.1);
	sim_result_free(&r);

	/* Heavy roulette (threshold 0.5) stays unbiased: same A, Rd, Tt as MCML's light one. */
	cfg_init(&c, 1.0, 1.0, 100000);
	cfg_layer(&c, 0.05, 1.4, 10.0, 90.0, 0.75);
	cfg_prepare(&c);
	c.opts.roulette_w = 1e-4;	/* MCML's */
	c.opts.roulette_chance = 0.1;
	run("roulette w 1e-4 chance 0.1", &c, &r);
	c.opts.roulette_w = 0.5;
	c.opts.roulette_chance = 0.3;
	c.seed++;
	run("roulette w 0.5 chance 0.3", &c, &r2);
	expect_close("roulette: A", r2.a[1].v, r2.a[1].err, r.a[1].v, r.a[1].err, 4.0, 0.0);
	expect_close("roulette: Rd", r2.rd.v, r2.rd.err, r.rd.v, r.rd.err, 4.0, 0.0);
	expect_close("roulette: Tt", r2.tt.v, r2.tt.err, r.tt.v, r.tt.err, 4.0, 0.0);
	sim_result_free(&r);
	sim_result_free(&r2);

	/* Schlick's model: still balanced, Rsp = R0 at normal incidence. */
	cfg_init(&c, 1.0, 1.0, 20000);
	cfg_layer(&c, 0.05, 1.4, 10.0, 90.0, 0.75);
	cfg_prepare(&c);
	c.opts.fresnel = OPTICS_FRESNEL_SCHLICK;
	run("schlick", &c, &r);
	assert_float_equal(r.rsp, fresnel_trig(1.0, 1.4, 0.0), 1e-15);
	sim_result_free(&r);
}

/* ---- bookkeeping, reproducibility ----------------------------------- */

static int same_bits(const void *a, const void *b, size_t n)
{
	return memcmp(a, b, n) == 0;
}

static int same_result(const struct sim_result *a, const struct sim_result *b)
{
	int ne = a->grid.n_theta * a->grid.n_phi, nt = a->grid.n_theta, nr = a->grid.n_r;
	return a->photons == b->photons && same_bits(&a->events, &b->events, sizeof a->events)
	    && same_bits(&a->rsp, &b->rsp, sizeof a->rsp) && same_bits(&a->rd, &b->rd, sizeof a->rd)
	    && same_bits(&a->rd_unscat, &b->rd_unscat, sizeof a->rd_unscat)
	    && same_bits(&a->tt, &b->tt, sizeof a->tt) && same_bits(&a->tt_unscat, &b->tt_unscat, sizeof a->tt_unscat)
	    && same_bits(&a->lost, &b->lost, sizeof a->lost) && same_bits(a->a, b->a, sizeof a->a)
	    && same_bits(&a->balance, &b->balance, sizeof a->balance)
	    && same_bits(a->fr, b->fr, sizeof(double) * (size_t)ne)
	    && same_bits(a->fr_err, b->fr_err, sizeof(double) * (size_t)ne)
	    && same_bits(a->fr_az, b->fr_az, sizeof(double) * (size_t)nt)
	    && same_bits(a->fr_az_err, b->fr_az_err, sizeof(double) * (size_t)nt)
	    && same_bits(a->rd_r, b->rd_r, sizeof(double) * (size_t)nr)
	    && same_bits(a->rd_r_err, b->rd_r_err, sizeof(double) * (size_t)nr);
}

/* The skin stack of the references at 550 nm, oblique. */
static void skin_config(struct sim_config *c, long photons)
{
	cfg_init(c, 1.0, 1.4, photons);
	cfg_layer(c, 0.001, 1.5, 0.0, 0.0, 0.0);
	cfg_layer(c, 0.01, 1.4, 50.0, 370.0, 0.8);
	cfg_layer(c, 0.25, 1.4, 7.0, 370.0, 0.8);
	cfg_prepare(c);
	c->theta_in = 30.0 * M_PI / 180.0;
}

static void test_threads_bit_identical(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result r[3];
	skin_config(&c, 20000);
	for (int k = 0; k < 3; k++) {
		c.threads = k + 1;
		run(k == 0 ? "1 thread" : k == 1 ? "2 threads" : "3 threads", &c, &r[k]);
	}
	assert_true(same_result(&r[0], &r[1]));
	assert_true(same_result(&r[0], &r[2]));
	/* A different seed or stream must change the tallies. */
	struct sim_result o;
	c.threads = 0;
	c.seed++;
	run("another seed", &c, &o);
	assert_false(o.rd.v == r[0].rd.v);
	sim_result_free(&o);
	c.seed--;
	c.stream = 7;
	run("another stream", &c, &o);
	assert_false(o.rd.v == r[0].rd.v);
	sim_result_free(&o);
	for (int k = 0; k < 3; k++)
		sim_result_free(&r[k]);
}

/* Photon i draws only from counter (seed, stream, i): a different split into
 * batches sums the same photons, equal up to summation order. */
static void test_batches_same_photons(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result a, b;
	skin_config(&c, 20000);
	run("32 batches", &c, &a);
	c.batches = 7;
	run("7 batches", &c, &b);
	assert_float_equal(a.rd.v, b.rd.v, 1e-12);
	assert_float_equal(a.tt.v, b.tt.v, 1e-12);
	assert_float_equal(a.a[2].v, b.a[2].v, 1e-12);
	assert_float_equal(a.events, b.events, 0.0);
	sim_result_free(&a);
	sim_result_free(&b);
}

/* ---- consistency with closed forms ---------------------------------- */

/* Splitting a layer into two identical halves changes nothing but rounding
 * (the index-matched interface draws no random number). */
static void test_split_layer(void **state)
{
	(void)state;
	struct sim_config c;
	struct sim_result a, b;
	cfg_init(&c, 1.0, 1.0, 100000);
	cfg_layer(&c, 0.02, 1.4, 10.0, 90.0, 0.75);
	cfg_prepare(&c);
	run("one layer", &c, &a);
	cfg_init(&c, 1.0, 1.0, 100000);
	cfg_layer(&c, 0.01, 1.4, 10.0, 90.0, 0.75);
	cfg_layer(&c, 0.01, 1.4, 10.0, 90.0, 0.75);
	cfg_prepare(&c);
	run("two halves", &c, &b);
	expect_close("split: Rd", b.rd.v, b.rd.err, a.rd.v, a.rd.err, 4.0, 0.0);
	expect_close("split: Tt", b.tt.v, b.tt.err, a.tt.v, a.tt.err, 4.0, 0.0);
	expect_close("split: A1 + A2 vs A", b.a[1].v + b.a[2].v, hypot(b.a[1].err, b.a[2].err), a.a[1].v,
	    a.a[1].err, 4.0, 0.0);
	/* The top half absorbs more than the bottom one. */
	assert_true(b.a[1].v > b.a[2].v);
	sim_result_free(&a);
	sim_result_free(&b);
}

/* Index-matched absorbing slab without scattering: each photon either goes
 * through (probability exp(-mua d / cos theta)) or is absorbed. */
static void test_beer_lambert(void **state)
{
	(void)state;
	const double th[] = { 0.0, 45.0, 75.0 };
	for (int k = 0; k < 3; k++) {
		struct sim_config c;
		struct sim_result r;
		cfg_init(&c, 1.0, 1.0, 400000);
		cfg_layer(&c, 0.1, 1.0, 10.0, 0.0, 0.0);
		cfg_prepare(&c);
		c.theta_in = th[k] * M_PI / 180.0;
		c.stream = (uint32_t)k;	/* independent photons per angle */
		run("beer-lambert", &c, &r);
		double p = exp(-1.0 / cos(c.theta_in));
		double se = sqrt(p * (1 - p) / c.photons);
		expect_close("Tt vs exp(-mua d / cos)", r.tt.v, r.tt.err, p, 0.0, 4.0, 0.0);
		/* The batch error estimates the binomial one (31 dof: within ~50 %). */
		assert_true(r.tt.err > 0.5 * se && r.tt.err < 1.5 * se);
		assert_true(r.rsp == 0.0 && r.rd.v == 0.0 && r.tt_unscat.v == r.tt.v);
		assert_float_equal(r.a[1].v, 1.0 - r.tt.v, 1e-12);
		sim_result_free(&r);
	}
	/* Refraction at entry: n 1.4 slab under air, index-matched below, at 60 deg:
	 * T = (1 - R(60)) exp(-mua d / cos theta_t). */
	struct sim_config c;
	struct sim_result r;
	cfg_init(&c, 1.0, 1.4, 400000);
	cfg_layer(&c, 0.1, 1.4, 10.0, 0.0, 0.0);
	cfg_prepare(&c);
	c.theta_in = 60.0 * M_PI / 180.0;
	run("beer-lambert refracted", &c, &r);
	double tht = asin(sin(c.theta_in) / 1.4);
	double T = (1 - fresnel_trig(1.0, 1.4, c.theta_in)) * exp(-1.0 / cos(tht));
	expect_close("Tt vs (1-R) exp(-mua d / cos theta_t)", r.tt.v, r.tt.err, T, 0.0, 4.0, 0.0);
	assert_true(r.rd.v == 0.0);
	sim_result_free(&r);
}

/* Specular reflectance at oblique incidence is the exact Fresnel value,
 * including the incoherent multiple reflections in a clear top film. */
static void test_oblique_rsp(void **state)
{
	(void)state;
	const double th[] = { 0.0, 30.0, 60.0, 80.0, 89.0 };
	for (int k = 0; k < 5; k++) {
		struct sim_config c;
		struct launch ln;
		double t = th[k] * M_PI / 180.0;
		cfg_init(&c, 1.0, 1.0, 1000);
		cfg_layer(&c, 0.1, 1.4, 1.0, 100.0, 0.9);
		cfg_prepare(&c);
		transport_launch(&c.slab, t, OPTICS_FRESNEL_EXACT, &ln);
		double ref = fresnel_trig(1.0, 1.4, t);
		print_message("# theta %4.1f: Rsp %.12f, Fresnel %.12f\n", th[k], ln.rsp, ref);
		assert_float_equal(ln.rsp, ref, 1e-12);
		assert_float_equal(ln.w0, 1.0 - ref, 1e-12);
		/* Snell: entry direction inside the slab. */
		assert_float_equal(ln.ux, sin(t) / 1.4, 1e-12);
		assert_float_equal(ln.ux * ln.ux + ln.uz * ln.uz, 1.0, 1e-12);

		/* Clear sebum film (n 1.5) on top. */
		cfg_init(&c, 1.0, 1.0, 1000);
		cfg_layer(&c, 0.001, 1.5, 0.0, 0.0, 0.0);
		cfg_layer(&c, 0.1, 1.4, 1.0, 100.0, 0.9);
		cfg_prepare(&c);
		transport_launch(&c.slab, t, OPTICS_FRESNEL_EXACT, &ln);
		double r1 = fresnel_trig(1.0, 1.5, t), r2 = fresnel_trig(1.5, 1.4, asin(sin(t) / 1.5));
		double rs = (r1 + r2 - 2 * r1 * r2) / (1 - r1 * r2);
		print_message("# theta %4.1f with sebum: Rsp %.12f, composite %.12f\n", th[k], ln.rsp, rs);
		assert_float_equal(ln.rsp, rs, 1e-12);
		if (k == 0)
			assert_float_equal(ln.rsp, 0.041096, 5e-7);	/* refs README */
		assert_int_equal(ln.layer, 2);
		assert_float_equal(ln.ux, sin(t) / 1.4, 1e-12);
	}
	/* The run reports the launch's Rsp. */
	struct sim_config c;
	struct sim_result r;
	cfg_init(&c, 1.0, 1.0, 2000);
	cfg_layer(&c, 0.1, 1.4, 1.0, 100.0, 0.9);
	cfg_prepare(&c);
	c.theta_in = 60.0 * M_PI / 180.0;
	run("theta_in 60", &c, &r);
	assert_float_equal(r.rsp, fresnel_trig(1.0, 1.4, c.theta_in), 1e-12);
	sim_result_free(&r);

	/* An all-clear stack transmits what it does not reflect. */
	cfg_init(&c, 1.0, 1.0, 100);
	cfg_layer(&c, 0.01, 1.5, 0.0, 0.0, 0.0);
	cfg_prepare(&c);
	c.theta_in = 40.0 * M_PI / 180.0;
	run("all clear", &c, &r);
	double r1 = fresnel_trig(1.0, 1.5, c.theta_in);
	assert_float_equal(r.rsp, 2 * r1 / (1 + r1), 1e-12);
	assert_float_equal(r.tt.v, (1 - r1) / (1 + r1), 1e-12);
	assert_true(r.rd.v == 0.0 && r.tt_unscat.v == r.tt.v);
	sim_result_free(&r);
}

/* The azimuth-averaged BRDF integrated over its theta_out bands (and the full
 * BRDF over its bins) gives back the scattered diffuse reflectance. */
static void test_brdf_integral(void **state)
{
	(void)state;
	const double th[] = { 0.0, 50.0 };
	for (int k = 0; k < 2; k++) {
		struct sim_config c;
		struct sim_result r;
		skin_config(&c, 20000);
		c.theta_in = th[k] * M_PI / 180.0;
		c.grid.n_theta = 9;
		c.grid.n_phi = 12;
		c.grid.n_r = 400;
		c.grid.dr = 0.01;
		run("brdf integral", &c, &r);
		int nt = c.grid.n_theta, np = c.grid.n_phi;
		double dth = 0.5 * M_PI / nt, dph = M_PI / np, s_az = 0.0, s_full = 0.0, s_r = 0.0;
		for (int i = 0; i < nt; i++) {
			s_az += r.fr_az[i] * sim_cos_solid_angle(i * dth, (i + 1) * dth, M_PI);
			for (int j = 0; j < np; j++)
				s_full += r.fr[i * np + j] * sim_cos_solid_angle(i * dth, (i + 1) * dth, dph);
		}
		for (int i = 0; i < c.grid.n_r; i++)
			s_r += r.rd_r[i] * M_PI * c.grid.dr * c.grid.dr * (2 * i + 1);
		double diffuse = r.rd.v - r.rd_unscat.v;
		print_message("# theta_in %g: Rd - Rd_unscat %.12f, sum fr_az %.12f, sum fr %.12f, sum Rd(r) %.12f\n",
		    th[k], diffuse, s_az, s_full, s_r);
		assert_float_equal(s_az, diffuse, 1e-12);
		assert_float_equal(s_full, diffuse, 1e-12);
		/* Rd(r) covers 4 cm: all but a sliver of the diffuse light. */
		assert_true(s_r <= diffuse + 1e-12 && s_r > 0.99 * diffuse);
		/* The cos-solid-angle of the hemisphere is pi. */
		assert_float_equal(sim_cos_solid_angle(0, M_PI / 2, M_PI), M_PI, 1e-14);
		sim_result_free(&r);
	}
}

/* Gauss-Legendre nodes and weights on [a, b] (Newton on P_n). */
static void gauss_legendre(int n, double a, double b, double *x, double *w)
{
	for (int i = 0; i < n; i++) {
		double z = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
		for (int it = 0; it < 100; it++) {
			double p0 = 1.0, p1 = z;
			for (int k = 2; k <= n; k++) {
				double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
				p0 = p1;
				p1 = p2;
			}
			dp = n * (z * p1 - p0) / (z * z - 1.0);
			double dz = p1 / dp;
			z -= dz;
			if (fabs(dz) < 1e-16)
				break;
		}
		x[i] = 0.5 * (a + b) + 0.5 * (b - a) * z;
		w[i] = (b - a) / ((1.0 - z * z) * dp * dp);
	}
}

/* Chandrasekhar's H function for isotropic scattering with albedo om, in the
 * form 1/H(mu) = sqrt(1 - om) + (om/2) int_0^1 mu' H(mu') / (mu + mu') dmu'
 * (Radiative Transfer, 1950, ch. V), solved by iteration on Gauss nodes. */
enum { HN = 96 };
struct hfun {
	double om, x[HN], w[HN], h[HN];
};

static double h_eval(const struct hfun *H, double mu)
{
	double s = 0.0;
	for (int j = 0; j < HN; j++)
		s += H->w[j] * H->x[j] * H->h[j] / (mu + H->x[j]);
	return 1.0 / (sqrt(1.0 - H->om) + 0.5 * H->om * s);
}

static void h_solve(struct hfun *H, double om)
{
	H->om = om;
	gauss_legendre(HN, 0.0, 1.0, H->x, H->w);
	for (int j = 0; j < HN; j++)
		H->h[j] = 1.0;
	for (int it = 0; it < 2000; it++) {
		double nh[HN], d = 0.0;
		for (int i = 0; i < HN; i++) {
			nh[i] = h_eval(H, H->x[i]);
			d = fmax(d, fabs(nh[i] - H->h[i]));
		}
		memcpy(H->h, nh, sizeof nh);
		if (d < 1e-15)
			break;
	}
}

/* The angular shape of the BRDF against an exact result: a semi-infinite,
 * index-matched, isotropically scattering medium reflects
 *   fr(mu, mu0) = om H(mu) H(mu0) / (4 pi (mu + mu0)),
 * so Rd(mu0) = 1 - sqrt(1 - om) H(mu0) (Chandrasekhar).  Each theta_out band's
 * azimuthal mean must match the band average of fr, at normal and oblique
 * incidence. */
static void test_brdf_chandrasekhar(void **state)
{
	(void)state;
	static struct hfun H;
	h_solve(&H, 0.9);
	/* The solver against the adding-doubling value for this medium (refs). */
	assert_float_equal(1.0 - sqrt(0.1) * h_eval(&H, 1.0), 0.414947, 2e-6);
	const double th[] = { 0.0, 60.0 };
	for (int k = 0; k < 2; k++) {
		struct sim_config c;
		struct sim_result r;
		cfg_init(&c, 1.0, 1.0, 400000);
		cfg_layer(&c, INFINITY, 1.0, 10.0, 90.0, 0.0);
		cfg_prepare(&c);
		c.theta_in = th[k] * M_PI / 180.0;
		c.grid.n_r = 0;
		c.stream = 11 + (uint32_t)k;
		run(k ? "isotropic half space, 60 deg" : "isotropic half space, 0 deg", &c, &r);
		double mu0 = cos(c.theta_in), h0 = h_eval(&H, mu0);
		expect_close("Rd vs 1 - sqrt(1-om) H(mu0)", r.rd.v, r.rd.err, 1.0 - sqrt(0.1) * h0, 0.0, 4.0, 0.0);
		int nt = c.grid.n_theta;
		double dth = 0.5 * M_PI / nt;
		for (int i = 0; i < nt; i++) {
			/* Band average: int fr mu dOmega / int mu dOmega over the band. */
			double x[16], w[16], num = 0.0;
			gauss_legendre(16, cos((i + 1) * dth), cos(i * dth), x, w);
			for (int q = 0; q < 16; q++)
				num += w[q] * 2.0 * M_PI * x[q] * 0.9 * h_eval(&H, x[q]) * h0 / (4.0 * M_PI * (x[q] + mu0));
			double ref = num / sim_cos_solid_angle(i * dth, (i + 1) * dth, M_PI);
			char label[64];
			snprintf(label, sizeof label, "theta_in %g, band %d-%d deg", th[k], 5 * i, 5 * i + 5);
			expect_close(label, r.fr_az[i], r.fr_az_err[i], ref, 0.0, 4.0, 0.0);
		}
		sim_result_free(&r);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_hard_g),
		cmocka_unit_test(test_hard_no_absorption),
		cmocka_unit_test(test_hard_coefficients),
		cmocka_unit_test(test_hard_no_scattering),
		cmocka_unit_test(test_hard_indices),
		cmocka_unit_test(test_hard_16_layers),
		cmocka_unit_test(test_guards_and_roulette),
		cmocka_unit_test(test_threads_bit_identical),
		cmocka_unit_test(test_batches_same_photons),
		cmocka_unit_test(test_split_layer),
		cmocka_unit_test(test_beer_lambert),
		cmocka_unit_test(test_oblique_rsp),
		cmocka_unit_test(test_brdf_integral),
		cmocka_unit_test(test_brdf_chandrasekhar),
	};
	return cmocka_run_group_tests_name("transport", tests, NULL, NULL);
}
