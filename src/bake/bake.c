/* bake: the driver from a bake spec to a solver's table plus the specular
 * stacks and subsurface radii the bake directory records (see bake.h). */
#include "config.h"
#include "bake/bake.h"

#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/util.h"
#include "engine/mc.h"
#include "skin/colour.h"

/* The method for a spec.  Monte Carlo is the only one today; a later
 * `--solver ad|mc|auto` chooses here (and asks Monte Carlo for the parts,
 * e.g. Rd(r), that the chosen method does not provide). */
static const struct solver_ops *bake_solver(const struct bake_spec *s, const void **settings,
    struct mc_settings *mc)
{
	mc_settings_default(mc);
	mc->seed = s->seed;
	mc->batch_photons = s->batch_photons;
	mc->min_batches = s->min_batches;
	mc->max_photons = s->max_photons;
	mc->nee = s->nee;
	mc->roulette_w = s->opts.roulette_w;
	mc->roulette_chance = s->opts.roulette_chance;
	mc->max_steps = s->opts.max_steps;
	*settings = mc;
	return &mc_solver;
}

int bake_run(const struct bake_spec *s, struct bake_result *r, char **cause)
{
	CHECK(s->n_wl >= 1 && s->n_wl <= BAKE_MAX_WL && s->n_ti >= 1 && s->n_ti <= BAKE_MAX_TI);
	memset(r, 0, sizeof *r);
	struct solver_problem p = {
		.n_wl = s->n_wl, .wl_nm = s->wl_nm, .slab = s->slab, .n_ti = s->n_ti, .theta_i = s->theta_i,
		.grid = { .n_theta = s->n_to, .n_phi = s->n_phi, .n_r = s->n_r, .dr = s->dr },
		.fresnel = s->opts.fresnel, .target_error = s->target_error,
	};
	struct solver_run run = {
		.threads = s->threads, .rank = s->rank, .n_ranks = s->n_ranks > 0 ? s->n_ranks : 1,
		.allreduce = s->allreduce, .progress = s->progress, .progress_user = s->progress_user,
	};
	struct mc_settings mc;
	const void *settings;
	const struct solver_ops *ops = bake_solver(s, &settings, &mc);
	if (solver_solve(ops, settings, &p, &run, &r->table, cause) != 0)
		return -1;
	r->solver = ops->name;
	r->stack = xcalloc((size_t)s->n_wl, sizeof *r->stack);
	r->mean_radius_cm = xcalloc((size_t)s->n_wl, sizeof *r->mean_radius_cm);
	for (int w = 0; w < s->n_wl; w++) {
		specular_stack_of_slab(&s->slab[w], s->opts.fresnel, &r->stack[w]);
		const struct brdf_entry *e = &r->table.entry[w * s->n_ti];
		r->mean_radius_cm[w] = tally_mean_radius(e->rd_r, s->n_r, s->dr);
	}
	return 0;
}

void bake_result_free(struct bake_result *r)
{
	brdf_table_free(&r->table);
	free(r->stack);
	free(r->mean_radius_cm);
	memset(r, 0, sizeof *r);
}

int bake_spec_layers(struct bake_spec *s, const struct skin_params *p, const char *label, char **cause)
{
	for (int w = 0; w < s->n_wl; w++) {
		char *why = NULL;
		if (tissue_slab(p, s->wl_nm[w], &s->slab[w], &why) != 0) {
			*cause = xasprintf("%s at %.0f nm: %s", label, s->wl_nm[w], why);
			free(why);
			return -1;
		}
	}
	return 0;
}

const char *bake_rgb_weights(const struct bake_spec *s, double *rgb_from_wl)
{
	colour_rgb_weights(s->n_wl, s->wl_nm, rgb_from_wl);
	int three = s->n_wl == 3 && s->wl_nm[0] == 470 && s->wl_nm[1] == 550 && s->wl_nm[2] == 656;
	return three ? "the paper's three wavelengths map directly: 656 nm -> R, 550 nm -> G, 470 nm -> B"
		     : "CIE 1931 2-degree colour matching under D65, reflectance normalised to the perfect white";
}
