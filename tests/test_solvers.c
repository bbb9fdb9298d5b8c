/* The bake's two methods against each other and the tools around them:
 *   - an adding-doubling bake and a Monte Carlo bake of `paper` (3
 *     wavelengths x 2 angles, 6 x 4 bins) agree cell by cell within their
 *     combined error;
 *   - adding-doubling bakes are bit-identical over thread counts and give
 *     the Monte Carlo's meanings (albedo = the table's integral, energy);
 *   - a target error of 0.05 costs far fewer photons than 0.01 (no floor:
 *     the first round is sized from the target), and the sized rounds stay
 *     bit-identical over thread counts;
 *   - `verify` passes on a good bake of either method and fails on the
 *     same table scaled by 1.1.
 * Fixed seeds.  Cost: about 12 s of CPU (mostly the Monte Carlo). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bake/bake.h"
#include "bake/bakefile.h"
#include "bake/verify.h"
#include "engine/sim.h"
#include "skin/preset.h"
#include "base/util.h"

/* `paper` at its three wavelengths, incidence 0 and 40 degrees, 6 x 4 bins. */
static void paper_spec(struct bake_spec *s, int method)
{
	memset(s, 0, sizeof *s);
	double th[2] = { 0.0, 40.0 };
	bake_spec_axes(s, NULL, 0, th, 2, 0);
	s->n_to = 6;
	s->n_phi = 4;
	s->n_r = 20;
	s->dr = 0.01;
	transport_opts_default(&s->opts);
	s->method = method;
	s->bin_means = 1;	/* the methods compared bin by bin */
	s->seed = 5;
	s->batch_photons = 1000;
	s->min_batches = 8;
	s->max_photons = 6L * 32 * 1000;	/* 32 batches per job */
	s->nee = 1;
	s->radial_error = 0.2;	/* the pilot's 1024 photons per wavelength do */
	s->n_ranks = 1;
	char *cause = NULL;
	struct skin_params *p = bake_spec_preset(s, "paper", NULL, &cause);
	if (p == NULL)
		fail_msg("%s", cause);
	preset_free(p);
	assert_int_equal(s->n_wl, 3);
}

static void write_bake(const char *dir, const struct bake_spec *s, const struct bake_result *r)
{
	static const double m[9] = { 0, 0, 1, 0, 1, 0, 1, 0, 0 };
	struct bake_meta meta = { .preset = "paper", .ior = 1.5, .roughness = 0.3, .rgb_from_wl = m };
	char *cause = NULL;
	if (bake_write(dir, s, r, &meta, &cause) != 0)
		fail_msg("%s", cause);
}

static void rm_rf(const char *dir)
{
	char *cmd = xasprintf("rm -rf '%s'", dir);
	assert_int_equal(system(cmd), 0);
	free(cmd);
}

/* Every bin: z = (f_ad - f_mc) / sqrt(e_ad^2 + e_mc^2).  The Monte Carlo
 * error comes from 32 batches, so z follows Student's t with 31 degrees
 * of freedom (the adding-doubling error is at most 0.3 of it, a tenth of
 * the variance, asserted; 0.18 here): E z^2 = 31/29 and
 * Var z^2 = 3 nu^2 / ((nu - 2)(nu - 4)) - (nu / (nu - 2))^2 = 2.54.  The
 * mean over the n bins is allowed 4 of its standard deviations sqrt(2.54 /
 * n) either way (bins of one job share photons, which widens the spread a
 * little), and no bin beyond |t| = 5 (P = 2e-5 per bin). */
static void test_ad_agrees_with_mc(void **state)
{
	(void)state;
	static struct bake_spec a, m;
	paper_spec(&a, solvers_index("ad"));
	paper_spec(&m, solvers_index("mc"));
	struct bake_result ra, rm;
	char *cause = NULL;
	if (bake_run(&a, &ra, &cause) != 0)
		fail_msg("%s", cause);
	assert_int_equal(bake_run(&m, &rm, &cause), 0);
	assert_string_equal(ra.solver, "ad");
	assert_string_equal(rm.solver, "mc");
	double z2 = 0.0, zmax = 0.0, rq = 0.0;
	int n = 0;
	for (int j = 0; j < 6; j++) {
		const struct brdf_entry *x = &ra.table.entry[j], *y = &rm.table.entry[j];
		assert_string_equal(x->method, "ad");
		assert_int_equal(y->batches, 32);
		for (int k = 0; k < 24; k++) {
			double z = (x->fr[k] - y->fr[k]) / sqrt(x->fr_err[k] * x->fr_err[k] + y->fr_err[k] * y->fr_err[k]);
			z2 += z * z;
			zmax = fmax(zmax, fabs(z));
			n++;
			rq = fmax(rq, x->fr_err[k] / y->fr_err[k]);
		}
		/* The same totals: albedo (scattered return), Rsp exact. */
		assert_float_equal(x->rsp, y->rsp, 1e-12);
		assert_true(fabs(x->albedo.v - y->albedo.v) < 4.0 * hypot(x->albedo.err, y->albedo.err));
		/* The albedo is the table's integral, as for the Monte Carlo (to the
		 * solver's accuracy: its bins and totals come from one solution). */
		double integ = 0.0;
		for (int it = 0; it < 6; it++)
			for (int ip = 0; ip < 4; ip++)
				integ += x->fr[it * 4 + ip] * sim_cos_solid_angle(it * M_PI / 12, (it + 1) * M_PI / 12, M_PI / 4);
		assert_true(fabs(integ - x->albedo.v) < 1e-3 * x->albedo.v);
		double sum = x->rsp + x->albedo.v + x->rd_unscat.v + x->tt.v + x->a_total.v;
		assert_float_equal(sum, 1.0, 1e-6);
	}
	z2 /= n;
	double sd = sqrt(2.54 / n);
	print_message("# ad vs mc: %d bins, mean z^2 = %.3f (expected 1.069 +- %.3f), max |z| = %.2f; largest error "
	    "ratio ad/mc %.3f; ad %.2f s, mc %.2f s\n", n, z2, sd, zmax, rq, ra.table.seconds, rm.table.seconds);
	assert_true(fabs(z2 - 31.0 / 29.0) < 4.0 * sd);
	assert_true(zmax < 5.0);
	assert_true(rq < 0.3);
	/* Rd(r) of the ad bake comes from its own Monte Carlo run; the radius
	 * agrees with the Monte Carlo bake's within the errors. */
	assert_int_equal(ra.radial_photons, 3 * BAKE_RADIAL_PILOT);
	for (int w = 0; w < 3; w++) {
		double d = ra.mean_radius_cm[w] - rm.mean_radius_cm[w];
		double e = hypot(ra.mean_radius_err_cm[w], rm.mean_radius_err_cm[w]);
		assert_true(e > 0.0 && fabs(d) < 4.0 * e);
	}
	/* Verify passes on both (the same function, either method). */
	char dir[64];
	snprintf(dir, sizeof dir, "tests/solvers.tmp.%ld", (long)getpid());
	struct verify_opts vo;
	verify_opts_default(&vo);
	vo.cells = 12;
	vo.photons = 20000;
	for (int i = 0; i < 2; i++) {
		write_bake(dir, i ? &m : &a, i ? &rm : &ra);
		struct verify_result vr;
		if (verify_bake(dir, &vo, &vr, &cause) != 0)
			fail_msg("%s", cause);
		print_message("# verify %s: %d cells, mean z^2 %.2f, max |z| %.2f: %s\n", vr.solver, vr.n_cells, vr.mean_z2,
		    vr.max_abs_z, vr.consistent ? "consistent" : "NOT consistent");
		assert_string_equal(vr.solver, i ? "mc" : "ad");
		assert_int_equal(vr.n_cells, 12);
		assert_true(vr.consistent);
		verify_result_free(&vr);
	}
	rm_rf(dir);
	bake_result_free(&ra);
	bake_result_free(&rm);
}

/* A table 10% off: with the re-run's errors of about 1-2% per bin every
 * cell is 5 or more sigma off. */
static void test_verify_fails_on_scaled_table(void **state)
{
	(void)state;
	static struct bake_spec a;
	paper_spec(&a, solvers_index("ad"));
	struct bake_result r;
	assert_int_equal(bake_run(&a, &r, NULL), 0);
	for (int j = 0; j < 6; j++)
		for (int k = 0; k < 24; k++)
			r.table.entry[j].fr[k] *= 1.1;
	char dir[64];
	snprintf(dir, sizeof dir, "tests/solvers-bad.tmp.%ld", (long)getpid());
	write_bake(dir, &a, &r);
	struct verify_opts vo;
	verify_opts_default(&vo);
	vo.cells = 12;
	vo.photons = 20000;
	struct verify_result vr;
	char *cause = NULL;
	if (verify_bake(dir, &vo, &vr, &cause) != 0)
		fail_msg("%s", cause);
	print_message("# verify, table x 1.1: mean z^2 %.1f, max |z| %.1f, beyond 3 sigma %.0f%%\n", vr.mean_z2, vr.max_abs_z,
	    100 * vr.frac_3sigma);
	assert_false(vr.consistent);
	assert_true(vr.frac_3sigma > 0.5);
	verify_result_free(&vr);
	rm_rf(dir);
	bake_result_free(&r);
}

static void test_ad_threads(void **state)
{
	(void)state;
	static struct bake_spec s;
	paper_spec(&s, solvers_index("ad"));
	s.n_r = 0;	/* the table only */
	struct bake_result a, b;
	s.threads = 1;
	assert_int_equal(bake_run(&s, &a, NULL), 0);
	s.threads = 2;
	assert_int_equal(bake_run(&s, &b, NULL), 0);
	for (int j = 0; j < 6; j++) {
		assert_memory_equal(a.table.entry[j].fr, b.table.entry[j].fr, sizeof(double) * 24);
		assert_memory_equal(a.table.entry[j].fr_err, b.table.entry[j].fr_err, sizeof(double) * 24);
		assert_memory_equal(&a.table.entry[j].albedo, &b.table.entry[j].albedo, sizeof(struct estimate));
	}
	assert_int_equal(a.radial_photons, 0);
	bake_result_free(&a);
	bake_result_free(&b);
}

/* Photons for a target, batch size left to the bake (sized from a pilot).
 * Errors fall as 1/sqrt(photons), and both targets start from the same
 * pilot (same seed), so the sized rounds differ by (0.05/0.01)^2 = 25 up to
 * the rounding of the batch size to whole photons (32 batches: at most 32
 * photons per round, 1.3% of the smaller one here); the pilot (2000
 * photons) adds to both.  The old first round (8 x 4000 photons) made the
 * two cost the same. */
static void test_target_error_photons(void **state)
{
	(void)state;
	static struct bake_spec s;
	paper_spec(&s, solvers_index("mc"));
	double wl = 550, th = 30;
	bake_spec_axes(&s, &wl, 1, &th, 1, 0);
	struct skin_params *p = preset_load_builtin("paper", NULL);
	assert_int_equal(bake_spec_layers(&s, p, "paper", NULL), 0);
	preset_free(p);
	s.n_to = s.n_phi = 18;
	s.n_r = 0;
	s.batch_photons = 0;
	s.max_photons = 100000000L;
	struct bake_result r5, r1, r5b;
	s.target_error = 0.05;
	s.threads = 1;
	assert_int_equal(bake_run(&s, &r5, NULL), 0);
	s.threads = 2;
	assert_int_equal(bake_run(&s, &r5b, NULL), 0);
	s.target_error = 0.01;
	assert_int_equal(bake_run(&s, &r1, NULL), 0);
	long t5 = r5.table.photons + r5.table.pilot_photons, t1 = r1.table.photons + r1.table.pilot_photons;
	print_message("# target 0.05: %ld + %ld pilot photons, error %.4f; 0.01: %ld + %ld, error %.4f; "
	    "ratio %.1f (sized rounds %.1f)\n", r5.table.photons, r5.table.pilot_photons, r5.table.rms_rel_err,
	    r1.table.photons, r1.table.pilot_photons, r1.table.rms_rel_err, (double)t1 / t5,
	    (double)r1.table.photons / r5.table.photons);
	assert_true(r5.table.target_met && r5.table.rms_rel_err <= 0.05);
	assert_true(r1.table.target_met && r1.table.rms_rel_err <= 0.01);
	assert_int_equal(r5.table.pilot_photons, 2000);
	assert_true(r1.table.photons >= 24.5 * r5.table.photons);
	assert_true(t1 > 10 * t5);
	/* Pilot and sized round: the same bits on 1 and 2 threads. */
	assert_int_equal(r5.table.photons, r5b.table.photons);
	assert_memory_equal(r5.table.entry[0].fr, r5b.table.entry[0].fr, sizeof(double) * 324);
	assert_memory_equal(r5.table.entry[0].fr_err, r5b.table.entry[0].fr_err, sizeof(double) * 324);
	bake_result_free(&r5);
	bake_result_free(&r5b);
	bake_result_free(&r1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ad_agrees_with_mc),
		cmocka_unit_test(test_verify_fails_on_scaled_table),
		cmocka_unit_test(test_ad_threads),
		cmocka_unit_test(test_target_error_photons),
	};
	return cmocka_run_group_tests_name("solvers", tests, NULL, NULL);
}
