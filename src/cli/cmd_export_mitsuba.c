/* skinbake export mitsuba: a scene file to a directory for Mitsuba 3
 * (export/mitsuba/mtsexport.h), rendered by exporters/mitsuba
 * (python -m skinbake_mitsuba render DIR). */
#include "config.h"

#include <stdlib.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "export/mitsuba/mtsexport.h"
#include "scene/scene_load.h"

static const char *CMD = "export mitsuba";

int cmd_export_mitsuba(int argc, char **argv)
{
	const char *scene_path = NULL;
	struct mts_options o = { 0 };
	int mode = 0;
	const struct opt opts[] = {
		{ "scene", OPT_PATH_IN, &scene_path, "FILE", .flags = OPT_REQUIRED | OPT_FILE,
		  .help = "scene file (scenes/README.md): meshes, lights, camera, skins" },
		{ "bake", OPT_PATH_IN, &o.bake, "DIR", .flags = OPT_DIR, .def_note = "each skin's own bake",
		  .help = "bake directory for skins that name none" },
		{ "mode", OPT_ENUM, &mode, .def = "both",
		  .choices = "both|table|volumetric|translucent",
		  .help = "the skin as the baked table, as the preset's layers in participating "
		  "media under the mesh surface (closed meshes only), both, or translucent (a "
		  "medium fitted to the bake's Rd(r) inside the mesh, closed meshes only)" },
		{ "out", OPT_PATH_OUT, &o.out, "DIR", .flags = OPT_REQUIRED, .help = "output directory (replaced as a whole)" },
		OPT_END
	};
	const struct opt_cmd cmd = { CMD, "--scene FILE --out DIR [options]",
		"Write a scene for Mitsuba 3: scene.json (lights, camera, skins), each mesh as PLY in\n"
		"Mitsuba's frame and manifest.json. Render it with\n"
		"  python -m skinbake_mitsuba render DIR --mode table|volumetric --out IMAGE.exr\n"
		"(exporters/mitsuba, the project venv; translucent: first python -m skinbake_mitsuba fit,\n"
		"docs/mitsuba.md). A scene feature Mitsuba cannot show, or a skin mesh with no interior\n"
		"for the volumetric layers or the translucent medium, is refused (exit 2).", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	o.mode = mode == 1 ? MTS_TABLE : mode == 2 ? MTS_VOLUMETRIC :
		 mode == 3 ? MTS_TRANSLUCENT : MTS_BOTH;
	char *cause = NULL;
	struct scene *s = scene_load(scene_path, &cause);
	int rc = CLI_EXIT_OK;
	if (s == NULL || mts_check(s, &o, &cause) != 0)
		rc = cli_usage_error(CMD, "%s", cause);
	else if (mts_export(s, &o, &cause) != 0)
		rc = cli_fail(CMD, "%s", cause);
	free(cause);
	scene_free(s);
	return rc;
}
