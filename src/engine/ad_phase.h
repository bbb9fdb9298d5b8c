/* ad_phase: the phase redistribution function of the adding-doubling
 * literature (van de Hulst 1980; Prahl 1995, "redistribution function"
 * h(nu, nu')) for the Henyey-Greenstein phase function: its azimuthal
 * Fourier components,
 *   h_m(x, y) = integral over psi in [0, 2 pi) of p(x y + sqrt(1-x^2) sqrt(1-y^2) cos psi) cos(m psi)
 *             = sum_{l >= m} (2l + 1)/2 chi_l L_l^m(x) L_l^m(y),
 * from the addition theorem of Legendre functions with HG's moments
 * chi_l = g^l (Henyey & Greenstein 1941) and the normalized associated
 * Legendre functions L_l^m = sqrt((l-m)!/(l+m)!) P_l^m.  The sum is exact
 * to 1e-15 once |g|^L < 1e-15; where the quadrature cannot resolve that many
 * terms it is cut at L terms by delta-M (Wiscombe, J. Atmos. Sci. 34, 1977):
 * the forward fraction f = g^L is moved into the unscattered beam, with
 * chi*_l = (g^l - f) / (1 - f), omega* = omega (1 - f) / (1 - omega f),
 * tau* = tau (1 - omega f).  A backward peak (g < 0) is cut the same way,
 * chi*_l = (g^l - f (-1)^l) / (1 - f) with f = |g|^L: the fraction f is
 * exact retro-reflection (mu -> -mu, azimuth + pi), which is scattering, so
 * omega and tau stay, and the solver puts it on the diagonal of h(mu, -mu)
 * with the sign (-1)^m (ad_order.c).  h_m of the remainder integrates to 1
 * over x in * [-1, 1] at m = 0. */
#ifndef SKINBAKE_AD_PHASE_H
#define SKINBAKE_AD_PHASE_H

struct ad_hg {
	double g;	/* anisotropy [-] */
	double f;	/* delta-M fraction [-] (forward for g > 0, backward for g < 0), 0 if the series is complete */
	int L;		/* Legendre terms kept, l = 0 .. L-1 */
	double *cl;	/* [L] (2l + 1)/2 chi*_l */
};

/* Moments for anisotropy g with at most l_max terms (even, >= 2). */
void ad_hg_init(struct ad_hg *h, double g, int l_max);
void ad_hg_free(struct ad_hg *h);

/* The phase redistribution matrices of order m at the quadrature nodes
 * (Prahl's h++ and h+-: both directions in the same hemisphere, and in
 * opposite ones): h_m(x_i, x_j) into Hpp and h_m(x_i, -x_j) into Hpm for rows i < nr and
 * columns j < np (column-major, leading dimension nr); x[0 .. np-1] in
 * [0, 1], rows are the first nr points.  work holds 2 np L + 2 L doubles. */
void ad_hg_fourier(const struct ad_hg *h, int m, const double *x, int nr, int np, double *Hpp, double *Hpm,
    double *work);
#endif
