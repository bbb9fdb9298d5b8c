/* ad_quad: the angular quadrature of the adding-doubling solver.
 *
 * Directions are labelled by s = n sin(theta), which Snell's law keeps
 * across every smooth interface, so one node stands for the same ray in
 * every medium and the Fresnel boundaries are diagonal (van de Hulst 1980;
 * Prahl 1995 does the same for one slab with its critical angle).  A medium
 * of index n has the nodes with s < n.  The s axis is cut at every
 * refractive index of the stack below the largest turbid one (the critical
 * angles), and each piece [s0, s1] gets Gauss-Legendre nodes in the angle
 * theta* of the medium of index n* = s1, in which the piece reaches
 * grazing.  Every quantity of the problem is an analytic function of
 * theta* on the piece: the cosines of all media that have these directions
 * (mu^2 = cos^2 theta* + (1 - (n* / n)^2) sin^2 theta*), the Fresnel factors,
 * and the Fourier orders of the radiance, which go as sin^m near normal
 * (so not as a polynomial in the cosine, but in the angle).  So the
 * quadrature and the interpolation between nodes converge exponentially
 * (measured: tests/test_ad.c).  The measure is
 * s ds = n*^2 sin theta* cos theta* d theta* = n^2 mu dmu in every medium. */
#ifndef SKINBAKE_AD_QUAD_H
#define SKINBAKE_AD_QUAD_H
#include "engine/slab.h"

#define AD_MAX_IV (SLAB_MAX_LAYERS + 2)

struct ad_quad {
	int n;				/* nodes per hemisphere in all pieces */
	int n_iv;			/* pieces of the s axis */
	double sigma[AD_MAX_IV + 1];	/* piece edges in s [-]: 0 = sigma[0] < ... */
	double nstar[AD_MAX_IV];	/* index whose angle is piece k's Gauss variable [-] */
	int first[AD_MAX_IV + 1];	/* piece k holds nodes first[k] .. first[k+1] - 1 */
	double *s;			/* [n] node's s [-], ascending */
	double *th;			/* [n] node's Gauss variable: angle in medium nstar [rad] */
	double *W;			/* [n] weight: sum W_i f(s_i) ~ integral of f(s) s ds */
	double *bary;			/* [n] barycentric interpolation weights within the piece */
};

/* Gauss-Legendre nodes x (ascending) and weights w on [a, b], n >= 1, by the
 * Golub-Welsch eigenvalue method (LAPACK dstev).  0, or -1 if LAPACK fails. */
int ad_gauss_legendre(int n, double a, double b, double *x, double *w);

/* Build for pieces with edges sigma[0..n_iv] (sigma[0] = 0, ascending) and
 * Gauss variables nstar[k] >= sigma[k+1]; piece k gets
 * max(n_min, ceil(density * len)) nodes, len its length in angle over pi/2
 * or in cosine, whichever is larger (density = nodes per hemisphere of a
 * medium without cuts).
 * -1 with *cause if LAPACK fails.  Free with ad_quad_free. */
int ad_quad_build(struct ad_quad *q, const double *sigma, const double *nstar, int n_iv, double density,
    int n_min, char **cause);
void ad_quad_free(struct ad_quad *q);

/* Nodes with s < n_medium: the directions that exist in that medium. */
int ad_quad_count(const struct ad_quad *q, double n_medium);

/* Cosine of node i in a medium of index n_medium > s_i (from the Gauss
 * variable, so no cancellation near grazing). */
double ad_quad_mu(const struct ad_quad *q, int i, double n_medium);

/* The piece holding s (the last one for s at or past the top). */
int ad_quad_piece(const struct ad_quad *q, double s);

/* Interpolation weights wt[0 .. first[k+1]-first[k]-1] over piece k's nodes
 * for the point s in that piece: a polynomial in the piece's Gauss variable
 * (barycentric form, Berrut & Trefethen, SIAM Review 46, 2004). */
void ad_quad_interp(const struct ad_quad *q, int k, double s, double *wt);
#endif
