/* bake_cmd: what `skinbake bake` does after its options (cmd_bake.c):
 * the preset's layer stacks, then one bake into its directory with the
 * summary, or a family (cmd_bake_family.c). */
#include "config.h"

#include "cli/bake_cmd.h"

#include <stdio.h>
#include <stdlib.h>

#include "bake/bake.h"
#include "bake/bakefile.h"
#include "bake/summary.h"
#include "cli/cli.h"
#include "skin/preset.h"

static const char *CMD = "bake";

int bake_cmd_run(struct bake_spec *s, const char *preset, const char *pfile, const char *out, int quiet,
    const struct bake_vary *vary, int argc, char **argv)
{
	char *cause = NULL, *cmdline = cli_command_line(argc, argv);
	const char *label = preset ? preset : pfile;
	struct skin_params *p = bake_spec_preset(s, preset, pfile, &cause);
	int rc = CLI_EXIT_OK;
	if (p == NULL)
		rc = cli_usage_error(CMD, "%s", cause);
	else if (vary->n > 0)
		rc = bake_family_run(s, p, label, out, vary, quiet, cmdline);
	else {
		s->rank = cli_par.rank;
		s->n_ranks = cli_par.size;
		s->allreduce = cli_par.allreduce;
		struct cli_progress pr;
		cli_progress_start(&pr, "bake");
		s->progress = cli_progress_update;
		s->progress_user = &pr;
		struct bake_result r;
		int e = bake_preset_to_dir(s, p, label, out, cmdline, &r, &cause);
		cli_progress_end(&pr);
		if (e != -1 && cli_par.rank == 0)
			bake_summary_notes(stderr, &r);	/* fallbacks are never silent, even with --quiet */
		if (e != 0)
			rc = e == -1 ? cli_usage_error(CMD, "%s", cause) : cli_fail(CMD, "%s", cause);
		else if (!quiet && cli_par.rank == 0)
			bake_summary(stdout, s, &r, label, out);
		bake_result_free(&r);	/* zeroed when the bake failed */
	}
	free(cause);
	free(cmdline);
	preset_free(p);
	return rc;
}
