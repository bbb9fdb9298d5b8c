/* POV-Ray exporter without POV-Ray: delta_phi from the light-view angle,
 * table axes, blend-map sizes and values, the separable fit, bump_size, the
 * include guard, and the scene parser's errors.  Renders are checked in
 * tests/pov_render.sh. */
#include "config.h"

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

#include "export/pov/littable.h"
#include "export/pov/bumpmap.h"
#include "export/pov/povfiles.h"
#include "export/pov/separable.h"
#include "export/pov/strategy.h"
#include "scene/placement.h"
#include "scene/scene.h"
#include "scene/scene_load.h"
#include "base/util.h"

/* Lambert with albedo (0.5, 0.4, 0.3) plus a term in delta_phi, so a wrong
 * delta_phi shows. */
static void test_brdf(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	(void)ctx;
	static const double rho[3] = { 0.5, 0.4, 0.3 };
	for (int c = 0; c < 3; c++)
		rgb[c] = rho[c] / M_PI + 0.05 * (1 + cos(dphi)) * sin(ti) * sin(to);
}

static void lambert(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	(void)ctx, (void)ti, (void)to, (void)dphi;
	rgb[0] = 0.6 / M_PI, rgb[1] = 0.45 / M_PI, rgb[2] = 0.3 / M_PI;
}

static char *memtext(void (*write)(FILE *, void *), void *arg)
{
	FILE *fp = tmpfile();
	write(fp, arg);
	long len = ftell(fp);
	char *buf = xmalloc((size_t)len + 1);
	rewind(fp);
	assert_int_equal(fread(buf, 1, (size_t)len, fp), (size_t)len);
	buf[len] = '\0';
	fclose(fp);
	return buf;
}

static int count(const char *s, const char *needle)
{
	int n = 0;
	for (const char *p = strstr(s, needle); p; p = strstr(p + 1, needle))
		n++;
	return n;
}

static void test_dphi(void **state)
{
	(void)state;
	/* cos gamma = cos ti cos to + sin ti sin to cos dphi, inverted. */
	for (double ti = 0.1; ti < 1.5; ti += 0.2)
		for (double to = 0.1; to < 1.5; to += 0.2)
			for (double dp = 0.0; dp <= M_PI; dp += 0.25) {
				double cg = cos(ti) * cos(to) + sin(ti) * sin(to) * cos(dp);
				assert_float_equal(littable_dphi(ti, to, cg), dp, 1e-6);
			}
	/* Back toward the light: gamma = |ti - to|; mirror side: ti + to. */
	assert_float_equal(littable_dphi(0.5, 0.3, cos(0.2)), 0.0, 1e-6);
	assert_float_equal(littable_dphi(0.5, 0.3, cos(0.8)), M_PI, 1e-6);
	/* Impossible combinations clamp instead of producing NaN. */
	assert_float_equal(littable_dphi(0.5, 0.3, cos(1.5)), M_PI, 1e-12);
	assert_true(littable_dphi(0.0, 0.3, 0.2) == 0.0);
}

static void test_cos_gamma(void **state)
{
	(void)state;
	struct pov_light l = { .parallel = 1, .dir = { 0, 0, -1 } };
	struct pov_view v = { .ortho = 1, .dir = { 0, 0, -1 } };
	double p[3] = { 0.3, 0.2, 0 }, lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 }, a, b;
	assert_float_equal(littable_cos_gamma(&l, &v, p), 1.0, 1e-12);
	littable_cos_gamma_range(&l, &v, lo, hi, &a, &b);
	assert_float_equal(a, b, 1e-12);
	/* A point light: gamma varies over the box. */
	struct pov_light pl = { .parallel = 0, .pos = { 3, 0, -3 } };
	littable_cos_gamma_range(&pl, &v, lo, hi, &a, &b);
	assert_true(b - a > 0.1);
	double q[3] = { 3, 0, 0 };
	assert_float_equal(littable_cos_gamma(&pl, &v, q), 1.0, 1e-12);
}

static void test_axis(void **state)
{
	(void)state;
	double out[LITTABLE_MAX_NODES], hint[4] = { 0.1, 0.4, 0.41, 1.2 };
	for (int n = 2; n <= LITTABLE_MAX_NODES; n += 31) {
		assert_int_equal(littable_axis(NULL, 0, n, out), n);
		assert_true(out[0] == 0.0 && out[n - 1] == M_PI / 2);
		for (int i = 1; i < n; i++)
			assert_true(out[i] > out[i - 1]);
	}
	/* Uniform without hints when n - 1 is a power of two. */
	littable_axis(NULL, 0, 65, out);
	for (int i = 0; i < 65; i++)
		assert_float_equal(out[i], (M_PI / 2) * i / 64, 1e-12);
	/* Hints are nodes. */
	assert_int_equal(littable_axis(hint, 4, 20, out), 20);
	for (int h = 0; h < 4; h++) {
		int found = 0;
		for (int i = 0; i < 20; i++)
			found |= fabs(out[i] - hint[h]) < 1e-12;
		assert_true(found);
	}
}

struct keyarg {
	int parallel, ortho, n, ng, used;
};

static void write_key(FILE *fp, void *arg)
{
	struct keyarg *k = arg;
	struct pov_brdf f = { .f_rgb = test_brdf };
	struct pov_light l = { .parallel = k->parallel, .pos = { 2, 1.5, -2.5 }, .dir = { 0.6, 0.48, -0.64 } };
	struct pov_view v = { .ortho = k->ortho, .pos = { 0, 0, -3 }, .dir = { 0, 0, -1 } };
	double lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 };
	k->used = littable_write_key(fp, "T", &f, &l, &v, lo, hi, k->n, k->ng);
}

static void test_key_table(void **state)
{
	(void)state;
	/* Parallel light, orthographic camera: a 2-D table. */
	struct keyarg k = { 1, 1, 17, 9, 0 };
	char *t = memtext(write_key, &k);
	assert_int_equal(k.used, 1);
	assert_true(strncmp(t, "#declare T = pigment {", 22) == 0);
	assert_int_equal(count(t, "aoi color_map"), 17);
	assert_int_equal(count(t, "slope {"), 1);
	assert_int_equal(count(t, "function"), 0);
	/* 17 aoi entries + the extra one at 0 per row. */
	assert_int_equal(count(t, "rgb <"), 17 * 18);
	/* theta_i = theta_o = 0 (pattern values 1, 1): pi f = the albedo + 0. */
	const char *last = strstr(t, "  [1.00000000 aoi");
	assert_non_null(last);
	const char *e = strstr(last, "[1.00000000 rgb <");
	assert_non_null(e);
	double r, g, b;
	assert_int_equal(sscanf(e, "[1.00000000 rgb <%lf,%lf,%lf>", &r, &g, &b), 3);
	assert_float_equal(r, 0.5, 1e-6);
	assert_float_equal(g, 0.4, 1e-6);
	assert_float_equal(b, 0.3, 1e-6);
	free(t);

	/* Point light, perspective camera: the gamma axis. */
	k = (struct keyarg){ 0, 0, 9, 5, 0 };
	t = memtext(write_key, &k);
	assert_int_equal(k.used, 5);
	assert_int_equal(count(t, "function {"), 1);
	assert_int_equal(count(t, "slope { point_at"), 5);
	assert_int_equal(count(t, "aoi color_map"), 5 * 9);
	free(t);

	/* The largest table keeps every blend map within 256 entries. */
	k = (struct keyarg){ 1, 1, LITTABLE_MAX_NODES, 1, 0 };
	t = memtext(write_key, &k);
	assert_int_equal(count(t, "aoi color_map"), LITTABLE_MAX_NODES);
	assert_int_equal(count(t, "rgb <"), LITTABLE_MAX_NODES * (LITTABLE_MAX_NODES + 1));
	assert_true(LITTABLE_MAX_NODES + 1 <= 256);
	free(t);
}

static void write_mix(FILE *fp, void *arg)
{
	double *spread = arg;
	struct pov_brdf f = { .f_rgb = test_brdf };
	struct pov_light l[2] = { { .parallel = 1, .dir = { 0.6, 0.48, -0.64 }, .rgb = { 1, 1, 1 } },
		{ .parallel = 1, .dir = { -0.8, 0, -0.6 }, .rgb = { 0.5, 0.5, 0.5 } } };
	struct pov_view v = { .ortho = 1, .dir = { 0, 0, -1 } };
	double lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 };
	littable_write_mixture(fp, "M", &f, l, &v, lo, hi, 9, spread);
}

static void test_mixture(void **state)
{
	(void)state;
	double spread = -1;
	char *t = memtext(write_mix, &spread);
	assert_float_equal(spread, 0.0, 1e-9);
	assert_int_equal(count(t, "slope {"), 1 + 9);
	assert_int_equal(count(t, "aoi color_map"), 9 * 9);
	/* With a Lambertian part only at theta = 0 rows, leaf = the albedo. */
	const char *e = strstr(t, "[1.00000000 aoi color_map {");
	assert_non_null(e);
	free(t);
}

static void test_separable(void **state)
{
	(void)state;
	struct pov_brdf f = { .f_rgb = lambert };
	struct pov_separable sep;
	separable_fit(&f, &sep);
	assert_float_equal(sep.brilliance, 1.0, 1e-3);
	assert_true(sep.rms < 1e-3);
	for (int k = 0; k < SEPARABLE_NODES; k++) {
		assert_float_equal(sep.a[k][0], 0.6, 1e-3);
		assert_float_equal(sep.a[k][2], 0.3, 1e-3);
	}
	/* A delta_phi-dependent BRDF is not separable: the error says so. */
	f.f_rgb = littable_brdf_analytic;
	separable_fit(&f, &sep);
	assert_true(sep.rms > 0.01);
}

static void test_bump_size(void **state)
{
	(void)state;
	/* 50 um of relief over a 5 mm, 512 px tile (pov.md section 4). */
	assert_float_equal(bumpmap_size(50, 512, 5), 5.12, 1e-12);
	assert_float_equal(bumpmap_size(0, 512, 5), 0.0, 1e-12);
}

static void test_filter_height(void **state)
{
	(void)state;
	/* A tile with one column of peaks: filtering by 4 keeps the mean
	 * height, re-encodes over the new range and keeps the tile periodic
	 * (blocks are aligned with the tile). */
	enum { N = 32 };
	uint16_t px[N * N];
	for (int y = 0; y < N; y++)
		for (int x = 0; x < N; x++)
			px[y * N + x] = x == 5 ? 65535 : 0;
	double lo, hi;
	uint16_t *f = bumpmap_filter(px, N, -10, 30, 4, &lo, &hi);
	assert_float_equal(lo, -10, 1e-9);
	assert_float_equal(hi, -10 + 40.0 / 4, 1e-9);
	for (int y = 0; y < N / 4; y++)
		for (int x = 0; x < N / 4; x++)
			assert_int_equal(f[y * (N / 4) + x], x == 1 ? 65535 : 0);
	free(f);
	assert_int_equal(bumpmap_filter_factor(512, 0.01, 0.005), 1);
	assert_int_equal(bumpmap_filter_factor(512, 0.01, 0.04), 4);	/* texel 0.04 = one pixel */
	assert_int_equal(bumpmap_filter_factor(512, 0.01, 0.5), 32);	/* 0.32 <= a pixel; stops at 16 px */
	assert_int_equal(bumpmap_filter_factor(64, 0.01, 10), 4);	/* stops at 16 px */
	assert_int_equal(bumpmap_filter_factor(48, 0.01, 0.5), 2);		/* 48 = 3 * 16 */
}

static char *write_tmp(const char *dir, const char *name, const char *text)
{
	char *p = xasprintf("%s/%s", dir, name);
	FILE *fp = fopen(p, "w");
	fputs(text, fp);
	fclose(fp);
	return p;
}

static const char *GOOD = "[scene]\nwidth = 64\nheight = 48\n[camera]\ntype = orthographic\nlocation = 0 0 -5\n"
			  "width = 2\n[light key]\nposition = 1 1 -1\n[light.fill]\ntype = point\nposition = -1 0 -2\n"
			  "color = 0.5 0.5 0.5\n[skin s]\npreset = paper\n[object ball]\nshape = sphere\nradius = 1\n";

static void test_scene(void **state)
{
	(void)state;
	char dir[] = "/tmp/test_pov.XXXXXX";
	assert_non_null(mkdtemp(dir));
	char *cause = NULL, *p = write_tmp(dir, "good.scene", GOOD);
	struct scene *s = scene_load(p, &cause);
	assert_non_null(s);
	assert_int_equal(s->width, 64);
	assert_int_equal(s->n_lights, 2);
	assert_true(s->lights[0].type == SCENE_LIGHT_PARALLEL && s->lights[1].type == SCENE_LIGHT_POINT);
	assert_string_equal(s->lights[1].name, "fill");
	assert_int_equal(s->objects[0].skin, 0);
	assert_int_equal(strategy_resolve(s, NULL, NULL), SCENE_LIGHTS_MIXTURE);
	double d[3], o[3] = { 0, 0, 0 };
	placement_light_dir(&s->lights[0], o, d);
	assert_float_equal(d[0], 1 / sqrt(3), 1e-12);

	/* The include: guard, version, restore; the scene file. */
	struct pov_skin ps = { .brdf = { .f_rgb = test_brdf }, .albedo_rgb = { 0.5, 0.4, 0.3 }, .ior = 1.5 };
	struct pov_options po = { .base = "t", .n_theta = 9, .n_gamma = 3, .n_mix = 5, .write_scene = 1 };
	struct pov_report r;
	assert_int_equal(povfiles_write(s, &ps, &po, dir, &r, &cause), 0);
	assert_int_equal(r.n_files, 3);
	povfiles_report_free(&r);
	char *inc = xasprintf("%s/t.inc", dir);
	FILE *fp = fopen(inc, "r");
	char buf[4096];
	size_t n = fread(buf, 1, sizeof buf - 1, fp);
	buf[n] = 0;
	fclose(fp);
	assert_non_null(strstr(buf, "#ifndef (Skinbake_t_Inc)"));
	assert_non_null(strstr(buf, "#version 3.7;"));
	assert_non_null(strstr(buf, "SKIN_Light_fill"));
	unlink(inc);
	free(inc);
	for (const char *f = "t.pov\0t.ini\0"; *f; f += strlen(f) + 1) {
		char *q = xasprintf("%s/%s", dir, f);
		assert_int_equal(access(q, R_OK), 0);
		unlink(q);
		free(q);
	}
	scene_free(s);
	unlink(p);
	free(p);

	/* Errors name the file and line and the offending key or section. */
	static const struct {
		const char *text, *want;
	} bad[] = {
		{ "[camera]\ntype = orthographic\ncolour = 1 1 1\n", ":3: [camera]: unknown key 'colour'" },
		{ "[lamp x]\nposition = 1 1 1\n", ":1: unknown section [lamp x]" },
		{ "[scene]\nwidth = 3\n", ":2: width = 3 is out of range [16, 8192]" },
		{ "[light k]\nposition = 1 1\n", ":2: position = '1 1' is not three numbers" },
		{ "[light k]\nposition = 1 1 1\n", "no [camera] section" },
		{ "[camera]\ntype = perspective\nlocation = 0 0 -5\n[light k]\nposition = 1 1 1\n[object a]\nshape = sphere\n",
		    "needs angle" },
		{ "[camera]\ntype = orthographic\nwidth = 2\nlocation = 0 0 -5\n[light k]\nposition = 1 1 1\n"
		  "[object a]\nshape = sphere\nradius = 1\nskin = nope\n[skin s]\npreset = paper\n",
		    ":8: [object a]: skin = 'nope' names no [skin] section" },
		{ "not ini\n", ":1: syntax error" },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		p = write_tmp(dir, "bad.scene", bad[i].text);
		cause = NULL;
		s = scene_load(p, &cause);
		assert_null(s);
		assert_non_null(cause);
		if (strstr(cause, bad[i].want) == NULL)
			fail_msg("scene %zu: '%s' lacks '%s'", i, cause, bad[i].want);
		assert_non_null(strstr(cause, "bad.scene"));
		free(cause);
		unlink(p);
		free(p);
	}
	rmdir(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_dphi),
		cmocka_unit_test(test_cos_gamma),
		cmocka_unit_test(test_axis),
		cmocka_unit_test(test_key_table),
		cmocka_unit_test(test_mixture),
		cmocka_unit_test(test_separable),
		cmocka_unit_test(test_bump_size),
		cmocka_unit_test(test_filter_height),
		cmocka_unit_test(test_scene),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
