/* family_nodes: the nodes of de axes of a family (family.h), placed by
 * equal CIEDE2000 steps of the albedo along a pilot of small bakes. */
#include "config.h"
#include "family/family.h"

#include <math.h>
#include <stdlib.h>

#include "base/util.h"
#include "engine/ad_cache.h"
#include "skin/colour.h"
#include "skin/preset.h"

/* The middle of an axis' range in its coordinate. */
static double axis_middle(const struct family_axis *a)
{
	return a->lo > 0 && a->spacing != FAMILY_SPACING_LIN ? sqrt(a->lo * a->hi) : 0.5 * (a->lo + a->hi);
}

/* Diffuse albedo at theta_i[0] in linear sRGB of parameters x: a bake of
 * one angle and one exit bin on this process alone. */
static int pilot_colour(const struct family_plan *pl, const double *x, struct bake_spec *ps, double rgb[3], char **cause)
{
	struct skin_params *p = family_params(pl->base, pl->axis, pl->n_axes, x, cause);
	if (p == NULL)
		return -1;
	int rc = bake_spec_layers(ps, p, "pilot", cause);
	preset_free(p);
	if (rc != 0)
		return -1;
	struct bake_result r;
	if (bake_run(ps, &r, cause) != 0)
		return -1;
	double w[3 * BAKE_MAX_WL];
	bake_rgb_weights(ps, w);
	for (int c = 0; c < 3; c++) {
		rgb[c] = 0.0;
		for (int k = 0; k < ps->n_wl; k++)
			rgb[c] += w[c * ps->n_wl + k] * r.table.entry[k * ps->n_ti].albedo.v;
	}
	bake_result_free(&r);
	return 0;
}

/* Nodes of de axis a: 90 % equal CIEDE2000 steps along the pilot's colour
 * curve, 10 % uniform in the coordinate (so that no stretch of the range
 * is left without nodes where the colour happens to stand still). */
static int place_axis(struct family_plan *pl, int a, struct bake_spec *ps, char **cause)
{
	struct family_axis *ax = &pl->axis[a];
	int lg = ax->lo > 0, P = FAMILY_PILOT;
	double x[FAMILY_MAX_AXES], lab[FAMILY_PILOT][3], c[FAMILY_PILOT];
	for (int b = 0; b < pl->n_axes; b++)
		x[b] = axis_middle(&pl->axis[b]);
	for (int k = 0; k < P; k++) {
		double t = (double)k / (P - 1);
		c[k] = lg ? log(ax->lo) + t * (log(ax->hi) - log(ax->lo)) : ax->lo + t * (ax->hi - ax->lo);
		x[a] = k == 0 ? ax->lo : k == P - 1 ? ax->hi : lg ? exp(c[k]) : c[k];
		ax->pilot_value[k] = x[a];
		double rgb[3];
		if (pilot_colour(pl, x, ps, rgb, cause) != 0)
			return -1;
		colour_linear_srgb_to_lab(rgb, lab[k]);
		ax->pilot_de[k] = k ? ax->pilot_de[k - 1] + colour_de2000(lab[k - 1], lab[k]) : 0.0;
	}
	ax->n_pilot = P;
	double total = ax->pilot_de[P - 1];
	ax->de_fallback = !(total >= 0.5);
	for (int j = 1; j < ax->n - 1; j++) {
		double u = (double)j / (ax->n - 1), cu = c[0] + u * (c[P - 1] - c[0]), cd = cu;
		if (!ax->de_fallback) {
			double s = u * total;
			int k = 0;
			while (k < P - 2 && ax->pilot_de[k + 1] < s)
				k++;
			double ds = ax->pilot_de[k + 1] - ax->pilot_de[k];
			cd = c[k] + (ds > 0 ? (s - ax->pilot_de[k]) / ds : 0.0) * (c[k + 1] - c[k]);
			cd = 0.9 * cd + 0.1 * cu;
		}
		ax->node[j] = lg ? exp(cd) : cd;
	}
	ax->node[0] = ax->lo;
	ax->node[ax->n - 1] = ax->hi;
	ax->log_coord = lg;
	return 0;
}

int family_place_nodes(struct family_plan *pl, char **cause)
{
	struct bake_spec *ps = xmalloc(sizeof *ps);
	*ps = pl->spec;
	ps->n_ti = 1;
	ps->n_to = ps->n_phi = 1;
	ps->n_r = 0;	/* colours only: no Rd(r) run */
	ps->rank = 0;
	ps->n_ranks = 1;
	ps->allreduce = NULL;
	ps->progress = NULL;
	/* The pilot wants colours to about 1 %; Monte Carlo gets there with small batches. */
	if (ps->batch_photons > 1000)
		ps->batch_photons = 1000;
	if (ps->target_error < 0.01)
		ps->target_error = 0.01;
	/* Adding-doubling at 8 nodes per unit cosine: albedos to about 1e-4.
	 * The albedo is order 0's alone: the higher orders (all the BRDF's
	 * azimuthal detail, 3-10x the work) are not solved; the albedos are
	 * bit for bit those of a solve of every order. */
	if (!(bake_method_ops(ps->method)->traits & SOLVER_SAMPLED) && ps->ad_quad == 0) {
		ps->ad_quad = 8;
		ps->ad_tol = 0.01;
	}
	ps->ad_orders = 1;
	/* The pilot's unchanged layers, solved once (engine/ad_cache.h). */
	void *cblock = xmalloc(FAMILY_AD_CACHE_BYTES / 8);
	struct ad_cache cache;
	ad_cache_init(&cache, cblock, FAMILY_AD_CACHE_BYTES / 8);
	ps->ad_cache = &cache;
	int rc = 0;
	for (int a = 0; a < pl->n_axes && rc == 0; a++)
		if (pl->axis[a].spacing == FAMILY_SPACING_DE)
			rc = place_axis(pl, a, ps, cause);
	free(ps);
	free(cblock);
	return rc;
}
