/* bake: the BRDF bake driver.  It turns a bake spec (the layer stack per
 * wavelength, the incidence angles and exit grid, the accuracy and the
 * method's settings) into a solver problem, asks a solver for the table
 * (engine/solver.h; Monte Carlo, engine/mc.h, is the method today) and adds
 * what the bake directory needs besides the table: the clear top stack for
 * the analytic specular and the mean exit radius per wavelength.  No files
 * are written here (bake/bakefile.h writes them).
 *
 * Seams for what is to come: the method is chosen in one place
 * (bake_solver in bake.c) and named in bake_result.solver, for a
 * `--solver` option and the manifest's record of it; a solver runs in
 * steps whose state can be saved between them (engine/solver.h), for
 * checkpoints; a family of bakes (one preset varied over parameters) is a
 * loop of bake_spec_layers and bake_run over the members. */
#ifndef SKINBAKE_BAKE_H
#define SKINBAKE_BAKE_H
#include <stdint.h>
#include "engine/slab.h"
#include "engine/solver.h"
#include "engine/specular.h"
#include "engine/transport.h"
#include "skin/tissue.h"

#define BAKE_MAX_WL 128
#define BAKE_MAX_TI 90

struct bake_spec {
	int n_wl;				/* wavelengths, 1..BAKE_MAX_WL */
	double wl_nm[BAKE_MAX_WL];		/* [nm] */
	struct slab slab[BAKE_MAX_WL];		/* layer stack per wavelength, prepared */
	int n_ti;				/* incidence nodes, 1..BAKE_MAX_TI */
	double theta_i[BAKE_MAX_TI];		/* [rad], ascending, in [0, pi/2) */
	int n_to, n_phi;			/* table bins over theta_o [0, 90] and delta_phi [0, 180] deg */
	int n_r;				/* radial bins of Rd(r) */
	double dr;				/* radial bin width [cm] */
	struct transport_opts opts;		/* boundary model and the kernel's roulette and step cap */
	uint64_t seed;
	long batch_photons;			/* photons per batch, >= 1 */
	int min_batches;			/* batches per job in the first round, >= 4 */
	double target_error;			/* RMS relative error to reach; 0 = run max_photons */
	long max_photons;			/* total photon budget of the bake */
	int nee;				/* exit bins by next-event estimation (nee.h) instead of escapes */
	int threads;				/* 0 = all cores */
	int rank, n_ranks;			/* MPI: this process takes units u with u % n_ranks == rank */
	/* MPI reduction hook: sum `n` doubles over ranks in place (NULL = single process). */
	void (*allreduce)(double *v, long n);
	void (*progress)(void *user, long done, long total);	/* may be NULL */
	void *progress_user;
};

/* What a bake computed: the solver's table and what the bake directory
 * needs besides it, so that its writer calls nothing back. */
struct bake_result {
	struct brdf_table table;	/* entries [n_wl * n_ti], entry = wavelength * n_ti + angle */
	const char *solver;		/* name of the method that made the table (static) */
	struct specular_stack *stack;	/* [n_wl] clear top stack per wavelength, for the analytic specular */
	double *mean_radius_cm;		/* [n_wl] mean exit radius of the diffuse light at theta_i[0] [cm]
					 * (tally_mean_radius; 0 without radial bins) */
};

/* Run the bake: 0, or -1 and *cause (caller frees) when the solver refuses
 * the spec.  Caller frees r with bake_result_free. */
int bake_run(const struct bake_spec *s, struct bake_result *r, char **cause);
void bake_result_free(struct bake_result *r);

/* Inputs from a skin preset.  bake_spec_layers fills s->slab[] at the
 * wavelengths s->wl_nm[0 .. n_wl) from p (checked and prepared); -1 and
 * *cause "LABEL at WL nm: problem" on the first that fails.
 * bake_rgb_weights puts the spectral -> linear sRGB weights of those
 * wavelengths into rgb_from_wl[3 * n_wl] (colour_rgb_weights) and returns
 * the sentence that says how they map, for the manifest. */
int bake_spec_layers(struct bake_spec *s, const struct skin_params *p, const char *label, char **cause);
const char *bake_rgb_weights(const struct bake_spec *s, double *rgb_from_wl);
#endif
