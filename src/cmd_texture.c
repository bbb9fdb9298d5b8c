/* Placeholder until the geom area lands; owned by that area. */
#include "config.h"
#include "cli.h"

int cmd_texture(int argc, char **argv)
{
	(void)argc;
	(void)argv;
	return cli_fail("texture", "not built yet");
}
