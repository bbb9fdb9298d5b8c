/* mc: the Monte Carlo method of the solver interface (solver.h).  A job is
 * one (wavelength, incidence angle) entry; each job runs fixed-size batches
 * of photons (photon indices b*batch .. (b+1)*batch-1 of stream = job id),
 * so a table is a pure function of the problem, the settings and the seed,
 * whatever the thread or rank count.  Batches run in parallel and are merged
 * in batch order.  A step is one round of batches; with a target error,
 * rounds are added until the solid-angle-weighted RMS relative error of the
 * whole table (all jobs) is below the target or the photon budget is spent.
 *
 * The first round: min_batches batches of batch_photons per job; or, when
 * batch_photons is 0 and there is a target, sized from the target: a pilot
 * of min_batches batches of pilot_photons per job measures the table's RMS
 * error E_p at P pilot photons per job, which (errors falling as
 * 1/sqrt(photons)) gives the photons per job for the target, N = P
 * (E_p / target)^2 (bins the pilot left empty aside; 10% margin); the pilot
 * is then set aside and the first round is sized_batches batches of
 * N / sized_batches photons (photon indices after the pilot's), so that a
 * loose target costs little and a tight one needs no extra rounds.  The
 * pilot is the table when it meets the target already.  Every decision
 * comes from the merged sums, so the table stays a pure function of the
 * problem, the settings and the seed.
 *
 * Exit bins are scored by the escapes or by next-event estimation (nee.h);
 * totals and Rd(r) always by the escapes. */
#ifndef SKINBAKE_MC_H
#define SKINBAKE_MC_H
#include <stdint.h>
#include "engine/solver.h"

struct mc_settings {
	uint64_t seed;
	long batch_photons;	/* photons per batch, >= 1; 0 = sized from the target (see top;
				 * MC_BATCH_PHOTONS without a target) */
	int min_batches;	/* batches per job in the first round or the pilot, >= 2 */
	long pilot_photons;	/* photons per batch of the pilot, >= 1 */
	int sized_batches;	/* batches per job of the round sized from the pilot, >= 2 */
	long max_photons;	/* photon budget of the whole table (the pilot's included) */
	int nee;		/* 1: exit bins by next-event estimation; 0: by the escapes */
	double roulette_w;	/* weight below which roulette plays [-] (transport_opts) */
	double roulette_chance;	/* survival probability in roulette [-] */
	long max_steps;		/* interactions per photon before the guard ends it */
	uint32_t stream0;	/* random stream of job 0 (job j uses stream0 + j) */
};

#define MC_BATCH_PHOTONS 4000

/* Defaults of the transport kernel (transport_opts_default), seed 1, batches
 * of MC_BATCH_PHOTONS photons, 8 in the first round, a pilot of 8 x 250
 * photons per job and 32 batches in the sized round (when batch_photons is
 * set to 0), budget 2e8, next-event estimation. */
void mc_settings_default(struct mc_settings *s);

/* The method: settings are a struct mc_settings.  Gives SOLVER_BRDF | SOLVER_RADIAL. */
extern const struct solver_ops mc_solver;
#endif
