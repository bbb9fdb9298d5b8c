/* opt_layer: --layer KEY=VALUE,... on the command line, one layer of a
 * slab each, top layer first (skinbake simulate): the keys (thickness,
 * index, absorption, scattering, anisotropy, the roughness of the layer's
 * top) and their parser. */
#ifndef SKINBAKE_OPT_LAYER_H
#define SKINBAKE_OPT_LAYER_H
#include "cli/opt.h"
#include "engine/slab.h"

/* The layers given so far, in order. */
struct opt_layers {
	int n;
	struct layer l[SLAB_MAX_LAYERS];
};

/* The keys of one --layer (ends with { NULL }), for the option's .keys. */
extern const struct opt_key opt_layer_keys[];

/* OPT_CUSTOM callback: parse SPEC into the next layer of o->dest (a
 * struct opt_layers); -1 after reporting. */
int opt_layer_add(struct opt_ctx *x, const struct opt *o, const char *spec);
#endif
