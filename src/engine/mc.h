/* mc: the Monte Carlo method of the solver interface (solver.h).  A job is
 * one (wavelength, incidence angle) entry; each job runs fixed-size batches
 * of photons (photon indices b*batch .. (b+1)*batch-1 of stream = job id),
 * so a table is a pure function of the problem, the settings and the seed,
 * whatever the thread or rank count.  Batches run in parallel and are merged
 * in batch order.  A step is one round of batches; with a target error,
 * rounds are added until the solid-angle-weighted RMS relative error of the
 * whole table (all jobs) is below the target or the photon budget is spent.
 * Exit bins are scored by the escapes or by next-event estimation (nee.h);
 * totals and Rd(r) always by the escapes. */
#ifndef SKINBAKE_MC_H
#define SKINBAKE_MC_H
#include <stdint.h>
#include "engine/solver.h"

struct mc_settings {
	uint64_t seed;
	long batch_photons;	/* photons per batch, >= 1 */
	int min_batches;	/* batches per job in the first round, >= 2 */
	long max_photons;	/* photon budget of the whole table */
	int nee;		/* 1: exit bins by next-event estimation; 0: by the escapes */
	double roulette_w;	/* weight below which roulette plays [-] (transport_opts) */
	double roulette_chance;	/* survival probability in roulette [-] */
	long max_steps;		/* interactions per photon before the guard ends it */
};

/* Defaults of the transport kernel (transport_opts_default), seed 1, batches
 * of 4000 photons, 8 in the first round, budget 2e8, next-event estimation. */
void mc_settings_default(struct mc_settings *s);

/* The method: settings are a struct mc_settings.  Gives SOLVER_BRDF | SOLVER_RADIAL. */
extern const struct solver_ops mc_solver;
#endif
