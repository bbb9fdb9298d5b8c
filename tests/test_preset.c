/* preset: built-ins parse, files round-trip, and bad presets give clear
 * errors naming file:line, key, value and range. */
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

#include "skin/preset.h"
#include "base/util.h"

static void test_builtins(void **state)
{
	(void)state;
	assert_true(preset_count() >= 14);
	for (int i = 0; i < preset_count(); i++) {
		char *cause = NULL;
		struct skin_params *p = preset_load_builtin(preset_name(i), &cause);
		if (p == NULL)
			fail_msg("%s: %s", preset_name(i), cause);
		assert_string_equal(preset_get_name(p), preset_name(i));
		assert_string_equal(p->description, preset_summary(i));
		double wl[SKIN_MAX_WL];
		int n = preset_default_wavelengths(p, wl, SKIN_MAX_WL);
		assert_true(n >= 3);
		for (int k = 0; k < n; k++) {
			struct slab s;
			if (tissue_slab(p, wl[k], &s, &cause) != 0)
				fail_msg("%s at %g: %s", preset_name(i), wl[k], cause);
		}
		/* The resolved INI loads back to the same values. */
		char *ini = preset_to_ini(p);
		struct skin_params *q = preset_load_string(ini, "round-trip", &cause);
		if (q == NULL)
			fail_msg("%s round trip: %s\n%s", preset_name(i), cause, ini);
		char *ini2 = preset_to_ini(q);
		assert_string_equal(ini, ini2);
		for (int k = 0; k < n; k++) {
			struct slab a, b;
			assert_int_equal(tissue_slab(p, wl[k], &a, &cause), 0);
			assert_int_equal(tissue_slab(q, wl[k], &b, &cause), 0);
			for (int l = 1; l <= a.n_layers; l++)
				assert_memory_equal(&a.layer[l], &b.layer[l], sizeof a.layer[l]);
		}
		free(ini);
		free(ini2);
		preset_free(q);
		preset_free(p);
	}
	assert_int_equal(preset_find("paper"), 0);
	assert_int_equal(preset_find("nope"), -1);
}

static void test_paper(void **state)
{
	(void)state;
	char *cause = NULL;
	struct skin_params *p = preset_load_builtin("paper", &cause);
	double wl[8];
	assert_int_equal(preset_default_wavelengths(p, wl, 8), 3);
	assert_float_equal(wl[0], 470, 0);
	assert_float_equal(wl[1], 550, 0);
	assert_float_equal(wl[2], 656, 0);	/* Table 2's "56" */
	assert_float_equal(preset_surface_ior(p), 1.5, 0);
	assert_float_equal(preset_surface_roughness(p), 0.25, 0);
	preset_free(p);
	p = preset_load_builtin("paper-dry", &cause);
	assert_non_null(p);
	assert_false(tissue_layer_present(p, SKIN_SEBUM));
	assert_float_equal(preset_surface_ior(p), 1.43, 0);	/* the epidermis's n */
	assert_float_equal(preset_surface_roughness(p), 0.35, 0);
	struct slab s;
	assert_int_equal(tissue_slab(p, 550, &s, &cause), 0);
	assert_int_equal(s.n_layers, 2);
	assert_float_equal(s.layer[1].mu_a, 50, 0);
	preset_free(p);
	/* Unknown built-in: the message lists the names. */
	assert_null(preset_load_builtin("purple", &cause));
	assert_non_null(strstr(cause, "unknown preset 'purple'"));
	assert_non_null(strstr(cause, "paper-dry"));
	free(cause);
}

/* Expect a load failure whose message contains every fragment. */
static void expect_error(const char *text, const char *f1, const char *f2)
{
	char *cause = NULL;
	struct skin_params *p = preset_load_string(text, "t.ini", &cause);
	if (p != NULL)
		fail_msg("loaded but should fail: %s", text);
	if (strstr(cause, f1) == NULL || (f2 && strstr(cause, f2) == NULL))
		fail_msg("message '%s' lacks '%s' / '%s'", cause, f1, f2 ? f2 : "");
	free(cause);
}

static void test_errors(void **state)
{
	(void)state;
	expect_error("[skin]\nmodel = chromophores\n[dermis]\ncolour = 3\n", "t.ini:4: unknown key 'colour' in [dermis]",
	    "blood");
	expect_error("[epidermis]\nmelanin = 0.9\n", "t.ini:2: epidermis.melanin = 0.9: out of range [0, 0.5]", NULL);
	expect_error("[dermis]\nblood = lots\n", "t.ini:2: dermis.blood = lots: not a decimal number", "[0, 0.2]");
	expect_error("[derm]\nblood = 0.1\n", "t.ini:1: unknown section [derm]", NULL);
	expect_error("blood = 0.1\n", "t.ini:1: key 'blood' outside any section", NULL);
	expect_error("[dermis]\nblood = 0.1\nblood = 0.2\n", "t.ini:3: dermis.blood is given twice", NULL);
	expect_error("[dermis]\nthis line has no equals sign\n", "t.ini:2: syntax error", NULL);
	expect_error("[epidermis]\nmelanin = 0.1\n[skin]\nbase = paper\n", "t.ini:4: skin.base = paper: base must be the first key",
	    NULL);
	expect_error("[skin]\nbase = nothing\n", "t.ini:2: skin.base = nothing: unknown preset 'nothing'", NULL);
	expect_error("[skin]\nwavelengths = 400, 390\n", "t.ini:2: skin.wavelengths = 400, 390:", "ascending");
	expect_error("[skin]\nwavelengths = 300:700:10\n", "300 nm is out of range [380, 780]", NULL);
	expect_error("[skin]\nmodel = magic\n", "skin.model = magic: not one of chromophores, tables", NULL);
	expect_error("[override.900]\nepidermis.mua = 3\n", "t.ini:1: [override.900]", "out of range [380, 780]");
	expect_error("[override.550]\nepidermis.mua = -3\n", "t.ini:2: override.550: epidermis.mua = -3: out of range [0, 100000]",
	    NULL);
	expect_error("[override.550]\nskin.mua = 3\n", "t.ini:2: unknown key 'skin.mua' in [override.550]", NULL);
	expect_error("[sebum]\nthickness = 0\n[override.550]\nsebum.mua = 3\n", "t.ini: [override.550] sets sebum values",
	    NULL);
	expect_error("[skin]\nmodel = tables\n[override.550]\nepidermis.mua = 3\nepidermis.mus = 30\ndermis.mua = 1\n",
	    "[override.550] lacks dermis.mus", NULL);
	expect_error("[skin]\nmodel = tables\nwavelengths = 500\n[override.550]\nepidermis.mua = 3\nepidermis.mus = 30\n"
	    "dermis.mua = 1\ndermis.mus = 30\n", "wavelengths includes 500 nm", "tabulated: 550");
	expect_error("[dermis]\nthickness = inf\n[subcutis]\nthickness = 1\n", "only the deepest layer may be semi-infinite",
	    NULL);
	expect_error("[subcutis]\nn = ding2006\n", "subcutis.n = ding2006", "only for epidermis and dermis");
	expect_error("[skin]\nname = my skin\n", "skin.name = my skin: use letters", NULL);
	expect_error("[dermis]\nblood = 0.1\n  so2 = 0.5\n", "t.ini:3: indented line continues 'blood'", NULL);

	/* An over-long line is an error naming its number, not a silent split. */
	char *longline = xasprintf("[skin]\n; fine\ndescription = %0200d\n", 7);
	expect_error(longline, "t.ini:3: line 3 is longer than 199 characters", NULL);
	free(longline);
	/* 199 characters are fine (with CRLF too). */
	char pad[200];
	memset(pad, 'x', sizeof pad);
	pad[198] = '\0';
	char *ok = xasprintf("[skin]\r\n;%s\r\ndescription = fine\r\n", pad);
	char *cause = NULL;
	struct skin_params *p = preset_load_string(ok, "ok.ini", &cause);
	if (p == NULL)
		fail_msg("%s", cause);
	assert_string_equal(p->description, "fine");
	preset_free(p);
	free(ok);
}

static void test_files(void **state)
{
	(void)state;
	char *cause = NULL;
	assert_null(preset_load_file("/nonexistent/dir/skin.ini", &cause));
	assert_string_equal(cause, "cannot open /nonexistent/dir/skin.ini: No such file or directory");
	free(cause);

	char path[] = "/tmp/skinbake-preset-XXXXXX";
	int fd = mkstemp(path);
	assert_true(fd >= 0);
	const char *text = "; my preset\n[skin]\nbase = fair-oily   ; start here\ndescription = fair, more blood\n"
	    "wavelengths = 400:700:50, 720\n[dermis]\nblood = 0.05\n[override.550]\ndermis.g = 0.9\n";
	assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
	close(fd);
	struct skin_params *p = preset_load_file(path, &cause);
	if (p == NULL)
		fail_msg("%s", cause);
	const char *base = strrchr(path, '/') + 1;
	assert_string_equal(p->name, base);	/* the file name */
	assert_string_equal(p->description, "fair, more blood");
	assert_string_equal(p->origin, path);
	assert_int_equal(p->n_wl, 8);
	assert_float_equal(p->wl[6], 700, 0);
	assert_float_equal(p->wl[7], 720, 0);
	assert_float_equal(p->layer[SKIN_DERMIS].blood, 0.05, 0);
	struct skin_params *f = preset_load_builtin("fair-oily", &cause);
	assert_float_equal(p->layer[SKIN_EPIDERMIS].melanin, f->layer[SKIN_EPIDERMIS].melanin, 0);
	struct layer l;
	assert_int_equal(tissue_layer_optics(p, SKIN_DERMIS, 550, &l, &cause), 0);
	assert_float_equal(l.g, 0.9, 0);
	assert_int_equal(tissue_layer_optics(p, SKIN_DERMIS, 560, &l, &cause), 0);
	assert_true(l.g < 0.85);	/* van Gemert elsewhere */
	preset_free(f);
	preset_free(p);

	/* Errors in a file carry its path and the line. */
	FILE *fp = fopen(path, "w");
	fputs("[skin]\nbase = paper\n\n[epidermis]\nthickness = 2\n", fp);
	fclose(fp);
	assert_null(preset_load_file(path, &cause));
	char *want = xasprintf("%s:5: epidermis.thickness = 2: out of range [0.001, 0.05] cm", path);
	assert_string_equal(cause, want);
	free(want);
	free(cause);
	unlink(path);
}

static void test_wavelength_list(void **state)
{
	(void)state;
	double wl[SKIN_MAX_WL];
	char *cause = NULL;
	assert_int_equal(preset_parse_wavelengths("380:780:1", wl, &cause), 401);
	assert_int_equal(preset_parse_wavelengths(" 470 , 550,656 ", wl, &cause), 3);
	assert_float_equal(wl[2], 656, 0);
	assert_int_equal(preset_parse_wavelengths("380:780:0.5", wl, &cause), -1);
	assert_non_null(strstr(cause, "more than 401"));
	free(cause);
	assert_int_equal(preset_parse_wavelengths("400:500", wl, &cause), -1);
	free(cause);
	assert_int_equal(preset_parse_wavelengths("", wl, &cause), -1);
	free(cause);
}

/* Numeric keys by name: range, set (range-checked), get; others refused. */
static void test_number_keys(void **state)
{
	(void)state;
	char *cause = NULL;
	struct skin_params *p = preset_load_builtin("fair-oily", &cause);
	assert_non_null(p);
	double lo, hi, v;
	const char *unit;
	assert_int_equal(preset_number_key("epidermis.melanin", &lo, &hi, &unit, &cause), 0);
	assert_true(lo == 0 && hi == 0.5 && strcmp(unit, "") == 0);
	assert_int_equal(preset_number_key("dermis.thickness", &lo, &hi, &unit, &cause), 0);
	assert_string_equal(unit, "cm");
	assert_int_equal(preset_set_number(p, "dermis.blood", 0.07, &cause), 0);
	assert_int_equal(preset_get_number(p, "dermis.blood", &v), 0);
	assert_true(v == 0.07 && p->layer[SKIN_DERMIS].blood == 0.07);
	assert_int_equal(preset_set_number(p, "surface.roughness_skin", 0.5, &cause), 0);
	assert_true(p->roughness_skin == 0.5);
	assert_int_equal(preset_set_number(p, "dermis.blood", 0.3, &cause), -1);
	assert_non_null(strstr(cause, "dermis.blood = 0.3: out of range [0, 0.2]"));
	free(cause);
	cause = NULL;
	for (const char *bad = "skin.name\0skin.wavelengths\0epidermis.colour\0melanin\0"; *bad; bad += strlen(bad) + 1) {
		assert_int_equal(preset_number_key(bad, &lo, &hi, &unit, &cause), -1);
		assert_non_null(strstr(cause, "is not a numeric preset key"));
		assert_non_null(strstr(cause, "epidermis.melanin"));
		free(cause);
		cause = NULL;
		assert_int_equal(preset_get_number(p, bad, &v), -1);
	}
	preset_free(p);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_builtins),
		cmocka_unit_test(test_paper),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_files),
		cmocka_unit_test(test_wavelength_list),
		cmocka_unit_test(test_number_keys),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
