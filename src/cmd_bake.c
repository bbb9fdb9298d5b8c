/* Placeholder until the bake area lands; owned by that area. */
#include "config.h"
#include "cli.h"

int cmd_bake(int argc, char **argv)
{
	(void)argc;
	(void)argv;
	return cli_fail("bake", "not built yet");
}
