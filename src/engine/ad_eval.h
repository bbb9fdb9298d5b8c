/* ad_eval: the diffuse BRDF from its Fourier series in the azimuth,
 *   f(theta_i, theta_o, dphi) = sum_m (-1)^m F_m(theta_o) cos(m dphi)
 * (dphi = 0 back toward the light; the series is in the difference of the
 * propagation azimuths, which is dphi - pi), at a point and as bin means.
 *
 * F_m is known at the quadrature's exit nodes.  Between them the smooth
 * part is interpolated: F_m divided by the top boundary's Fresnel
 * transmittance is the radiance just inside the skin, a smooth function of
 * the internal cosine (the escape cone is away from internal grazing), so
 * it is interpolated by a polynomial in each quadrature piece's Gauss
 * variable and multiplied by the exact transmittance again, the sharp part
 * near grazing exit.  Bin means in theta_o are Gauss-Legendre integrals of
 * that (8 points per bin, split at the critical angles); in dphi they are
 * exact: the mean of cos(m dphi) over [p0, p1] is
 * (sin m p1 - sin m p0) / (m (p1 - p0)). */
#ifndef SKINBAKE_AD_EVAL_H
#define SKINBAKE_AD_EVAL_H
#include "engine/ad_order.h"

/* One solve's series with what evaluation needs. */
struct ad_series {
	struct ad_model md;	/* for the top boundary */
	struct ad_level lv;
};

/* Points per bin in theta_o for the bin means. */
#define AD_EVAL_POINTS 8
/* Nodes of the least-squares line that gives the value at grazing exit under
 * a rough top (ad_eval.c grazing_line). */
#define AD_EVAL_GRAZING_NODES 4

/* f for beam e at exit theta_o, dphi [rad]; orders m < m_max (all if
 * m_max <= 0 or larger than the series). */
double ad_series_point(const struct ad_series *sr, int e, double theta_o, double dphi, int m_max);

/* The coefficients of cos(m dphi) of f at exit theta_o, m < min(max, M);
 * returns their number. */
int ad_series_fourier(const struct ad_series *sr, int e, double theta_o, double *coef, int max);

/* Bin means over n_to bins in theta_o [0, pi/2] and n_phi in dphi [0, pi]:
 * fr[e * n_to * n_phi + it * n_phi + ip] and the azimuthal means
 * fr_az[e * n_to + it], from orders m < m_max (all if m_max <= 0).  With
 * last != NULL, also the contribution of the orders m_max .. M-1 alone
 * there (the same layout as fr). */
void ad_series_table(const struct ad_series *sr, int n_to, int n_phi, int m_max, double *fr, double *fr_az,
    double *last);
#endif
