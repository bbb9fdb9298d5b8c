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

/* Pieces of a microfacet lobe, for callers that build their own (e.g. an
 * analytic test BRDF).  alpha2 is the GGX alpha squared. */
/* Schlick's Fresnel reflectance r0 + (1 - r0)(1 - c)^5, r0 = ((n-1)/(n+1))^2,
 * at cosine c from a medium of index 1 into index n. */
double specular_schlick(double cos_i, double n);
/* The GGX normal distribution alpha2 / (pi (cos_h^2 (alpha2 - 1) + 1)^2) [1/sr]. */
double specular_ggx_d(double cos_h, double alpha2);
/* Smith's masking for GGX, 2 c / (c + sqrt(alpha2 + (1 - alpha2) c^2)), c > 0. */
double specular_smith_g1(double cos_v, double alpha2);

/* GGX BRDF [1/sr] for incidence theta_i, exit theta_o [rad, 0..pi/2] and
 * delta_phi [rad] (0 = back toward the light, pi = mirror side); alpha > 0. */
double specular_ggx(const struct specular_stack *s, double alpha, double theta_i, double theta_o, double dphi);
#endif
