/* Placeholder until the bake area lands; owned by that area. */
#include "config.h"
#include "cli.h"

int cmd_eval(int argc, char **argv)
{
	(void)argc;
	(void)argv;
	return cli_fail("eval", "not built yet");
}
