/* macro: a second, larger scale of roughness over a baked BRDF.  The skin
 * surface at the mm scale (furrows, the tilt of whole patches) is a field of
 * tilted facets, each reflecting with the facet-scale BRDF f0 (the table
 * plus the analytic lobe) in its own frame.  Their slopes are Gaussian
 * (Beckmann: RMS slope m over all directions, m / sqrt(2) along each axis),
 * shadowing and masking at that scale are the height-correlated Smith term
 * G2 = 1 / (1 + Lambda(wi) + Lambda(wo)) of the Beckmann surface (Heitz,
 * "Understanding the masking-shadowing function in microfacet-based BRDFs",
 * JCGT 3(2), 2014, eq. 99), and the BRDF seen from afar is
 *
 *   f(wi, wo) = 1 / (cos_i cos_o) int f0(wi_m, wo_m) <wi.m> <wo.m> G2 D(m) dm
 *
 * (the same integral as Walter et al. 2007 eq. 19 with an arbitrary facet
 * BRDF; with Lambertian facets it is the model Oren & Nayar 1994
 * approximate).  D(m) dm = P(p, q) dp dq / cos_m over the slopes (p, q),
 * so a product Gauss-Hermite rule over the slopes does the integral.
 *
 * Energy: single scattering at the macro scale.  Light the facets shadow or
 * mask is lost, not scattered again (no interreflection between facets):
 * for Lambertian facets of albedo 1 the loss is 0.5 %, 1.9 % and 6.7 % of
 * the incident light at m = 0.1, 0.2, 0.4, nearly the same from 0 to 80 deg
 * (tests/test_macro.c).  The rule: 16 x 16 Gauss-Hermite nodes, within
 * 4e-3 of a 32 x 32 rule to grazing angles at m <= 0.4.
 * f is reciprocal when f0 is (G2 and the weights are symmetric in wi, wo).
 * m = 0 is the identity: f0 itself, with no quadrature.
 *
 * Angles as the bake's: theta_i, theta_o in [0, pi/2], delta_phi in [0, pi]
 * with 0 back toward the light (both directions on one side) and pi the
 * mirror side.  Pure functions; no allocation. */
#ifndef SKINBAKE_MACRO_H
#define SKINBAKE_MACRO_H

#define MACRO_NQ 16			/* Gauss-Hermite nodes per slope axis (bakes) */
#define MACRO_NQ_MAX 32			/* most nodes per axis (tests' reference) */
#define MACRO_N (MACRO_NQ_MAX * MACRO_NQ_MAX)
#define MACRO_SLOPE_MAX 0.8		/* largest RMS slope taken [-] */
#define MACRO_MAX_OUT 256		/* most values per evaluation */

/* The quadrature over facet normals for RMS slope m_rms in [0, MACRO_SLOPE_MAX]. */
struct macro_rule {
	double m_rms;		/* Beckmann m: RMS slope, all directions [-]; 0 = identity */
	int n;			/* normals in the rule (0 when m_rms == 0) */
	double m[MACRO_N][3];	/* facet normals (unit, z up) */
	double w[MACRO_N];	/* weights of the slope density, summing to 1 */
};

/* Fill r for RMS slope m_rms (clamped to [0, MACRO_SLOPE_MAX]) with nq
 * Gauss-Hermite nodes per slope axis (clamped to [2, MACRO_NQ_MAX];
 * MACRO_NQ is the bake's). */
void macro_rule_init(struct macro_rule *r, double m_rms, int nq);

/* The facet-scale BRDF: n values at local angles (as above) into out. */
typedef void (*macro_fn)(void *ctx, double theta_i, double theta_o, double dphi, double *out);

/* The macro-scale BRDF at (theta_i, theta_o, dphi): n values into out
 * (each the integral above of the matching value of f), f called once per
 * facet normal that sees both directions (once, unchanged, when
 * r->m_rms == 0; the mean of the rule in the frames of wi and of wo, so the
 * result is reciprocal where f is).  Directions within 0.05 deg of the horizon are taken at
 * 89.95 deg (the integral's 1 / cos has a finite limit there).  n <= MACRO_MAX_OUT. */
void macro_eval(const struct macro_rule *r, macro_fn f, void *ctx, int n, double theta_i,
    double theta_o, double dphi, double *out);

/* The height-correlated Smith term at the macro scale for directions at
 * cosines cos_i, cos_o to the mean normal [-]. */
double macro_g2(const struct macro_rule *r, double cos_i, double cos_o);
#endif
