/* spectra: spectral optical properties of skin constituents for 380-780 nm,
 * from compiled-in tables (hemoglobin, fat) and published closed forms
 * (melanin, bloodless baseline, scattering power laws, anisotropy, index).
 * Sources: ../shared/notes/skin-optics.md section A2 and the tables in
 * ../shared/skin_data; each function cites its own.  Wavelengths in nm,
 * coefficients in 1/cm.  Pure functions; no state. */
#ifndef SKINBAKE_SPECTRA_H
#define SKINBAKE_SPECTRA_H

#define SPECTRA_WL_MIN 380.0	/* shortest supported wavelength [nm] */
#define SPECTRA_WL_MAX 780.0	/* longest supported wavelength [nm] */

/* Whole-blood hemoglobin concentration used for blood absorption [g/L]. */
#define SPECTRA_HB_G_PER_L 150.0

/* All functions below expect wl in [SPECTRA_WL_MIN, SPECTRA_WL_MAX] and clamp
 * outside it (the caller validates ranges). */

/* Eumelanin absorption of the melanosome interior [1/cm]:
 * 6.6e11 * wl^-3.33 (Jacques 1998 OMLC; = Donner & Jensen 2006 eumelanin). */
double spectra_mua_eumelanin(double wl);
/* Pheomelanin absorption [1/cm]: 2.9e15 * wl^-4.75 (Donner & Jensen 2006,
 * 2.9e14 mm^-1). */
double spectra_mua_pheomelanin(double wl);
/* Bloodless skin baseline [1/cm]: 0.244 + 85.3 exp(-(wl - 154)/66.2)
 * (Jacques 1998). */
double spectra_mua_baseline(double wl);
/* Whole blood (150 g/L) fully oxygenated / deoxygenated [1/cm]:
 * ln(10) eps C / 64500 with eps from Prahl's table (2 nm steps, linear
 * interpolation); hemoglobin_molar_extinction_prahl.tsv. */
double spectra_mua_blood_oxy(double wl);
double spectra_mua_blood_deoxy(double wl);
/* Blood at oxygen saturation so2 in [0, 1] [1/cm]. */
double spectra_mua_blood(double wl, double so2);
/* Molar extinction of HbO2 and Hb [cm^-1/M, decadic] (Prahl), interpolated. */
void spectra_hb_extinction(double wl, double *eps_hbo2, double *eps_hb);
/* Fat (lard) absorption [1/cm] (van Veen et al. 2005 via VTS; the table
 * starts at 400 nm and is held constant below). */
double spectra_mua_fat(double wl);
/* Reduced scattering power law a * (wl/500)^-b [1/cm]. */
double spectra_musp_power(double wl, double a_500, double b);
/* Anisotropy g(wl) = 0.62 + 0.29e-3 wl (van Gemert et al. 1989). */
double spectra_g_vangemert(double wl);
/* Cauchy fits of Ding et al. 2006: epidermis 1.4134 + 7907.96/wl^2,
 * dermis 1.3696 + 3916.80/wl^2. */
double spectra_n_epidermis(double wl);
double spectra_n_dermis(double wl);

/* Scattering power-law defaults: our fits to Salomatina et al. 2006
 * (skin-optics.md A2.6), mu_s' = a (wl/500)^-b. */
#define SPECTRA_MUSP_EPI_A 69.9		/* epidermis [1/cm] */
#define SPECTRA_MUSP_EPI_B 1.322	/* [-] */
#define SPECTRA_MUSP_DERM_A 46.0	/* dermis [1/cm] */
#define SPECTRA_MUSP_DERM_B 1.482	/* [-] */
#define SPECTRA_MUSP_HYPO_A 35.0	/* hypodermis [1/cm] */
#define SPECTRA_MUSP_HYPO_B 1.136	/* [-] */
#endif
