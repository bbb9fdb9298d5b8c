/* bake: the BRDF bake driver.  A job is one (wavelength, incidence angle)
 * pair; each job runs fixed-size batches of photons (photon indices
 * b*batch .. (b+1)*batch-1 of stream = job id), so a bake is a pure function
 * of its settings and seed, whatever the thread or rank count.  Batches run
 * in parallel and are merged in batch order.  With a target error, rounds of
 * batches are added until the solid-angle-weighted RMS
 * relative error of the whole table (all jobs) is below the target, or the
 * photon budget is spent.  No files are written here. */
#ifndef SKINBAKE_BAKE_H
#define SKINBAKE_BAKE_H
#include <stdint.h>
#include "engine/slab.h"
#include "engine/specular.h"
#include "engine/transport.h"

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
	struct transport_opts opts;
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

struct bake_job {
	double wl_nm;
	double theta_i;		/* [rad] */
	long batches;		/* batches run */
	long photons;
	double rsp;		/* specular reflectance of the smooth top (exact) */
	double albedo, albedo_err;	/* directional-hemispherical diffuse albedo [-] (scattered light) */
	double rd_unscat;	/* returned without scattering (in the analytic part) */
	double tt, tt_err;	/* transmitted through the bottom */
	double a_total;		/* absorbed, all layers */
	double lost;
	double rms_rel_err;	/* solid-angle-weighted RMS relative error of this job's table */
	double *fr, *fr_err;	/* [n_to * n_phi] diffuse BRDF bin means [1/sr] */
	double *rd_r, *rd_r_err;	/* [n_r] radial profile [1/cm^2] */
	double events;
};

struct bake_result {
	int n_jobs;		/* n_wl * n_ti, job = wl * n_ti + ti */
	struct bake_job *job;
	double rms_rel_err;	/* over the whole table */
	long photons;		/* total */
	double seconds;
	int target_met;
};

/* Run the bake; never fails on a checked spec.  Caller frees. */
void bake_run(const struct bake_spec *s, struct bake_result *r);
void bake_result_free(struct bake_result *r);
/* Mean exit radius of the diffusely reflected light from a radial profile [cm]. */
double bake_mean_radius(const double *rd_r, int n_r, double dr);
/* The clear stack above the first turbid layer, for the analytic specular. */
void bake_specular_stack(const struct slab *s, enum optics_fresnel model, struct specular_stack *out);
#endif
