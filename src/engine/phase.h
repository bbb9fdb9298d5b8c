/* phase: the Henyey-Greenstein phase function and the direction update
 * ("spin").  Pure functions of their uniform inputs.
 *
 * The seed paper (Li & Ng, eqs. 2 and 16) misprints the inversion of the HG
 * cumulative distribution; this is the correct one (Henyey & Greenstein 1941,
 * as in Wang & Jacques' MCML manual eq. 3.28):
 *   cos = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g),  cos = 2u - 1 at g = 0. */
#ifndef SKINBAKE_PHASE_H
#define SKINBAKE_PHASE_H
#include <math.h>

/* HG density of cos(theta) on [-1, 1] (integrates to 1 over cos). */
double hg_pdf_cos(double g, double cos_theta);

/* Per-layer constants of the HG inversion, so the kernel divides once per
 * scattering instead of twice. */
struct hg_const {
	double g;		/* anisotropy [-] */
	double one_m_g2;	/* 1 - g^2 */
	double one_p_g2;	/* 1 + g^2 */
	double inv_2g;		/* 1 / (2 g), 0 when |g| < 0.5 (unused there) */
};

static inline void hg_const_init(struct hg_const *h, double g)
{
	h->g = g;
	h->one_m_g2 = 1.0 - g * g;
	h->one_p_g2 = 1.0 + g * g;
	h->inv_2g = (g > -0.5 && g < 0.5) ? 0.0 : 1.0 / (2.0 * g);
}

/* Sample cos(theta) from HG with u in (0, 1).  Stable for g near 0 of either
 * sign and for |g| near 1; result in [-1, 1]. */
static inline double hg_sample_cos_c(const struct hg_const *h, double u)
{
	double g = h->g, xi = 2.0 * u - 1.0, c;
	if (g > -0.5 && g < 0.5) {
		/* The textbook form divides by 2g and cancels catastrophically as
		 * g -> 0.  Expanding it over the common denominator D^2, D = 1 + g xi,
		 * leaves a polynomial with no cancellation (exactly xi at g = 0). */
		double d = 1.0 + g * xi;
		double num = xi + g * (0.5 * (xi * xi + 3.0) + g * (xi + 0.5 * g * (xi * xi - 1.0)));
		c = num / (d * d);
	} else {
		double s = h->one_m_g2 / (1.0 + g * xi);
		c = (h->one_p_g2 - s * s) * h->inv_2g;
	}
	return c < -1.0 ? -1.0 : (c > 1.0 ? 1.0 : c);
}

/* The same for an anisotropy g in (-1, 1) given directly. */
static inline double hg_sample_cos(double g, double u)
{
	struct hg_const h;
	hg_const_init(&h, g);
	return hg_sample_cos_c(&h, u);
}

/* A uniformly distributed azimuth from u in (0, 1), as its cosine and sine,
 * without calling sincos (which profiling showed to cost 40% of a step).
 * u picks the nearest quarter turn q and an offset a in [-pi/4, pi/4];
 * Taylor series to a^15 / a^16 are exact to double rounding there. */
static inline void azimuth_sample(double u, double *cos_p, double *sin_p)
{
	double t = 4.0 * u;
	int q = (int)(t + 0.5);
	double a = (t - q) * (M_PI / 2.0), a2 = a * a;
	double s = a * (1.0 + a2 * (-1.0 / 6 + a2 * (1.0 / 120 + a2 * (-1.0 / 5040 + a2 * (1.0 / 362880 +
	    a2 * (-1.0 / 39916800 + a2 * (1.0 / 6227020800.0 + a2 * (-1.0 / 1307674368000.0))))))));
	double c = 1.0 + a2 * (-0.5 + a2 * (1.0 / 24 + a2 * (-1.0 / 720 + a2 * (1.0 / 40320 + a2 * (-1.0 / 3628800 +
	    a2 * (1.0 / 479001600.0 + a2 * (-1.0 / 87178291200.0 + a2 * (1.0 / 20922789888000.0))))))));
	switch (q & 3) {
	case 0: *cos_p = c; *sin_p = s; break;
	case 1: *cos_p = -s; *sin_p = c; break;
	case 2: *cos_p = -c; *sin_p = -s; break;
	default: *cos_p = s; *sin_p = -c; break;
	}
}

/* Rotate the unit direction (*ux, *uy, *uz) by polar cosine cos_t and the
 * azimuth whose cosine and sine are cos_p, sin_p (MCML's Spin, in cosines). */
static inline void spin_dir(double *ux, double *uy, double *uz, double cos_t, double cos_p, double sin_p)
{
	double sin_t = sqrt(1.0 - cos_t * cos_t);	/* sqrt() is cheaper than sin() */
	double x = *ux, y = *uy, z = *uz;
	if (z > 0.99999 || z < -0.99999) {
		*ux = sin_t * cos_p;
		*uy = sin_t * sin_p;
		*uz = z > 0.0 ? cos_t : -cos_t;
	} else {
		double t = sqrt(1.0 - z * z), k = sin_t / t;
		*ux = k * (x * z * cos_p - y * sin_p) + x * cos_t;
		*uy = k * (y * z * cos_p + x * sin_p) + y * cos_t;
		*uz = -sin_t * cos_p * t + z * cos_t;
	}
}
#endif
