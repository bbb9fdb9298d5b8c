/* spectra and tissue: tables and formulas against values quoted in
 * ../shared/notes/skin-optics.md and ../shared/skin_data. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "skin/preset.h"
#include "skin/spectra.h"
#include "skin/tissue.h"

static void close_rel(double got, double want, double rel)
{
	if (fabs(got - want) > rel * fabs(want))
		fail_msg("got %.6g, want %.6g (rel. tol. %g)", got, want, rel);
}

/* Whole-blood table of skin-optics.md A2.3 (values rounded there). */
static void test_blood(void **state)
{
	(void)state;
	static const double t[][3] = { { 420, 2572, 2182 }, { 450, 336, 553 }, { 500, 112, 112 },
		{ 542, 285, 258 }, { 560, 175, 288 }, { 576, 297, 215 }, { 600, 17.1, 78.6 }, { 660, 1.7, 17.3 } };
	for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
		close_rel(spectra_mua_blood_oxy(t[i][0]), t[i][1], 0.02);
		close_rel(spectra_mua_blood_deoxy(t[i][0]), t[i][2], 0.02);
	}
	/* Prahl's table itself: HbO2 at 420 nm and the 780 nm end. */
	double o, d;
	spectra_hb_extinction(420, &o, &d);
	assert_float_equal(o, 480360, 1e-6);
	spectra_hb_extinction(421, &o, &d);	/* halfway between 420 and 422 */
	double o2, d2;
	spectra_hb_extinction(422, &o2, &d2);
	assert_float_equal(o, 0.5 * (480360 + o2), 1e-6);
	/* Mixing by saturation. */
	assert_float_equal(spectra_mua_blood(550, 0.75),
	    0.75 * spectra_mua_blood_oxy(550) + 0.25 * spectra_mua_blood_deoxy(550), 1e-9);
}

/* Closed forms against chromophores_scattering_formulas_380_780.tsv rows. */
static void test_formulas(void **state)
{
	(void)state;
	close_rel(spectra_mua_eumelanin(400), 1427.9, 1e-4);
	close_rel(spectra_mua_pheomelanin(400), 1266.5, 1e-4);
	close_rel(spectra_mua_baseline(400), 2.3194, 1e-4);
	close_rel(spectra_musp_power(400, 69.9, 1.322), 93.884, 1e-4);
	close_rel(spectra_musp_power(380, 46.0, 1.482), 69.086, 1e-4);
	close_rel(spectra_g_vangemert(400), 0.736, 1e-9);
	close_rel(spectra_n_epidermis(380), 1.4682, 1e-4);
	close_rel(spectra_n_dermis(380), 1.3967, 1e-4);
	/* Fat: VTS table 6.63e-6 mm^-1 is water; fat at 400 nm is 2.7272e-2 mm^-1. */
	close_rel(spectra_mua_fat(400), 0.27272, 1e-9);
	close_rel(spectra_mua_fat(390), 0.27272, 1e-9);	/* held below the table */
	/* Clamped outside the supported range. */
	assert_float_equal(spectra_mua_eumelanin(300), spectra_mua_eumelanin(380), 0);
}

/* The refstack preset (the `paper` preset before issue 16) reproduces the
 * reference stack of ../shared/refs at 550 nm. */
static void test_refstack_slab(void **state)
{
	(void)state;
	char *cause = NULL;
	struct skin_params *p = preset_load_builtin("refstack", &cause);
	assert_non_null(p);
	struct slab s;
	assert_int_equal(tissue_slab(p, 550, &s, &cause), 0);
	assert_int_equal(s.n_layers, 3);
	assert_float_equal(s.n_above, 1.0, 0);
	assert_float_equal(s.n_below, 1.4, 0);
	assert_float_equal(s.layer[1].n, 1.5, 0);
	assert_float_equal(s.layer[1].mu_a + s.layer[1].mu_s, 0, 0);
	assert_float_equal(s.layer[2].mu_a, 50, 0);
	assert_float_equal(s.layer[2].mu_s, 370, 0);
	assert_float_equal(s.layer[2].g, 0.8, 0);
	assert_float_equal(s.layer[2].d, 0.01, 0);
	assert_float_equal(s.layer[3].mu_a, 7, 0);
	assert_float_equal(s.layer[3].mu_s, 370, 0);
	assert_float_equal(s.layer[3].d, 0.25, 0);
	/* 656 nm is a tabulated wavelength (Table 2's "56"); 500 nm is not. */
	assert_int_equal(tissue_slab(p, 656, &s, &cause), 0);
	assert_int_equal(tissue_slab(p, 500, &s, &cause), -1);
	assert_non_null(strstr(cause, "470, 550 and 656"));
	free(cause);
	preset_free(p);
}

/* The paper presets hold Li & Ng's Tables 1-2 (../shared/paper): mu_a as
 * printed; the scattering row as mu_s' (paper: mu_s = mu_s' / (1 - g)) or as
 * mu_s (paper-literal), the same in epidermis and dermis. */
static void test_paper_tables(void **state)
{
	(void)state;
	static const double wl[3] = { 470, 550, 656 };
	static const double mua_epi[3] = { 85, 50, 28 }, mua_derm[3] = { 6, 7, 0.58 }, sc[3] = { 60, 37, 23 };
	for (int lit = 0; lit < 2; lit++) {
		char *cause = NULL;
		struct skin_params *p = preset_load_builtin(lit ? "paper-literal" : "paper", &cause);
		assert_non_null(p);
		for (int i = 0; i < 3; i++) {
			struct slab s;
			assert_int_equal(tissue_slab(p, wl[i], &s, &cause), 0);
			assert_int_equal(s.n_layers, 3);
			assert_float_equal(s.n_below, 1.43, 0);
			assert_float_equal(s.layer[1].n, 1.5, 0);
			assert_float_equal(s.layer[2].mu_a, mua_epi[i], 0);
			assert_float_equal(s.layer[3].mu_a, mua_derm[i], 0);
			for (int l = 2; l <= 3; l++) {
				double musp = s.layer[l].mu_s * (lit ? 1.0 : 1.0 - s.layer[l].g);
				assert_float_equal(musp, sc[i], 1e-9);
				assert_float_equal(s.layer[l].g, 0.8, 0);
				assert_float_equal(s.layer[l].n, 1.43, 0);
			}
			assert_float_equal(s.layer[2].d, 0.01, 0);
			assert_float_equal(s.layer[3].d, 0.25, 0);
		}
		preset_free(p);
	}
}

/* Chromophore mixing in a physiological preset. */
static void test_mixing(void **state)
{
	(void)state;
	char *cause = NULL;
	struct skin_params *p = preset_load_builtin("medium-oily", &cause);
	assert_non_null(p);
	struct layer l;
	const struct skin_layer_params *e = &p->layer[SKIN_EPIDERMIS], *d = &p->layer[SKIN_DERMIS];
	assert_int_equal(tissue_layer_optics(p, SKIN_EPIDERMIS, 500, &l, &cause), 0);
	double mel = e->eumelanin * spectra_mua_eumelanin(500) + (1 - e->eumelanin) * spectra_mua_pheomelanin(500);
	assert_float_equal(l.mu_a, e->melanin * mel + (1 - e->melanin) * spectra_mua_baseline(500), 1e-9);
	/* mu_s' at 500 nm is musp500 whatever the Rayleigh share. */
	assert_float_equal(l.mu_s * (1 - l.g), e->musp_500, 1e-9);
	assert_float_equal(l.n, spectra_n_epidermis(500), 1e-12);
	assert_int_equal(tissue_layer_optics(p, SKIN_DERMIS, 576, &l, &cause), 0);
	assert_float_equal(l.mu_a, d->blood * spectra_mua_blood(576, d->so2) + (1 - d->blood) * spectra_mua_baseline(576),
	    1e-9);
	/* More melanin absorbs more, at every wavelength. */
	struct skin_params *q = preset_load_builtin("dark-oily", &cause);
	assert_non_null(q);
	for (double wl = 380; wl <= 780; wl += 20) {
		struct layer a, b;
		assert_int_equal(tissue_layer_optics(p, SKIN_EPIDERMIS, wl, &a, &cause), 0);
		assert_int_equal(tissue_layer_optics(q, SKIN_EPIDERMIS, wl, &b, &cause), 0);
		assert_true(b.mu_a > a.mu_a);
	}
	/* Every physiological stack checks at every wavelength: 4 layers, semi-infinite subcutis. */
	struct slab s;
	assert_int_equal(tissue_slab(p, 380, &s, &cause), 0);
	assert_int_equal(s.n_layers, 4);
	assert_true(isinf(s.layer[4].d));
	assert_float_equal(s.n_below, 1.44, 0);
	assert_int_equal(tissue_slab(p, 379, &s, &cause), -1);
	assert_non_null(strstr(cause, "[380, 780]"));
	free(cause);
	preset_free(q);
	preset_free(p);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_blood),
		cmocka_unit_test(test_formulas),
		cmocka_unit_test(test_refstack_slab),
		cmocka_unit_test(test_paper_tables),
		cmocka_unit_test(test_mixing),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
