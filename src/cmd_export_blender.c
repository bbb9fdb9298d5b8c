/* Placeholder until the blender area lands; owned by that area. */
#include "config.h"
#include "cli.h"

int cmd_export_blender(int argc, char **argv)
{
	(void)argc;
	(void)argv;
	return cli_fail("export_blender", "not built yet");
}
