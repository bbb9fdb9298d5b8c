/* ad: the deterministic solver of the skin's radiative transfer by
 * adding-doubling, the same problem the Monte Carlo samples: plane-parallel
 * layers (1..16, the last may be a half space) with refractive index,
 * mu_a, mu_s and a Henyey-Greenstein phase function; smooth Fresnel
 * interfaces (exact or Schlick, as in optics.h) with refraction and total
 * internal reflection, or rough ones (GGX microfacets, single scattering:
 * ad_rough.h; their shadowed light is the beam's facet_loss, their own
 * reflection of the beam is rsp, not in the BRDF); clear layers of any
 * thickness crossed incoherently;
 * ambient media above and below; collimated incidence at any angles.
 *
 * The parts carry the names of the adding-doubling literature (van de
 * Hulst 1980, Multiple Light Scattering; Prahl 1995, The Adding-Doubling
 * Method): the phase redistribution function and matrix (ad_phase.h), the
 * reflection and transmission matrices R and T of a layer and the doubling
 * that makes them (ad_layer.h), the adding of layers and boundaries
 * (ad_stack.h), one azimuthal Fourier order at a time (ad_order.h).
 *
 * One call solves all incidence angles from one set of reflection
 * matrices (each a collimated beam riding along with the quadrature).  It
 * returns per angle Rsp, Rd, Tt and the absorption per layer (as
 * struct sim_result defines them: Rd excludes Rsp and includes light that
 * returns unscattered), the diffuse BRDF's bin means on the bake's table
 * (theta_o uniform over [0, 90] deg, dphi over [0, 180] deg, both sides of
 * the incidence plane, dphi = 0 back toward the light; power through the
 * bin over the bin's integral of cos d(omega), as bake.c) with their
 * azimuthal means, and the BRDF at any point (ad_brdf).  Unscattered light
 * is not in the BRDF (it leaves only along the mirror direction).
 *
 * Every value comes with an error estimate (ad_err.h): the difference from
 * a second solve at half the quadrature nodes (which bounds the error where
 * doubling the nodes at least halves it, and is scaled up from a third
 * solve at a quarter where it does not), plus the size of the Fourier
 * orders beyond those kept where the series was cut.  rms_rel_err is the table's
 * solid-angle-weighted RMS relative error, defined as the Monte Carlo
 * bake's.  Asked for a tolerance, the solver doubles its nodes until the
 * estimate meets it, up to n_quad_max (slow falls at few nodes often speed
 * up once peaks are resolved: g = 0.99 meets 1e-3 at 256), and fails (-1
 * and *cause, with the error reached there) where it cannot.
 *
 * The solver sets OpenBLAS to one thread (process-wide: its matrices are
 * small) and runs Fourier orders on `threads` OpenMP threads instead.
 *
 * Method and sources: ad_quad.h (angles), ad_phase.h (phase function,
 * delta-M), ad_layer.h (starting layer, doubling), ad_stack.h (boundaries,
 * adding, fluxes), ad_order.h (Fourier orders), ad_eval.h (the BRDF between
 * nodes).  Matrix work through BLAS and LAPACK (OpenBLAS, LAPACKE).
 * The solver allocates; it never prints or exits. */
#ifndef SKINBAKE_AD_H
#define SKINBAKE_AD_H
#include "engine/ad_types.h"
#include "engine/optics.h"
#include "engine/slab.h"

#define AD_MAX_BEAMS 256

struct ad_cache;

struct ad_opts {
	double tol;		/* wanted accuracy: table RMS relative error and relative error of Rd, Tt;
				 * (0, 0.1]; also sets where the Fourier series is cut */
	int n_quad;		/* quadrature nodes per unit cosine per hemisphere, [4, 1024];
				 * 0 = the fewest from 16 up (doubling) that meet tol */
	int n_quad_max;		/* largest automatic n_quad */
	int error_estimate;	/* 1 = second solve at n_quad / 2 for the errors; 0 = none (errors 0) */
	double dtau_frac;	/* starting layer's optical thickness over the smallest cosine, (0, 1] */
	double dm_terms;	/* Legendre terms of the phase function kept per node of a medium; delta-M beyond */
	int max_orders;		/* Fourier orders at most, >= 1 */
	int n_to, n_phi;	/* table bins over theta_o and dphi, >= 1 each */
	int threads;		/* OpenMP threads over Fourier orders; 0 = all */
	int doubling_only;	/* 1: every layer by a diamond start and doubling (ad_layer.h), none
				 * by its eigenvectors; for comparisons */
	struct ad_cache *cache;	/* layer solutions kept across solves (ad_cache.h); NULL: none */
};

void ad_opts_default(struct ad_opts *o);

/* Solve slab s (checked and prepared) for incidence angles theta_i[k] in
 * [0, pi/2) [rad], 1 <= n_beams <= AD_MAX_BEAMS.  0, or -1 with *cause
 * (caller frees) on bad input, a LAPACK failure or an accuracy the solver
 * cannot reach.  Free r with ad_result_free after success. */
int ad_solve(const struct slab *s, enum optics_fresnel model, const double *theta_i, int n_beams,
    const struct ad_opts *o, struct ad_result *r, char **cause);

/* Diffuse BRDF [1/sr] of angle k at exit theta_o in [0, pi/2] and dphi
 * [rad]; its error estimate into *err when err != NULL. */
double ad_brdf(const struct ad_result *r, int k, double theta_o, double dphi, double *err);

/* The Fourier series of the diffuse BRDF of angle k at exit theta_o:
 * f(dphi) = sum_m coef[m] cos(m dphi), m < the return value (at most max;
 * dphi = 0 back toward the light). */
int ad_brdf_fourier(const struct ad_result *r, int k, double theta_o, double *coef, int max);

/* The diffuse BRDF of angle k at the points (theta_o[it], phi[ip]) [rad],
 * into f[it * n_phi + ip] [1/sr] with its error estimate in err (as
 * ad_brdf's), from one Fourier series per exit angle. */
void ad_brdf_points(const struct ad_result *r, int k, const double *theta_o, int n_to, const double *phi, int n_phi,
    double *f, double *err);

void ad_result_free(struct ad_result *r);

/* Once, early in main: BLAS single-threaded (the solver's matrices are small
 * and its orders or wavelengths run in parallel instead) and OpenBLAS's
 * worker threads ended.  A pthreads OpenBLAS starts one worker per core
 * when it loads; each spins (sched_yield) for about 2^28 cycles waiting for
 * work that never comes, 0.02-0.1 s of CPU per process (a quarter of
 * `bake --preset paper`'s under load). */
void ad_blas_init(void);
#endif
