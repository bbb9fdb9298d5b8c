/* ad_types: the adding-doubling solver's results (struct ad_result: per
 * incidence angle the totals and the diffuse BRDF table, each value with its
 * error estimate), apart from ad.h so that the error estimates (ad_err.h)
 * fill them without depending on the solver that calls them.  Units and
 * conventions as in ad.h. */
#ifndef SKINBAKE_AD_TYPES_H
#define SKINBAKE_AD_TYPES_H
#include "engine/slab.h"

struct ad_value {
	double v;	/* value */
	double err;	/* error estimate (ad.h, top) */
};

/* Results for one incidence angle. */
struct ad_beam {
	double theta_i;			/* [rad] */
	double rsp;			/* specular reflectance of the top and clear layers on
					 * it: exact for smooth ones; a rough top's own
					 * reflection of the beam (glossy, never entered a turbid
					 * layer) to the facet rule's error otherwise */
	struct ad_value rd;		/* diffuse reflectance: leaves the top, excluding rsp */
	double rd_unscat;		/* part of rd that never scattered */
	struct ad_value tt;		/* leaves the bottom, unscattered included */
	double tt_unscat;		/* part of tt that never scattered */
	struct ad_value a[SLAB_MAX_LAYERS + 2];	/* absorbed per layer, index as in struct slab */
	struct ad_value facet_loss;	/* rough boundaries: shadowed and masked by their
					 * single-scattering facets, 1 - rsp - rd - tt - sum a
					 * (0 when all are smooth) */
	double balance;			/* rsp + rd + tt + sum a - 1 (absorption from each
					 * layer's own R, T); with rough boundaries the
					 * loss takes it: 0, no check */
	double *fr, *fr_err;		/* [n_to * n_phi] diffuse BRDF bin means
					 * [1/sr], it * n_phi + ip */
	double *fr_az, *fr_az_err;	/* [n_to] their azimuthal means [1/sr] */
	double rms_rel_err;		/* this angle's table */
};

struct ad_series;

struct ad_result {
	int n_beams;
	struct ad_beam *beam;		/* [n_beams] */
	int n_to, n_phi;
	double rms_rel_err;		/* the whole table's (all angles) */
	int n_quad;			/* nodes per unit cosine used */
	int n_nodes;			/* quadrature nodes per hemisphere */
	int n_orders;			/* Fourier orders kept */
	int series_complete;		/* 1 if the phase function has no higher orders
					 * (no truncation) */
	long doublings;			/* doubling steps, all orders and layers */
	double delta_m_f;		/* largest delta-M forward fraction moved to the
					 * unscattered beam */
	double norm_max;		/* largest correction of the phase function's discrete
					 * normalization */
	double conv_factor;		/* factor on |X_N - X_N/2| in the errors, >= 1 (ad_err.h) */
	double seconds;			/* wall time [s] */
	struct ad_series *series, *series_lo;	/* for ad_brdf */
};
#endif
