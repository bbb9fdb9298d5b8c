/* opt_layer: --layer KEY=VALUE,... into a layer of a slab (opt_layer.h). */
#include "config.h"

#include "cli/opt_layer.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>

/* --layer d=CM,n=N,mua=1/CM,mus=1/CM,g=G,rough=ALPHA, top layer first. */
const struct opt_key opt_layer_keys[] = {
	{ "d", OPT_DOUBLE, offsetof(struct layer, d), .lo = 0, .hi = INFINITY, .unit = "cm",
	  .flags = OPT_REQUIRED | OPT_LO_OPEN | OPT_HI_OPEN | OPT_INF,
	  .help = "thickness (the last layer may be inf)" },
	{ "n", OPT_DOUBLE, offsetof(struct layer, n), "1", .lo = 1, .hi = 10,
	  .help = "refractive index" },
	{ "mua", OPT_DOUBLE, offsetof(struct layer, mu_a), .lo = 0, .hi = 1e8, .unit = "1/cm",
	  .flags = OPT_REQUIRED, .help = "absorption coefficient" },
	{ "mus", OPT_DOUBLE, offsetof(struct layer, mu_s), .lo = 0, .hi = 1e8, .unit = "1/cm",
	  .flags = OPT_REQUIRED, .help = "scattering coefficient" },
	{ "g", OPT_DOUBLE, offsetof(struct layer, g), "0", .lo = -1, .hi = 1,
	  .flags = OPT_LO_OPEN | OPT_HI_OPEN, .help = "Henyey-Greenstein anisotropy" },
	{ "rough", OPT_DOUBLE, offsetof(struct layer, rough), "0", .lo = 0, .hi = 1,
	  .help = "GGX alpha of the boundary on the layer's top (0 = smooth; both solvers)" },
	{ .name = NULL },
};

int opt_layer_add(struct opt_ctx *x, const struct opt *o, const char *spec)
{
	struct opt_layers *ls = o->dest;
	char label[32];
	snprintf(label, sizeof label, "--layer %d", ls->n + 1);
	ls->l[ls->n] = (struct layer){ 0 };
	if (opt_keys(x, label, spec, opt_layer_keys, &ls->l[ls->n]) != 0)
		return -1;
	ls->n++;
	return 0;
}
