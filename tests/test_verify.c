/* verify's false-alarm rate and power (issue 26), through the library.
 *   - 20 right tables: 10 Monte Carlo bakes of `paper` at 550 nm with
 *     seeds 1..10 (bin means), and 10 adding-doubling bakes of ten presets
 *     at 550 nm (point values at the default nodes), each verified with a
 *     seed of its own, 8 independent cells of 20000 photons.  verify.h
 *     states a false-alarm rate of at most 0.2 % per table for independent
 *     cells: more than one alarm in 20 has probability below 1e-3.  The
 *     mean z^2 over the Monte Carlo tables' cells is printed (1.07 expected
 *     for Student's t with 31 degrees of freedom).
 *   - a table scaled by 1 %: an adding-doubling table of bin means on a
 *     3 x 2 grid (large bins: the re-runs' 3e5 photons give about 0.4 %
 *     per bin, so E z^2 = 1 + (1 / 0.4)^2, about 7, against the limit 3.3
 *     for 8 cells) must be found NOT consistent.
 * About 60 s of CPU (mostly the 168 Monte Carlo re-runs). */
#include "config.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bake/bake.h"
#include "bake/bakefile.h"
#include "bake/verify.h"
#include "base/util.h"
#include "skin/preset.h"

static void spec(struct bake_spec *s, const char *preset, int method, uint64_t seed, int n_to, int n_phi)
{
	memset(s, 0, sizeof *s);
	double wl = 550.0, th[2] = { 0.0, 40.0 };
	s->n_to = n_to;
	s->n_phi = n_phi;
	if (method == solvers_index("mc"))
		bake_spec_axes(s, &wl, 1, th, 2, 0);
	else
		bake_spec_axes(s, &wl, 1, NULL, 0, 0);	/* the default nodes */
	s->n_r = 0;
	transport_opts_default(&s->opts);
	s->method = method;
	s->seed = seed;
	s->batch_photons = 1000;
	s->min_batches = 32;
	s->max_photons = 2L * 32 * 1000;
	s->nee = 1;
	s->n_ranks = 1;
	char *cause = NULL;
	struct skin_params *p = bake_spec_preset(s, preset, NULL, &cause);
	if (p == NULL)
		fail_msg("%s", cause);
	preset_free(p);
}

/* Bake s into dir, its table scaled by `scale`. */
static void bake_to(const struct bake_spec *s, double scale, const char *dir)
{
	struct bake_result r;
	char *cause = NULL;
	if (bake_run(s, &r, &cause) != 0)
		fail_msg("%s", cause);
	size_t nb = (size_t)s->n_to * s->n_phi;
	for (int j = 0; j < s->n_wl * s->n_ti; j++)
		for (size_t k = 0; k < nb; k++)
			r.table.entry[j].fr[k] *= scale;
	static const double m[3] = { 1, 1, 1 };
	struct bake_meta meta = { .preset = "test", .ior = 1.5, .roughness = 0.3, .rgb_from_wl = m };
	if (bake_write(dir, s, &r, &meta, &cause) != 0)
		fail_msg("%s", cause);
	bake_result_free(&r);
}

static void rm_rf(const char *dir)
{
	char *cmd = xasprintf("rm -rf '%s'", dir);
	assert_int_equal(system(cmd), 0);
	free(cmd);
}

static void test_false_alarms(void **state)
{
	(void)state;
	static const char *ad_presets[10] = { "paper", "paper-dry", "curet39", "refstack", "very-fair-oily", "fair-oily",
		"medium-dry", "olive-oily", "brown-dry", "dark-oily" };
	char dir[64];
	snprintf(dir, sizeof dir, "tests/verify.tmp.%ld", (long)getpid());
	int alarms = 0;
	double z2_mc = 0.0;
	int n_mc = 0;
	for (int t = 0; t < 20; t++) {
		static struct bake_spec s;
		int mc = t < 10;
		spec(&s, mc ? "paper" : ad_presets[t - 10], mc ? solvers_index("mc") : solvers_index("ad"), (uint64_t)t + 1,
		    mc ? 6 : 9, mc ? 4 : 6);
		bake_to(&s, 1.0, dir);
		struct verify_opts vo;
		verify_opts_default(&vo);
		vo.cells = 8;
		vo.photons = 20000;
		vo.seed = 1000 + 100 * (uint64_t)t;
		struct verify_result vr;
		char *cause = NULL;
		if (verify_bake(dir, &vo, &vr, &cause) != 0)
			fail_msg("%s", cause);
		assert_int_equal(vr.n_cells, 8);
		assert_int_equal(vr.n_pairs, 8);	/* a re-run per cell */
		print_message("# %-14s %s: mean z^2 %.2f (limit %.2f), max |z| %.2f (limit %.2f): %s\n",
		    mc ? "paper" : ad_presets[t - 10], vr.solver, vr.mean_zn2, vr.mean_z2_limit, vr.max_abs_zn,
		    vr.max_z_limit, vr.consistent ? "consistent" : "NOT consistent");
		alarms += !vr.consistent;
		if (mc) {
			z2_mc += vr.mean_z2 * vr.n_cells;
			n_mc += vr.n_cells;
		}
		verify_result_free(&vr);
		rm_rf(dir);
	}
	print_message("# 20 right tables: %d false alarms; Monte Carlo tables' mean z^2 over %d cells %.3f\n", alarms,
	    n_mc, z2_mc / n_mc);
	assert_true(alarms <= 1);
}

static void test_scaled_caught(void **state)
{
	(void)state;
	static struct bake_spec s;
	spec(&s, "fair-oily", solvers_index("ad"), 1, 3, 2);
	s.bin_means = 1;
	char dir[64];
	snprintf(dir, sizeof dir, "tests/verify-bad.tmp.%ld", (long)getpid());
	bake_to(&s, 1.01, dir);
	struct verify_opts vo;
	verify_opts_default(&vo);
	vo.cells = 8;
	vo.photons = 300000;
	struct verify_result vr;
	char *cause = NULL;
	if (verify_bake(dir, &vo, &vr, &cause) != 0)
		fail_msg("%s", cause);
	double rel = 0.0;
	for (int i = 0; i < vr.n_cells; i++)
		rel = fmax(rel, vr.cell[i].e_mc / vr.cell[i].f_mc);
	print_message("# table x 1.01: mean z^2 %.1f (limit %.2f), max |z| %.1f; re-runs' largest relative error %.2g\n",
	    vr.mean_zn2, vr.mean_z2_limit, vr.max_abs_zn, rel);
	assert_false(vr.consistent);
	verify_result_free(&vr);
	rm_rf(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_false_alarms),
		cmocka_unit_test(test_scaled_caught),
	};
	return cmocka_run_group_tests_name("verify", tests, NULL, NULL);
}
