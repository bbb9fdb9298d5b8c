/* skinbake presets: list the built-in skin presets, one per line. */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "skin/preset.h"

int cmd_presets(int argc, char **argv)
{
	if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
		printf("usage: skinbake presets\n\n"
		    "Lists the built-in skin presets: name and summary, one per line.\n"
		    "`skinbake preset show NAME` prints one's layers per wavelength.\n");
		return CLI_EXIT_OK;
	}
	if (argc > 1)
		return cli_usage_error("presets", "unexpected argument '%s' (takes none)", argv[1]);
	for (int i = 0; i < preset_count(); i++)
		printf("%-16s %s\n", preset_name(i), preset_summary(i));
	return CLI_EXIT_OK;
}
