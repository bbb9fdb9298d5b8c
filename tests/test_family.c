/* family: axes (nodes, refusals), the interpolation stencil (exact at the
 * nodes, exact for cubics in the axis coordinate, a partition of unity),
 * and family.json written and read back, with the messages for another
 * format version and a missing field. */
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

#include "family/family.h"
#include "base/util.h"

static void test_axes(void **state)
{
	(void)state;
	struct family_axis a;
	char *cause = NULL;
	assert_int_equal(family_axis_init(&a, "epidermis.melanin", 0.01, 0.16, 5, FAMILY_SPACING_LOG, NULL, &cause), 0);
	assert_float_equal(a.node[1], 0.02, 1e-15);
	assert_float_equal(a.node[2], 0.04, 1e-15);
	assert_true(a.node[0] == 0.01 && a.node[4] == 0.16 && a.log_coord == 1);
	assert_int_equal(family_axis_init(&a, "dermis.blood", 0, 0.1, 3, FAMILY_SPACING_LIN, NULL, &cause), 0);
	assert_true(a.node[1] == 0.05 && a.log_coord == 0);
	double list[3] = { 0.2, 0.3, 0.5 };
	assert_int_equal(family_axis_init(&a, "surface.roughness_skin", 0, 0, 3, FAMILY_SPACING_LIST, list, &cause), 0);
	assert_true(a.lo == 0.2 && a.hi == 0.5 && a.node[1] == 0.3 && a.log_coord == 1);
	static const struct {
		const char *key;
		double lo, hi;
		int n;
		enum family_spacing sp;
		const char *msg;
	} bad[] = {
		{ "epidermis.colour", 0, 1, 3, FAMILY_SPACING_LIN, "is not a numeric preset key" },
		{ "skin.name", 0, 1, 3, FAMILY_SPACING_LIN, "is not a numeric preset key" },
		{ "dermis.blood", 0.01, 0.3, 3, FAMILY_SPACING_LIN, "outside the key's range [0, 0.2]" },
		{ "dermis.blood", 0, 0.1, 3, FAMILY_SPACING_LOG, "log spacing needs a start > 0" },
		{ "dermis.blood", 0.1, 0.01, 3, FAMILY_SPACING_LIN, "is empty" },
		{ "dermis.blood", 0.01, 0.1, 1, FAMILY_SPACING_LIN, "1 nodes is out of range [2, 64]" },
		{ "dermis.blood", 0.01, 0.1, 65, FAMILY_SPACING_LIN, "65 nodes is out of range" },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		cause = NULL;
		assert_int_equal(family_axis_init(&a, bad[i].key, bad[i].lo, bad[i].hi, bad[i].n, bad[i].sp, NULL, &cause), -1);
		if (strstr(cause, bad[i].msg) == NULL)
			fail_msg("case %zu: '%s' lacks '%s'", i, cause, bad[i].msg);
		free(cause);
	}
	double desc[3] = { 0.3, 0.2, 0.5 };
	cause = NULL;
	assert_int_equal(family_axis_init(&a, "dermis.blood", 0, 0, 3, FAMILY_SPACING_LIST, desc, &cause), -1);
	assert_non_null(strstr(cause, "must ascend strictly"));
	free(cause);
}

/* A family in memory: axes with uneven nodes, members with the albedo of
 * a given function (no tables). */
static struct family *toy(int n_axes, const int *n, double (*fn)(const double *x, int w))
{
	struct family *f = xcalloc(1, sizeof *f);
	char *cause = NULL;
	static const char *keys[] = { "epidermis.melanin", "dermis.blood", "dermis.so2" };
	static const double lo[] = { 0.005, 0.004, 0.5 }, hi[] = { 0.3, 0.1, 0.9 };
	for (int a = 0; a < n_axes; a++) {
		assert_int_equal(family_axis_init(&f->axis[a], keys[a], lo[a], hi[a], n[a], a == 2 ? FAMILY_SPACING_LIN
		    : FAMILY_SPACING_LOG, NULL, &cause), 0);
		for (int i = 1; i < n[a] - 1; i++)	/* uneven on purpose */
			f->axis[a].node[i] *= 1.0 + 0.05 * ((i % 2) ? 1 : -1);
	}
	f->n_axes = n_axes;
	f->n_members = 1;
	for (int a = 0; a < n_axes; a++)
		f->n_members *= n[a];
	f->n_wl = 2;
	f->wl_nm = xcalloc(2, sizeof(double));
	f->wl_nm[0] = 450, f->wl_nm[1] = 650;
	f->rgb_from_wl = xcalloc(6, sizeof(double));
	f->rgb_from_wl[1] = f->rgb_from_wl[2] = f->rgb_from_wl[4] = 1.0;	/* R = 650, G = 450, B = 650 */
	f->member = xcalloc((size_t)f->n_members, sizeof *f->member);
	for (int m = 0; m < f->n_members; m++) {
		int idx[FAMILY_MAX_AXES];
		family_member_index(f, m, idx);
		struct family_member *fm = &f->member[m];
		for (int a = 0; a < n_axes; a++)
			fm->param[a] = f->axis[a].node[idx[a]];
		fm->albedo_wl = xcalloc(2, sizeof(double));
		for (int w = 0; w < 2; w++)
			fm->albedo_wl[w] = fn(fm->param, w);
		for (int c = 0; c < 3; c++)
			fm->albedo_rgb[c] = fm->albedo_wl[c == 1 ? 0 : 1], fm->sss_radius_rgb_cm[c] = 0.1 * (c + 1);
		fm->rms_rel_err = 0.001 * m;
	}
	f->preset = xstrdup("toy");
	f->solver = xstrdup("mc");
	f->spec = xcalloc(1, sizeof *f->spec);
	f->spec->n_ti = 1, f->spec->n_to = 2, f->spec->n_phi = 3, f->spec->n_r = 4, f->spec->dr = 0.01;
	f->spec->seed = 7, f->spec->batch_photons = 100, f->spec->min_batches = 8, f->spec->max_photons = 1000000;
	transport_opts_default(&f->spec->opts);
	return f;
}

/* exp of a cubic in (log m, log b, s): what the stencil must reproduce. */
static double cubic_exp(const double *x, int w)
{
	double u = log(x[0]), v = log(x[1]), s = x[2];
	return exp(-0.1 * u * u * u - 0.3 * u * v + 0.02 * v * v * v - (w + 1) * 0.2 * s * s * s + 0.1 * s * u);
}

static void test_stencil(void **state)
{
	(void)state;
	int n[3] = { 6, 5, 4 };
	struct family *f = toy(3, n, cubic_exp);
	struct family_stencil st;
	/* At a node: that member alone, weight exactly 1. */
	for (int m = 0; m < f->n_members; m += 7) {
		family_stencil(f, f->member[m].param, &st);
		assert_int_equal(st.n, 1);
		assert_int_equal(st.member[0], m);
		assert_true(st.w[0] == 1.0);
	}
	/* Between nodes: the weights sum to 1 and exp(cubic) comes back exactly
	 * (to rounding), because log-blending is Lagrange on the logarithm. */
	for (int k = 0; k < 50; k++) {
		double x[3] = { 0.005 * pow(60.0, (k * 0.137 + 0.05) - floor(k * 0.137 + 0.05)),
			0.004 * pow(25.0, (k * 0.291 + 0.1) - floor(k * 0.291 + 0.1)), 0.5 + 0.4 * ((k * 0.173) - floor(k * 0.173)) };
		family_stencil(f, x, &st);
		double s = 0;
		for (int j = 0; j < st.n; j++)
			s += st.w[j];
		assert_float_equal(s, 1.0, 1e-12);
		double a[2], rgb[3], rad[3];
		family_albedo(f, x, a, rgb, rad);
		for (int w = 0; w < 2; w++)
			if (fabs(a[w] / cubic_exp(x, w) - 1) > 1e-10)
				fail_msg("x = %g %g %g: %.15g vs %.15g", x[0], x[1], x[2], a[w], cubic_exp(x, w));
		assert_float_equal(rgb[1], a[0], 1e-15);
		assert_float_equal(rad[2], 0.3, 1e-12);
	}
	/* Outside the nodes: clamped to the end, and family_contains says so. */
	double out[3] = { 0.4, 0.05, 0.7 }, in[3] = { 0.3, 0.05, 0.7 };
	int ax = -1;
	assert_false(family_contains(f, out, &ax));
	assert_int_equal(ax, 0);
	assert_true(family_contains(f, in, &ax));
	double ao[2], ai[2], rgb[3];
	family_albedo(f, out, ao, rgb, NULL);
	family_albedo(f, in, ai, rgb, NULL);
	assert_true(ao[0] == ai[0] && ao[1] == ai[1]);
	family_free(f);
}

static double gentle(const double *x, int w)
{
	return 0.2 + 0.5 * x[0] + 0.1 * x[1] + 0.05 * w;
}

static void test_directory(void **state)
{
	(void)state;
	int n[2] = { 4, 3 };
	struct family *f = toy(2, n, gentle), *g;
	f->albedo_theta_i = 0.1;
	char dir[] = "/tmp/test_family.XXXXXX", *cause = NULL;
	assert_non_null(mkdtemp(dir));
	assert_int_equal(family_write_index(dir, f, "test", &cause), 0);
	g = family_load(dir, &cause);
	if (g == NULL)
		fail_msg("%s", cause);
	assert_int_equal(g->n_axes, 2);
	assert_int_equal(g->n_members, 12);
	for (int a = 0; a < 2; a++) {
		assert_string_equal(g->axis[a].key, f->axis[a].key);
		for (int i = 0; i < n[a]; i++)
			assert_true(g->axis[a].node[i] == f->axis[a].node[i]);
		assert_int_equal(g->axis[a].spacing, f->axis[a].spacing);
	}
	for (int m = 0; m < 12; m++)
		for (int w = 0; w < 2; w++)
			assert_true(g->member[m].albedo_wl[w] == f->member[m].albedo_wl[w]);
	assert_true(g->albedo_theta_i == 0.1 && g->spec->seed == 7 && g->spec->n_phi == 3);
	assert_float_equal(g->rms_rel_err, 0.011, 1e-15);
	family_free(g);
	/* Another format version, a missing field, a member off its node. */
	char path[256], cmd[600];
	snprintf(path, sizeof path, "%s/family.json", dir);
	static const struct {
		const char *sed, *msg;
	} bad[] = {
		{ "s/\"format_version\":1/\"format_version\":2/", "field format_version = 2, expected 1" },
		{ "s/\"wavelengths_nm\"/\"wavelengths\"/", "field wavelengths_nm is missing or not an array" },
		{ "s/\"format\":\"skinbake-family\"/\"format\":\"skinbake-bake\"/", "field format = 'skinbake-bake'" },
		{ "s/\"spacing\":\"log\"/\"spacing\":\"cubic\"/", "spacing = 'cubic', expected lin, log, de or list" },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		assert_int_equal(family_write_index(dir, f, "test", &cause), 0);
		snprintf(cmd, sizeof cmd, "sed -i '%s' %s", bad[i].sed, path);
		assert_int_equal(system(cmd), 0);
		cause = NULL;
		assert_null(family_load(dir, &cause));
		if (strstr(cause, bad[i].msg) == NULL || strstr(cause, path) == NULL)
			fail_msg("case %zu: '%s' lacks '%s' or the path", i, cause, bad[i].msg);
		free(cause);
	}
	snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
	assert_int_equal(system(cmd), 0);
	family_free(f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_axes),
		cmocka_unit_test(test_stencil),
		cmocka_unit_test(test_directory),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
