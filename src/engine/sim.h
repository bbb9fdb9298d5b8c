/* sim: one simulation run (a slab, one incidence angle), split into
 * independent batches that OpenMP threads take in any order; batches are
 * merged in index order, so the result is bit-identical for any thread
 * count.  Standard errors come from the spread between batch means. */
#ifndef SKINBAKE_SIM_H
#define SKINBAKE_SIM_H
#include <stdint.h>
#include "engine/batchstat.h"
#include "engine/tally.h"
#include "engine/transport.h"

struct sim_config {
	struct slab slab;		/* checked and prepared */
	double theta_in;		/* incidence angle [rad], [0, pi/2) */
	struct transport_opts opts;
	struct tally_grid grid;
	long photons;			/* total photons, >= 1 */
	int batches;			/* independent batches for the error, >= 2 */
	uint64_t seed;
	uint32_t stream;		/* job id under one seed */
	int threads;			/* 0 = OpenMP default */
};

struct sim_result {
	long photons;
	double seconds;		/* wall time of the run [s] */
	double events;		/* scattering events in total */
	double rsp;		/* exact, no error (smooth top); a Monte Carlo mean with rsp_err (rough top) */
	double rsp_err;		/* standard error of rsp, 0 for a smooth top */
	/* Fractions of the incident power with their standard errors; facet_loss
	 * is what the rough boundaries' single-scattering microfacets lose. */
	struct estimate rd, rd_unscat, tt, tt_unscat, lost, facet_loss;
	struct estimate a[SLAB_MAX_LAYERS + 2];	/* index as in struct slab */
	int n_layers;
	struct tally_grid grid;
	/* Diffuse (scattered) BRDF [1/sr]: mean over each (theta_out, delta_phi) bin,
	 * [n_theta * n_phi]; and its azimuthal average per theta_out band [n_theta]. */
	double *fr, *fr_err;
	double *fr_az, *fr_az_err;
	/* Radial profile Rd(r) [1/cm^2] per bin [n_r], bin edges k*dr. */
	double *rd_r, *rd_r_err;
	/* Sum of all booked fractions minus 1 (should be ~1e-15). */
	double balance;
};

void sim_config_default(struct sim_config *c);
/* Run; never fails on checked input.  progress(user, done, total) is called
 * from one thread as batches finish (may be NULL).  Caller frees with sim_result_free. */
void sim_run(const struct sim_config *c, struct sim_result *res,
    void (*progress)(void *user, long done, long total), void *user);
void sim_result_free(struct sim_result *res);
/* tally_cos_omega under its older name (kept for existing callers). */
static inline double sim_cos_solid_angle(double t0, double t1, double dphi)
{
	return tally_cos_omega(t0, t1, dphi);
}
#endif
