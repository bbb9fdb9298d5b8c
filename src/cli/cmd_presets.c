/* skinbake presets: list the built-in skin presets, one per line. */
#include "config.h"

#include <stdio.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "skin/preset.h"

int cmd_presets(int argc, char **argv)
{
	const struct opt opts[] = { OPT_END };
	const struct opt_cmd cmd = { "presets", "", "List the built-in skin presets: name and summary, one per "
		"line.  `skinbake preset show NAME` prints one's layers per wavelength.", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	for (int i = 0; i < preset_count(); i++)
		printf("%-16s %s\n", preset_name(i), preset_summary(i));
	return CLI_EXIT_OK;
}
