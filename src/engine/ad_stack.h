/* ad_stack: the layer stack for one azimuthal Fourier order: smooth Fresnel
 * boundaries (diagonal in the nodes), the adding method (R and T of two
 * elements combined into those of both: adding-doubling's second half,
 * ad_layer.h the first) of layers and boundaries from the bottom up, and for order 0 the sweep down
 * that gives every flux.
 *
 * The stack is B0 L1 B1 ... LK BK: K turbid layers and K + 1 boundaries.
 * A boundary is everything between two turbid media (or an ambient and a
 * turbid medium): the interfaces and the clear layers between them, crossed
 * incoherently (optics_stack_reflectance: the formula the Monte Carlo launch
 * uses, and the mean of what its photons do at each interface).  Vectors
 * and operators are in the form of ad_layer.h: N node rows, then one column
 * per collimated beam; d is the collimated (specular or unscattered) part.
 *
 * Adding (van de Hulst 1980; Prahl 1995, the same formulas for unequal
 * sides): for element A above a stack whose reflection is U,
 *   R = R_A + T_A (I - U R_A)^-1 U T_A,
 * one LU solve with N + E right-hand sides per element. */
#ifndef SKINBAKE_AD_STACK_H
#define SKINBAKE_AD_STACK_H
#include <stddef.h>
#include "engine/ad_elem.h"
#include "engine/optics.h"
#include "engine/slab.h"

/* An operator: a [N x (N + E)] (node matrix, then beam columns, ld N), d [E]. */
struct ad_op {
	double *a;
	double *d;
};

/* A boundary: reflectance and transmittance per node and per beam; a
 * boundary with a rough interface has full operators for the order in x
 * (ad_elem.h), which then stand for it (r, t, re, te unused). */
struct ad_bnd {
	double *r, *t;		/* [N] */
	double *re, *te;	/* [E] */
	const struct ad_elem *x;	/* NULL: smooth (diagonal) */
};

/* The order-0 fluxes for every beam, fractions of the incident power. */
struct ad_flux {
	double *rsp;		/* [E] specular reflection of the top boundary */
	double *rd;		/* [E] diffuse reflectance (scattered) */
	double *rd_d;		/* [E] returned collimated but not Rsp
				 * (unscattered, via lower boundaries) */
	double *tt;		/* [E] diffuse transmittance (scattered) */
	double *tt_d;		/* [E] collimated transmittance (unscattered) */
	double *a;		/* [K * E] absorbed in turbid layer k, beam e at a[k * E + e] */
};

/* Reflectance r and transmittance t at s of the boundary with index list
 * nl[0 .. cnt-1]: r = 1, t = 0 where the direction exists on one side only
 * (total internal reflection), both 0 where it exists on neither. */
void ad_bnd_rt(enum optics_fresnel model, const double *nl, int cnt, double s, double *r,
    double *t);

/* Fill boundary b for the index list nl[0 .. cnt-1] (medium above first,
 * medium below last) at node s values s[0 .. N-1] and beam s values
 * se[0 .. E-1]. */
void ad_bnd_fill(struct ad_bnd *b, enum optics_fresnel model, const double *nl, int cnt,
    const double *s, int N, const double *se, int E);

/* Doubles of workspace for the functions below. */
size_t ad_stack_work(int N, int E);

/* Reflection of the whole stack seen from above each element: U[j] for the
 * elements j = 0 .. 2K (B0, L1, B1, ..., BK), U[0] the stack seen from the
 * ambient above.  R[k], T[k] are turbid layer k's operators (R.d = 0).
 * -1 with *cause if a solve fails. */
int ad_stack_reflect(int N, int E, int K, const struct ad_bnd *bnd, const struct ad_op *R,
    const struct ad_op *T, struct ad_op *U, double *work, char **cause);

/* Order 0: the fields between the elements for unit collimated flux from
 * above, and from them the fluxes (a rough top's reflection of the beam,
 * diffuse or collimated, is rsp: the light that never entered) (absorption
 * from each layer's own R and T, so Rsp + Rd + Tt + sum A = 1 checks the
 * adding).  sqW[N] = sqrt(W). */
int ad_stack_flux(int N, int E, int K, const struct ad_bnd *bnd, const struct ad_op *R,
    const struct ad_op *T, const struct ad_op *U, const double *sqW, struct ad_flux *fx,
    double *work, char **cause);
#endif
