/* skinbake export: the exporter table; each exporter is one command file
 * (cmd_export_NAME.c) and one line here. */
#include "config.h"

#include "cli/cli.h"
#include "cli/opt.h"

static const struct opt_sub exporters[] = {
	{ "pov", "POV-Ray 3.7 include files and scenes that evaluate the baked table", cmd_export_pov },
	{ "blender", "an image set for Blender's importer (exporters/blender/import_skin.py)", cmd_export_blender },
	{ "mitsuba", "a scene directory for Mitsuba 3 (exporters/mitsuba): the table or volumetric skin", cmd_export_mitsuba },
	{ NULL, NULL, NULL },
};

int cmd_export(int argc, char **argv)
{
	return opt_dispatch("export", exporters, argc, argv);
}
