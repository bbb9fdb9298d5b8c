/* Placeholder until the skin area lands; owned by that area. */
#include "config.h"
#include "cli.h"

int cmd_presets(int argc, char **argv)
{
	(void)argc;
	(void)argv;
	return cli_fail("presets", "not built yet");
}
