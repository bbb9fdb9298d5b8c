/* skinbake export pov: a bake (and micro-geometry maps) plus a scene file,
 * or lights and a camera given on the command line, to POV-Ray 3.7 files
 * (export/pov/povexport.h does the work). */
#include "config.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "cli/opt_scene.h"
#include "export/pov/littable.h"
#include "export/pov/povexport.h"

/* --bake/--textures [SKIN=]DIR, once per skin. */
static int bind(struct opt_ctx *x, const struct opt *o, const char *v)
{
	struct povexport_options *po = ((void)x, o->dest);
	return !strcmp(o->name, "bake") ? (po->bakes[po->n_bakes++] = v, 0) : (po->texs[po->n_texs++] = v, 0);
}

static int set_size(struct opt_ctx *x, const struct opt *o, const char *v)
{
	struct povexport_options *po = o->dest;
	int end = 0;
	int bad = sscanf(v, "%dx%d%n", &po->width, &po->height, &end) != 2 || v[end] != '\0' || po->width < 16
	    || po->width > 8192 || po->height < 16 || po->height > 8192;
	return bad ? (opt_error(x, "--size = '%s' is not WxH with W and H in [16, 8192] pixels", v), -1) : 0;
}

int cmd_export_pov(int argc, char **argv)
{
	struct scene cl = { 0 }; /* lights and camera from the command line */
	struct povexport_options po = { .cmdline = &cl, .plan_out = stdout };
	int lights = 0, filter = 0;
	const struct opt opts[] = {
		{ "scene", OPT_PATH_IN, &po.scene_path, "FILE", .flags = OPT_FILE, .excl = "light|camera|unit-mm",
		  .help = "scene file (scenes/README.md): writes BASE.inc, .pov, .ini" },
		{ "light", OPT_CUSTOM, &cl, "SPEC", .flags = OPT_REPEAT, .max = SCENE_MAX_LIGHTS, .keys = opt_scene_light_keys,
		  .fn = opt_scene_light, .excl = "scene", .help = "without --scene, once per light: KEY=VALUE,..." },
		{ "camera", OPT_CUSTOM, &cl, "SPEC", .keys = opt_scene_camera_keys, .fn = opt_scene_camera, .excl = "scene",
		  .help = "without --scene (then only the include is written): KEY=VALUE,..." },
		{ "bake", OPT_CUSTOM, &po, "[SKIN=]DIR", .flags = OPT_REPEAT, .max = POVEXPORT_MAX_BIND, .fn = bind, .excl = "family",
		  .def_note = "the scene skin's bake = DIR", .help = "`skinbake bake` output for skin SKIN (bare: every skin)" },
		{ "textures", OPT_CUSTOM, &po, "[SKIN=]DIR", .flags = OPT_REPEAT, .max = POVEXPORT_MAX_BIND, .fn = bind,
		  .def_note = "the skin's textures = DIR", .help = "`skinbake texture` output (height.png) per skin" },
		{ "out", OPT_PATH_OUT, &po.out, "DIR", .help = "output directory, created if missing (required but with --plan)" },
		{ "name", OPT_STRING, &po.name, "BASE", .def_note = "the scene file's name; skin without one",
		  .help = "base name of the files" },
		{ "lights", OPT_ENUM, &lights, .choices = "auto|key|mixture|passes|separable", .def_note = "the scene's, else auto",
		  .help = "light strategy (docs/pov.md; auto: key for 1, mixture for 2 when within 0.5 %, else passes)" },
		{ "nodes", OPT_INT, &po.n_theta, "N", "65", .lo = 2, .hi = LITTABLE_MAX_NODES, .help = "lit-table theta nodes," },
		{ "gamma-nodes", OPT_INT, &po.n_gamma, "N", "17", .lo = 1, .hi = 256, .help = "light-view angle nodes," },
		{ "mix-nodes", OPT_INT, &po.n_mix, "N", "25", .lo = 2, .hi = LITTABLE_MAX_NODES, .help = "mixture nodes per axis," },
		{ "size", OPT_CUSTOM, &po, "WxH", .fn = set_size, .def_note = "the scene's; 320x240", .help = "image size [px]" },
		{ "unit-mm", OPT_DOUBLE, &po.unit_mm, "MM", .lo = 1e-3, .hi = 1e6, .unit = "mm", .excl = "scene",
		  .def_note = "10", .help = "without --scene: one scene unit (sets the bump map's size)" },
		{ "data-dir", OPT_PATH_IN, &po.data_dir, "DIR", .flags = OPT_DIR,
		  .def_note = "$SKINBAKE_DATADIR, " PKGDATADIR ", ../exporters/pov", .help = "where skinbake_shapes.inc is" },
		{ "bump-filter", OPT_ENUM, &filter, .choices = "auto|off", .def = "auto",
		  .help = "box-filter the height map to half an image pixel" },
		{ "diffuse-relief", OPT_ENUM, &po.sharp_diffuse, .choices = "blurred|sharp",
		  .def = "blurred",
		  .help = "blurred: the diffuse part sees the height map blurred by the bake's "
		  "Rd(r) (docs/relief.md)" },
		{ "analytic", OPT_FLAG, &po.analytic, .excl = "family", .help = "an analytic skin-like BRDF, no bake (tests)" },
		{ "family", OPT_PATH_IN, &po.family, "DIR", .flags = OPT_DIR, .excl = "bake|analytic", .help = "with --maps: "
		  "a family (bake --vary) blended per texel by the maps, one light (docs/maps.md)" },
		{ "maps", OPT_PATH_IN, &po.maps, "DIR", .flags = OPT_DIR, .help = "with --family: `skinbake maps` output" },
		{ "plan", OPT_FLAG, &po.plan, .help = "print the incidence angles the scene needs from a bake, write nothing" },
		{ "mode", OPT_ENUM, &po.translucent, .choices = "exact|translucent|auto", .def = "auto",
		  .help = "auto: translucent for skin meshes where it applies, else exact "
		  "(docs/translucency.md)" },
		{ "sss-samples", OPT_INT, &po.sss_samples, "N", "64", .lo = 1, .hi = 100000, .help = "translucent: samples" },
		OPT_END
	};
	const struct opt_cmd cmd = { "export pov",
		"--bake [SKIN=]DIR [--textures [SKIN=]DIR] (--scene FILE | --light SPEC ... --camera SPEC) --out DIR",
		"Write POV-Ray 3.7 SDL that evaluates a baked skin BRDF as 'lit tables' (pigment = pi*f_r over slope/aoi\n"
		"blend maps, finish diffuse 1): shadows, area lights and bumps stay right.  See docs/pov.md.", opts,
		"Renders are linear (assumed_gamma 1): pixel = pi * radiance.", 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	po.have_camera = opt_given(&x, "camera");
	po.bump_filter = filter == 0;
	po.lights = opt_given(&x, "lights") ? opt_text(&x, "lights") : NULL;
	if (!po.family != !po.maps)
		return opt_error(&x, "--family and --maps go together");
	struct povexport_result r = { 0 };
	char *cause = NULL;
	int e = povexport_run(&po, &r, &cause), ok = e == 0;
	for (int i = 0; i < r.n_msgs; i++)
		fprintf(stderr, "skinbake %s: %s\n", cmd.name, r.msgs[i]);
	for (int i = 0; i < r.n_files; i++)
		printf("%s\n", r.files[i]);
	if (!ok)
		(e == -1 ? cli_usage_error : cli_fail)(cmd.name, "%s", cause);
	povexport_result_free(&r);
	free(cause);
	return ok ? CLI_EXIT_OK : e == -1 ? CLI_EXIT_USAGE : CLI_EXIT_FAIL;
}
