/* colour: CMF fits, D65, sRGB, CIELAB and the RGB weight matrix. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "skin/colour.h"

/* D65 chromaticity with the 1931 fit: x 0.3127, y 0.3290 (CIE 15). */
static void test_white_point(void **state)
{
	(void)state;
	double w[3];
	colour_white_xyz(COLOUR_CIE1931_2DEG, w);
	double s = w[0] + w[1] + w[2];
	assert_float_equal(w[1], 1.0, 1e-12);
	assert_float_equal(w[0] / s, 0.3127, 0.001);
	assert_float_equal(w[1] / s, 0.3290, 0.001);
	/* 10 degree: x10 0.3138, y10 0.3310 (CIE 15); the single-lobe fit is coarser. */
	colour_white_xyz(COLOUR_CIE1964_10DEG, w);
	s = w[0] + w[1] + w[2];
	assert_float_equal(w[0] / s, 0.3138, 0.004);
	assert_float_equal(w[1] / s, 0.3310, 0.004);
	/* The white reflector is sRGB white within the fit's error. */
	double rgb[3];
	colour_white_xyz(COLOUR_CIE1931_2DEG, w);
	colour_xyz_to_linear_srgb(w, rgb);
	for (int c = 0; c < 3; c++)
		assert_float_equal(rgb[c], 1.0, 0.002);
}

static void test_cmf_values(void **state)
{
	(void)state;
	/* CIE 1931 table: ybar(555) = 1.0000, xbar(600) = 1.0622, zbar(450) = 1.7471. */
	double c[3];
	colour_cmf(COLOUR_CIE1931_2DEG, 555, c);
	assert_float_equal(c[1], 1.0, 0.01);
	colour_cmf(COLOUR_CIE1931_2DEG, 600, c);
	assert_float_equal(c[0], 1.0622, 0.02);
	colour_cmf(COLOUR_CIE1931_2DEG, 450, c);
	assert_float_equal(c[2], 1.7471, 0.04);
	/* CIE 1964: xbar10(600) = 1.1115, ybar10(560) = 0.9972. */
	colour_cmf(COLOUR_CIE1964_10DEG, 600, c);
	assert_float_equal(c[0], 1.1115, 0.02);
	colour_cmf(COLOUR_CIE1964_10DEG, 560, c);
	assert_float_equal(c[1], 0.9972, 0.02);
	assert_float_equal(colour_d65(560), 100.0, 1e-12);
	assert_float_equal(colour_d65(562.5), 0.5 * (100.0 + 98.1671), 1e-9);
	assert_float_equal(colour_d65(300), 0.0, 0);
}

static void test_lab(void **state)
{
	(void)state;
	double one[3] = { 1, 1, 1 }, lab[3];
	colour_linear_srgb_to_lab(one, lab);
	assert_float_equal(lab[0], 100, 1e-9);
	assert_float_equal(lab[1], 0, 1e-9);
	assert_float_equal(lab[2], 0, 1e-9);
	double grey[3] = { 0.18, 0.18, 0.18 };
	colour_linear_srgb_to_lab(grey, lab);
	assert_float_equal(lab[0], 49.496, 0.01);	/* L* of 18% grey */
	assert_float_equal(lab[1], 0, 1e-6);
	double red[3] = { 1, 0, 0 };
	colour_linear_srgb_to_lab(red, lab);	/* sRGB red: 53.24, 80.09, 67.20 */
	assert_float_equal(lab[0], 53.24, 0.05);
	assert_float_equal(lab[1], 80.09, 0.1);
	assert_float_equal(lab[2], 67.20, 0.1);
	double l2[3] = { 60, 0, 10 };
	assert_float_equal(colour_ita(l2), 45.0, 1e-9);
}

/* Our D65/10-degree CIELAB of the Xiao 2016 representative spectra against
 * the values in that file's footer (computed with the tabulated CMFs). */
static void test_xiao_spectra(void **state)
{
	(void)state;
	/* p50 spectrum (Lpct50_row33), 380..740 nm. */
	static const double r[] = { 0.0916, 0.1028, 0.1117, 0.1164, 0.1199, 0.1312, 0.1516, 0.1740, 0.1915,
		0.2053, 0.2138, 0.2239, 0.2354, 0.2424, 0.2420, 0.2357, 0.2319, 0.2346, 0.2416, 0.2451, 0.2581,
		0.2977, 0.3419, 0.3729, 0.3942, 0.4075, 0.4167, 0.4254, 0.4326, 0.4405, 0.4475, 0.4547, 0.4614,
		0.4645, 0.4674, 0.4685, 0.4672 };
	double wl[37];
	for (int i = 0; i < 37; i++)
		wl[i] = 380 + 10 * i;
	double xyz[3], w[3], lab[3];
	colour_white_xyz(COLOUR_CIE1964_10DEG, w);
	colour_spectrum_xyz(COLOUR_CIE1964_10DEG, 37, wl, r, xyz);
	colour_xyz_to_lab(xyz, w, lab);
	assert_float_equal(lab[0], 58.4, 0.5);
	assert_float_equal(lab[1], 8.7, 1.5);
	assert_float_equal(lab[2], 16.7, 0.5);
}

static void test_weights(void **state)
{
	(void)state;
	/* The paper's set maps directly, whatever the order. */
	double p[3] = { 550, 656, 470 }, m[9];
	colour_rgb_weights(3, p, m);
	double want[9] = { 0, 1, 0, 1, 0, 0, 0, 0, 1 };
	for (int i = 0; i < 9; i++)
		assert_float_equal(m[i], want[i], 0);
	/* A white reflector gives (1, 1, 1) for any set, a grey one its level. */
	double wl[16], mm[3 * 16];
	for (int i = 0; i < 16; i++)
		wl[15 - i] = 400 + 20 * i;	/* descending on purpose */
	colour_rgb_weights(16, wl, mm);
	for (int c = 0; c < 3; c++) {
		double s = 0;
		for (int i = 0; i < 16; i++)
			s += mm[c * 16 + i];
		assert_float_equal(s, 1.0, 1e-12);
	}
	/* The weights reproduce colour_spectrum_xyz -> sRGB (up to the white scale). */
	double refl[16], sorted_wl[16], sorted_r[16];
	for (int i = 0; i < 16; i++)
		refl[i] = 0.2 + 0.3 * (wl[i] - 400) / 300;	/* reddish ramp */
	for (int i = 0; i < 16; i++)
		sorted_wl[i] = wl[15 - i], sorted_r[i] = refl[15 - i];
	double xyz[3], rgb[3], rgbw[3] = { 0, 0, 0 }, white[3], wrgb[3];
	colour_spectrum_xyz(COLOUR_CIE1931_2DEG, 16, sorted_wl, sorted_r, xyz);
	colour_xyz_to_linear_srgb(xyz, rgb);
	colour_white_xyz(COLOUR_CIE1931_2DEG, white);
	colour_xyz_to_linear_srgb(white, wrgb);
	for (int c = 0; c < 3; c++) {
		for (int i = 0; i < 16; i++)
			rgbw[c] += mm[c * 16 + i] * refl[i];
		assert_float_equal(rgbw[c], rgb[c] / wrgb[c], 1e-9);
	}
	assert_true(rgbw[0] > rgbw[1] && rgbw[1] > rgbw[2]);
	/* One wavelength: grey. */
	double one = 550, m1[3];
	colour_rgb_weights(1, &one, m1);
	assert_true(m1[0] == 1 && m1[1] == 1 && m1[2] == 1);
}

/* CIEDE2000 against the 34 pairs of Sharma, Wu & Dalal 2005 (Table 1),
 * published to 4 decimals: agreement within 5e-5 (rounding), both orders. */
static void test_de2000(void **state)
{
	(void)state;
	const char *top = getenv("top_srcdir");
	char path[4096];
	snprintf(path, sizeof path, "%s/tests/data/ciede2000_sharma2005.tsv", top ? top : ".");
	FILE *fp = fopen(path, "r");
	assert_non_null(fp);
	char line[512];
	int n = 0;
	while (fgets(line, sizeof line, fp)) {
		double l1[3], l2[3], de;
		int k;
		if (line[0] == '#' || sscanf(line, "%d %lf %lf %lf %lf %lf %lf %lf", &k, &l1[0], &l1[1], &l1[2], &l2[0],
		    &l2[1], &l2[2], &de) != 8)
			continue;
		double d12 = colour_de2000(l1, l2), d21 = colour_de2000(l2, l1);
		if (fabs(d12 - de) > 5e-5 || fabs(d21 - de) > 5e-5)
			fail_msg("pair %d: dE00 %.6f / %.6f, published %.4f", k, d12, d21, de);
		n++;
	}
	fclose(fp);
	assert_int_equal(n, 34);
	double a[3] = { 55, 12, 16 };
	assert_float_equal(colour_de2000(a, a), 0.0, 0);
}

/* Lab -> XYZ -> Lab is the identity; through linear sRGB it is up to the
 * 7-digit IEC matrices, which are inverses to about 1e-7 (1e-4 in Lab). */
static void test_lab_inverse(void **state)
{
	(void)state;
	static const double labs[][3] = { { 58.4, 8.7, 16.7 }, { 5.0, 1.0, -2.0 }, { 95.0, -3.0, 4.0 }, { 0.5, 0, 0 } };
	double w[3];
	colour_white_xyz(COLOUR_CIE1931_2DEG, w);
	for (size_t i = 0; i < sizeof labs / sizeof labs[0]; i++) {
		double xyz[3], rgb[3], back[3];
		colour_lab_to_xyz(labs[i], w, xyz);
		colour_xyz_to_lab(xyz, w, back);
		for (int c = 0; c < 3; c++)
			assert_float_equal(back[c], labs[i][c], 1e-9);
		colour_lab_to_linear_srgb(labs[i], rgb);
		colour_linear_srgb_to_lab(rgb, back);
		for (int c = 0; c < 3; c++)
			assert_float_equal(back[c], labs[i][c], 1e-4);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_white_point),
		cmocka_unit_test(test_cmf_values),
		cmocka_unit_test(test_lab),
		cmocka_unit_test(test_xiao_spectra),
		cmocka_unit_test(test_weights),
		cmocka_unit_test(test_de2000),
		cmocka_unit_test(test_lab_inverse),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
