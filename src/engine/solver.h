/* solver: the seam between the bake driver and the methods that compute a
 * BRDF table.  The driver states a problem (prepared slabs, one per
 * wavelength; incidence angles; the exit grid; the accuracy wanted) and a
 * run environment (threads, MPI ranks, progress), and gets back a table:
 * per (wavelength, incidence angle) the bin means of the diffuse BRDF over
 * (theta_o, delta_phi) with their standard errors, Rsp, the diffuse albedo,
 * Tt, absorption per layer, optionally the radial profile Rd(r), and what it
 * cost.  The driver knows nothing of how a method works.
 *
 * A method is a table of functions (struct solver_ops) that works in units:
 * begin, then step until it says it is done, then finish.  A unit is what a
 * method can stop after (Monte Carlo: one round of photon batches; a
 * deterministic method: one slab), so a later checkpoint can save the state
 * between steps.  Monte Carlo is engine/mc.h.  A method that cannot give
 * some part of the table (e.g. adding-doubling has no Rd(r)) says so in
 * `provides` and leaves that part at 0; the driver then asks another
 * method for it.  A method whose settings let it refuse entries it cannot
 * solve to its accuracy leaves them empty with `refused` set, for the
 * driver to ask another method (engine/ad_solver.h). */
#ifndef SKINBAKE_SOLVER_H
#define SKINBAKE_SOLVER_H
#include <stddef.h>
#include "engine/batchstat.h"
#include <stdint.h>
#include "engine/optics.h"
#include "engine/sim.h"
#include "engine/slab.h"
#include "engine/tally.h"

/* What to compute, independent of the method. */
struct solver_problem {
	int n_wl;			/* wavelengths (slabs), >= 1 */
	const double *wl_nm;		/* [n_wl] [nm], labels of the table's entries */
	const struct slab *slab;	/* [n_wl] checked and prepared */
	int n_ti;			/* incidence angles, >= 1 */
	const double *theta_i;		/* [n_ti] [rad], ascending, in [0, pi/2) */
	struct tally_grid grid;		/* exit bins over theta_o [0, 90] x delta_phi [0, 180] deg; Rd(r) bins (n_r = 0: none) */
	enum optics_fresnel fresnel;	/* reflectance model at every boundary */
	double target_error;		/* solid-angle-weighted RMS relative error of the whole table
					 * to reach [-]; 0 = the method's own budget decides */
	/* Point values: a method that gives the BRDF at points (adding-doubling)
	 * puts fr at the exit nodes (point_theta_o[it], point_phi[ip]) instead of
	 * the bin means when these are set; Monte Carlo ignores them (bin means). */
	const double *point_theta_o;	/* [grid.n_theta] [rad], or NULL */
	const double *point_phi;	/* [grid.n_phi] [rad], or NULL */
	/* Adding-doubling's layer solutions kept across solves (ad_cache.h,
	 * owned by the caller); NULL: none.  Other methods ignore it. */
	struct ad_cache *ad_cache;
};

struct solver_ops;
struct ad_cache;

/* Checkpoints (bake/checkpoint.h keeps them in a file; the methods only
 * pack their state into bytes).  After begin, restore may put a saved state
 * of this solve into the method's: 1 when that state was the finished one
 * (no step runs), 0 to step on from it (or from the start when nothing was
 * saved), -1 and *cause when the saved bytes do not fit.  After every step,
 * save gets the state (done: 1 after the last step). */
struct solver_ckpt {
	int (*restore)(void *user, const struct solver_ops *ops, void *state, char **cause);
	void (*save)(void *user, const struct solver_ops *ops, const void *state, int done);
	void *user;
};

/* Where and how a method runs; none of it changes the numbers. */
struct solver_run {
	int threads;			/* OpenMP threads, 0 = all cores */
	int rank, n_ranks;		/* MPI: this process and the number of processes (1 = none) */
	void (*allreduce)(double *v, long n);	/* sum n doubles over ranks in place; NULL = one process */
	void (*progress)(void *user, long done, long total);	/* work units done of total; may be NULL */
	void *progress_user;
	const struct solver_ckpt *ckpt;	/* NULL: no checkpoints */
};

/* One table entry: one (wavelength, incidence angle) pair.  Fractions are
 * of the incident power; errors are standard errors (0 for exact values). */
struct brdf_entry {
	double wl_nm;		/* [nm] */
	double theta_i;		/* [rad] */
	double rsp;		/* specular reflectance of the top and clear layers on top [-] (exact when
				 * smooth; Monte Carlo, error in albedo's, when rough) */
	struct estimate albedo;	/* directional-hemispherical diffuse albedo (scattered light) [-];
				 * Monte Carlo states the error of all returned light here */
	struct estimate rd_unscat;	/* returned without scattering below the clear top [-] */
	struct estimate tt;	/* transmitted through the bottom [-] */
	struct estimate a_total;	/* absorbed in all layers [-] */
	struct estimate a[SLAB_MAX_LAYERS + 2];	/* absorbed per layer, index as in struct slab [-] */
	struct estimate lost;	/* ended by a guard of the method (e.g. step cap) [-] */
	struct estimate facet_loss;	/* shadowed and masked at rough boundaries: what the
				 * single-scattering microfacet model loses (engine/microfacet.h) [-] */
	double *fr, *fr_err;	/* [n_theta * n_phi] diffuse BRDF bin means and errors [1/sr],
				 * row-major [theta_o][delta_phi] */
	double *rd_r, *rd_r_err;	/* [n_r] radial profile Rd(r) [1/cm^2], NULL without radial bins */
	double rms_rel_err;	/* solid-angle-weighted RMS relative error of this entry's fr [-] */
	const char *method;	/* name of the method that filled the entry (static); NULL: none did */
	char *refused;		/* why the method left the entry empty (all values 0), when its
				 * settings let it refuse parts of a problem; NULL otherwise */
	/* Cost and resolution. */
	long batches;		/* Monte Carlo batches (0 for other methods) */
	long photons;		/* Monte Carlo photons (0 for other methods) */
	double events;		/* scattering events, or the method's own unit of work */
	int n_quad;		/* adding-doubling: quadrature nodes per unit cosine (0 for other methods) */
	int n_orders;		/* adding-doubling: Fourier orders kept (0 for other methods) */
};

struct brdf_table {
	int n_wl, n_ti;
	struct tally_grid grid;
	struct brdf_entry *entry;	/* [n_wl * n_ti], entry = wavelength * n_ti + angle */
	double rms_rel_err;	/* over the whole table [-] */
	int target_met;		/* 1 when target_error was 0 or is met */
	long photons;		/* total (Monte Carlo) in the table's values */
	long pilot_photons;	/* Monte Carlo photons traced to size the rounds, not in the values */
	double seconds;		/* wall time of the steps [s] */
};

/* Parts of a table a method can give. */
enum {
	SOLVER_BRDF = 1,	/* fr, fr_err and the totals */
	SOLVER_RADIAL = 2	/* rd_r, rd_r_err */
};

/* What kind of values a method gives (solver_ops.traits). */
enum {
	SOLVER_SAMPLED = 1,	/* errors are standard errors of sampling (batches of photons) */
	SOLVER_POINTS = 2	/* fr at the problem's point nodes when it names them */
};

/* The settings a bake or `simulate` gives, for every method: each method's
 * settings() reads the ones it has (knobs of the others are ignored). */
struct solver_knobs {
	/* Sampling (Monte Carlo). */
	uint64_t seed;
	long batch_photons;	/* 0: sized from the target */
	int min_batches;
	long max_photons;
	int nee;		/* exit bins by next-event estimation */
	double roulette_w, roulette_chance;
	long max_steps;
	/* Quadrature (adding-doubling): 0 = the method's default. */
	double tol;		/* tolerance of the table [-] */
	int n_quad, n_quad_max, n_orders;
	int strict;		/* refuse the problem rather than leave entries for a fallback */
};

/* What a deterministic method's `simulate` tells beside the sim_result
 * (Monte Carlo leaves it zero: method NULL). */
struct sim_solve_info {
	const char *method;	/* its name, as the report writes it */
	double tol;		/* tolerance asked [-] */
	int n_quad;		/* quadrature nodes per unit cosine used */
	int n_orders;		/* Fourier orders kept */
	double rms_rel_err;	/* estimated RMS relative error of the BRDF bins [-] */
};

struct json_object;
/* A progress callback: work units done of total. */
typedef void solver_progress(void *user, long done, long total);

struct solver_ops {
	const char *name;	/* as in --solver NAME and the manifest, e.g. "mc" */
	const char *title;	/* for messages, e.g. "Monte Carlo" */
	unsigned provides;	/* SOLVER_BRDF | SOLVER_RADIAL */
	unsigned traits;	/* SOLVER_SAMPLED | SOLVER_POINTS */
	/* The method that solves the entries this one refuses (bake --solver
	 * auto), by name; NULL: it refuses none. */
	const char *fallback;
	/* What the errors of its entries are, for the manifest's solver.error. */
	const char *error_doc;
	/* New settings (caller frees) from the knobs: what begin takes. */
	void *(*settings)(const struct solver_knobs *k);
	/* The tolerance it works to for p under settings [-]; NULL: none (sampled). */
	double (*tol)(const void *settings, const struct solver_problem *p);
	/* Its block of the manifest's "solver" object, under its name (NULL:
	 * none): the settings it worked with, tol as tol() gave it. */
	struct json_object *(*manifest)(const struct solver_knobs *k, double tol);
	/* `skinbake simulate`: one stack at one angle (c; k for what c does not
	 * hold) into r, and info for a deterministic method; 0, or -1 and *cause
	 * when it refuses.  sim_ignores: simulate's options it does not read
	 * (refused when given with it), NULL-terminated. */
	int (*simulate)(const struct sim_config *c, const struct solver_knobs *k,
	    struct sim_result *r, struct sim_solve_info *info, solver_progress *progress,
	    void *user, char **cause);
	const char *const *sim_ignores;
	/* Check p against the method's settings and set up; NULL and *cause
	 * (caller frees) when the method cannot solve p. */
	void *(*begin)(const struct solver_problem *p, const void *settings, char **cause);
	/* Do one unit of work: 1 while more remain, 0 when the table is done. */
	int (*step)(void *state, const struct solver_run *run);
	/* Fill out (caller frees with brdf_table_free) and free the state. */
	void (*finish)(void *state, struct brdf_table *out);
	/* The state between steps as bytes (a new buffer of *len bytes, caller
	 * frees), and back: unpack replaces a fresh state's progress (after
	 * begin with the same problem and settings) by packed bytes; -1 when
	 * they do not fit.  Restoring and stepping on gives the same table,
	 * byte for byte, as never stopping. */
	void *(*pack)(const void *state, size_t *len);
	int (*unpack)(void *state, const void *buf, size_t len);
};

/* Byte buffers for pack and unpack: put appends (growing p), get reads at
 * pos (bad set when short).  Numbers are stored in the machine's format: a
 * checkpoint is resumed on the machine that wrote it. */
struct solver_buf {
	unsigned char *p;
	size_t len, cap, pos;
	int bad;
};
void solver_buf_put(struct solver_buf *b, const void *v, size_t n);
void solver_buf_get(struct solver_buf *b, void *v, size_t n);
/* One table entry's values (not its labels wl_nm, theta_i); get sets
 * method to `method` when the packed entry had one. */
void solver_entry_put(struct solver_buf *b, const struct brdf_entry *e, const struct tally_grid *g);
void solver_entry_get(struct solver_buf *b, struct brdf_entry *e, const struct tally_grid *g, const char *method);

/* begin, (restore from run->ckpt,) step until done (saving to run->ckpt
 * after each step), finish; out->seconds is the wall time of the steps.
 * -1 and *cause when begin refuses the problem or restore fails. */
int solver_solve(const struct solver_ops *ops, const void *settings, const struct solver_problem *p,
    const struct solver_run *run, struct brdf_table *out, char **cause);

/* The solid-angle-weighted RMS relative error of every entry's fr (an
 * empty bin counts as 100%): the accuracy of a table as target_error
 * means it, the same for every method [-]. */
double brdf_table_rms(const struct brdf_table *t);

/* An empty table for p (entries labelled, arrays zeroed), for a method's finish. */
void brdf_table_init(struct brdf_table *t, const struct solver_problem *p);
void brdf_table_free(struct brdf_table *t);
#endif
