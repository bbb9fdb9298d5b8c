/* ad_layer: the reflection and transmission matrices R and T of one
 * homogeneous layer (van de Hulst 1980; Prahl 1995) for one azimuthal
 * Fourier order, by a thin starting layer and doubling (the doubling
 * method: a layer of thickness 2D from two of thickness D).
 *
 * Representation (shared by the whole solver): a vector holds, per node i,
 * the Fourier component of the flux carried by the node's cell divided by
 * sqrt(W_i) (W the medium-independent weight of ad_quad), so that
 * reflection matrices are symmetric (reciprocity) in every medium and
 * Fresnel boundaries are diagonal.  An operator is a node matrix
 * (n x n, column-major, column = incoming node) followed by one column per
 * collimated beam (the diffuse output per unit collimated flux), plus the
 * collimated output per beam (dT here).
 *
 * Start: the diamond initialization (Wiscombe, J. Quant. Spectrosc. Radiat.
 * Transfer 16, 1976; Prahl 1995): the discrete-ordinate equations
 * integrated over a layer of optical thickness D by the trapezoidal rule,
 *   T + R = 2 (I + D/2 (a - b))^-1 - I,  T - R = 2 (I + D/2 (a + b))^-1 - I,
 * with a = M^-1 - omega Q H++ Q, b = omega Q H+- Q (Q = sqrt(w/mu); H++,
 * H+- the phase redistribution matrices of ad_phase.h).  The
 * collimated beams get the same rule with the same Pade attenuation
 * (1 - D/2mu)/(1 + D/2mu), so a beam along a node direction gives exactly
 * that node's column (reciprocity between beams holds to rounding).
 * Doubling (van de Hulst 1980): with S = R + T and D = R - T,
 *   S' = R + T (I - R)^-1 T,  D' = R - T (I + R)^-1 T,
 * each by a Cholesky factorization (I -+ R are symmetric positive definite
 * for a reflecting layer), an LU factorization where that fails.
 *
 * By default a layer thicker than its starting layer is solved instead at
 * its full thickness from the eigenvectors of the same discrete-ordinate
 * equations (exact in the thickness, the beams' attenuation e^{-tau/mu}
 * exactly; formulas at eigen_layer in ad_layer.c; issue 28); the diamond
 * start and doubling remain for thin layers, for layers the eigenvectors
 * decline and when doubling_only is set. */
#ifndef SKINBAKE_AD_LAYER_H
#define SKINBAKE_AD_LAYER_H
#include <stddef.h>

struct ad_layer_in {
	int n, ne;		/* nodes in this medium, collimated beams */
	const double *mu;	/* [n] node cosines in the medium [-] */
	const double *w;	/* [n] cosine weights: sum w_i f(mu_i) ~ integral over [0, 1] */
	const double *mu_e;	/* [ne] beam cosines in the medium [-]; 0 = the beam cannot exist here */
	const double *ext_e;	/* [ne] beam extinction factor 1 - omega (1 - S_e) (see ad_stack.c) */
	const double *Hpp;	/* [n x (n + ne)] h_m(mu_i, mu_j) then h_m(mu_i, mu_e), ld n */
	const double *Hpm;	/* [n x (n + ne)] the same with the second cosine negated */
	double tau;		/* optical thickness [-], INFINITY for a half space */
	double omega;		/* single-scattering albedo [-] */
	double dtau_max;	/* thickest starting layer [-] */
	double n_index;		/* refractive index of the medium [-] */
	int doubling_only;	/* 1: diamond start and doubling always (no eigenvectors) */
};

struct ad_layer_out {
	double *R, *T;		/* [n x (n + ne)], ld n; caller-owned */
	double *dT;		/* [ne] collimated transmission (Pade); caller-owned */
	int doublings;		/* doubling steps taken */
	double t_drop;		/* largest transmittance set to 0 when it became negligible */
	int eigen;		/* 1 if solved by eigenvectors (no doubling) */
};

/* Doubles of workspace ad_layer_solve needs. */
size_t ad_layer_work(int n, int ne);
/* Fill out for in; -1 with *cause if LAPACK fails or a half space does not
 * converge. */
int ad_layer_solve(const struct ad_layer_in *in, struct ad_layer_out *out, double *work, char **cause);
#endif
