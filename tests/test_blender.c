/* The Blender image-set writer: atlas layout and row order, the sampler the
 * importer's node tree mirrors, the albedo mean, the files and manifest, and
 * bad input that must leave no output. */
#include "config.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <json-c/json.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "export/blender/blender.h"
#include "geom/texdir.h"
#include "export/blender/blender_detail.h"
#include "export/blender/blender_fit.h"
#include "engine/specular.h"
#include "blender_analytic.h"
#include "io/exrio.h"
#include "io/pngio.h"
#include "base/util.h"

/* Linear in cos_l, cos_v and dphi with a different mix per channel, so the
 * bilinear sampler reproduces it exactly and any axis swap shows. */
static void linear_f(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	(void)ctx;
	rgb[0] = 1.0 + 0.5 * cos(ti) + 0.25 * cos(to) + 0.125 * dphi;
	rgb[1] = 2.0 - 0.5 * cos(ti);
	rgb[2] = 3.0 + 0.25 * dphi;
}

static void linear_model(struct brdf_source *m)
{
	analytic_model(m);
	m->f_rgb = linear_f;
}

static char *tmpdir(void)
{
	char *d = xstrdup("/tmp/test_blender.XXXXXX");
	if (mkdtemp(d) == NULL)
		fail_msg("mkdtemp failed");
	return d;
}

static void rmtree(const char *d)
{
	char *cmd = xasprintf("rm -rf '%s'", d);
	if (system(cmd) != 0)
		fail_msg("%s failed", cmd);
	free(cmd);
}

static int exists(const char *path)
{
	struct stat st;
	return stat(path, &st) == 0;
}

static void test_lut_layout(void **state)
{
	(void)state;
	struct brdf_source m;
	linear_model(&m);
	int n = 8, np = 3, w = n * np;
	float *lut = blender_lut(&m, n, np);
	size_t plane = (size_t)w * (size_t)n;
	for (int k = 0; k < np; k++)
		for (int r = 0; r < n; r++)
			for (int j = 0; j < n; j++) {
				double cl = 1.0 - (double)r / (n - 1), cv = (double)j / (n - 1), dphi = M_PI * k / (np - 1);
				double want[3];
				linear_f(NULL, acos(cl), acos(cv), dphi, want);
				for (int c = 0; c < 3; c++)
					assert_float_equal(lut[(size_t)c * plane + (size_t)r * w + (size_t)k * n + j],
					    M_PI * want[c], 1e-5);
			}
	/* Row 0 (top of the file) is cos_light = 1; the last row is grazing light. */
	assert_float_equal(lut[0], M_PI * (1.0 + 0.5), 1e-5);
	assert_float_equal(lut[(size_t)(n - 1) * w], M_PI * 1.0, 1e-5);
	free(lut);
}

static void test_lut_sample(void **state)
{
	(void)state;
	struct brdf_source m;
	linear_model(&m);
	int n = 9, np = 5;
	float *lut = blender_lut(&m, n, np);
	/* Exact for a function linear in each axis, at and between nodes and at the ends. */
	double pts[][3] = { { 1, 0, 0 }, { 0, 1, M_PI }, { 0.37, 0.81, 1.1 }, { 0.999, 0.001, 3.14 },
		{ 0.5, 0.5, M_PI / 4 }, { 0.05, 0.93, 2.9 } };
	for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
		double got[3], want[3];
		blender_lut_sample(lut, n, np, pts[i][0], pts[i][1], pts[i][2], got);
		linear_f(NULL, acos(pts[i][0]), acos(pts[i][1]), pts[i][2], want);
		for (int c = 0; c < 3; c++)
			assert_float_equal(got[c], M_PI * want[c], 1e-5);
	}
	free(lut);

	/* The analytic BRDF at a default-sized table: interpolation error well below 0.1 %. */
	analytic_model(&m);
	lut = blender_lut(&m, 32, 19);
	for (double cl = 0.05; cl < 1; cl += 0.11)
		for (double cv = 0.03; cv < 1; cv += 0.13)
			for (double ph = 0.01; ph < M_PI; ph += 0.37) {
				double got[3], want[3];
				blender_lut_sample(lut, 32, 19, cl, cv, ph, got);
				analytic_f(NULL, acos(cl), acos(cv), ph, want);
				for (int c = 0; c < 3; c++)
					assert_true(fabs(got[c] / (M_PI * want[c]) - 1) < 1e-3);
			}
	free(lut);
}

static void test_albedo_mean(void **state)
{
	(void)state;
	struct brdf_source m;
	analytic_model(&m);
	double a[3];
	blender_albedo_mean(&m, a);
	for (int c = 0; c < 3; c++)
		assert_float_equal(a[c], analytic_rho[c], 1e-9);
	/* a(theta) linear from a0 to a1 over [0, pi/2]: 2 int theta cos sin = pi/4, so the mean is (a0+a1)/2. */
	static const double th[2] = { 0, M_PI / 2 }, al[6] = { 0.2, 0.6, 0.5, 0.1, 0.3, 0.3 };
	m.theta_albedo = th;
	m.albedo_rgb = al;
	blender_albedo_mean(&m, a);
	assert_float_equal(a[0], 0.4, 1e-6);
	assert_float_equal(a[1], 0.3, 1e-6);
	assert_float_equal(a[2], 0.3, 1e-9);
	/* One node at 0: past the last node the albedo ramps to 0 at 90 deg
	 * (nothing enters at grazing; issue 26, no clamp), so the mean is a0/2. */
	m.n_albedo = 1;
	blender_albedo_mean(&m, a);
	assert_float_equal(a[0], 0.1, 1e-6);
}

static json_object *read_manifest(const char *dir)
{
	char *p = xasprintf("%s/manifest.json", dir);
	json_object *j = json_object_from_file(p);
	free(p);
	assert_non_null(j);
	return j;
}

static double jget(json_object *j, const char *path)
{
	/* "a.b.c" or "a.b[i]" */
	char *s = xstrdup(path), *save = NULL;
	json_object *x = j;
	for (char *t = strtok_r(s, ".", &save); t; t = strtok_r(NULL, ".", &save)) {
		char *br = strchr(t, '[');
		int idx = -1;
		if (br) {
			idx = atoi(br + 1);
			*br = '\0';
		}
		assert_true(json_object_object_get_ex(x, t, &x));
		if (idx >= 0)
			x = json_object_array_get_idx(x, (size_t)idx);
		assert_non_null(x);
	}
	free(s);
	return json_object_get_double(x);
}

static void test_export_flat(void **state)
{
	(void)state;
	char *d = tmpdir(), *out = xasprintf("%s/set", d), *cause = NULL, *p;
	struct brdf_source m;
	struct blender_options o;
	analytic_model(&m);
	blender_options_default(&o);
	o.lut_cos = 16;
	o.lut_phi = 7;
	o.map_size = 5;
	assert_int_equal(blender_export(&m, &o, out, &cause), 0);

	int w, h;
	float px[25];
	p = xasprintf("%s/albedo.exr", out);
	assert_int_equal(exrio_size(p, &w, &h, &cause), 0);
	assert_int_equal(w, 5);
	assert_int_equal(h, 5);
	assert_int_equal(exrio_read_channel(p, "G", 5, 5, px, &cause), 0);
	assert_float_equal(px[24], 0.4, 1e-6);
	free(p);

	p = xasprintf("%s/brdf_lut.exr", out);
	assert_int_equal(exrio_size(p, &w, &h, &cause), 0);
	assert_int_equal(w, 16 * 7);
	assert_int_equal(h, 16);
	float *lr = xmalloc(sizeof(float) * (size_t)(w * h));
	assert_int_equal(exrio_read_channel(p, "R", w, h, lr, &cause), 0);
	/* Top row: normal incidence, no delta_phi term.  Bottom row (grazing light),
	 * first column of a tile (grazing view): the last tile is the mirror side,
	 * tile 0 back toward the light; the last column of a tile views along the normal. */
	assert_float_equal(lr[0], 0.6, 1e-6);
	assert_float_equal(lr[(size_t)(h - 1) * w + 6 * 16], 0.6 * (1 - ANALYTIC_B), 1e-6);
	assert_float_equal(lr[(size_t)(h - 1) * w], 0.6 * (1 + ANALYTIC_B), 1e-6);
	assert_float_equal(lr[(size_t)(h - 1) * w + 15], 0.6, 1e-6);
	free(lr);
	free(p);

	int ch, bits;
	p = xasprintf("%s/roughness.png", out);
	uint16_t *r = pngio_read(p, &w, &h, &ch, &bits, &cause);
	assert_non_null(r);
	assert_int_equal(ch, 1);
	assert_int_equal(bits, 16);
	assert_int_equal(r[0], (uint16_t)lround(sqrt(0.35) * 65535));
	free(r);
	free(p);
	p = xasprintf("%s/normal.png", out);
	r = pngio_read(p, &w, &h, &ch, &bits, &cause);
	assert_non_null(r);
	assert_int_equal(ch, 3);
	assert_int_equal(r[0], 32768);
	assert_int_equal(r[2], 65535);
	free(r);
	free(p);

	json_object *j = read_manifest(out), *x;
	assert_int_equal((int)jget(j, "format_version"), BLENDER_FORMAT_VERSION);
	assert_true(json_object_object_get_ex(j, "detail", &x));
	assert_true(json_object_get_boolean(json_object_object_get(x, "flat")));
	assert_float_equal(jget(j, "sss_radius_m[0]"), 0.0012, 1e-12);
	assert_float_equal(jget(j, "albedo_rgb[2]"), 0.3, 1e-9);
	assert_float_equal(jget(j, "roughness"), sqrt(0.35), 1e-12);
	assert_int_equal((int)jget(j, "files.brdf_lut.width"), 16 * 7);
	/* The reference: sun at 45 deg elevation, camera at 60, azimuths 45 deg apart. */
	double cl = jget(j, "exact.reference.cos_light"), cv = jget(j, "exact.reference.cos_view");
	assert_float_equal(cl, sqrt(0.5), 1e-12);
	assert_float_equal(cv, sin(M_PI / 3), 1e-12);
	assert_float_equal(jget(j, "exact.reference.delta_phi_deg"), 45.0, 1e-9);
	double f[3];
	analytic_f(NULL, acos(cl), acos(cv), M_PI / 4, f);
	assert_float_equal(jget(j, "exact.reference.radiance_rgb[0]"), 3.0 * cl * f[0], 1e-12);
	/* 30 deg delta_phi steps here: linear interpolation of cos(dphi) is off by a few 1e-3. */
	assert_true(fabs(jget(j, "exact.reference.pi_fr_lut_rgb[1]") / (M_PI * f[1]) - 1) < 5e-3);
	/* The general-mode fit and the detail values. */
	assert_true(jget(j, "general_fit.rms_error") > 0);
	assert_true(jget(j, "general_fit.furnace_bake_rgb[0]") > 0.59);
	assert_float_equal(jget(j, "detail.mean_normal_z"), 1.0, 1e-9);
	for (int c = 0; c < 3; c++) {
		char key[64];
		snprintf(key, sizeof key, "exact.reference.radiance_detail_rgb[%d]", c);
		double rd = jget(j, key);
		snprintf(key, sizeof key, "exact.reference.radiance_rgb[%d]", c);
		assert_true(fabs(rd / jget(j, key) - 1) < 5e-3);	/* flat map: the table's interpolation only */
	}
	json_object_put(j);
	free(out);
	rmtree(d);
	free(d);
}

static void write_textures(const char *dir, int bits_height, int with_tile)
{
	int w = 6, h = 5;
	uint16_t hp[30], np[90];
	for (int i = 0; i < w * h; i++) {
		hp[i] = (uint16_t)(bits_height == 16 ? 1000 * i : i);
		np[3 * i] = (uint16_t)(30000 + i);
		np[3 * i + 1] = 33000;
		np[3 * i + 2] = 64000;
	}
	struct png_text_kv t[] = { { "skinbake:tile_mm", "8" }, { "skinbake:height_min_um", "-20" },
		{ "skinbake:height_max_um", "35" } };
	char *cause = NULL, *p = xasprintf("%s/height.png", dir);
	assert_int_equal(pngio_write(p, w, h, 1, bits_height, hp, 0, with_tile ? 3 : 0, t, &cause), 0);
	free(p);
	p = xasprintf("%s/normal.png", dir);
	assert_int_equal(pngio_write(p, w, h, 3, 16, np, 0, 0, NULL, &cause), 0);
	free(p);
}

static void test_export_textures(void **state)
{
	(void)state;
	char *d = tmpdir(), *tex = xasprintf("%s/tex", d), *out = xasprintf("%s/set", d), *cause = NULL;
	assert_int_equal(util_mkdirs(tex, &cause), 0);
	write_textures(tex, 16, 1);
	struct brdf_source m;
	struct blender_options o;
	analytic_model(&m);
	blender_options_default(&o);
	o.lut_cos = 8;
	o.lut_phi = 2;
	struct texdir *td = texdir_load(tex, 1, &cause);
	assert_non_null(td);
	m.detail = td;
	assert_int_equal(blender_export(&m, &o, out, &cause), 0);
	int w, h, ch, bits;
	char *p = xasprintf("%s/height.png", out);
	uint16_t *hp = pngio_read(p, &w, &h, &ch, &bits, &cause);
	assert_non_null(hp);
	assert_int_equal(w, 6);
	assert_int_equal(h, 5);
	assert_int_equal(hp[29], 29000);	/* bottom-right stays bottom-right */
	char *tmm = pngio_read_text(p, "skinbake:tile_mm");
	assert_string_equal(tmm, "8");
	free(tmm);
	free(hp);
	free(p);
	p = xasprintf("%s/normal.png", out);
	hp = pngio_read(p, &w, &h, &ch, &bits, &cause);
	assert_int_equal(hp[3 * 29], 30029);
	free(hp);
	free(p);
	json_object *j = read_manifest(out);
	assert_float_equal(jget(j, "detail.tile_mm"), 8.0, 0);
	assert_float_equal(jget(j, "detail.height_max_um"), 35.0, 0);
	assert_int_equal((int)jget(j, "files.normal.width"), 6);
	json_object_put(j);
	texdir_free(td);
	free(tex);
	free(out);
	rmtree(d);
	free(d);
}

/* Bad input: a message naming the problem and no output directory at all. */
static void test_export_bad_input(void **state)
{
	(void)state;
	char *d = tmpdir(), *tex = xasprintf("%s/tex", d), *out = xasprintf("%s/set", d), *cause = NULL;
	struct brdf_source m;
	struct blender_options o;
	analytic_model(&m);
	blender_options_default(&o);

	/* Textures are read into the source before the export (texdir_load). */
	assert_null(texdir_load(tex, 1, &cause));	/* does not exist */
	assert_non_null(strstr(cause, "height.png"));
	free(cause);
	cause = NULL;

	assert_int_equal(util_mkdirs(tex, &cause), 0);
	write_textures(tex, 8, 1);
	assert_null(texdir_load(tex, 1, &cause));
	assert_non_null(strstr(cause, "16-bit gray"));
	free(cause);
	cause = NULL;
	write_textures(tex, 16, 0);
	assert_null(texdir_load(tex, 1, &cause));
	assert_non_null(strstr(cause, "skinbake:tile_mm"));
	free(cause);
	cause = NULL;
	/* Detail maps read without the normal map cannot be exported. */
	write_textures(tex, 16, 1);
	struct texdir *td = texdir_load(tex, 0, &cause);
	assert_non_null(td);
	m.detail = td;
	assert_int_equal(blender_export(&m, &o, out, &cause), -1);
	assert_non_null(strstr(cause, "normal.png"));
	free(cause);
	cause = NULL;
	m.detail = NULL;
	texdir_free(td);
	assert_false(exists(out));

	o.lut_cos = 3;
	assert_int_equal(blender_export(&m, &o, out, &cause), -1);
	assert_string_equal(cause, "lut_cos = 3 is out of range [8, 1024]");
	free(cause);
	cause = NULL;
	blender_options_default(&o);
	o.sun_elevation = 0;
	assert_int_equal(blender_export(&m, &o, out, &cause), -1);
	free(cause);
	cause = NULL;
	blender_options_default(&o);
	m.sss_radius_cm[1] = 0;
	assert_int_equal(blender_export(&m, &o, out, &cause), -1);
	assert_non_null(strstr(cause, "subsurface radius[1]"));
	free(cause);
	assert_false(exists(out));
	free(tex);
	free(out);
	rmtree(d);
	free(d);
}

/* A BRDF that is exactly the general mode's mixture: subsurface weights s,
 * Ashikhmin-Shirley weights g (exponent 4, view-independent here) and the
 * GGX lobe of the model's index and alpha. */
static const double mix_s[3] = { 0.5, 0.3, 0.2 }, mix_g[3] = { 0.04, 0.03, 0.02 };

static void mix_f(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	const struct brdf_source *m = ctx;
	struct specular_stack st = { .n = 2, .n_list = { 1.0, m->ior }, .model = OPTICS_FRESNEL_EXACT };
	double cl = cos(ti), cv = cos(to), sl = sin(ti), sv = sin(to), x = 1 - cl;
	double h[3] = { sl + sv * cos(dphi), sv * sin(dphi), cl + cv }, hn = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
	double hz = h[2] / hn, hl = (sl * h[0] + cl * h[2]) / hn;
	double as = 5.0 / 8.0 * pow(hz, 4) / (hl * (cl > cv ? cl : cv));
	double fl = pow(x, 5), fv = pow(1 - cv, 5), rr = BLENDER_FIT_SSS_ROUGHNESS * (1 + cl * cv + sl * sv * cos(dphi));
	double d = 1 - 0.5 * fl + rr * (fl + fv + fl * fv * (rr - 1)), sp = specular_ggx(&st, m->roughness, ti, to, dphi);
	for (int c = 0; c < 3; c++)
		rgb[c] = (mix_s[c] * d + mix_g[c] * as) / M_PI + sp;
}

static void test_fit_recovers_mixture(void **state)
{
	(void)state;
	struct brdf_source m;
	struct blender_fit f;
	char *cause = NULL;
	analytic_model(&m);
	m.f_rgb = mix_f;
	m.ctx = &m;
	assert_int_equal(blender_fit_general(&m, &f, &cause), 0);
	assert_true(f.specular);
	assert_float_equal(f.glossy_exponent, 4.0, 0);
	assert_float_equal(f.glossy_roughness, sqrt(sqrt(2.0 / 6.0)), 1e-12);
	assert_float_equal(f.cos_min, 0.1, 1e-12);	/* albedo nodes reach 90 deg */
	for (int j = 0; j < f.n_view; j++)
		for (int c = 0; c < 3; c++) {
			assert_float_equal(f.sss_rgb[j][c], mix_s[c], 1e-9);
			assert_float_equal(f.glossy_rgb[j][c], mix_g[c], 1e-9);
		}
	for (int c = 0; c < 3; c++) {
		assert_true(f.rms_weighted[c] < 1e-9);
		assert_true(f.max_rel[c] < 1e-8);
	}
	double a[3], b[3];
	blender_fit_eval(&f, 0.3, 0.7, 2.0, a);
	mix_f(&m, acos(0.3), acos(0.7), 2.0, b);
	for (int c = 0; c < 3; c++)
		assert_float_equal(a[c], M_PI * b[c], 1e-9);
}

/* The analytic test BRDF has a back-scatter term the mixture cannot follow
 * and no specular lobe: the fit drops the lobe and states its error. */
static void test_fit_analytic(void **state)
{
	(void)state;
	struct brdf_source m;
	struct blender_fit f;
	char *cause = NULL;
	analytic_model(&m);
	assert_int_equal(blender_fit_general(&m, &f, &cause), 0);
	assert_false(f.specular);
	for (int c = 0; c < 3; c++) {
		assert_true(f.rms_weighted[c] > 0.01 && f.rms_weighted[c] < 0.2);
		assert_true(f.rms_uniform[c] >= f.rms_weighted[c] * 0.5);
		for (int j = 0; j < f.n_view; j++)
			assert_true(f.sss_rgb[j][c] >= 0 && f.glossy_rgb[j][c] >= 0);
	}
	assert_true(f.n_checked > 1000);
}

static void test_detail(void **state)
{
	(void)state;
	/* Normals (0, 0, 1) and (0.6, 0, 0.8): mean z 0.9. */
	uint16_t nm[6];
	double n2[3] = { 0.6, 0, 0.8 };
	nm[0] = nm[1] = 32768;
	nm[2] = 65535;
	for (int c = 0; c < 3; c++)
		nm[3 + c] = (uint16_t)lround((n2[c] + 1) / 2 * 65535);
	assert_float_equal(blender_detail_mean_nz(nm, 2), 0.9, 1e-4);
	/* One tilted facet under a Lambert atlas (pi f = 0.5): E cos_l 0.5/pi / n_z. */
	struct brdf_source m;
	linear_model(&m);
	m.f_rgb = analytic_f;
	float *lut = blender_lut(&m, 16, 5);
	size_t plane = (size_t)16 * 5 * 16;
	for (size_t i = 0; i < 3 * plane; i++)
		lut[i] = 0.5f;
	double sun[3] = { 0, 0, 1 }, view[3] = { 0, 0, 1 }, rgb[3];
	blender_detail_radiance(nm + 3, 1, 1, sun, view, 2.0, lut, 16, 5, rgb);
	for (int c = 0; c < 3; c++)
		assert_float_equal(rgb[c], 2.0 * 0.8 * 0.5 / M_PI / 0.8, 2e-4);
	/* The area factor keeps the plane's mean irradiance: flat and tilted facets alike. */
	blender_detail_radiance(nm, 2, 1, sun, view, 2.0, lut, 16, 5, rgb);
	assert_float_equal(rgb[0], 2.0 * 0.5 / M_PI, 2e-4);
	free(lut);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_lut_layout),
		cmocka_unit_test(test_lut_sample),
		cmocka_unit_test(test_albedo_mean),
		cmocka_unit_test(test_export_flat),
		cmocka_unit_test(test_export_textures),
		cmocka_unit_test(test_export_bad_input),
		cmocka_unit_test(test_fit_recovers_mixture),
		cmocka_unit_test(test_fit_analytic),
		cmocka_unit_test(test_detail),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
