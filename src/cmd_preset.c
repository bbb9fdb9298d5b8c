/* Placeholder until the skin area lands; owned by that area. */
#include "config.h"
#include "cli.h"

int cmd_preset(int argc, char **argv)
{
	(void)argc;
	(void)argv;
	return cli_fail("preset", "not built yet");
}
