/* colour: CIE colorimetry for reflectance spectra under D65.
 * - Colour-matching functions by analytic fits: CIE 1931 2-degree, multi-lobe
 *   piecewise Gaussians of Wyman, Sloan & Shirley, JCGT 2(2) 2013 (sec. 2.2);
 *   CIE 1964 10-degree, their single-lobe fit (sec. 2.3).
 * - D65 relative SPD: CIE 15 table, 380-780 nm in 5 nm steps, linear
 *   interpolation in between (the CIE-recommended way).
 * - XYZ <-> linear sRGB: IEC 61966-2-1 matrices (D65 white); CIELAB: CIE 15.
 * - Colour difference CIEDE2000: CIE 142-2001, as written out by Sharma, Wu
 *   & Dalal, Color Res. Appl. 30(1) 2005, eqs. 1-23 (tests/test_colour.c
 *   checks their 34 published test pairs).
 * Wavelengths in nm.  Pure functions; no state. */
#ifndef SKINBAKE_COLOUR_H
#define SKINBAKE_COLOUR_H

enum colour_observer {
	COLOUR_CIE1931_2DEG,	/* for RGB output (sRGB is defined on it) */
	COLOUR_CIE1964_10DEG	/* for comparing with skin L*a*b* data (D65/10 deg) */
};

/* Colour-matching functions x, y, z at wl [nm] (0 far outside 360-830). */
void colour_cmf(enum colour_observer obs, double wl, double xyz[3]);
/* D65 relative spectral power, 100 at 560 nm; 0 outside 380-780 nm. */
double colour_d65(double wl);

/* XYZ of a reflectance spectrum under D65, scaled so the perfect white
 * reflector has Y = 1.  The spectrum is n samples refl[i] at increasing
 * wavelengths wl[i], taken as piecewise linear between samples and constant
 * beyond the end samples; integrated at 1 nm over 380-780 nm.  n >= 1. */
void colour_spectrum_xyz(enum colour_observer obs, int n, const double *wl, const double *refl,
    double xyz[3]);
/* XYZ (D65 white, Y of white = 1) of the observer's perfect white reflector. */
void colour_white_xyz(enum colour_observer obs, double xyz[3]);

void colour_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);
void colour_linear_srgb_to_xyz(const double rgb[3], double xyz[3]);
/* CIELAB relative to the white white_xyz. */
void colour_xyz_to_lab(const double xyz[3], const double white_xyz[3], double lab[3]);
/* CIELAB of a linear sRGB colour, D65 white (sRGB's (1,1,1)). */
void colour_linear_srgb_to_lab(const double rgb[3], double lab[3]);
/* The inverses: CIELAB (relative to white_xyz) -> XYZ, and CIELAB with the
 * D65 white of sRGB -> linear sRGB. */
void colour_lab_to_xyz(const double lab[3], const double white_xyz[3], double xyz[3]);
void colour_lab_to_linear_srgb(const double lab[3], double rgb[3]);
/* CIEDE2000 colour difference of two CIELAB colours, parametric factors
 * kL = kC = kH = 1 (symmetric in its arguments). */
double colour_de2000(const double lab1[3], const double lab2[3]);
/* Individual typology angle ITA = atan2(L* - 50, b*) [degrees] (Chardon 1991). */
double colour_ita(const double lab[3]);

/* The 3 x n_wl matrix m (row-major: m[c * n_wl + i], c = R, G, B) that turns
 * reflectance samples at wavelengths wl_nm (any order, distinct, in
 * [380, 780]) into linear sRGB under D65 with the CIE 1931 observer: the
 * spectrum is piecewise linear between the sorted samples and constant
 * beyond them (as colour_spectrum_xyz).  Each row is then scaled to sum to 1,
 * so a perfect white reflector (all samples 1) gives exactly (1, 1, 1).
 * Exception: for exactly the paper's three wavelengths {470, 550, 656} the
 * mapping is direct, 656 -> R, 550 -> G, 470 -> B (a 3-band renderer treats
 * them as its primaries; Li & Ng's Table 2 labels 656 nm "56").
 * One wavelength gives grey: all three weights 1. */
void colour_rgb_weights(int n_wl, const double *wl_nm, double *m);
#endif
