/* The baked BRDF as a function at every angle (issue 26): a default
 * adding-doubling bake (fair-oily, 550 nm, --resolution 18x18, the default
 * incidence nodes) through bake_eval_diffuse, against adding-doubling's own
 * point values from a separate solve at 64 nodes per unit cosine (the bake
 * chose 16) and a 10x tighter tolerance (1e-4: more Fourier orders), on
 * a dense grid: theta_i, theta_o = 1, 2, ..., 89, 89.9 deg, delta_phi = 0,
 * 10, ..., 180 deg.
 *   - coverage: |eval - ref| <= eval's error + the reference's at >= 95 %
 *     of the points (ref > 0);
 *   - interior (theta_i <= 81, theta_o < 80 deg): RMS relative error
 *     <= 0.2 %;
 *   - grazing (the rest): |eval - ref| <= GRAZING_BOUND x the BRDF's largest
 *     value at that theta_i (relative errors mean little where f -> 0);
 *   - reciprocity: |eval(a, b) - eval(b, a)| <= eval's error;
 *   - the hemispherical integral of eval at theta_i = 0, 45, 80, 85, 89 deg
 *     equals adding-doubling's albedo there within 1e-4;
 *   - the same bake as bin means (s.bin_means: what Monte Carlo tables
 *     hold, here without noise): eval reads them linearly, and its error
 *     (bakeinterp.h: the means' curvature) covers the actual error at
 *     >= 95 % of the points (measured 99.8 %; the interior RMS error, 0.59 %,
 *     is what reading means costs).
 * The numbers go to the TAP log (BENCHMARKS.md quotes them).  About 15 s. */
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
#include "base/util.h"
#include "engine/ad.h"
#include "engine/ad_quad.h"
#include "skin/preset.h"
#include "lib/small_bake.h"

#define NT 90		/* theta nodes of the dense grid */
#define NP 19		/* delta_phi nodes */
#define GRAZING_BOUND 0.01

static struct bake *bk, *bk_means;	/* point values; the same bake as bin means */
static struct slab slab550;
static double th[NT], ph[NP];
static double *ref, *ref_err;	/* [NT theta_i][NT theta_o][NP] */
static char dir[64], dir_means[64];

static double deg(double d)
{
	return d * M_PI / 180.0;
}

/* Bake s with preset p into dir and load it. */
static struct bake *bake_at(struct bake_spec *s, const struct skin_params *p, const char *d)
{
	char *cause = NULL;
	struct bake_result r;
	if (bake_preset_to_dir(s, p, "fair-oily", d, "test_grazing", &r, &cause) != 0)
		fail_msg("%s", cause);
	bake_result_free(&r);
	struct bake *b = bake_load(d, &cause);
	if (b == NULL)
		fail_msg("%s", cause);
	return b;
}

static int setup(void **state)
{
	(void)state;
	struct bake_spec s;
	small_bake_spec(&s, 550.0);
	char *cause = NULL;
	struct skin_params *p = bake_spec_preset(&s, "fair-oily", NULL, &cause);
	if (p == NULL)
		fail_msg("%s", cause);
	snprintf(dir, sizeof dir, "/tmp/test_grazing.%ld", (long)getpid());
	snprintf(dir_means, sizeof dir_means, "/tmp/test_grazing_means.%ld", (long)getpid());
	bk = bake_at(&s, p, dir);
	s.bin_means = 1;
	bk_means = bake_at(&s, p, dir_means);
	preset_free(p);
	slab550 = s.slab[0];
	for (int i = 0; i < NT; i++)
		th[i] = deg(i < NT - 1 ? i + 1 : 89.9);
	for (int j = 0; j < NP; j++)
		ph[j] = deg(10.0 * j);
	struct ad_opts o;
	ad_opts_default(&o);
	o.tol = 1e-4;
	o.n_quad = 64;
	o.n_to = o.n_phi = 2;
	struct ad_result a;
	if (ad_solve(&slab550, OPTICS_FRESNEL_EXACT, th, NT, &o, &a, &cause) != 0)
		fail_msg("%s", cause);
	print_message("# reference: %d nodes per unit cosine, %d orders\n", a.n_quad, a.n_orders);
	ref = xmalloc(sizeof(double) * NT * NT * NP);
	ref_err = xmalloc(sizeof(double) * NT * NT * NP);
	for (int i = 0; i < NT; i++)
		ad_brdf_points(&a, i, th, NT, ph, NP, ref + (size_t)i * NT * NP, ref_err + (size_t)i * NT * NP);
	ad_result_free(&a);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	bake_free(bk);
	bake_free(bk_means);
	free(ref);
	free(ref_err);
	char *cmd = xasprintf("rm -rf '%s' '%s'", dir, dir_means);
	if (system(cmd) != 0)
		print_message("# could not remove %s\n", dir);
	free(cmd);
	return 0;
}

static int dcmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static double eval_in(const struct bake *b, double ti, double to, double p, double *err)
{
	double f, e;
	bake_eval_diffuse(b, ti, to, p, &f, &e);
	if (err)
		*err = e;
	return f;
}

static double eval(double ti, double to, double p, double *err)
{
	return eval_in(bk, ti, to, p, err);
}

struct grid_stats {
	long n, covered;	/* points (ref > 0); where eval's error + ref's covers the actual */
	double rms_int, worst_int;	/* interior relative error */
	double worst_graz, at[2];	/* grazing: |eval - ref| / the largest f at that theta_i */
};

/* Bake b through eval against the reference on the dense grid. */
static void dense_grid(const struct bake *b, const char *what, struct grid_stats *g)
{
	long n_int = 0;
	double *ratio = xmalloc(sizeof(double) * NT * NT * NP), s2 = 0.0;
	memset(g, 0, sizeof *g);
	for (int i = 0; i < NT; i++) {
		double fpeak = 0.0;
		for (int k = 0; k < NT * NP; k++)
			fpeak = fmax(fpeak, ref[(size_t)i * NT * NP + k]);
		for (int o = 0; o < NT; o++)
			for (int j = 0; j < NP; j++) {
				size_t k = ((size_t)i * NT + o) * NP + j;
				double err, f = eval_in(b, th[i], th[o], ph[j], &err);
				double d = fabs(f - ref[k]);
				if (ref[k] <= 0.0)
					continue;
				ratio[g->n++] = d > 0.0 ? (err + ref_err[k]) / d : INFINITY;
				g->covered += d <= err + ref_err[k];
				if (th[i] <= deg(81.0) + 1e-12 && th[o] < deg(80.0)) {
					s2 += (d / ref[k]) * (d / ref[k]);
					n_int++;
					g->worst_int = fmax(g->worst_int, d / ref[k]);
				} else if (d / fpeak > g->worst_graz) {
					g->worst_graz = d / fpeak;
					g->at[0] = th[i] * 180 / M_PI;
					g->at[1] = th[o] * 180 / M_PI;
				}
			}
	}
	g->rms_int = sqrt(s2 / (double)n_int);
	qsort(ratio, (size_t)g->n, sizeof(double), dcmp);
	print_message("# %s: reported error over actual: 5th percentile %.3g, median %.3g\n", what,
	    ratio[g->n / 20], ratio[g->n / 2]);
	free(ratio);
	print_message("# %s: dense grid: %ld points; reported error covers the actual at %.2f %%\n",
	    what, g->n, 100.0 * g->covered / g->n);
	print_message("# %s: interior (theta_i <= 81, theta_o < 80 deg): RMS relative error "
	    "%.3g %%, worst %.3g %%\n", what, 100 * g->rms_int, 100 * g->worst_int);
	print_message("# %s: grazing: worst |eval - ref| %.3g %% of the largest f at that theta_i "
	    "(at %.1f, %.1f deg)\n", what, 100 * g->worst_graz, g->at[0], g->at[1]);
}

static void test_dense_grid(void **state)
{
	(void)state;
	struct grid_stats g;
	dense_grid(bk, "point values", &g);
	assert_true(g.covered >= 0.95 * g.n);
	assert_true(g.rms_int <= 0.002);
	assert_true(g.worst_graz <= GRAZING_BOUND);
}

/* The same bake as bin means (what Monte Carlo tables hold), without noise:
 * eval reads them as means, and its error must cover what that costs. */
static void test_bin_means(void **state)
{
	(void)state;
	struct grid_stats g;
	dense_grid(bk_means, "bin means", &g);
	assert_true(g.covered >= 0.95 * g.n);
}

static void test_reciprocity(void **state)
{
	(void)state;
	double worst = 0.0;
	for (int i = 0; i < NT; i += 3)
		for (int o = 0; o < NT; o += 2)
			for (int j = 0; j < NP; j += 3) {
				double ea, eb, a = eval(th[i], th[o], ph[j], &ea), b = eval(th[o], th[i], ph[j], &eb);
				assert_true(fabs(a - b) <= fmin(ea, eb) + 1e-15);
				if (a > 0.0)
					worst = fmax(worst, fabs(a - b) / a);
			}
	print_message("# reciprocity through eval: worst relative asymmetry %.2g\n", worst);
}

static void test_albedo(void **state)
{
	(void)state;
	const double ti[5] = { 0, 45, 80, 85, 89 };
	double t[5];
	for (int k = 0; k < 5; k++)
		t[k] = deg(ti[k]);
	struct ad_opts o;
	ad_opts_default(&o);
	o.tol = 1e-4;
	o.n_quad = 64;
	o.n_to = o.n_phi = 2;
	struct ad_result a;
	char *cause = NULL;
	if (ad_solve(&slab550, OPTICS_FRESNEL_EXACT, t, 5, &o, &a, &cause) != 0)
		fail_msg("%s", cause);
	enum { NG = 96, NPH = 64 };
	double x[NG], w[NG];
	ad_gauss_legendre(NG, 0.0, 0.5 * M_PI, x, w);
	for (int k = 0; k < 5; k++) {
		double sum = 0.0;	/* int f cos(theta_o) d omega, both sides of the plane */
		for (int g = 0; g < NG; g++)
			for (int q = 0; q < NPH; q++) {
				double p = M_PI * (q + 0.5) / NPH;
				sum += w[g] * cos(x[g]) * sin(x[g]) * (2.0 * M_PI / NPH) * eval(t[k], x[g], p, NULL);
			}
		double alb = a.beam[k].rd.v - a.beam[k].rd_unscat;
		print_message("# theta_i %4.1f deg: hemispherical integral of eval %.6f, adding-doubling albedo %.6f "
		    "(difference %.1e)\n", ti[k], sum, alb, sum - alb);
		assert_true(fabs(sum - alb) <= 1e-4);
	}
	ad_result_free(&a);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_dense_grid),
		cmocka_unit_test(test_bin_means),
		cmocka_unit_test(test_reciprocity),
		cmocka_unit_test(test_albedo),
	};
	return cmocka_run_group_tests_name("grazing", tests, setup, teardown);
}
