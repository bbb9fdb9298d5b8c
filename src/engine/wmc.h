/* wmc: Rd(r) of many absorption variants of one slab from one Monte Carlo
 * run (white Monte Carlo, tally.h): the photons walk the slab with the
 * smallest absorption per layer and every escape counts for each variant
 * with its weight times exp(-sum dmua_l L_l).  Exact (no approximation
 * beyond Monte Carlo noise) when the variants differ only in mu_a; each
 * variant's standard errors come from the spread between batches, so a
 * variant whose weights spread widely (absorption far above the walk's)
 * reports the larger error it has. */
#ifndef SKINBAKE_WMC_H
#define SKINBAKE_WMC_H
#include <stdint.h>
#include "engine/slab.h"
#include "engine/transport.h"

struct wmc_radial {
	int n_var;		/* variants */
	int n_r;		/* radial bins */
	double dr;		/* bin width [cm] */
	double *rd_r;		/* [n_var * n_r] Rd(r) per variant [1/cm^2] */
	double *rd_r_err;	/* [n_var * n_r] its standard error [1/cm^2] */
	long photons;		/* photons walked (shared by all variants) */
	double seconds;		/* wall time of the run [s] */
};

/* 1 when slab v is slab s but for mu_a (same layers, thicknesses, indices,
 * scattering, anisotropy, roughness and clear layers), else 0. */
int wmc_same_scattering(const struct slab *s, const struct slab *v);
/* The walk's slab of variants vs[n] (wmc_same_scattering with vs[0]): each
 * layer's smallest mu_a; prepared.  dmua[n * (SLAB_MAX_LAYERS + 2)] gets
 * each variant's excess over it [1/cm]. */
void wmc_reference(const struct slab *vs, int n, struct slab *ref, double *dmua);
/* Rd(r) at theta_in [rad] of the n_var variants dmua of the prepared slab
 * ref: `photons` photons (rounded up to whole batches of `batches` >= 2) of
 * random stream (seed, stream), on `threads` threads (0 = all).  Caller
 * frees out with wmc_radial_free. */
void wmc_radial_run(const struct slab *ref, const double *dmua, int n_var, double theta_in,
    const struct transport_opts *o, int n_r, double dr, long photons, int batches, uint64_t seed,
    uint32_t stream, int threads, struct wmc_radial *out);
void wmc_radial_free(struct wmc_radial *w);
/* The batches behind such a run, for estimators of their own: batches
 * b0 .. b0 + nb - 1 of bp photons each (batch b is photons b bp .. of
 * stream (seed, stream), so later calls continue the sequence).  Per batch
 * b (from 0), per photon: variant 0's weight leaving through radial bin i
 * into prof[b * n_r + i] (not per area) and every variant's reweighted
 * scattered weight leaving the top at any radius into tot[b * n_var + v]. */
void wmc_batches(const struct slab *ref, const double *dmua, int n_var, double theta_in,
    const struct transport_opts *o, int n_r, double dr, long bp, int b0, int nb, uint64_t seed,
    uint32_t stream, int threads, double *prof, double *tot);
#endif
