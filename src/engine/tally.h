/* tally: what the transport kernel scores for one batch of photons.  Plain
 * sums of photon weight; the driver divides by the photon count and forms
 * standard errors from the spread between batches. */
#ifndef SKINBAKE_TALLY_H
#define SKINBAKE_TALLY_H
#include <stdint.h>
#include "engine/slab.h"

/* Absorption variants of the walked slab, scored by white Monte Carlo
 * (absorption reweighting): a variant differs from the slab only by mu_a,
 * and an escaping photon counts for it with its weight times
 * exp(-sum_l dmua_l L_l), L_l its path length in layer l.  This is exact
 * because with implicit capture the weight over a path is the scattering
 * part alone times exp(-mu_a L) per layer (Alerstam, Andersson-Engels &
 * Svensson, J. Biomed. Opt. 13:041304, 2008). */
struct tally_variants {
	int n;			/* variants */
	const double *dmua;	/* [n * (SLAB_MAX_LAYERS + 2)] mu_a of the variant minus the
				 * slab's, per layer [1/cm] */
};

/* Resolution of the exit tallies. */
struct tally_grid {
	int n_theta;	/* exit bands in theta_out over [0, 90] deg, uniform in angle */
	int n_phi;	/* bins in delta_phi over [0, 180] deg, uniform in angle */
	int n_r;	/* radial bins of Rd(r); 0 turns off lateral tracking */
	double dr;	/* radial bin width [cm] */
	const struct tally_variants *var;	/* Rd(r) of absorption variants too; NULL: none */
};

struct tally {
	double rd;		/* weight leaving the top, excluding Rsp */
	double rd_unscat;	/* part of rd that never scattered */
	double tt;		/* weight leaving the bottom */
	double tt_unscat;	/* part of tt that never scattered */
	double lost;		/* weight ended by a guard (step cap, stuck photon) */
	double rsp;		/* reflected by the top without entering the first turbid layer
				 * (rough boundaries on top; smooth ones give struct launch's rsp) */
	double facet_loss;	/* shadowed or masked at rough boundaries (single-scattering microfacets) */
	double a[SLAB_MAX_LAYERS + 2];	/* absorbed per layer (index as in struct slab) */
	double events;		/* scattering events (a count, for throughput) */
	double *exit;		/* [n_theta * n_phi] scattered weight leaving the top */
	double *radial;		/* [n_r] weight leaving the top by exit radius */
	double *radial_var;	/* [var->n * n_r] the same per variant (grid.var), reweighted;
				 * NULL without */
	double *var_total;	/* [var->n] each variant's reweighted scattered weight leaving the
				 * top at any radius (the bins' and beyond); NULL without */
};

/* Allocate zeroed arrays for grid (caller frees with tally_free). */
/* The angular bins from their widths [deg]: n_theta = 90/theta_step and
 * n_phi = 180/phi_step; -1 and *cause (naming the option as the CLI spells
 * it) when a width does not divide its range or the bins exceed 1e6. */
int tally_grid_steps(struct tally_grid *g, double theta_step_deg, double phi_step_deg, char **cause);
void tally_alloc(struct tally *t, const struct tally_grid *g);
void tally_free(struct tally *t);
void tally_zero(struct tally *t, const struct tally_grid *g);
/* dst += src, element by element. */
void tally_add(struct tally *dst, const struct tally *src, const struct tally_grid *g);

/* Geometry of the bins, for turning sums into BRDF and Rd(r) values. */
/* Integral of cos(theta) d(omega) over theta in [t0, t1] [rad] and a
 * delta_phi range of width dphi [rad] on both sides of the incidence plane [sr]. */
double tally_cos_omega(double t0, double t1, double dphi);
/* Plain solid angle of one bin of exit band it (both sides of the
 * incidence plane) [sr]. */
double tally_bin_omega(const struct tally_grid *g, int it);
/* Area of radial bin i, the annulus between i dr and (i + 1) dr [cm^2]. */
double tally_annulus_area(double dr, int i);
/* Mean exit radius of the light in a radial profile rd_r[n_r] [1/cm^2]
 * with bins of width dr [cm]: the first moment of Rd(r) over the bins [cm]
 * (light beyond the last bin is not counted); 0 for an empty profile. */
double tally_mean_radius(const double *rd_r, int n_r, double dr);
/* Its standard error from the bins' errors rd_r_err[n_r] [cm]: first-order
 * propagation through the ratio, bins taken as independent (their
 * covariance through the shared photons is of the order of the squared
 * bin fractions, negligible with many bins); 0 for an empty profile. */
double tally_mean_radius_err(const double *rd_r, const double *rd_r_err, int n_r, double dr);
#endif
