/* ad_solver: adding-doubling (engine/ad.h) as a method of the solver
 * interface (engine/solver.h).  A step solves the next wavelengths, as many
 * as there are threads, one per OpenMP thread (each solve with one thread:
 * wavelengths parallelise better than Fourier orders when the machine is
 * shared); a lone wavelength gets all threads for its orders.  Every MPI
 * rank solves every wavelength (seconds of work), so all ranks hold the
 * same table without a reduction.
 *
 * Each entry gets the solver's values (fr: the BRDF at the problem's
 * point nodes when it names them, ad_brdf_points; else the bin means) with
 * its error estimates in place of standard errors (fr_err, albedo.err, tt.err, a[].err: ad.h says how they
 * are formed), with the meanings the Monte Carlo gives them: albedo is Rd
 * minus the light that returns unscattered (struct brdf_entry), rd_unscat is
 * exact.  No Rd(r): provides SOLVER_BRDF only, rd_r stays 0.
 *
 * The tolerance is settings.ad.tol, or the problem's target_error when that
 * is smaller.  Where the solver cannot meet it (ad_solve refuses: peaked
 * phase functions it cannot resolve within n_quad_max), the wavelength's
 * entries are left empty with the cause in entry.refused, so that a driver
 * can ask another method for them; with `strict` the steps stop there. */
#ifndef SKINBAKE_AD_SOLVER_H
#define SKINBAKE_AD_SOLVER_H
#include "engine/ad.h"
#include "engine/sim.h"
#include "engine/solver.h"

struct ad_solver_settings {
	struct ad_opts ad;	/* tol, n_quad, n_quad_max, ...; the table's bins and the threads
				 * come from the problem and the run */
	int strict;		/* 1: stop after the first wavelength refused */
};

/* ad_opts_default (tolerance 1e-3, automatic quadrature), not strict. */
void ad_solver_settings_default(struct ad_solver_settings *s);

/* The tolerance the method works to for problem p [-]. */
double ad_solver_tol(const struct ad_solver_settings *s, const struct solver_problem *p);

/* The method: settings are a struct ad_solver_settings.  Gives SOLVER_BRDF. */
extern const struct solver_ops ad_solver;
/* One stack at one angle, as sim_run gives it by Monte Carlo (`skinbake
 * simulate --solver ad`): the solve of c's slab at c->theta_in, Fresnel
 * model and exit grid (no Rd(r)) to tolerance tol at n_quad nodes per unit
 * cosine (0: the fewest that meet tol, as ad_opts), with c->threads over the
 * Fourier orders, as a sim_result (errors: the error estimates; no photons)
 * and what else it tells (info).  0, or -1 and *cause where the solver refuses. */
int ad_sim_run(const struct sim_config *c, double tol, int n_quad, struct sim_result *r,
    struct sim_solve_info *info, char **cause);
#endif
