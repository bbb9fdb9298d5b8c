/* microfacet_ms: the reflection of a rough top that the single-scattering
 * GGX lobe leaves out, as an albedo-based lobe (Kulla & Conty, "Revisiting
 * physically based shading at Imageworks", SIGGRAPH 2017 course).
 *
 * With [surface] multiple_scattering = 1 the transport's rough top is the
 * random walk on the Smith microsurface (microfacet_sample_ms, Heitz et al.
 * 2016): it reflects R_walk(mu) of the beam, none of it lost.  That
 * reflection is Rsp, never in the table; the analytic lobe that stands for
 * it (specular_ggx, Walter et al. 2007 with the separable Smith G1 G1)
 * reflects only R_sep(mu).  The difference
 *
 *     dR(mu) = [R_hc(mu) - R_sep(mu)] + R_2(mu)
 *
 * (R_hc: the walk's first bounce, the height-correlated Smith term
 * 1 / (1 + Li + Lo); R_2: its second and later bounces that leave above)
 * is returned as the lobe
 *
 *     f_ms(mu_i, mu_o) = dR(mu_i) dR(mu_o) / (pi E),  E = 2 int_0^1 dR(mu) mu dmu,
 *
 * symmetric (reciprocal), with int f_ms mu_o domega_o = dR(mu_i) exactly
 * (energy), and 0 as alpha -> 0.  dR is at MICROFACET_MS_NMU cosines,
 * linear between them: R_hc and R_sep by a deterministic rule over the
 * facet normals (GGX: uniform in the D cos_m measure), R_2 by walks on
 * fixed random streams (the same numbers at every call). */
#ifndef SKINBAKE_MICROFACET_MS_H
#define SKINBAKE_MICROFACET_MS_H
#include "engine/microfacet.h"

#define MICROFACET_MS_NMU 24		/* cosine nodes (k + 1/2) / NMU */
#define MICROFACET_MS_WALKS 40000	/* walks per cosine for R_2 */

struct microfacet_ms {
	double alpha, n_i, n_t;			/* the interface [-] */
	double mu[MICROFACET_MS_NMU];		/* incidence cosines, ascending */
	double r_sep[MICROFACET_MS_NMU];	/* the separable lobe's reflectance [-] */
	double r_hc[MICROFACET_MS_NMU];		/* the walk's first bounce [-] */
	double r_2[MICROFACET_MS_NMU];		/* its later bounces, leaving above [-] */
	double r_2_err[MICROFACET_MS_NMU];	/* standard error of r_2 [-] */
	double dr[MICROFACET_MS_NMU];		/* r_hc - r_sep + r_2 (>= 0) [-] */
	double e;				/* 2 int dR mu dmu [-] (0: no lobe) */
};

/* Tabulate the missing reflectance of the GGX interface alpha from index
 * n_i (the light's side) into n_t, with the Fresnel model fresnel; walks
 * per cosine for the later bounces (0: MICROFACET_MS_WALKS).  alpha <= 0
 * or n_i == n_t gives an empty lobe (e = 0). */
void microfacet_ms_init(struct microfacet_ms *c, double alpha, double n_i, double n_t,
    enum optics_fresnel fresnel, int walks);

/* dR at incidence cosine cos_i (linear between the nodes, constant beyond). */
double microfacet_ms_missing(const struct microfacet_ms *c, double cos_i);

/* The lobe f_ms [1/sr] between incidence and exit cosines (both > 0). */
double microfacet_ms_eval(const struct microfacet_ms *c, double cos_i, double cos_o);
#endif
