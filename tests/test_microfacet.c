/* The rough dielectric interface (engine/microfacet) against closed forms:
 * D normalised, reciprocity, the BSDF integrated over outgoing directions
 * against the same integral over facet normals, the sampler's estimator
 * against both, the smooth Fresnel limit and the single-scattering loss. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>

#include "engine/microfacet.h"
#include "engine/optics.h"
#include "base/rng.h"

static const double pairs[][2] = { { 1.0, 1.5 }, { 1.5, 1.0 }, { 1.0, 1.44 }, { 1.44, 1.0 }, { 1.5, 1.44 } };
#define N_PAIRS ((int)(sizeof pairs / sizeof pairs[0]))

static void dir(double cos_t, double phi, double w[3])
{
	double s = sqrt(fmax(0.0, 1.0 - cos_t * cos_t));
	w[0] = s * cos(phi);
	w[1] = s * sin(phi);
	w[2] = cos_t;
}

/* int D cos d(omega) = 1 and int D(h) cos G1(v) (v.h)+ d(omega_h) = cos_v
 * (the Smith relation: the visible projected area of the facets equals the
 * macro surface's), for both distributions. */
static void test_normalisation(void **state)
{
	(void)state;
	for (int d = 0; d < 2; d++)
		for (double a = 0.05; a <= 1.0; a += 0.15) {
			struct microfacet m = { d ? MICROFACET_BECKMANN : MICROFACET_GGX, a, OPTICS_FRESNEL_EXACT };
			enum { N = 4000, P = 256 };
			double sum = 0.0, vis = 0.0, cv = 0.3, v[3];
			dir(cv, 0.0, v);
			for (int i = 0; i < N; i++) {
				/* cos_h = 1 - x^2 puts nodes where narrow lobes are. */
				double x = (i + 0.5) / N, ch = 1.0 - x * x, dmu = 2.0 * x / N;
				double D = microfacet_d(&m, ch);
				sum += D * ch * 2.0 * M_PI * dmu;
				for (int p = 0; p < P; p++) {
					double h[3];
					dir(ch, 2.0 * M_PI * (p + 0.5) / P, h);
					double vh = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
					if (vh > 0.0)
						vis += D * vh * dmu * 2.0 * M_PI / P;
				}
			}
			assert_float_equal(sum, 1.0, 1e-4);
			assert_float_equal(vis * microfacet_g1(&m, cv), cv, 2e-4);
		}
}

/* f_r(i, o) = f_r(o, i); f_t(i, o) / n_t^2 = f_t(o, i) / n_i^2 with the
 * reverse problem seen from the other side. */
static void test_reciprocity(void **state)
{
	(void)state;
	for (int d = 0; d < 2; d++)
		for (int p = 0; p < N_PAIRS; p++)
			for (double a = 0.05; a < 1.0; a += 0.2)
				for (int k = 0; k < 200; k++) {
					struct microfacet m = { d ? MICROFACET_BECKMANN : MICROFACET_GGX, a,
						OPTICS_FRESNEL_EXACT };
					double ni = pairs[p][0], nt = pairs[p][1], wi[3], wo[3];
					dir(0.02 + 0.98 * fmod(k * 0.618034, 1.0), 0.0, wi);
					dir(0.02 + 0.98 * fmod(k * 0.414214, 1.0), fmod(k * 2.71828, 2 * M_PI), wo);
					double fr = microfacet_bsdf(&m, ni, nt, wi, wo);
					double rr = microfacet_bsdf(&m, ni, nt, wo, wi);
					assert_float_equal(fr, rr, 1e-12 * fmax(1.0, fr));
					wo[2] = -wo[2];
					double ft = microfacet_bsdf(&m, ni, nt, wi, wo);
					double a1[3] = { wo[0], wo[1], -wo[2] }, a2[3] = { wi[0], wi[1], -wi[2] };
					double tr = microfacet_bsdf(&m, nt, ni, a1, a2);
					assert_float_equal(ft / (nt * nt), tr / (ni * ni), 1e-12 * fmax(1.0, ft));
					assert_true(fr >= 0.0 && ft >= 0.0);
				}
}

/* R and T from the BSDF over outgoing directions (midpoint rule in
 * cos_o = 1 - x^2 and phi) against the facet-normal quadrature of
 * microfacet_albedo: two independent routes through the formulas (the
 * Jacobians of reflection and refraction, Walter eqs. 14 and 17). */
static void test_bsdf_integral(void **state)
{
	(void)state;
	const double alphas[] = { 0.1, 0.2, 0.5 }, cos_i[] = { 1.0, 0.7, 0.3, 0.0872 };
	for (int d = 0; d < 2; d++)
		for (int p = 0; p < N_PAIRS; p++)
			for (int ia = 0; ia < 3; ia++)
				for (int ic = 0; ic < 4; ic++) {
					struct microfacet m = { d ? MICROFACET_BECKMANN : MICROFACET_GGX, alphas[ia],
						OPTICS_FRESNEL_EXACT };
					double ni = pairs[p][0], nt = pairs[p][1], wi[3], R = 0.0, T = 0.0;
					dir(cos_i[ic], 0.0, wi);
					enum { N = 600, P = 300 };
					for (int i = 0; i < N; i++) {
						double x = (i + 0.5) / N, co = 1.0 - x * x, dmu = 2.0 * x / N;
						for (int q = 0; q < P; q++) {
							double wo[3], phi = M_PI * (q + 0.5) / P;
							dir(co, phi, wo);
							/* symmetric in phi: half the circle, twice */
							R += 2.0 * microfacet_bsdf(&m, ni, nt, wi, wo) * co * dmu * M_PI / P;
							wo[2] = -wo[2];
							T += 2.0 * microfacet_bsdf(&m, ni, nt, wi, wo) * co * dmu * M_PI / P;
						}
					}
					double Ra, Ta;
					microfacet_albedo(&m, ni, nt, cos_i[ic], 400, 400, &Ra, &Ta);
					/* 1.5 | 1.44 refracts so little that the transmitted
					 * lobe is narrower than the outgoing grid: R only. */
					if (fabs(R - Ra) > 1e-3 || (p < 4 && fabs(T - Ta) > 1e-3))
						fail_msg("d %d pair %d alpha %g cos %g: R %g / %g, T %g / %g", d, p, alphas[ia],
						    cos_i[ic], R, Ra, T, Ta);
				}
}

/* The sampler's estimator, mean weight into each side, against the
 * albedo, within 4 standard errors (at most 5e-4 for GGX with 10^6
 * samples: the choice between reflection and refraction is a coin with
 * the facet's Fresnel reflectance). */
static void test_sampling(void **state)
{
	(void)state;
	const double alphas[] = { 0.05, 0.2, 0.5 }, cos_i[] = { 1.0, 0.6, 0.0872 };
	for (int d = 0; d < 2; d++)
		for (int p = 0; p < N_PAIRS; p++)
			for (int ia = 0; ia < 3; ia++)
				for (int ic = 0; ic < 3; ic++) {
					struct microfacet m = { d ? MICROFACET_BECKMANN : MICROFACET_GGX, alphas[ia],
						OPTICS_FRESNEL_EXACT };
					double ni = pairs[p][0], nt = pairs[p][1], wi[3];
					dir(cos_i[ic], 0.0, wi);
					const int N = d ? 200000 : 1000000;
					double s[2] = { 0, 0 }, s2[2] = { 0, 0 };
					struct rng r;
					rng_seed(&r, 7, (uint32_t)(d * 100 + p * 10 + ia), (uint64_t)ic);
					for (int k = 0; k < N; k++) {
						double wo[3];
						double u1 = rng_uniform(&r), u2 = rng_uniform(&r), u3 = rng_uniform(&r);
						double w = microfacet_sample(&m, ni, nt, wi, u1, u2, u3, wo);
						int side = wo[2] < 0.0;
						if (w == 0.0)
							continue;
						assert_true(fabs(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2] - 1.0) < 1e-9);
						s[side] += w;
						s2[side] += w * w;
					}
					double Ra, Ta;
					microfacet_albedo(&m, ni, nt, cos_i[ic], 400, 400, &Ra, &Ta);
					double want[2] = { Ra, Ta };
					for (int side = 0; side < 2; side++) {
						double mean = s[side] / N, var = s2[side] / N - mean * mean;
						double se = sqrt(var / N);
						if (fabs(mean - want[side]) > 4.0 * se + 1e-5)
							fail_msg("d %d pair %d alpha %g cos %g side %d: %g vs %g (se %g)", d, p,
							    alphas[ia], cos_i[ic], side, mean, want[side], se);
					}
				}
}

/* Where the sampler sends the light: the weight per band of cos_o against
 * the BSDF times |cos_o| integrated over the band (4 standard errors). */
static void test_sampling_bands(void **state)
{
	(void)state;
	const int cases[][2] = { { 0, 60 }, { 3, 30 }, { 3, 60 }, { 2, 85 } };
	for (int c = 0; c < 4; c++) {
		struct microfacet m = { MICROFACET_GGX, 0.3, OPTICS_FRESNEL_EXACT };
		double ni = pairs[cases[c][0]][0], nt = pairs[cases[c][0]][1], wi[3];
		dir(cos(cases[c][1] * M_PI / 180.0), 0.0, wi);
		enum { NB = 10, N = 400000 };
		double s[2 * NB] = { 0 }, s2[2 * NB] = { 0 };
		struct rng r;
		rng_seed(&r, 11, 3, (uint64_t)c);
		for (int k = 0; k < N; k++) {
			double wo[3], u1 = rng_uniform(&r), u2 = rng_uniform(&r), u3 = rng_uniform(&r);
			double w = microfacet_sample(&m, ni, nt, wi, u1, u2, u3, wo);
			if (w == 0.0)
				continue;
			int b = (int)(fabs(wo[2]) * NB);
			b = (b >= NB ? NB - 1 : b) + (wo[2] < 0.0 ? NB : 0);
			s[b] += w;
			s2[b] += w * w;
		}
		for (int b = 0; b < 2 * NB; b++) {
			double want = 0.0, sign = b < NB ? 1.0 : -1.0;
			enum { Q = 200, P = 400 };
			for (int i = 0; i < Q; i++) {
				double co = ((b % NB) + (i + 0.5) / Q) / NB;
				for (int q = 0; q < P; q++) {
					double wo[3];
					dir(co, M_PI * (q + 0.5) / P, wo);
					wo[2] *= sign;
					want += 2.0 * microfacet_bsdf(&m, ni, nt, wi, wo) * co * (1.0 / (NB * Q)) * (M_PI / P);
				}
			}
			double mean = s[b] / N, se = sqrt(fmax(0.0, s2[b] / N - mean * mean) / N);
			if (fabs(mean - want) > 4.0 * se + 2e-4)
				fail_msg("case %d band %d: sampled %g, BSDF %g (se %g)", c, b, mean, want, se);
		}
	}
}

/* alpha -> 0: R and T of the smooth interface (optics_fresnel), total
 * internal reflection included, to 1e-3 up to 85 degrees. */
static void test_smooth_limit(void **state)
{
	(void)state;
	for (int d = 0; d < 2; d++)
		for (int p = 0; p < N_PAIRS; p++)
			for (double th = 0.0; th <= 85.0; th += 5.0) {
				struct microfacet m = { d ? MICROFACET_BECKMANN : MICROFACET_GGX, 1e-4,
					OPTICS_FRESNEL_EXACT };
				double ni = pairs[p][0], nt = pairs[p][1], c = cos(th * M_PI / 180.0), ct, R, T;
				double F = optics_fresnel(OPTICS_FRESNEL_EXACT, ni, nt, c, &ct);
				microfacet_albedo(&m, ni, nt, c, 200, 64, &R, &T);
				/* Near the critical angle the facets straddle it: skip
				 * the 1-degree window where Fresnel is not smooth. */
				if (ni > nt && fabs(th - asin(nt / ni) * 180.0 / M_PI) < 1.0)
					continue;
				if (fabs(R - F) > 1e-3 || fabs(T - (1.0 - F)) > 1e-3)
					fail_msg("d %d pair %d theta %g: R %g T %g, Fresnel %g", d, p, th, R, T, F);
			}
}

/* Energy: R + T <= 1, nothing is lost at normal incidence for small alpha,
 * the loss grows with alpha at grazing incidence; prints the loss. */
static void test_energy(void **state)
{
	(void)state;
	const double alphas[] = { 0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0 }, ths[] = { 0, 45, 70, 85 };
	for (int p = 0; p < 4; p++) {
		double ni = pairs[p][0], nt = pairs[p][1], prev[4] = { 0, 0, 0, 0 };
		print_message("# GGX single-scattering loss 1 - R - T, n %.2f -> %.2f, theta 0/45/70/85 deg:\n", ni, nt);
		for (int ia = 0; ia < 7; ia++) {
			struct microfacet m = { MICROFACET_GGX, alphas[ia], OPTICS_FRESNEL_EXACT };
			double loss[4];
			for (int k = 0; k < 4; k++) {
				double R, T;
				microfacet_albedo(&m, ni, nt, cos(ths[k] * M_PI / 180.0), 400, 200, &R, &T);
				loss[k] = 1.0 - R - T;
				assert_true(loss[k] > -1e-9);
			}
			print_message("#   alpha %.2f: %.4f %.4f %.4f %.4f\n", alphas[ia], loss[0], loss[1], loss[2], loss[3]);
			if (ia == 0 && ni < nt)
				assert_true(loss[0] < 1e-3);
			assert_true(loss[3] >= prev[3] - 1e-6);
			for (int k = 0; k < 4; k++)
				prev[k] = loss[k];
		}
	}
}

static double uni(void *r)
{
	return rng_uniform(r);
}

/* The first order of the walk in closed form: on the uniform-height
 * microsurface the first hit has c = C1(h) with P(c < x) = x^(1 + Li), and
 * the ray leaves with probability c^Lo after reflection, (1 - c)^Lo after
 * refraction; so the height-correlated Smith terms (Heitz 2014) replace
 * G1(wo): (1 + Li) / (1 + Li + Lo) and (1 + Li) B(1 + Li, 1 + Lo).  The
 * facet-normal quadrature of microfacet_albedo with these. */
static void first_order(const struct microfacet *m, double ni, double nt, double ci, double *R, double *T)
{
	double wi[3] = { sqrt(1.0 - ci * ci), 0.0, ci }, li = microfacet_lambda(m, ci), a2 = m->alpha * m->alpha;
	enum { NM = 400, NP = 200 };
	*R = *T = 0.0;
	for (int a = 0; a < NM; a++)
		for (int b = 0; b < NP; b++) {
			double sv = (a + 0.5) / NM, u = 1.0 - sv * sv, c2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u), h[3], wo[3], ct;
			dir(sqrt(c2), 2.0 * M_PI * (b + 0.5) / NP, h);
			double ih = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
			if (ih <= 0.0)
				continue;
			double F = optics_fresnel(m->fresnel, ni, nt, ih, &ct), w = 2.0 * sv * ih / (ci * h[2]) / (NM * NP);
			for (int k = 0; k < 3; k++)
				wo[k] = 2.0 * ih * h[k] - wi[k];
			if (wo[2] > 0.0)
				*R += w * F / (1.0 + li + microfacet_lambda(m, wo[2]));
			if (F >= 1.0)
				continue;
			for (int k = 0; k < 3; k++)
				wo[k] = (ni / nt * ih - ct) * h[k] - ni / nt * wi[k];
			if (wo[2] < 0.0) {
				double lo = microfacet_lambda(m, wo[2]);
				*T += w * (1.0 - F) * exp(lgamma(1.0 + li) + lgamma(1.0 + lo) - lgamma(2.0 + li + lo));
			}
		}
}

/* The multiple-scattering walk (Heitz 2016): its light that leaves after
 * one bounce is first_order's (which checks the heights and the visible
 * normals), nothing is lost, every direction is a unit vector; prints
 * what the higher orders add back. */
static void test_multiple_scattering(void **state)
{
	(void)state;
	const double alphas[] = { 0.05, 0.35, 0.8 }, ths[] = { 0, 60, 85 };
	print_message("# GGX multiple scattering: R, T (orders >= 2 in parentheses), n_i -> n_t, theta:\n");
	for (int p = 0; p < 4; p++)
		for (int ia = 0; ia < 3; ia++)
			for (int k = 0; k < 3; k++) {
				struct microfacet m = { MICROFACET_GGX, alphas[ia], OPTICS_FRESNEL_EXACT };
				double ni = pairs[p][0], nt = pairs[p][1], wi[3];
				dir(cos(ths[k] * M_PI / 180.0), 0.0, wi);
				enum { N = 300000 };
				double s1[2] = { 0, 0 }, sm[2] = { 0, 0 };
				struct rng r;
				rng_seed(&r, 5, (uint32_t)(p * 10 + ia), (uint64_t)k);
				for (int i = 0; i < N; i++) {
					double wo[3];
					int order;
					double w = microfacet_sample_ms(&m, ni, nt, wi, uni, &r, wo, &order);
					assert_true(w == 1.0);
					assert_true(fabs(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2] - 1.0) < 1e-9);
					int side = wo[2] < 0.0;
					if (order == 1)
						s1[side] += 1.0;
					else
						sm[side] += 1.0;
				}
				double R, T;
				first_order(&m, ni, nt, cos(ths[k] * M_PI / 180.0), &R, &T);
				double want[2] = { R, T };
				for (int side = 0; side < 2; side++) {
					double mean = s1[side] / N, se = sqrt(mean * (1.0 - mean) / N);
					if (fabs(mean - want[side]) > 4.0 * se + 2e-4)
						fail_msg("pair %d alpha %g theta %g side %d: first order %g, single scattering %g (se %g)",
						    p, alphas[ia], ths[k], side, mean, want[side], se);
				}
				print_message("#   %.2f -> %.2f alpha %.2f theta %2.0f: R %.4f (%.4f) T %.4f (%.4f)\n", ni, nt,
				    alphas[ia], ths[k], (s1[0] + sm[0]) / N, sm[0] / N, (s1[1] + sm[1]) / N, sm[1] / N);
			}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_normalisation),
		cmocka_unit_test(test_reciprocity),
		cmocka_unit_test(test_bsdf_integral),
		cmocka_unit_test(test_sampling),
		cmocka_unit_test(test_sampling_bands),
		cmocka_unit_test(test_smooth_limit),
		cmocka_unit_test(test_energy),
		cmocka_unit_test(test_multiple_scattering),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
