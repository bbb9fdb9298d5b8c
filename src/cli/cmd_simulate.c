/* skinbake simulate: one Monte Carlo run (or an adding-doubling solve) on a layer
 * stack given on the command line; a readable table or one JSON object on stdout. */
#include "config.h"

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "cli/opt_layer.h"
#include "engine/sim_report.h"
#include "engine/solvers.h"
#include "base/util.h"

int cmd_simulate(int argc, char **argv)
{
	struct sim_config c;
	sim_config_default(&c);
	struct opt_layers ls = { 0 };
	double na, nbw, th, tos, phs;
	uint64_t seed;
	int json = 0, fresnel, solver;
	struct solver_knobs k = { 0 };
	char *cause = NULL;
	const struct opt opts[] = {
		{ "layer", OPT_CUSTOM, &ls, "SPEC", .fn = opt_layer_add, .keys = opt_layer_keys,
		  .max = SLAB_MAX_LAYERS, .flags = OPT_REQUIRED | OPT_REPEAT,
		  .help = "one layer, top layer first: KEY=VALUE,... with these keys" },
		{ "n-above", OPT_DOUBLE, &na, "N", "1", .lo = 1, .hi = 10,
		  .help = "index of the medium above" },
		{ "n-below", OPT_DOUBLE, &nbw, "N", "1", .lo = 1, .hi = 10,
		  .help = "index of the medium below" },
		{ "theta-in", OPT_DOUBLE, &th, "DEG", "0", .lo = 0, .hi = 90, .flags = OPT_HI_OPEN,
		  .unit = "deg", .help = "incidence angle" },
		{ "solver", OPT_ENUM, &solver, .def = solvers[0]->name,
		  .choices = solvers_choices(),
		  .help = "Monte Carlo (mc) or adding-doubling (ad: no Rd(r); errors are its error "
		  "estimates)" },
		{ "ad-tol", OPT_DOUBLE, &k.tol, "E", "1e-4", .lo = 1e-6, .hi = 0.1,
		  .help = "ad: estimated RMS relative error of the BRDF bins to reach "
		  "(and of Rd, Tt)" },
		{ "ad-quad", OPT_INT, &k.n_quad, "N", "0", .lo = 0, .hi = 1024,
		  .help = "ad: quadrature nodes per unit cosine, 4 or more (0 = the fewest from 16 "
		  "up, doubling, that meet --ad-tol)" },
		{ "photons", OPT_LONG, &c.photons, "N", "1e6", .lo = 1, .hi = 1e12,
		  .help = "mc: photons" },
		{ "seed", OPT_U64, &seed, "N", "1", .help = "mc: random seed (exact)" },
		{ "threads", OPT_INT, &c.threads, "N", "0", .lo = 0, .hi = 1024,
		  .help = "OpenMP threads (0 = all cores)" },
		{ "batches", OPT_INT, &c.batches, "N", "32", .lo = 2, .hi = 100000,
		  .help = "mc: independent batches for standard errors" },
		{ "fresnel", OPT_ENUM, &fresnel, .def = "exact", .choices = "exact|schlick",
		  .help = "reflectance model at every boundary" },
		{ "theta-out-step", OPT_DOUBLE, &tos, "DEG", "5", .lo = 0.01, .hi = 90,
		  .unit = "deg", .help = "width of theta_out bands (must divide 90)" },
		{ "phi-step", OPT_DOUBLE, &phs, "DEG", "5", .lo = 0.01, .hi = 180, .unit = "deg",
		  .help = "width of delta_phi bins (must divide 180)" },
		{ "r-step", OPT_DOUBLE, &c.grid.dr, "CM", "0.005", .lo = 1e-7, .hi = 100,
		  .unit = "cm", .help = "mc: radial bin width of Rd(r)" },
		{ "r-bins", OPT_INT, &c.grid.n_r, "N", "100", .lo = 0, .hi = 100000,
		  .help = "mc: radial bins of Rd(r) (0 = off)" },
		{ "roulette-w", OPT_DOUBLE, &c.opts.roulette_w, "W", "0.2", .lo = 0, .hi = 1,
		  .help = "mc: weight threshold for roulette" },
		{ "roulette-chance", OPT_DOUBLE, &c.opts.roulette_chance, "P", "0.3", .lo = 0,
		  .hi = 1, .flags = OPT_LO_OPEN, .help = "mc: roulette survival probability" },
		{ "max-steps", OPT_LONG, &c.opts.max_steps, "N", "1e6", .lo = 1, .hi = 1e12,
		  .help = "mc: interactions per photon before the guard ends it "
		  "(booked as 'lost')" },
		{ "json", OPT_FLAG, &json, .help = "one JSON object on stdout instead of a table" },
		OPT_END
	};
	const struct opt_cmd cmd = {
		.name = "simulate",
		.usage = "--layer SPEC [--layer SPEC ...] [options]",
		.about = "Light transport in a stack of plane-parallel layers, top layer first, by "
		    "Monte Carlo\n(MCML with oblique incidence) or adding-doubling.  mua = mus = 0 "
		    "makes a clear layer\n(e.g. sebum).  Options marked mc: or ad: apply to that "
		    "solver only.",
		.opts = opts,
		.notes = "Rd excludes the specular reflection Rsp (MCML convention); Tt includes\n"
		"unscattered light.  BRDF values are in 1/sr: the fraction of incident power\n"
		"leaving through a band divided by the band's integral of cos(theta) d(omega).\n"
		"delta_phi = 0 points back toward the source, 180 to the mirror side.",
	};
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	/* The ranges keep each count in [1, 18000]. */
	if (tally_grid_steps(&c.grid, tos, phs, &cause) != 0) {
		int rc = opt_error(&x, "%s", cause);
		free(cause);
		return rc;
	}
	c.seed = seed;
	c.opts.fresnel = fresnel == 0 ? OPTICS_FRESNEL_EXACT : OPTICS_FRESNEL_SCHLICK;
	slab_init(&c.slab, na, nbw);
	for (int i = 0; i < ls.n; i++)
		slab_add(&c.slab, &ls.l[i], &cause);
	if (slab_check(&c.slab, &cause) != 0) {
		int rc = opt_error(&x, "--%s", cause);
		free(cause);
		return rc;
	}
	if (k.n_quad > 0 && k.n_quad < 4)
		return opt_error(&x,
		    "--ad-quad = %d: 0 (automatic) or 4..1024 nodes per unit cosine", k.n_quad);
	slab_prepare(&c.slab);
	c.theta_in = th * M_PI / 180.0;
	const struct solver_ops *ops = solvers[solver];
	for (const char *const *o = ops->sim_ignores; o && *o; o++)
		if (opt_given(&x, *o) && (strcmp(*o, "r-bins") != 0 || c.grid.n_r > 0))
			return opt_error(&x, "--%s applies to --solver %s only", *o,
			    solvers_reading(*o));
	struct sim_result r;
	struct sim_solve_info info = { 0 };
	struct cli_progress pr;
	cli_progress_start(&pr, "simulate");
	if (ops->simulate(&c, &k, &r, &info, cli_progress_update, &pr, &cause) != 0) {
		int rc = opt_error(&x, "--solver %s: %s (--solver %s samples it)", ops->name, cause,
		    ops->fallback ? ops->fallback : solvers[0]->name);
		free(cause);
		return rc;
	}
	cli_progress_end(&pr);
	const struct sim_solve_info *told = info.method ? &info : NULL;
	char *text = json ? sim_report_json(&c, &r, told) : NULL;
	if (json)
		printf("%s\n", text);
	else
		sim_report_table(stdout, &c, &r, told);
	free(text);
	sim_result_free(&r);
	return CLI_EXIT_OK;
}
