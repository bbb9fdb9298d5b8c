/* skinbake scene: read a scene file (scene/scene.h) and write it as
 * scene.json (scene/scene_json.h, docs/scene-json.md), the renderer-neutral
 * form other renderers' importers read. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include <json-c/json.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "io/json.h"
#include "scene/scene.h"
#include "scene/scene_load.h"
#include "scene/scene_json.h"

int cmd_scene(int argc, char **argv)
{
	const char *path = NULL;
	const char *out = NULL;
	const struct opt opts[] = {
		{ "scene", OPT_PATH_IN, &path, "FILE", .flags = OPT_REQUIRED | OPT_FILE,
		  .help = "scene file (scenes/README.md)" },
		{ "out", OPT_STRING, &out, "FILE", .def_note = "standard output",
		  .help = "write scene.json here (all or nothing)" },
		OPT_END
	};
	const struct opt_cmd cmd = { "scene", "--scene FILE [--out FILE]",
		"Read and check a scene file (camera, lights, skins, objects; model files are read and\n"
		"placed) and write it as JSON: the renderer-neutral scene of docs/scene-json.md.", opts,
		NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	char *cause = NULL;
	struct scene *s = scene_load(path, &cause);
	if (s == NULL) {
		int rc = cli_usage_error(cmd.name, "%s", cause);
		free(cause);
		return rc;
	}
	int rc = CLI_EXIT_OK;
	if (out == NULL) {
		struct json_object *j = scene_json(s);
		char *text = json_text(j, JSON_PRETTY);
		printf("%s\n", text);
		free(text);
		json_object_put(j);
	} else if (scene_json_write(s, out, &cause) != 0) {
		rc = cli_fail(cmd.name, "%s", cause);
		free(cause);
	}
	scene_free(s);
	return rc;
}
