/* radial: a bake's Rd(r) by Monte Carlo with control variates from
 * adding-doubling, for the wavelengths whose table method gives no Rd(r).
 *
 * Every photon that leaves the top scattered also scores, for K absorption
 * shifts s_k (RADIAL_CV_SHIFTS, added to every turbid layer's mu_a), its
 * weight times exp(-s_k L), L its path length in the turbid layers (white
 * Monte Carlo, engine/wmc.h), at any radius.  The expectation of each such
 * control is the diffuse reflectance (scattered, Rsp excluded) of the stack
 * with mu_a + s_k, which adding-doubling gives (m = 0 order, RADIAL_CV_TOL).
 * The controls follow the path length, and the exit radius follows it too,
 * so the regression estimator (profile bins, and the mean radius's numerator
 * and denominator, each regressed on the controls over the batches; Glasserman,
 * Monte Carlo Methods in Financial Engineering, 2003, section 4.1) has 2.5-4x
 * less variance than the plain mean on the skin stacks.  Exact up to Monte
 * Carlo noise and adding-doubling's error in the controls' means: their
 * effect (|d mean radius / d mean_k| times each error estimate) is added in
 * quadrature to the mean radius's standard error.  Standard errors from the
 * residuals over the batches (B - K - 1 degrees of freedom).  Without a
 * usable adding-doubling solve the controls are dropped (the plain
 * estimator, errors from the batches).
 *
 * Sizing as bake.h says: a pilot, then batches added until the mean
 * radius's relative standard error is within target (at most RADIAL_ROUNDS
 * rounds and `cap` photons). */
#ifndef SKINBAKE_RADIAL_H
#define SKINBAKE_RADIAL_H
#include <stdint.h>
#include "engine/optics.h"
#include "engine/slab.h"
#include "engine/transport.h"

#define RADIAL_CV_TOL 1e-4		/* adding-doubling tolerance of the controls' means */
#define RADIAL_BATCH 16			/* photons per batch */

struct radial_spec {
	const struct slab *slab;	/* prepared */
	double theta_in;		/* [rad] */
	const struct transport_opts *opts;
	int n_r;			/* radial bins */
	double dr;			/* their width [cm] */
	double rd0, rd0_err;		/* the scattered diffuse reflectance at theta_in and its
					 * error estimate when known (the table's), else rd0 < 0 */
	double target;			/* relative standard error of the mean radius to reach */
	long pilot;			/* photons of the first round */
	long cap;			/* photons at most */
	double margin;			/* photons added: the estimate of those needed times this */
	int rounds;			/* runs added to the pilot at most */
	uint64_t seed;
	uint32_t stream;
	int threads;			/* OpenMP threads, 0 = all */
};

struct radial_out {
	double *rd_r, *rd_r_err;	/* [n_r] Rd(r) [1/cm^2] and its standard error (the
					 * caller's arrays) */
	double mean_radius_cm;		/* tally_mean_radius of rd_r */
	double mean_radius_err_cm;	/* its standard error */
	long photons;			/* walked */
	int controls;			/* control variates used (0: the plain estimator) */
	double seconds;			/* wall time [s] */
};

/* Rd(r) of sp into out (rd_r, rd_r_err set by the caller to n_r doubles). */
void radial_solve(const struct radial_spec *sp, struct radial_out *out);
#endif
