/* ad_rough: a rough dielectric interface (engine/microfacet.h: GGX facets,
 * Fresnel per facet, separable Smith G, single scattering) as an element of
 * the adding-doubling stack (ad_elem.h), one azimuthal Fourier order at a
 * time (the anchor: Jakob, d'Eon, Jakob & Marschner, "A comprehensive
 * framework for rendering layered materials", SIGGRAPH 2014: the BSDF's
 * Fourier orders in the azimuth difference on the solver's quadrature).
 *
 * Column j of an operator is the light leaving per unit light arriving
 * along node j's direction (or beam e's), in the representation of
 * ad_layer.h (per node: flux / sqrt(W), W the s ds weight of ad_quad.h,
 * the same in every medium: s ds = n^2 mu dmu carries the n^2 scaling of
 * radiance across the interface):
 *   X_ij = sqrt(W_j / W_i) P_m(i | j),   X_ie = P_m(i | e) / sqrt(W_i),
 *   P_m(i | j) = integral of f(j -> o) cos(m dphi) h_i(o) |mu_o| d(omega_o),
 * f the BSDF (Walter et al. 2007: reflection, or transmission into the
 * other medium, total internal reflection included), dphi the difference
 * of the travel azimuths, h_i node i's share of the outgoing direction:
 * linear between the two nodes around it in the quadrature piece's Gauss
 * variable (the shares sum to 1, so power is kept exactly).  In the point
 * value limit (a smooth f) this is X_ij = sqrt(W_i W_j) f_m(j -> i) / n_i^2,
 * f_m = integral of f cos(m dphi) over the full turn.
 *
 * The integral runs over the facet normals, not the outgoing directions: a
 * product midpoint rule of n_u x n_u points in the variables of the GGX
 * visible-normal sampling (Heitz 2018), each facet both reflecting (weight
 * F G1(o)) and refracting ((1 - F) G1(o)); microfacet_sample_split.  So a
 * narrow lobe lands whole on its nodes and alpha -> 0 gives the smooth
 * interface's diagonal exactly (test_ad_rough); what the Smith term shadows
 * is lost (the single-scattering loss, 1 - R - T of microfacet_albedo).
 * Reciprocity (R symmetric, Tu the transpose of Td) holds to the rules'
 * error, which shrinks with the nodes and n_u (test_ad_rough).
 *
 * The facet rule must resolve node i's share in the outgoing angle, so it
 * grows with the nodes: n_u = 3 per node per unit cosine, within
 * [AD_ROUGH_NU_MIN, AD_ROUGH_NU_MAX] (measured, test_ad_rough: at 64 nodes
 * per unit cosine n_u = 96 changes the table by 3e-4 from n_u = 192, 48 by
 * 5e-3).  The facets are worked out once per interface (ad_rough_init):
 * their power goes to the nodes and, in the azimuth, to AD_ROUGH_NPHI
 * points on [0, pi] by 4-point Lagrange weights (cos(m phi) is even about
 * 0 and pi, so the points fold over at the ends); each order is then one
 * sum over those points (ad_rough_order), exact for m = 0 and within
 * (m dphi)^4 / 100 of the facets' own sum above.
 *
 * Multiple scattering on the facets (walks > 0; [surface]
 * multiple_scattering = 1, the Monte Carlo's microfacet_sample_ms, Heitz,
 * Hanika, d'Eon & Dachsbacher 2016): the first order is the rule above
 * with the height-correlated Smith terms of the uniform-height
 * microsurface in place of the separable G1(wi) G1(wo) (1 / (1 + Li + Lo)
 * for reflection, B(1 + Li, 1 + Lo) for refraction: the walk's first
 * bounce exactly), and the higher orders, broad and smooth, from
 * AD_ROUGH_MS_WALKS walks at each of AD_ROUGH_MS_NI incoming cosines on
 * fixed streams of base/rng.h: their Fourier orders binned on
 * AD_ROUGH_MS_NB outgoing cosines (tables built once per interface, the same
 * at every node count, so the solver's error estimate from half the nodes
 * does not see their noise), interpolated to the nodes as point values and
 * scaled per column to 1 - its first order (the walk loses nothing; the
 * scale absorbs the tables' interpolation and the first order's error:
 * within 2e-2 of the incident power, test_ad_rough). */
#ifndef SKINBAKE_AD_ROUGH_H
#define SKINBAKE_AD_ROUGH_H
#include "engine/ad_elem.h"
#include "engine/ad_quad.h"
#include "engine/optics.h"

#define AD_ROUGH_NU 64
/* Multiple scattering: walks per incoming cosine, incoming cosines, outgoing
 * cosine bins, Fourier orders kept (the higher orders are broad), the seed. */
#define AD_ROUGH_MS_WALKS 8192
#define AD_ROUGH_MS_NI 24
#define AD_ROUGH_MS_NB 24
#define AD_ROUGH_MS_M 12
#define AD_ROUGH_MS_SEED 21
#define AD_ROUGH_NPHI 128
/* Lobes this many nodes wide (standard deviation) or more get point values. */
#define AD_ROUGH_WIDE 2.0
#define AD_ROUGH_WIDE_PHI 0.1	/* [rad] */
/* Point values' azimuth rule: intervals, points in all. */
#define AD_ROUGH_GIV 8
#define AD_ROUGH_GNP (8 * AD_ROUGH_GIV)

/* The facet rule per axis for a quadrature of `density` nodes per unit
 * cosine. */
int ad_rough_nu(double density);

/* One incoming direction's outgoing power: nodes lo .. lo + cnt - 1, each
 * with AD_ROUGH_NPHI azimuth points, a[(i - lo) * AD_ROUGH_NPHI + b]. */
struct ad_rough_col {
	int lo, cnt;
	int point;	/* 0: facet rule, AD_ROUGH_NPHI uniform azimuth points; 1: point values,
			 * AD_ROUGH_GNP Gauss points (ad_rough.c) */
	float *a;
};

struct ad_rough {
	int N, E;
	struct ad_rough_col *top_r;	/* [N + E] from above (nodes, then beams): reflected */
	struct ad_rough_col *top_t;	/* [N + E] from above: transmitted */
	struct ad_rough_col *bot_r;	/* [N] from below: reflected */
	struct ad_rough_col *bot_t;	/* [N] from below: transmitted */
	/* Multiple scattering's orders >= 2 (NULL: single scattering): f_m tables
	 * [AD_ROUGH_MS_NI][2: reflected, transmitted][AD_ROUGH_MS_NB][AD_ROUGH_MS_M + 1]
	 * for light from above and below, and the columns' cosines above and below. */
	double *ms_top, *ms_bot, *mu_a, *mu_b;
	double *ms_scale_a, *ms_scale_b;	/* per column: scales the tables' power to
						 * 1 - the first order */
	double n_above, n_below;
	double lost_max;		/* largest power of a column sent off the quadrature [-] */
};

/* Work out the outgoing light of the interface between n_above and n_below
 * with GGX alpha in (0, 1] at quadrature q for the beams at se[0 .. E-1]
 * (s values), with n_u x n_u facets per incoming direction (n_u >= 2);
 * walks = 0 single scattering, > 0 multiple scattering (its tables take
 * AD_ROUGH_MS_WALKS walks per incoming cosine).  Allocates; free with
 * ad_rough_free. */
void ad_rough_init(struct ad_rough *r, const struct ad_quad *q, double n_above, double n_below,
    double alpha, enum optics_fresnel model, const double *se, int E, int n_u, int walks);

/* Order m of the interface into x (bound by ad_elem_bind, overwritten);
 * sqW[N] = sqrt(W).  The collimated factors are 0: nothing passes a rough
 * interface collimated. */
void ad_rough_order(const struct ad_rough *r, int m, const double *sqW, struct ad_elem *x);

void ad_rough_free(struct ad_rough *r);
#endif
