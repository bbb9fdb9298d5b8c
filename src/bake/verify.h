/* verify: a bake's table checked by an independent Monte Carlo run.  A
 * sample of cells, spread over wavelengths, incidence angles, theta_o and
 * delta_phi, is recomputed from the layer stacks the manifest records (the
 * engine's Monte Carlo with next-event estimation, 32 batches, one re-run
 * with a seed of its own per cell by default: the bins of one run share its
 * photons, so their errors are correlated and would widen the spread of z
 * beyond the limits below, as measured before issue 26) and compared bin
 * by bin (a table of point values, bakefile.h, by its interpolated
 * function's mean over the bin and the mean of its error):
 *
 *   z = (f_bake - f_mc) / sqrt(e_bake^2 + e_mc^2),
 *
 * with e the bake's error (standard error, or adding-doubling's error
 * estimate) and the Monte Carlo standard error.  Batch-means errors are
 * themselves estimates, so z follows Student's t with the Welch-Satterthwaite
 * degrees of freedom of the two (adding-doubling's counting as exact); for
 * the verdict each z is mapped to the standard normal quantile of the same
 * tail probability (z_n).  The table is consistent when both
 *   - the mean of z_n^2 is below the 99.9% quantile of chi^2_n / n, and
 *   - the largest |z_n| is below the two-sided quantile that n independent
 *     cells exceed with probability 0.1% (Bonferroni),
 * so that a correct table fails at most about 0.2% of the time with
 * independent cells (less where the bake's error is adding-doubling's
 * bound; more with cells_per_pair > 1, whose z move together), while a
 * table off by k times the re-runs' relative error fails when k^2 is well
 * above the mean limit (a 1% scale needs re-runs of about 0.3% error).
 * Cells are chosen without randomness: re-runs cycle through the
 * wavelengths with the angles stepped evenly, and bins within a run are
 * visited by a golden-ratio stride. */
#ifndef SKINBAKE_VERIFY_H
#define SKINBAKE_VERIFY_H
#include <stdint.h>
#include <stdio.h>

struct verify_opts {
	int cells;		/* cells to compare, >= 1 (at most the table's) */
	int cells_per_pair;	/* cells per re-run, >= 1 (default 1: independent cells) */
	long photons;		/* Monte Carlo photons per re-run, >= 64 */
	uint64_t seed;		/* base seed; pair k runs with seed + k (pick one other than the bake's) */
	int threads;		/* OpenMP threads, 0 = all cores */
	void (*progress)(void *user, long done, long total);	/* pairs done; may be NULL */
	void *progress_user;
};

struct verify_cell {
	double wl_nm, theta_i_deg;	/* the entry */
	double theta_o_deg, dphi_deg;	/* the bin's centre */
	double f_bake, e_bake;		/* the table's value and error [1/sr] */
	double f_mc, e_mc;		/* the re-run's mean and standard error [1/sr] */
	double z;			/* (f_bake - f_mc) / sqrt(e_bake^2 + e_mc^2) */
	double dof;			/* degrees of freedom of that combined error (INFINITY: exact) */
	double z_n;			/* z as a standard normal quantile (same tail probability) */
};

struct verify_result {
	char solver[16];		/* the bake's solver (manifest) */
	int n_cells;
	struct verify_cell *cell;	/* [n_cells] */
	int n_pairs;			/* Monte Carlo re-runs (of a (wavelength, angle) pair each) */
	long photons;			/* Monte Carlo photons in all */
	double seconds;			/* wall time of the re-runs [s] */
	double mean_z2, max_abs_z;	/* of z */
	double frac_3sigma;		/* fraction of cells with |z| > 3 */
	double mean_zn2, max_abs_zn;	/* of z_n, for the verdict */
	double mean_z2_limit;		/* 99.9% quantile of chi^2_n / n */
	double max_z_limit;		/* |z_n| that n cells exceed with probability 0.001 */
	int consistent;			/* 1: both below their limits */
};

void verify_opts_default(struct verify_opts *o);
/* Check bake DIR; 0, or -1 and *cause (caller frees) when it cannot be read. */
int verify_bake(const char *dir, const struct verify_opts *o, struct verify_result *r, char **cause);
void verify_result_free(struct verify_result *r);

/* The result as one JSON object (one line, caller frees): bake, solver,
 * cells[] and summary{}. */
char *verify_json(const char *dir, const struct verify_result *r);
/* The result as a readable table on fp. */
void verify_table(FILE *fp, const char *dir, const struct verify_result *r);
#endif
