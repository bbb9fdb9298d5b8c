/* bake: the BRDF bake driver.  It turns a bake spec (the layer stack per
 * wavelength, the incidence angles and exit grid, the accuracy and the
 * methods' settings) into a solver problem, asks a solver for the table
 * (engine/solver.h) and adds what the bake directory needs besides the
 * table: the clear top stack for the analytic specular and the mean exit
 * radius per wavelength.  No files are written here (bake/bakefile.h
 * writes them).
 *
 * The method (bake_spec.method): Monte Carlo (engine/mc.h), adding-doubling
 * (engine/ad_solver.h), or auto: adding-doubling, and Monte Carlo for the
 * wavelengths where adding-doubling cannot meet its tolerance (each such
 * fallback is stated in bake_result.notes for the caller to show).  With
 * adding-doubling alone a wavelength it refuses fails the bake with its
 * cause.  Adding-doubling has no radial profile: Rd(r) (and the mean exit
 * radius behind a renderer's subsurface radius) then comes from a separate
 * Monte Carlo run per wavelength at theta_i[0] (exit bins by escapes on a
 * 1 x 1 grid, bake/radial.h: a regression on control variates whose means
 * adding-doubling gives): a pilot of BAKE_RADIAL_PILOT photons per
 * wavelength gives each mean radius with its relative standard error e;
 * where e is above radial_error, that wavelength runs N ((e /
 * radial_error)^2 BAKE_RADIAL_MARGIN - 1) more photons (N the photons so
 * far; at least N / 4 and at most 3 N, radial_photons in all), continuing its
 * random stream, estimated again from all of them, and so on for at most
 * BAKE_RADIAL_ROUNDS rounds.  The result carries the standard errors
 * reached.
 *
 * A solver runs in steps whose state can be saved between them
 * (engine/solver.h), for checkpoints; a family of bakes (one preset varied
 * over parameters) is a loop of bake_spec_layers and bake_run over the members. */
#ifndef SKINBAKE_BAKE_H
#define SKINBAKE_BAKE_H
#include <stdint.h>
#include "engine/slab.h"
#include "engine/solver.h"
#include "engine/solvers.h"
#include "engine/specular.h"
#include "engine/transport.h"
#include "skin/tissue.h"

#define BAKE_MAX_WL 128
#define BAKE_MAX_TI 90
#define BAKE_RADIAL_PILOT 1024		/* photons per wavelength of the Rd(r) pilot (64 batches) */
#define BAKE_RADIAL_ERROR 0.02		/* default radial_error */
#define BAKE_RADIAL_PHOTONS 1000000	/* default radial_photons */
#define BAKE_RADIAL_ROUNDS 4		/* Rd(r) runs added to the pilot at most */
#define BAKE_RADIAL_MARGIN 1.1		/* photons over the estimate of those needed */

/* The method of a bake (bake_spec.method): an index of solvers[]
 * (engine/solvers.h: 0, Monte Carlo, as before there was a choice), or
 * BAKE_SOLVER_AUTO: solvers_auto, and its fallback for the wavelengths it
 * refuses.  The methods are the engine's table: nothing here names one. */
#define BAKE_SOLVER_AUTO (-1)
#define BAKE_SOLVER_NONE (-2)	/* no method of that name */
/* Row i of --solver's choices (the id of the method), BAKE_SOLVER_NONE past
 * the last: auto first, then auto's method and its fallbacks, then the others. */
int bake_method_at(int i);
/* The name of method ID, for --solver, the manifest's solver.requested and
 * family.json's bake.requested. */
const char *bake_method_name(int id);
/* The id of the method named NAME, or BAKE_SOLVER_NONE. */
int bake_method_named(const char *name);
/* The names joined by '|', as OPT_ENUM choices ("auto|ad|mc"). */
const char *bake_method_choices(void);
/* The engine method that method ID runs first (auto: solvers_auto's). */
const struct solver_ops *bake_method_ops(int id);

/* Rd(r) made outside bake_run for some wavelengths (a family's members
 * share one white Monte Carlo run per wavelength, family/family_radial.h). */
struct bake_radial_given {
	const double *rd_r[BAKE_MAX_WL];	/* [n_r] Rd(r) [1/cm^2] per
						 * wavelength; NULL: bake_run runs it */
	const double *rd_r_err[BAKE_MAX_WL];	/* [n_r] its standard error [1/cm^2] */
	long photons;				/* photons of the shared runs behind them */
	double seconds;				/* their wall time [s] */
	int n_shared;				/* members sharing the runs */
};

struct bake_spec {
	int n_wl;				/* wavelengths, 1..BAKE_MAX_WL */
	double wl_nm[BAKE_MAX_WL];		/* [nm] */
	struct slab slab[BAKE_MAX_WL];		/* layer stack per wavelength, prepared */
	int n_ti;				/* incidence nodes, 1..BAKE_MAX_TI */
	double theta_i[BAKE_MAX_TI];		/* [rad], ascending, in [0, pi/2) */
	int n_to, n_phi;			/* table bins over theta_o [0, 90]
						 * and delta_phi [0, 180] deg */
	int n_r;				/* radial bins of Rd(r) */
	double dr;				/* radial bin width [cm] */
	struct transport_opts opts;		/* boundary model and the
						 * kernel's roulette and step cap */
	int method;				/* BAKE_SOLVER_AUTO or an index of solvers[] */
	double ad_tol;				/* adding-doubling tolerance (table RMS
						 * relative error); 0 = 1e-3; the target
						 * error when that is smaller */
	int ad_quad;				/* its quadrature nodes per
						 * unit cosine; 0 = automatic */
	int ad_quad_max;			/* largest automatic ad_quad (its cost bound);
						 * 0 = the solver's default */
	int ad_orders;				/* Fourier orders at most; 0 = all the table
						 * needs, 1 = the albedos only (order 0; the
						 * table's bins then hold its azimuthal mean) */
	int bin_means;				/* 1: bin means from every method (no point values;
					 * for comparing methods bin by bin) */
	double radial_error;			/* relative standard error of the
						 * mean exit radius that the Rd(r)
						 * run of an adding-doubling table
						 * aims at; 0 = BAKE_RADIAL_ERROR */
	long radial_photons;			/* its photons per wavelength at most;
						 * 0 = BAKE_RADIAL_PHOTONS */
	const struct bake_radial_given *radial_given;	/* Rd(r) already made (NULL: none) */
	/* Adding-doubling layer solutions kept across bakes (engine/ad_cache.h;
	 * the caller's); NULL: none. */
	struct ad_cache *ad_cache;
	/* Monte Carlo. */
	uint64_t seed;
	long batch_photons;			/* photons per batch; 0 = sized
						 * from the target (mc.h) */
	int min_batches;			/* batches per job in the
						 * first round or pilot, >= 4 */
	double target_error;			/* RMS relative error to
						 * reach; 0 = run max_photons */
	long max_photons;			/* total photon budget of the bake */
	int nee;				/* exit bins by next-event estimation
						 * (nee.h) instead of escapes */
	int threads;				/* 0 = all cores */
	int rank, n_ranks;			/* MPI: this process takes units u
						 * with u % n_ranks == rank */
	/* MPI reduction hook: sum `n` doubles over ranks in place (NULL = single process). */
	void (*allreduce)(double *v, long n);
	void (*progress)(void *user, long done, long total);	/* may be NULL */
	void *progress_user;
	/* Checkpoints (bake/checkpoint.h): the output directory the checkpoint
	 * goes beside (NULL: none), whether to resume from it, and the interval
	 * between writes [s].  One process only: under MPI a checkpoint is
	 * neither written nor resumed (resume is refused). */
	const char *checkpoint_out;
	int resume;
	double checkpoint_s;
};

/* What a bake computed: the solver's table and what the bake directory
 * needs besides it, so that its writer calls nothing back. */
struct bake_result {
	struct brdf_table table;	/* entries [n_wl * n_ti], entry =
					 * wavelength * n_ti + angle */
	const char *solver;		/* the methods that made the table: "mc", "ad", or "ad+mc"
					 * (static; each entry's method says which) */
	double tol;			/* tolerance the (deterministic) method worked
					 * to (0 when it has none: Monte Carlo) [-] */
	char *notes;			/* lines for the user (the fallbacks,
					 * with causes); NULL: none */
	char **fallback_cause;		/* [n_wl] why adding-doubling refused the wavelength
					 * (Monte Carlo made it); NULL entries where it did
					 * not, NULL array without any */
	struct specular_stack *stack;	/* [n_wl] clear top stack per wavelength,
					 * for the analytic specular */
	double *mean_radius_cm;		/* [n_wl] mean exit radius of the diffuse
					 * light at theta_i[0] [cm]
					 * (tally_mean_radius; 0 without radial bins) */
	double *mean_radius_err_cm;	/* [n_wl] its standard error [cm] (tally_mean_radius_err) */
	long radial_photons;		/* photons of the separate Rd(r) run (0 when the
					 * table's method gave it) */
	double radial_seconds;		/* its wall time [s] */
	double *radial_err_cm;		/* [n_wl] the separate Rd(r) run's mean radius standard
					 * error (from its batches, bake/radial.h; 0 or NULL: from
					 * the bins) */
	int radial_controls;		/* control variates of that run (the fewest of any
					 * wavelength) */
	int radial_shared;		/* > 0: Rd(r) came from white Monte Carlo runs shared by
					 * this many family members (radial_photons,
					 * radial_seconds are those runs') */
};

/* Run the bake: 0, or -1 and *cause (caller frees) when the solver refuses
 * the spec or the checkpoint cannot be used (stale without resume, of
 * another bake, damaged, resume under MPI).  Caller frees r with bake_result_free. */
int bake_run(const struct bake_spec *s, struct bake_result *r, char **cause);
void bake_result_free(struct bake_result *r);
/* The identity of a bake spec for its checkpoint (bake/checkpoint.h): a
 * 64-bit FNV-1a hash of everything that changes the numbers (wavelengths,
 * layer stacks, angles, grid, methods and their settings, seed; not the
 * thread count or the output). */
uint64_t bake_spec_identity(const struct bake_spec *s);

/* Inputs from a skin preset.  bake_spec_layers fills s->slab[] at the
 * wavelengths s->wl_nm[0 .. n_wl) from p (checked and prepared); -1 and
 * *cause "LABEL at WL nm: problem" on the first that fails.
 * bake_rgb_weights puts the spectral -> linear sRGB weights of those
 * wavelengths into rgb_from_wl[3 * n_wl] (colour_rgb_weights) and returns
 * the sentence that says how they map, for the manifest. */
int bake_spec_layers(struct bake_spec *s, const struct skin_params *p, const char *label,
    char **cause);
const char *bake_rgb_weights(const struct bake_spec *s, double *rgb_from_wl);
/* s's wavelengths wl_nm[n_wl] (0: the preset's, set later) and incidence
 * angles: theta_deg[n_theta] [deg], or when n_theta is 0 the nodes
 * 90 k / nodes deg, k = 0 .. nodes - 1, or when nodes is 0 too the table's
 * exit nodes below 90 deg (bake_nodes_theta(s->n_to), the last dropped:
 * the BRDF is 0 there; needs n_to >= 3, else 10 nodes as above). */
void bake_spec_axes(struct bake_spec *s, const double *wl_nm, int n_wl, const double *theta_deg,
    int n_theta, int nodes);
/* Load preset NAME, or the preset file PFILE when NAME is NULL, and fill
 * s's wavelengths (the preset's default ones when s->n_wl is 0) and layer
 * stacks; for Monte Carlo, check that the photon budget covers the first
 * round.  The preset (caller frees with preset_free), or NULL and *cause. */
struct skin_params *bake_spec_preset(struct bake_spec *s, const char *name, const char *pfile,
    char **cause);
/* Estimated needs per table cell (wavelength x theta_i x theta_o x
 * delta_phi): measured about 30 bytes of memory (tables, tallies, the
 * writer's planes) and 10 bytes of files (12 uncompressed); with margin. */
#define BAKE_MEM_PER_CELL 64.0
#define BAKE_DISK_PER_CELL 16.0
/* N_BAKES bakes of s's size (a family: members held packed as well) fit in
 * memory and under out on disk (base/budget.h)?  0, or -1 and *cause with
 * the numbers and the options that lower them.  bake_preset_to_dir and
 * family_bake call it before any work. */
int bake_budget(const struct bake_spec *s, int n_bakes, const char *out, char **cause);
/* The table's nodes where it holds point values (adding-doubling entries,
 * bake_spec_points): n >= 2 angles theta_k = pi/4 (1 - cos(k pi / (n - 1)))
 * [rad] over [0, pi/2], both ends included (Chebyshev-Lobatto in theta:
 * the BRDF of smooth boundaries is analytic in theta up to grazing, so
 * polynomial interpolation on them converges exponentially; dense where the
 * Fresnel factors change fast); and n >= 2 azimuths j pi / (n - 1) [rad]
 * over [0, pi] (trigonometric interpolation is exact for the Fourier orders
 * below n).  n = 1: theta 0 and phi 0 (an azimuthal mean). */
void bake_nodes_theta(int n, double *theta);
void bake_nodes_phi(int n, double *phi);
/* 1 when adding-doubling entries of s's table are point values at those
 * nodes (method ad or auto, n_to >= 3 and n_phi >= 2, not bin_means);
 * Monte Carlo entries are always bin means. */
int bake_spec_points(const struct bake_spec *s);
#endif
