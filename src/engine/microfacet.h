/* microfacet: a rough dielectric interface, the single-scattering
 * microfacet BSDF of Walter, Marschner, Li & Torrance, "Microfacet models
 * for refraction through rough surfaces" (EGSR 2007): reflection and
 * refraction on facets with normals from a GGX or Beckmann distribution,
 * Fresnel per facet (optics.h; total internal reflection where the facet
 * allows no refraction) and the separable Smith shadowing-masking
 * G = G1(wi) G1(wo).  Sampling of the visible normals of GGX follows Heitz,
 * "Sampling the GGX distribution of visible normals" (JCGT 7(4), 2018).
 *
 * Frame: the macro normal is +z, the incident side is z > 0 with index
 * n_i, the other side has index n_t.  Directions are unit vectors pointing
 * away from the surface (wi toward where the light comes from).  The BSDF
 * is the radiance one: f(wi, wo) |wo.z| d(omega_o) is the fraction of the
 * power from wi that leaves into d(omega_o), so reflection is symmetric and
 * transmission obeys f(wi, wo) / n_t^2 = f(wo, wi) / n_i^2 (Walter eq. 21).
 *
 * The model scatters once on the facets: light the Smith term shadows or
 * masks is lost, not scattered again.  What that loses, 1 - (R + T), grows
 * with alpha and toward grazing (microfacet_albedo; docs/validation.md).
 * Pure functions: no allocation, printing or random state (uniform numbers
 * come in as arguments). */
#ifndef SKINBAKE_MICROFACET_H
#define SKINBAKE_MICROFACET_H
#include "engine/optics.h"

enum microfacet_dist {
	MICROFACET_GGX,		/* Trowbridge-Reitz / GGX (Walter 2007 eq. 33) */
	MICROFACET_BECKMANN	/* Beckmann (Walter 2007 eq. 25) */
};

struct microfacet {
	enum microfacet_dist dist;
	double alpha;		/* roughness [-], (0, 1]: GGX alpha or Beckmann m (rms slope) */
	enum optics_fresnel fresnel;	/* Fresnel model per facet */
};

/* Normal distribution D at facet cosine cos_m [1/sr], normalised so that
 * the integral of D cos_m over the hemisphere is 1; 0 for cos_m <= 0. */
double microfacet_d(const struct microfacet *m, double cos_m);

/* Smith's Lambda for a direction at cosine cos_v to the macro normal; the
 * masking of that direction is G1 = 1 / (1 + Lambda) (|cos_v| is used). */
double microfacet_lambda(const struct microfacet *m, double cos_v);
double microfacet_g1(const struct microfacet *m, double cos_v);

/* The BSDF [1/sr] from wi (wi[2] > 0) to wo: reflection when wo[2] > 0,
 * transmission into index n_t when wo[2] < 0.  n_i == n_t (no interface)
 * gives 0: the transmission is then a delta straight through. */
double microfacet_bsdf(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    const double wo[3]);

/* Scatter the light from wi (wi[2] > 0) at the interface: pick a facet
 * normal (GGX: from the visible normals; Beckmann: from D cos_m), reflect
 * with the facet's Fresnel reflectance or refract, and store the outgoing
 * direction in wo.  Returns the weight of the estimator, f |wo.z| / pdf:
 * G1(wo) for GGX (in [0, 1]), |wi.m| G / (wi.z cos_m) for Beckmann; 0 when
 * the path is shadowed (wo on the wrong side).  u1, u2 choose the facet,
 * u3 reflection or refraction; all uniform in (0, 1).  n_i == n_t passes
 * straight through with weight 1. */
double microfacet_sample(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    double u1, double u2, double u3, double wo[3]);

/* Both outcomes of microfacet_sample at once (GGX only), for deterministic
 * rules over the facets: the facet chosen by u1, u2 reflects into wr with
 * weight *w_r = F G1(wr) and refracts into wt with *w_t = (1 - F) G1(wt);
 * a weight is 0 where that path is shadowed or impossible (total internal
 * reflection on the facet).  Their means over u1, u2 are the directional
 * albedos R and T.  n_i == n_t passes straight through with *w_t = 1. */
void microfacet_sample_split(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    double u1, double u2, double wr[3], double *w_r, double wt[3], double *w_t);

/* The multiple-scattering alternative to microfacet_sample (GGX only):
 * the random walk on the Smith microsurface of Heitz, Hanika, d'Eon &
 * Dachsbacher (SIGGRAPH 2016) with uniform heights, which reflects or
 * refracts at every facet it meets until it leaves on either side; nothing
 * is shadowed away, so the weight is 1 (0 after MICROFACET_MAX_BOUNCES
 * bounces, which does not happen in practice).  uniform(rng) gives the
 * numbers in (0, 1).  The bounces taken go to *order (may be NULL); the
 * light leaving after one bounce is microfacet_sample's. */
#define MICROFACET_MAX_BOUNCES 256
double microfacet_sample_ms(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    double (*uniform)(void *), void *rng, double wo[3], int *order);

/* Directional albedo from wi at incidence cosine cos_i: the reflected (R)
 * and transmitted (T) fractions of the power, by a deterministic product
 * quadrature of the BSDF over the outgoing sphere with n_mu x n_phi points
 * per hemisphere (the lobe's width sets how many are needed: n_mu = 400,
 * n_phi = 400 resolve alpha >= 0.02 to 1e-5).  The single-scattering loss is
 * 1 - R - T. */
void microfacet_albedo(const struct microfacet *m, double n_i, double n_t, double cos_i, int n_mu,
    int n_phi, double *R, double *T);
#endif
