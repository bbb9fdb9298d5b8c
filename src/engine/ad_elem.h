/* ad_elem: a boundary of the adding-doubling stack as a general element,
 * for boundaries with a rough interface (ad_rough.h), where reflection and
 * transmission couple every node with every other (a smooth boundary is
 * diagonal: struct ad_bnd).  The element has four operators in the form of
 * ad_layer.h (node columns, then one column per collimated beam for light
 * from above) and the collimated-to-collimated factors per beam; light
 * from below has no beam columns (a collimated beam only comes back up
 * through a boundary it went down through collimated, and a boundary with
 * a rough interface lets none through collimated).
 *
 * Several interfaces with clear layers between them (crossed incoherently
 * and without loss, as the smooth boundaries' optics_stack_reflectance)
 * become one element by adding them from the bottom up: for A above B,
 * with the fields between them (van de Hulst 1980; the unequal-sides
 * formulas of Prahl 1995),
 *   d = (I - Rb_A Rt_B)^-1 (s_d + Rb_A s_u),  u = s_u + Rt_B d,
 *   Rt = Rt_A + Tu_A u,  Td = Td_B d (+ B's columns for the collimated part),
 * s_d the light A sends down into the gap, s_u what B sends up from the
 * collimated beam; one LU factorization serves both sides. */
#ifndef SKINBAKE_AD_ELEM_H
#define SKINBAKE_AD_ELEM_H
#include <stddef.h>
#include "engine/optics.h"

struct ad_elem {
	double *rt;	/* [N x (N + E)] reflection of light from above, ld N */
	double *td;	/* [N x (N + E)] transmission down */
	double *rb;	/* [N x N] reflection of light from below */
	double *tu;	/* [N x N] transmission up */
	double *rt_d, *td_d, *rb_d, *tu_d;	/* [E] collimated in, collimated out
						 * (from above: r, t; below) */
};

/* Doubles one element needs (ad_elem_bind carves them). */
size_t ad_elem_size(int N, int E);
/* Point e's arrays into block (ad_elem_size(N, E) doubles). */
void ad_elem_bind(struct ad_elem *e, double *block, int N, int E);

/* A smooth interface between indices n_above and n_below at the nodes' s
 * values s[N] and the beams' se[E] (diagonal, optics.h Fresnel). */
void ad_elem_smooth(struct ad_elem *x, int N, int E, enum optics_fresnel model, double n_above,
    double n_below, const double *s, const double *se);

/* Doubles of workspace ad_elem_add needs. */
size_t ad_elem_work(int N, int E);
/* out = A above B (out may be B).  -1 if the LU solve fails. */
int ad_elem_add(int N, int E, const struct ad_elem *A, const struct ad_elem *B, struct ad_elem *out,
    double *work);
#endif
