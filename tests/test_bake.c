/* The bake driver and the bake directory: round trip through the files is
 * exact, tables agree with independent `simulate` runs within error, the
 * target error is met, energy is conserved, threads do not change bits,
 * reciprocity holds within error; a second method drops into the solver
 * interface. */
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
#include "engine/sim.h"
#include "engine/solver.h"
#include "base/util.h"

/* The engine issue's skin stack at 550 nm. */
static void skin_slab(struct slab *s)
{
	char *cause = NULL;
	slab_init(s, 1.0, 1.4);
	struct layer l1 = { 0.001, 1.5, 0, 0, 0 }, l2 = { 0.01, 1.4, 50, 370, 0.8 }, l3 = { 0.25, 1.4, 7, 370, 0.8 };
	slab_add(s, &l1, &cause);
	slab_add(s, &l2, &cause);
	slab_add(s, &l3, &cause);
	assert_int_equal(slab_check(s, &cause), 0);
	slab_prepare(s);
}

static void base_spec(struct bake_spec *s)
{
	memset(s, 0, sizeof *s);
	s->n_wl = 2;
	s->wl_nm[0] = 550;
	s->wl_nm[1] = 600;
	skin_slab(&s->slab[0]);
	skin_slab(&s->slab[1]);
	s->slab[1].layer[2].mu_a = 20;	/* a second "wavelength": less absorbing epidermis */
	slab_prepare(&s->slab[1]);
	s->n_ti = 3;
	s->theta_i[0] = 0;
	s->theta_i[1] = 30 * M_PI / 180;
	s->theta_i[2] = 60 * M_PI / 180;
	s->n_to = 6;
	s->n_phi = 4;
	s->n_r = 20;
	s->dr = 0.01;
	transport_opts_default(&s->opts);
	s->seed = 11;
	s->batch_photons = 2000;
	s->min_batches = 8;
	s->target_error = 0;
	s->max_photons = 6L * 16 * 2000;
	s->n_ranks = 1;
}

static char tmpdir[64];

static void test_roundtrip_exact(void **state)
{
	(void)state;
	static struct bake_spec s;
	base_spec(&s);
	struct bake_result r;
	assert_int_equal(bake_run(&s, &r, NULL), 0);
	double m[6] = { 0.3, 0.7, 0.5, 0.5, 0.9, 0.1 };
	struct bake_meta meta = { .preset = "test", .ior = 1.5, .roughness = 0.3, .rgb_from_wl = m };
	char *cause = NULL;
	snprintf(tmpdir, sizeof tmpdir, "tests/bake.tmp.%ld", (long)getpid());
	assert_int_equal(bake_write(tmpdir, &s, &r, &meta, &cause), 0);
	struct bake *b = bake_load(tmpdir, &cause);
	if (b == NULL)
		fail_msg("%s", cause);
	assert_int_equal(b->n_wl, 2);
	assert_int_equal(b->n_ti, 3);
	assert_int_equal(b->n_to, 6);
	assert_int_equal(b->n_phi, 4);
	size_t per = (size_t)b->n_ti * b->n_to * b->n_phi;
	for (int w = 0; w < 2; w++)
		for (int ti = 0; ti < 3; ti++)
			for (int k = 0; k < 24; k++) {
				float want = (float)r.table.entry[w * 3 + ti].fr[k];
				assert_memory_equal(&b->fr[w * per + (size_t)ti * 24 + k], &want, sizeof want);
				float werr = (float)r.table.entry[w * 3 + ti].fr_err[k];
				assert_memory_equal(&b->fr_err[w * per + (size_t)ti * 24 + k], &werr, sizeof werr);
			}
	/* RGB table is the stated linear combination. */
	for (size_t k = 0; k < per; k++) {
		double want = 0.3 * b->fr[k] + 0.7 * b->fr[per + k];
		assert_float_equal(b->fr_rgb[k], want, 1e-6 * (fabs(want) + 1e-6));
	}
	/* Interpolation reproduces the table at its nodes; the error there is the
	 * standard error plus a bin mean's offset from its centre value
	 * (bakeinterp.h, issue 26). */
	double f[2], e[2];
	bake_eval_diffuse(b, b->theta_i[1], b->theta_o[2], b->phi[3], f, e);
	assert_float_equal(f[0], b->fr[(size_t)1 * 24 + 2 * 4 + 3], 1e-7);
	assert_true(e[1] >= b->fr_err[per + (size_t)1 * 24 + 2 * 4 + 3] - 1e-7);
	/* A missing file makes loading fail with a message. */
	char *p = xasprintf("%s/brdf_rgb.exr", tmpdir);
	unlink(p);
	free(p);
	struct bake *b2 = bake_load(tmpdir, &cause);
	assert_null(b2);
	assert_non_null(strstr(cause, "brdf_rgb.exr"));
	free(cause);
	bake_free(b);
	bake_result_free(&r);
	char *cmd = xasprintf("rm -rf %s", tmpdir);
	assert_int_equal(system(cmd), 0);
	free(cmd);
}

static void test_energy_and_threads(void **state)
{
	(void)state;
	static struct bake_spec s;
	base_spec(&s);
	s.threads = 1;
	struct bake_result a, b;
	assert_int_equal(bake_run(&s, &a, NULL), 0);
	s.threads = 2;
	assert_int_equal(bake_run(&s, &b, NULL), 0);
	for (int j = 0; j < (a.table.n_wl * a.table.n_ti); j++) {
		const struct brdf_entry *x = &a.table.entry[j], *y = &b.table.entry[j];
		assert_memory_equal(x->fr, y->fr, sizeof(double) * 24);
		assert_memory_equal(x->fr_err, y->fr_err, sizeof(double) * 24);
		assert_memory_equal(&x->albedo, &y->albedo, sizeof x->albedo);
		double sum = x->rsp + x->albedo.v + x->rd_unscat.v + x->tt.v + x->a_total.v + x->lost.v;
		assert_float_equal(sum, 1.0, 1e-9);
		/* Absorption per layer adds up to the total. */
		double al = 0.0;
		for (int i = 0; i < SLAB_MAX_LAYERS + 2; i++)
			al += x->a[i].v;
		assert_float_equal(al, x->a_total.v, 1e-12);
		/* The table integrates to the albedo (bins are cos-weighted means). */
		double integ = 0.0;
		for (int it = 0; it < 6; it++)
			for (int ip = 0; ip < 4; ip++)
				integ += x->fr[it * 4 + ip] * sim_cos_solid_angle(it * M_PI / 12, (it + 1) * M_PI / 12, M_PI / 4);
		assert_float_equal(integ, x->albedo.v, 1e-9);
	}
	bake_result_free(&a);
	bake_result_free(&b);
}

/* Bake entries against independent simulate runs (other seed): the mean
 * squared z-score over all bins is 1 within its own statistical spread. */
static void test_agrees_with_simulate(void **state)
{
	(void)state;
	static struct bake_spec s;
	base_spec(&s);
	s.max_photons = 6L * 40 * 2000;
	struct bake_result r;
	assert_int_equal(bake_run(&s, &r, NULL), 0);
	double z2 = 0.0, zmax = 0.0;
	int n = 0;
	for (int j = 0; j < (r.table.n_wl * r.table.n_ti); j++) {
		static struct sim_config c;
		sim_config_default(&c);
		c.slab = s.slab[j / 3];
		c.theta_in = s.theta_i[j % 3];
		c.grid = (struct tally_grid){ .n_theta = 6, .n_phi = 4, .n_r = 0, .dr = 0.01 };
		c.photons = 80000;
		c.seed = 999;
		struct sim_result sr;
		sim_run(&c, &sr, NULL, NULL);
		for (int k = 0; k < 24; k++) {
			double d = r.table.entry[j].fr[k] - sr.fr[k];
			double se = sqrt(r.table.entry[j].fr_err[k] * r.table.entry[j].fr_err[k] + sr.fr_err[k] * sr.fr_err[k]);
			double z = d / se;
			z2 += z * z;
			zmax = fmax(zmax, fabs(z));
			n++;
		}
		sim_result_free(&sr);
	}
	z2 /= n;
	print_message("# bake vs simulate: %d bins, mean z^2 = %.3f, max |z| = %.2f\n", n, z2, zmax);
	/* chi^2/n has standard deviation sqrt(2/n); allow 4 of them, and no bin beyond 4.5 sigma. */
	assert_true(z2 < 1.0 + 4.0 * sqrt(2.0 / n));
	assert_true(z2 > 1.0 - 4.0 * sqrt(2.0 / n));
	assert_true(zmax < 4.5);
	bake_result_free(&r);
}

/* The next-event estimator's table against plain binning of an independent
 * run: the same bin means within the combined errors (chi-square per bin). */
static void test_nee_unbiased(void **state)
{
	(void)state;
	static struct bake_spec a, b;
	base_spec(&a);
	a.n_to = 9;
	a.n_phi = 6;
	a.max_photons = 6L * 12 * 2000;
	b = a;
	a.nee = 1;
	b.nee = 0;
	b.seed = 4242;
	b.max_photons = 6L * 150 * 2000;
	struct bake_result ra, rb;
	assert_int_equal(bake_run(&a, &ra, NULL), 0);
	assert_int_equal(bake_run(&b, &rb, NULL), 0);
	double z2 = 0.0, zmax = 0.0, ea = 0.0, eb = 0.0;
	int n = 0;
	for (int j = 0; j < (ra.table.n_wl * ra.table.n_ti); j++) {
		for (int k = 0; k < 54; k++) {
			double se = sqrt(ra.table.entry[j].fr_err[k] * ra.table.entry[j].fr_err[k] + rb.table.entry[j].fr_err[k] * rb.table.entry[j].fr_err[k]);
			double z = (ra.table.entry[j].fr[k] - rb.table.entry[j].fr[k]) / se;
			z2 += z * z;
			zmax = fmax(zmax, fabs(z));
			n++;
		}
		ea += ra.table.entry[j].rms_rel_err;
		eb += rb.table.entry[j].rms_rel_err;
		/* Totals are scored by escapes either way: energy still balances. */
		const struct brdf_entry *x = &ra.table.entry[j];
		assert_float_equal(x->rsp + x->albedo.v + x->rd_unscat.v + x->tt.v + x->a_total.v + x->lost.v, 1.0, 1e-9);
	}
	z2 /= n;
	print_message("# nee vs bins: %d bins, mean z^2 = %.3f, max |z| = %.2f; mean RMS error nee %.4f "
	    "(%ld photons), bins %.4f (%ld photons)\n", n, z2, zmax, ea / (ra.table.n_wl * ra.table.n_ti), ra.table.photons, eb / (rb.table.n_wl * rb.table.n_ti), rb.table.photons);
	assert_true(z2 < 1.0 + 4.0 * sqrt(2.0 / n));
	assert_true(z2 > 1.0 - 4.0 * sqrt(2.0 / n));
	assert_true(zmax < 4.5);
	bake_result_free(&ra);
	bake_result_free(&rb);
}

static void test_target_error_met(void **state)
{
	(void)state;
	static struct bake_spec s;
	base_spec(&s);
	s.n_wl = 1;
	s.n_ti = 2;
	s.target_error = 0.01;
	s.nee = 1;	/* the default estimator */
	s.max_photons = 100000000L;
	struct bake_result r;
	assert_int_equal(bake_run(&s, &r, NULL), 0);
	long first = (long)(r.table.n_wl * r.table.n_ti) * s.min_batches * s.batch_photons;
	print_message("# target 0.01: reached %.4f with %ld photons (first round %ld)\n", r.table.rms_rel_err, r.table.photons, first);
	assert_true(r.table.target_met);
	assert_true(r.table.rms_rel_err <= 0.01);
	/* Beyond the first round the whole-table criterion stops close to the
	 * target instead of driving every job below it. */
	if (r.table.photons > first)
		assert_true(r.table.rms_rel_err > 0.01 * 0.6);
	bake_result_free(&r);
}

/* f(i, o) = f(o, i): incidence nodes at bin centres, compare the
 * azimuth-averaged values of the two bins at (a, b) and (b, a). */
static void test_reciprocity(void **state)
{
	(void)state;
	static struct bake_spec s;
	base_spec(&s);
	s.n_wl = 1;
	s.n_to = 9;
	s.n_phi = 1;
	s.n_ti = 2;
	s.theta_i[0] = 25 * M_PI / 180;	/* centre of bin 2 (20-30) */
	s.theta_i[1] = 55 * M_PI / 180;	/* centre of bin 5 (50-60) */
	s.max_photons = 2L * 200 * 2000;
	struct bake_result r;
	assert_int_equal(bake_run(&s, &r, NULL), 0);
	double f_ab = r.table.entry[0].fr[5], e_ab = r.table.entry[0].fr_err[5];
	double f_ba = r.table.entry[1].fr[2], e_ba = r.table.entry[1].fr_err[2];
	double z = (f_ab - f_ba) / sqrt(e_ab * e_ab + e_ba * e_ba);
	print_message("# reciprocity: f(25,55) = %.5f +- %.5f, f(55,25) = %.5f +- %.5f, z = %.2f\n", f_ab, e_ab, f_ba, e_ba, z);
	assert_true(fabs(z) < 3.5);
	bake_result_free(&r);
}

/* A second method through the solver interface: a Lambertian table with a
 * 1 % error, one step per wavelength, that refuses radial bins.  The
 * driver's loop, the labels and the accuracy criterion work for it. */
struct lambert_state {
	struct solver_problem p;
	int steps;
};

static void *lambert_begin(const struct solver_problem *p, const void *settings, char **cause)
{
	(void)settings;
	if (p->grid.n_r > 0) {
		*cause = xasprintf("no Rd(r)");
		return NULL;
	}
	struct lambert_state *st = xcalloc(1, sizeof *st);
	st->p = *p;
	return st;
}

static int lambert_step(void *state, const struct solver_run *run)
{
	(void)run;
	struct lambert_state *st = state;
	return ++st->steps < st->p.n_wl;
}

static void lambert_finish(void *state, struct brdf_table *out)
{
	struct lambert_state *st = state;
	brdf_table_init(out, &st->p);
	for (int j = 0; j < out->n_wl * out->n_ti; j++)
		for (int k = 0; k < out->grid.n_theta * out->grid.n_phi; k++) {
			out->entry[j].fr[k] = 0.5 / M_PI;
			out->entry[j].fr_err[k] = 0.01 * 0.5 / M_PI;
		}
	out->rms_rel_err = brdf_table_rms(out);
	assert_int_equal(st->steps, st->p.n_wl);
	free(st);
}

static void test_solver_seam(void **state)
{
	(void)state;
	static const struct solver_ops lambert = {
		.name = "lambert", .provides = SOLVER_BRDF, .begin = lambert_begin, .step = lambert_step,
		.finish = lambert_finish,
	};
	static struct bake_spec s;
	base_spec(&s);
	struct solver_problem p = { .n_wl = s.n_wl, .wl_nm = s.wl_nm, .slab = s.slab, .n_ti = s.n_ti,
		.theta_i = s.theta_i, .grid = { .n_theta = 6, .n_phi = 4, .n_r = 0, .dr = 0.01 } };
	struct solver_run run = { .n_ranks = 1 };
	struct brdf_table t;
	char *cause = NULL;
	assert_int_equal(solver_solve(&lambert, NULL, &p, &run, &t, &cause), 0);
	assert_int_equal(t.n_wl * t.n_ti, 6);
	assert_float_equal(t.entry[4].wl_nm, 600, 0);
	assert_float_equal(t.entry[4].theta_i, s.theta_i[1], 0);
	assert_null(t.entry[0].rd_r);
	assert_float_equal(t.rms_rel_err, 0.01, 1e-12);
	brdf_table_free(&t);
	p.grid.n_r = 5;
	assert_int_equal(solver_solve(&lambert, NULL, &p, &run, &t, &cause), -1);
	assert_string_equal(cause, "no Rd(r)");
	free(cause);
}

/* ad_orders = 1 (the family's node pilot): only Fourier order 0, and the
 * albedos, Rsp and Tt bit for bit those of the bake of every order. */
static void test_ad_orders_albedo(void **state)
{
	(void)state;
	static struct bake_spec s;
	base_spec(&s);
	s.method = solvers_index("ad");
	s.n_r = 0;
	s.ad_quad = 8;
	s.ad_tol = 0.01;
	struct bake_result a, b;
	assert_int_equal(bake_run(&s, &a, NULL), 0);
	s.ad_orders = 1;
	assert_int_equal(bake_run(&s, &b, NULL), 0);
	for (int j = 0; j < s.n_wl * s.n_ti; j++) {
		assert_true(a.table.entry[j].albedo.v == b.table.entry[j].albedo.v);
		assert_true(a.table.entry[j].rsp == b.table.entry[j].rsp);
		assert_true(a.table.entry[j].tt.v == b.table.entry[j].tt.v);
		assert_true(a.table.entry[j].albedo.v > 0.0);
		assert_int_equal(b.table.entry[j].n_orders, 1);
		assert_true(a.table.entry[j].n_orders > 1);
	}
	bake_result_free(&a);
	bake_result_free(&b);
}

/* A mean radius with a stated error of exactly 0 is refused (a Monte Carlo
 * estimate of returned light always has a spread): given profiles (the
 * family's shared Rd(r) path) with no photon in the bins, and with all of
 * them in the first bin; a profile with a spread is baked. */
static void test_zero_radius_error_refused(void **state)
{
	(void)state;
	static struct bake_spec s;
	base_spec(&s);
	s.method = solvers_index("ad");
	s.ad_quad = 8;
	s.ad_tol = 0.01;
	s.n_ti = 1;
	static double zero[20], err0[20], one[20], spread[20], spread_err[20];
	one[0] = 5.0;
	for (int i = 0; i < 20; i++) {
		spread[i] = 10.0 * exp(-i / 4.0);
		spread_err[i] = 0.02 * spread[i];
	}
	const double *cases[3][2] = { { zero, err0 }, { one, err0 }, { spread, spread_err } };
	for (int c = 0; c < 3; c++) {
		struct bake_radial_given g = { .photons = 1000, .n_shared = 2 };
		for (int w = 0; w < s.n_wl; w++) {
			g.rd_r[w] = cases[c][0];
			g.rd_r_err[w] = cases[c][1];
		}
		s.radial_given = &g;
		struct bake_result r;
		char *cause = NULL;
		int rc = bake_run(&s, &r, &cause);
		if (c < 2) {
			assert_int_equal(rc, -1);
			assert_non_null(strstr(cause, "stated error of 0"));
			free(cause);
		} else {
			assert_int_equal(rc, 0);
			assert_true(r.mean_radius_err_cm[0] > 0.0);
			bake_result_free(&r);
		}
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_roundtrip_exact),
		cmocka_unit_test(test_energy_and_threads),
		cmocka_unit_test(test_agrees_with_simulate),
		cmocka_unit_test(test_nee_unbiased),
		cmocka_unit_test(test_target_error_met),
		cmocka_unit_test(test_reciprocity),
		cmocka_unit_test(test_solver_seam),
		cmocka_unit_test(test_ad_orders_albedo),
		cmocka_unit_test(test_zero_radius_error_refused),
	};
	return cmocka_run_group_tests_name("bake", tests, NULL, NULL);
}
