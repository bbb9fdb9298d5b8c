/* radial: a bake's Rd(r) by Monte Carlo with control variates from
 * adding-doubling, for the wavelengths whose table method gives no Rd(r).
 *
 * Every photon that leaves the top scattered also scores, for absorption
 * shifts s_k (0 and 2/cm, radial.c; added to every turbid layer's mu_a),
 * its weight times exp(-s_k L), L its path length in the turbid layers
 * (white Monte Carlo, engine/wmc.h), at any radius.  The expectation of
 * each such control is the scattered diffuse reflectance (Rsp excluded) of
 * the stack with mu_a + s_k, which adding-doubling gives: for s = 0 the
 * table's albedo (rd0), else an m = 0 solve at RADIAL_CV_TOL.  The
 * controls follow the path length, and the exit radius follows it too, so
 * the regression estimator (profile bins, and the mean radius's numerator
 * and denominator, each regressed on the controls over batches of
 * RADIAL_BATCH photons; Glasserman, Monte Carlo Methods in Financial
 * Engineering, 2003, section 4.1) has 2.5-3.9x less variance in the mean
 * radius than the plain mean on the skin stacks (a single ring's power
 * gains little).  Exact up to Monte Carlo noise and adding-doubling's
 * error in the controls' means: their effect (|d mean radius / d mean_k|
 * times each error estimate) is added in quadrature to the mean radius's
 * standard error.  Standard errors from the residuals over the batches
 * (B - K - 1 degrees of freedom).  Without a usable adding-doubling solve,
 * or with fewer than K + 9 batches, the controls are dropped (the plain
 * estimator, errors from the batches).
 *
 * The walk plays far roulette (engine/transport.h) beyond n_r dr from the
 * entry point, where nothing it scores counts: unbiased; on fair-oily at
 * 640-700 nm (mean radii 0.10-0.12 cm, far at 0.5 cm) 1.2-1.5x fewer
 * scattering events per photon for 1.0-1.13x the variance of the mean
 * radius.
 *
 * Sizing as bake.h says: a pilot (at least 32 batches where the cap
 * allows), then batches added until the mean radius's relative standard
 * error is within target (at most `rounds` more runs, each at most 3x the
 * batches so far, and `cap` photons in all). */
#ifndef SKINBAKE_RADIAL_H
#define SKINBAKE_RADIAL_H
#include <stdint.h>
#include "engine/optics.h"
#include "engine/slab.h"
#include "engine/transport.h"

/* Adding-doubling tolerance of the controls' means: the table's default, at
 * which the s = 0 control (the table's albedo) already is.  Their error
 * estimates enter the mean radius's error in quadrature; on the paper
 * stack each adds 0.05-0.1 % of the mean radius to the Monte Carlo's 2 %
 * (sqrt(0.0177^2 + 0.00101^2 + 0.00108^2) = 0.01776 against 0.01773 with
 * 1e-4 at 470 nm), while 1e-4 took the 470 nm solve from 16 to 32 nodes
 * per unit cosine, 35 ms CPU of its 89 ms bake without the walk. */
#define RADIAL_CV_TOL 1e-3
#define RADIAL_BATCH 16			/* photons per batch */
/* Expected photons back below which a run with none scored in the bins is
 * plausible: P(none) = exp(-photons x rd0) > exp(-20) = 2e-9. */
#define RADIAL_ZERO_PLAUSIBLE 20.0

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
