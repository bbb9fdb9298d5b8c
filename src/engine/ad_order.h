/* ad_order: one adding-doubling solve at one quadrature: the Fourier orders
 * of the azimuth difference one after another (each an independent
 * problem, Jakob et al., SIGGRAPH 2014; the boundaries are the same for
 * all), until the orders no longer matter or the phase function has none
 * left.  Gives the BRDF's Fourier coefficients at the quadrature's exit
 * directions and, from order 0, every flux. */
#ifndef SKINBAKE_AD_ORDER_H
#define SKINBAKE_AD_ORDER_H
#include "engine/ad_quad.h"
#include "engine/optics.h"
#include "engine/slab.h"

/* The slab as the solver sees it: turbid layers with the boundaries (clear
 * layers and interfaces) between them. */
struct ad_model {
	int K;					/* turbid layers, >= 1 */
	int slab_layer[SLAB_MAX_LAYERS];	/* index in struct slab of turbid layer k */
	double n[SLAB_MAX_LAYERS];		/* refractive index [-] */
	double tau[SLAB_MAX_LAYERS];		/* optical thickness (mu_a + mu_s)
						 * d [-], INFINITY allowed */
	double omega[SLAB_MAX_LAYERS];		/* single-scattering albedo [-] */
	double g[SLAB_MAX_LAYERS];		/* HG anisotropy [-] */
	int bcnt[SLAB_MAX_LAYERS + 1];		/* boundary k's index list length */
	double bn[SLAB_MAX_LAYERS + 1][SLAB_MAX_LAYERS + 2];	/* its indices, medium above
								 * first [-] */
	double n_above;				/* ambient above [-] */
	/* Rough interfaces (ad_rough.h): GGX alpha of boundary k's interface j,
	 * between bn[k][j] and bn[k][j + 1]; 0 = smooth. */
	double balpha[SLAB_MAX_LAYERS + 1][SLAB_MAX_LAYERS + 1];
	int brough[SLAB_MAX_LAYERS + 1];	/* 1 if boundary k has a rough interface */
	int rough_nu;				/* facet rule per axis; 0 =
						 * ad_rough_nu of the quadrature */
	int rough_walks;			/* multiple scattering on the facets: walks per
						 * direction (ad_rough.h); 0 = single scattering */
	enum optics_fresnel fresnel;		/* at every interface */
	int n_iv;				/* quadrature pieces (ad_quad.h) */
	double sigma[AD_MAX_IV + 1];		/* piece edges in s [-] */
	double nstar[AD_MAX_IV];		/* pieces' Gauss variables [-] */
};

struct ad_cache;

struct ad_level_opts {
	double density;		/* nodes per unit cosine per hemisphere */
	int n_min;		/* nodes at least per piece */
	double dtau_frac;	/* starting layer / smallest cosine */
	double dm_terms;	/* Legendre terms kept per node of a medium (delta-M beyond) */
	int max_orders;		/* Fourier orders at most (>= 1) */
	double tol_f;		/* stop when two orders in a row add less than this, relative */
	int threads;		/* OpenMP threads over orders (>= 1) */
	int doubling_only;	/* 1: no layer by eigenvectors (ad_layer.h) */
	struct ad_cache *cache;	/* layer solutions kept across solves (ad_cache.h); NULL: none */
};

/* The result of one solve. */
struct ad_level {
	struct ad_quad q;
	int N;			/* nodes (directions in the densest turbid medium) */
	int E;			/* beams */
	int na;			/* exit nodes: directions that exist in the ambient above */
	int M;			/* Fourier orders computed */
	int complete;		/* 1 if the phase function has no orders beyond M */
	double *F;		/* [M * E * na] BRDF coefficient of
				 * cos(m psi) [1/sr] at (m, e, i) */
	double *t_air;		/* [na] transmittance of the top boundary at the exit nodes (smooth
				 * interfaces: the exit interpolation's divisor, ad_eval.h) */
	double *order_size;	/* [M] largest |F_m| / largest F_0 */
	/* Order-0 fluxes per beam, fractions of the incident power. */
	double *rsp, *rd, *rd_d, *tt, *tt_d;	/* [E] each */
	double *a;		/* [K * E] absorbed in turbid layer k */
	/* Diagnostics. */
	long doublings;		/* doubling steps over all orders and layers */
	double f_max;		/* largest delta-M forward fraction */
	double norm_max;	/* largest |1 - discrete normalization| of h_0 */
	double t_drop;		/* largest transmittance dropped as negligible */
	double rough_lost;	/* largest power a rough interface sends off the quadrature */
};

/* Solve md for beams arriving at s = n_above sin(theta_i) given in se[E].
 * -1 with *cause on failure; free with ad_level_free either way. */
int ad_level_solve(const struct ad_model *md, const double *se, int E,
    const struct ad_level_opts *o, struct ad_level *lv, char **cause);
void ad_level_free(struct ad_level *lv);
#endif
