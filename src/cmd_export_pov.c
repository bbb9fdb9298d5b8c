/* Placeholder until the pov area lands; owned by that area. */
#include "config.h"
#include "cli.h"

int cmd_export_pov(int argc, char **argv)
{
	(void)argc;
	(void)argv;
	return cli_fail("export_pov", "not built yet");
}
