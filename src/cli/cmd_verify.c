/* skinbake verify: a bake's table against an independent Monte Carlo run,
 * cell by cell (bake/verify.h); exit 0 when consistent, 1 when not. */
#include "config.h"

#include <limits.h>
#include <stdlib.h>

#include "bake/verify.h"
#include "cli/cli.h"
#include "cli/opt.h"

int cmd_verify(int argc, char **argv)
{
	struct verify_opts o;
	verify_opts_default(&o);
	const char *dir;
	long seed;
	int json = 0;
	const struct opt opts[] = {
		{ "bake", OPT_PATH_IN, &dir, "DIR", .flags = OPT_REQUIRED | OPT_DIR,
		  .help = "a directory written by skinbake bake (either solver)" },
		{ "cells", OPT_INT, &o.cells, "N", "32", .lo = 1, .hi = 100000,
		  .help = "table cells to recompute, each by a Monte Carlo re-run of its own (independent cells)" },
		{ "photons", OPT_LONG, &o.photons, "N", "5e4", .lo = 1000, .hi = 1e10,
		  .help = "Monte Carlo photons per re-run (about 1.4% error per bin of paper's 18 x 18 table)" },
		{ "seed", OPT_LONG, &seed, "N", "20261", .lo = 0, .hi = (double)LONG_MAX,
		  .help = "random seed of the re-runs (re-run k uses N + k; choose one other than the bake's)" },
		{ "threads", OPT_INT, &o.threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "json", OPT_FLAG, &json, .help = "one JSON object: bake, solver, cells[] (z per cell) and summary" },
		OPT_END
	};
	const struct opt_cmd cmd = { "verify", "--bake DIR [--cells N] [--photons N] [--json]",
		"Recompute a sample of a bake's table cells (spread over wavelengths, incidence\n"
		"angles, theta_o and delta_phi) by Monte Carlo from the layers in its manifest and\n"
		"report the agreement as z-scores, z = (f_bake - f_mc) / sqrt(e_bake^2 + e_mc^2).", opts,
		"Exit status 0 when the table is consistent with the re-run (mean z^2 below the\n"
		"99.9% quantile of chi^2/n and no |z| beyond the 0.1% Bonferroni limit, with each z\n"
		"taken through Student's t at the errors' degrees of freedom), 1 when it is not,\n"
		"2 on bad input.", 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	o.seed = (uint64_t)seed;
	struct cli_progress pr;
	cli_progress_start(&pr, "verify");
	o.progress = cli_progress_update, o.progress_user = &pr;
	struct verify_result r;
	char *cause = NULL;
	int rc = verify_bake(dir, &o, &r, &cause);
	cli_progress_end(&pr);
	if (rc != 0) {
		rc = cli_usage_error(cmd.name, "--bake: %s", cause);
		free(cause);
		return rc;
	}
	if (json) {
		char *t = verify_json(dir, &r);
		printf("%s\n", t);
		free(t);
	} else
		verify_table(stdout, dir, &r);
	rc = r.consistent ? CLI_EXIT_OK : CLI_EXIT_FAIL;
	verify_result_free(&r);
	return rc;
}
