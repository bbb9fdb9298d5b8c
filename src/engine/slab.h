/* slab: a stack of plane-parallel layers between two ambient half spaces,
 * with the per-layer constants the transport kernel needs precomputed.
 * z grows downward into the tissue, z = 0 at the top surface. */
#ifndef SKINBAKE_SLAB_H
#define SKINBAKE_SLAB_H

#define SLAB_MAX_LAYERS 16

struct layer {
	double d;	/* thickness [cm]; INFINITY allowed for the last layer */
	double n;	/* refractive index [-], >= 1 */
	double mu_a;	/* absorption coefficient [1/cm], >= 0 */
	double mu_s;	/* scattering coefficient [1/cm], >= 0 */
	double g;	/* Henyey-Greenstein anisotropy [-], in (-1, 1) */
	double rough;	/* GGX alpha of the boundary on this layer's top (to the layer above) [-]:
			 * 0 = smooth, (0, 1] = a rough interface (engine/microfacet.h) */
};

struct slab {
	int n_layers;		/* 1..SLAB_MAX_LAYERS */
	double n_above;		/* ambient index above the stack [-] */
	double n_below;		/* ambient index below the stack [-] */
	/* Index 0 is the ambient above, 1..n_layers the tissue, n_layers+1 the
	 * ambient below, so boundaries need no special case (as in MCML). */
	struct layer layer[SLAB_MAX_LAYERS + 2];
	/* Derived by slab_prepare(): */
	double z_top[SLAB_MAX_LAYERS + 2];	/* depth of the layer's top [cm] */
	double z_bot[SLAB_MAX_LAYERS + 2];	/* depth of the layer's bottom [cm] */
	double mu_t[SLAB_MAX_LAYERS + 2];	/* mu_a + mu_s [1/cm] */
	double inv_mu_t[SLAB_MAX_LAYERS + 2];	/* 1 / mu_t [cm], 0 if clear */
	double albedo[SLAB_MAX_LAYERS + 2];	/* mu_s / mu_t [-], 0 if clear */
	double cos_crit_up[SLAB_MAX_LAYERS + 2];	/* critical cosine into the layer above, 0 if none */
	double cos_crit_down[SLAB_MAX_LAYERS + 2];	/* critical cosine into the layer below */
	int first_turbid;	/* first layer with mu_t > 0, or n_layers+1 if none */
	int rough_top;		/* 1 if a boundary above the first turbid layer is rough */
	int rough_any;		/* 1 if any boundary is rough */
	int rough_ms;		/* set by the caller: 1 = rough boundaries scatter light as often as it
				 * meets their facets (microfacet_sample_ms), 0 = once (the rest is lost) */
};

/* Start an empty stack with the given ambient indices. */
void slab_init(struct slab *s, double n_above, double n_below);
/* Append a layer; -1 with *cause if the stack is full. */
int slab_add(struct slab *s, const struct layer *l, char **cause);
/* Validate every field; -1 with *cause (naming the layer, field, value and
 * allowed range; caller frees) on the first bad one. */
int slab_check(const struct slab *s, char **cause);
/* Fill the derived fields.  Call after slab_check() succeeded. */
void slab_prepare(struct slab *s);
/* A layer is clear when it neither absorbs nor scatters (e.g. sebum). */
int slab_layer_clear(const struct slab *s, int i);
#endif
