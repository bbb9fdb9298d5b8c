/* transport: steady-state Monte Carlo light transport in a layered slab
 * (MCML: Wang, Jacques & Zheng, Comput. Methods Programs Biomed. 47:131,
 * 1995), with collimated incidence at any angle (Li & Ng).  The kernel never
 * allocates, prints or exits; it scores into a caller-owned tally. */
#ifndef SKINBAKE_TRANSPORT_H
#define SKINBAKE_TRANSPORT_H
#include <stdint.h>
#include "engine/optics.h"
#include "engine/slab.h"
#include "engine/tally.h"
#include "engine/nee.h"

struct transport_opts {
	enum optics_fresnel fresnel;	/* model at every boundary (per facet at rough ones) */
	double roulette_w;		/* weight below which roulette plays [-], >= 0 */
	double roulette_chance;		/* survival probability in roulette [-], (0, 1] */
	long max_steps;			/* interactions per photon before the guard ends it */
	double far_cm;			/* 0, or the distance from the entry point
					 * beyond which photons play far roulette (below),
					 * for tallies that ignore what leaves beyond it
					 * (Rd(r) of n_r dr); only without nee */
};

/* Where and how photons enter the first turbid layer. */
struct launch {
	double rsp;	/* specular reflectance of the top surface and any clear layers on top [-] */
	double w0;	/* weight entering the first turbid layer = 1 - rsp */
	int layer;	/* first turbid layer; n_layers + 1 when the stack is all clear;
			 * 0 (the ambient above) when a boundary on top is rough: the
			 * walk then crosses the top itself and scores rsp in the tally */
	double z;	/* entry depth [cm] */
	double ux, uz;	/* direction cosines in that layer (uy = 0: incidence plane is xz) */
};

/* Far roulette (far_cm > 0): each time a photon, at an interaction, is
 * further from where it entered (the 3-D distance, so depth counts too)
 * than far_cm + k far_cm / TRANSPORT_FAR_LEVELS for the first time (k = 0,
 * 1, ...), it survives with chance 1/2 at twice its weight (the change
 * booked against absorption, as the weight roulette's), and the weight
 * roulette then plays at roulette_w times its weight's growth.  Unbiased
 * for every tally; it spends less time on the photons that would have to
 * come a long way back to count.  On fair-oily at 700 nm (mean radius
 * 0.117 cm, far_cm 0.5) the walk took 1.2x less CPU at the same
 * variance of the mean radius (bake/radial.h). */
#define TRANSPORT_FAR_LEVELS 4
/* The nearest far_cm the radial runs use: a profile of 10 bins of 20 um
 * (0.02 cm) put the roulette levels 50 um apart, a photon 1 mm out had
 * doubled its weight 16 times, and paper's 656 nm mean radius came out 0
 * with a stated error of 0 (blender_scene_json.sh's bake). */
#define TRANSPORT_FAR_MIN_CM 0.5

/* Defaults: roulette below weight 0.2 with survival chance 0.3 (tuned on the
 * skin stack: about 3x the efficiency of MCML's 1e-4 / 0.1, see BENCHMARKS.md),
 * and a cap of 10^6 interactions. */
void transport_opts_default(struct transport_opts *o);

/* Specular reflection at the top and the entry state.  A clear layer (no
 * absorption or scattering) on top is crossed analytically: its incoherent
 * multiple reflections count into rsp, the MCML and adding-doubling
 * convention.  With a rough boundary on top (s->rough_top) the photons
 * start above the surface instead (rsp = 0, w0 = 1) and what comes back
 * without entering the first turbid layer is the tally's rsp.
 * theta_in in [0, pi/2) [rad]; s prepared. */
void transport_launch(const struct slab *s, double theta_in, enum optics_fresnel model, struct launch *ln);

/* Trace photons first .. first+count-1 of (seed, stream) and add their
 * weights to t (not zeroed here).  Photon i uses only the random numbers of
 * counter (seed, stream, i), so any split of the range gives the same sums.
 * With nee (allocated for grid's n_theta x n_phi; refilled here per photon), the exit bins are
 * scored by next-event estimation instead of by the escapes (see nee.h);
 * the totals and Rd(r) are always scored by the escapes. */
void transport_run(const struct slab *s, const struct launch *ln, const struct transport_opts *o,
    const struct tally_grid *grid, struct nee *nee, uint64_t seed, uint32_t stream, uint64_t first,
    uint64_t count, struct tally *t);
#endif
