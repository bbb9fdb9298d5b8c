/* specular: the analytic surface reflection of the skin's top, kept out of
 * the Monte Carlo tables.  A GGX microfacet lobe (Walter, Marschner, Li &
 * Torrance, EGSR 2007) whose facet reflectance is that of the clear top
 * stack (e.g. air/sebum/epidermis with incoherent multiple reflections in
 * the sebum), so light that returns without scattering is here too. */
#ifndef SKINBAKE_SPECULAR_H
#define SKINBAKE_SPECULAR_H
#include "engine/optics.h"
#include "engine/slab.h"

#define SPECULAR_MAX_IFACES 18

/* Refractive indices from the ambient medium down to the first turbid layer. */
struct specular_stack {
	int n;					/* indices in n_list, >= 2 */
	double n_list[SPECULAR_MAX_IFACES];	/* [-], n_list[0] = ambient above */
	enum optics_fresnel model;
};

/* The clear stack of slab s (prepared): the indices from the ambient above
 * down to the first turbid layer (or the ambient below when all is clear). */
void specular_stack_of_slab(const struct slab *s, enum optics_fresnel model, struct specular_stack *out);

/* Reflectance of the clear stack at incidence cosine cos_i (adding of
 * lossless interfaces, the same formula the transport launch uses). */
double specular_stack_reflectance(const struct specular_stack *s, double cos_i);

/* GGX BRDF [1/sr] for incidence theta_i, exit theta_o [rad, 0..pi/2] and
 * delta_phi [rad] (0 = back toward the light, pi = mirror side); alpha > 0. */
double specular_ggx(const struct specular_stack *s, double alpha, double theta_i, double theta_o, double dphi);
#endif
