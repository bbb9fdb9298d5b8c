/* skinbake export pov|blender: dispatch to the exporter. */
#include "config.h"

#include <string.h>

#include "cli/cli.h"

int cmd_export(int argc, char **argv)
{
	if (argc >= 2 && strcmp(argv[1], "pov") == 0)
		return cmd_export_pov(argc - 1, argv + 1);
	if (argc >= 2 && strcmp(argv[1], "blender") == 0)
		return cmd_export_blender(argc - 1, argv + 1);
	if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
		printf("usage: skinbake export pov|blender [options]   (skinbake export pov --help)\n");
		return CLI_EXIT_OK;
	}
	return cli_usage_error("export", "expected 'pov' or 'blender', got '%s'", argc >= 2 ? argv[1] : "");
}
