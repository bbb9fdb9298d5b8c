/* colour: CMF fits, D65, sRGB and CIELAB; see colour.h for the sources. */
#include "config.h"
#include "skin/colour.h"

#include <math.h>
#include <stdlib.h>

#include "base/util.h"

/* CIE 15 D65 relative SPD, 380-780 nm in 5 nm steps. */
static const double d65_5nm[81] = {
	49.9755, 52.3118, 54.6482, 68.7015, 82.7549, 87.1204, 91.486, 92.4589, 93.4318,
	90.057, 86.6823, 95.7736, 104.865, 110.936, 117.008, 117.41, 117.812, 116.336,
	114.861, 115.392, 115.923, 112.367, 108.811, 109.082, 109.354, 108.578, 107.802,
	106.296, 104.79, 106.239, 107.689, 106.047, 104.405, 104.225, 104.046, 102.023,
	100.0, 98.1671, 96.3342, 96.0611, 95.788, 92.2368, 88.6856, 89.3459, 90.0062,
	89.8026, 89.5991, 88.6489, 87.6987, 85.4936, 83.2886, 83.4939, 83.6992, 81.863,
	80.0268, 80.1207, 80.2146, 81.2462, 82.2778, 80.281, 78.2842, 74.0027, 69.7213,
	70.6652, 71.6091, 72.979, 74.349, 67.9765, 61.604, 65.7448, 69.8856, 72.4863,
	75.087, 69.3398, 63.5927, 55.0054, 46.4182, 56.6118, 66.8054, 65.0941, 63.3828,
};

/* IEC 61966-2-1 (sRGB) primaries and D65 white, at full precision. */
static const double rgb_to_xyz[3][3] = {
	{ 0.4124564, 0.3575761, 0.1804375 },
	{ 0.2126729, 0.7151522, 0.0721750 },
	{ 0.0193339, 0.1191920, 0.9503041 },
};
static const double xyz_to_rgb[3][3] = {
	{ 3.2404542, -1.5371385, -0.4985314 },
	{ -0.9692660, 1.8760108, 0.0415560 },
	{ 0.0556434, -0.2040259, 1.0572252 },
};

/* Piecewise Gaussian of Wyman et al. 2013: width s1 left of the mean, s2 right. */
static double pg(double x, double mu, double s1, double s2)
{
	double t = (x - mu) / (x < mu ? s1 : s2);
	return exp(-0.5 * t * t);
}

void colour_cmf(enum colour_observer obs, double wl, double xyz[3])
{
	if (obs == COLOUR_CIE1931_2DEG) {
		/* Multi-lobe fit, Wyman, Sloan & Shirley 2013, eq. 2. */
		xyz[0] = 1.056 * pg(wl, 599.8, 37.9, 31.0) + 0.362 * pg(wl, 442.0, 16.0, 26.7)
		    - 0.065 * pg(wl, 501.1, 20.4, 26.2);
		xyz[1] = 0.821 * pg(wl, 568.8, 46.9, 40.5) + 0.286 * pg(wl, 530.9, 16.3, 31.1);
		xyz[2] = 1.217 * pg(wl, 437.0, 11.8, 36.0) + 0.681 * pg(wl, 459.0, 26.0, 13.8);
		return;
	}
	/* CIE 1964 10-degree single-lobe fit, Wyman et al. 2013, eq. 3; the logs
	 * need wl inside (265.8, 1338). */
	if (wl <= 266.0 || wl >= 1337.0) {
		xyz[0] = xyz[1] = xyz[2] = 0.0;
		return;
	}
	double a = log((wl + 570.1) / 1014.0), b = log((1338.0 - wl) / 743.5);
	double c = (wl - 556.1) / 46.14, d = log((wl - 265.8) / 180.4);
	xyz[0] = 0.398 * exp(-1250.0 * a * a) + 1.132 * exp(-234.0 * b * b);
	xyz[1] = 1.011 * exp(-0.5 * c * c);
	xyz[2] = 2.06 * exp(-32.0 * d * d);
}

double colour_d65(double wl)
{
	if (wl < 380.0 || wl > 780.0)
		return 0.0;
	double t = (wl - 380.0) / 5.0;
	int i = (int)t;
	if (i >= 80)
		return d65_5nm[80];
	double f = t - i;
	return d65_5nm[i] * (1.0 - f) + d65_5nm[i + 1] * f;
}

/* Sum over 380..780 nm at 1 nm of D65 * ybar, the white's Y before scaling. */
static double white_norm(enum colour_observer obs)
{
	double s = 0.0, c[3];
	for (int l = 380; l <= 780; l++) {
		colour_cmf(obs, l, c);
		s += colour_d65(l) * c[1];
	}
	return s;
}

void colour_white_xyz(enum colour_observer obs, double xyz[3])
{
	double k = 1.0 / white_norm(obs), c[3];
	xyz[0] = xyz[1] = xyz[2] = 0.0;
	for (int l = 380; l <= 780; l++) {
		colour_cmf(obs, l, c);
		double e = colour_d65(l) * k;
		for (int j = 0; j < 3; j++)
			xyz[j] += e * c[j];
	}
}

/* Value at wl of a spectrum given at increasing wavelengths: linear between
 * samples, constant beyond the ends. */
static double sample_spectrum(int n, const double *wl, const double *v, double x)
{
	if (x <= wl[0])
		return v[0];
	if (x >= wl[n - 1])
		return v[n - 1];
	int i = 0;
	while (i + 1 < n && wl[i + 1] < x)
		i++;
	double f = (x - wl[i]) / (wl[i + 1] - wl[i]);
	return v[i] * (1.0 - f) + v[i + 1] * f;
}

void colour_spectrum_xyz(enum colour_observer obs, int n, const double *wl, const double *refl,
    double xyz[3])
{
	double k = 1.0 / white_norm(obs), c[3];
	xyz[0] = xyz[1] = xyz[2] = 0.0;
	for (int l = 380; l <= 780; l++) {
		colour_cmf(obs, l, c);
		double e = colour_d65(l) * k * sample_spectrum(n, wl, refl, l);
		for (int j = 0; j < 3; j++)
			xyz[j] += e * c[j];
	}
}

static void mat3(const double m[3][3], const double in[3], double out[3])
{
	for (int i = 0; i < 3; i++)
		out[i] = m[i][0] * in[0] + m[i][1] * in[1] + m[i][2] * in[2];
}

void colour_xyz_to_linear_srgb(const double xyz[3], double rgb[3])
{
	mat3(xyz_to_rgb, xyz, rgb);
}

void colour_linear_srgb_to_xyz(const double rgb[3], double xyz[3])
{
	mat3(rgb_to_xyz, rgb, xyz);
}

/* CIE 15 f(t) with the linear segment below (6/29)^3. */
static double lab_f(double t)
{
	const double e = 216.0 / 24389.0, k = 24389.0 / 27.0;
	return t > e ? cbrt(t) : (k * t + 16.0) / 116.0;
}

void colour_xyz_to_lab(const double xyz[3], const double white_xyz[3], double lab[3])
{
	double fx = lab_f(xyz[0] / white_xyz[0]);
	double fy = lab_f(xyz[1] / white_xyz[1]);
	double fz = lab_f(xyz[2] / white_xyz[2]);
	lab[0] = 116.0 * fy - 16.0;
	lab[1] = 500.0 * (fx - fy);
	lab[2] = 200.0 * (fy - fz);
}

void colour_linear_srgb_to_lab(const double rgb[3], double lab[3])
{
	static const double one[3] = { 1.0, 1.0, 1.0 };
	double xyz[3], white[3];
	colour_linear_srgb_to_xyz(rgb, xyz);
	colour_linear_srgb_to_xyz(one, white);
	colour_xyz_to_lab(xyz, white, lab);
}

/* CIE 15 inverse of lab_f. */
static double lab_finv(double f)
{
	const double d = 6.0 / 29.0;
	return f > d ? f * f * f : 3.0 * d * d * (f - 4.0 / 29.0);
}

void colour_lab_to_xyz(const double lab[3], const double white_xyz[3], double xyz[3])
{
	double fy = (lab[0] + 16.0) / 116.0;
	xyz[0] = white_xyz[0] * lab_finv(fy + lab[1] / 500.0);
	xyz[1] = white_xyz[1] * lab_finv(fy);
	xyz[2] = white_xyz[2] * lab_finv(fy - lab[2] / 200.0);
}

void colour_lab_to_linear_srgb(const double lab[3], double rgb[3])
{
	static const double one[3] = { 1.0, 1.0, 1.0 };
	double xyz[3], white[3];
	colour_linear_srgb_to_xyz(one, white);
	colour_lab_to_xyz(lab, white, xyz);
	colour_xyz_to_linear_srgb(xyz, rgb);
}

/* Hue angle [deg] in [0, 360); 0 for a neutral colour (Sharma et al. eq. 4). */
static double hue_deg(double b, double ap)
{
	if (b == 0.0 && ap == 0.0)
		return 0.0;
	double h = atan2(b, ap) * 180.0 / M_PI;
	return h < 0.0 ? h + 360.0 : h;
}

double colour_de2000(const double lab1[3], const double lab2[3])
{
	const double d2r = M_PI / 180.0, p25_7 = 6103515625.0;	/* 25^7 */
	/* eqs. 2-5: a' stretched by G, C', h'. */
	double c1 = hypot(lab1[1], lab1[2]), c2 = hypot(lab2[1], lab2[2]);
	double cb7 = pow(0.5 * (c1 + c2), 7.0);
	double g = 0.5 * (1.0 - sqrt(cb7 / (cb7 + p25_7)));
	double a1 = (1.0 + g) * lab1[1], a2 = (1.0 + g) * lab2[1];
	double cp1 = hypot(a1, lab1[2]), cp2 = hypot(a2, lab2[2]);
	double h1 = hue_deg(lab1[2], a1), h2 = hue_deg(lab2[2], a2);
	/* eqs. 8-10: differences. */
	double dl = lab2[0] - lab1[0], dc = cp2 - cp1, dh = 0.0;
	if (cp1 * cp2 != 0.0) {
		dh = h2 - h1;
		if (dh > 180.0)
			dh -= 360.0;
		else if (dh < -180.0)
			dh += 360.0;
	}
	double dhh = 2.0 * sqrt(cp1 * cp2) * sin(0.5 * dh * d2r);
	/* eqs. 12-22: means, weights and the rotation term. */
	double lb = 0.5 * (lab1[0] + lab2[0]), cb = 0.5 * (cp1 + cp2), hb = h1 + h2;
	if (cp1 * cp2 != 0.0) {
		if (fabs(h1 - h2) <= 180.0)
			hb = 0.5 * (h1 + h2);
		else if (h1 + h2 < 360.0)
			hb = 0.5 * (h1 + h2 + 360.0);
		else
			hb = 0.5 * (h1 + h2 - 360.0);
	}
	double t = 1.0 - 0.17 * cos((hb - 30.0) * d2r) + 0.24 * cos(2.0 * hb * d2r) + 0.32 * cos((3.0 * hb + 6.0) * d2r)
	    - 0.20 * cos((4.0 * hb - 63.0) * d2r);
	double dtheta = 30.0 * exp(-((hb - 275.0) / 25.0) * ((hb - 275.0) / 25.0));
	double cb7p = pow(cb, 7.0);
	double rc = 2.0 * sqrt(cb7p / (cb7p + p25_7));
	double l50 = (lb - 50.0) * (lb - 50.0);
	double sl = 1.0 + 0.015 * l50 / sqrt(20.0 + l50), sc = 1.0 + 0.045 * cb, sh = 1.0 + 0.015 * cb * t;
	double rt = -sin(2.0 * dtheta * d2r) * rc;
	double xl = dl / sl, xc = dc / sc, xh = dhh / sh;
	return sqrt(fmax(0.0, xl * xl + xc * xc + xh * xh + rt * xc * xh));
}

double colour_ita(const double lab[3])
{
	return atan2(lab[0] - 50.0, lab[2]) * 180.0 / M_PI;
}

static int is_paper_set(int n, const double *wl, int idx[3])
{
	static const double paper[3] = { 656.0, 550.0, 470.0 };	/* R, G, B */
	if (n != 3)
		return 0;
	for (int c = 0; c < 3; c++) {
		idx[c] = -1;
		for (int i = 0; i < 3; i++)
			if (fabs(wl[i] - paper[c]) < 1e-9)
				idx[c] = i;
		if (idx[c] < 0)
			return 0;
	}
	return 1;
}

void colour_rgb_weights(int n_wl, const double *wl_nm, double *m)
{
	int idx[3];
	for (int i = 0; i < 3 * n_wl; i++)
		m[i] = 0.0;
	if (n_wl == 1) {
		m[0] = m[1] = m[2] = 1.0;
		return;
	}
	if (is_paper_set(n_wl, wl_nm, idx)) {
		for (int c = 0; c < 3; c++)
			m[c * n_wl + idx[c]] = 1.0;
		return;
	}
	/* Sort the wavelengths (keeping the caller's order in ord). */
	int *ord = xmalloc(sizeof(int) * (size_t)n_wl);
	double *ws = xmalloc(sizeof(double) * (size_t)n_wl);
	for (int i = 0; i < n_wl; i++)
		ord[i] = i;
	for (int i = 1; i < n_wl; i++)
		for (int j = i; j > 0 && wl_nm[ord[j]] < wl_nm[ord[j - 1]]; j--) {
			int t = ord[j];
			ord[j] = ord[j - 1];
			ord[j - 1] = t;
		}
	for (int i = 0; i < n_wl; i++)
		ws[i] = wl_nm[ord[i]];
	/* XYZ weight of sorted sample i: the integral of D65 * cmf * hat_i, where
	 * hat_i is the piecewise-linear basis function of sample i. */
	double k = 1.0 / white_norm(COLOUR_CIE1931_2DEG), c[3];
	double *wx = xcalloc((size_t)n_wl * 3, sizeof(double));
	for (int l = 380; l <= 780; l++) {
		colour_cmf(COLOUR_CIE1931_2DEG, l, c);
		double e = colour_d65(l) * k;
		int i0, i1;
		double f;
		if (l <= ws[0]) {
			i0 = i1 = 0;
			f = 0.0;
		} else if (l >= ws[n_wl - 1]) {
			i0 = i1 = n_wl - 1;
			f = 0.0;
		} else {
			i0 = 0;
			while (ws[i0 + 1] < l)
				i0++;
			i1 = i0 + 1;
			f = (l - ws[i0]) / (ws[i1] - ws[i0]);
		}
		for (int j = 0; j < 3; j++) {
			wx[i0 * 3 + j] += e * c[j] * (1.0 - f);
			wx[i1 * 3 + j] += e * c[j] * f;
		}
	}
	for (int i = 0; i < n_wl; i++) {
		double rgb[3];
		colour_xyz_to_linear_srgb(&wx[i * 3], rgb);
		for (int ch = 0; ch < 3; ch++)
			m[ch * n_wl + ord[i]] = rgb[ch];
	}
	/* The fitted CMFs and the sampling put the white a little off (1,1,1);
	 * a per-channel scale (von Kries in sRGB) puts it back exactly. */
	for (int ch = 0; ch < 3; ch++) {
		double s = 0.0;
		for (int i = 0; i < n_wl; i++)
			s += m[ch * n_wl + i];
		for (int i = 0; i < n_wl; i++)
			m[ch * n_wl + i] /= s;
	}
	free(wx);
	free(ws);
	free(ord);
}
