/* skinbake export pov: a bake (and micro-geometry maps) plus a scene file,
 * or lights and a camera given on the command line, to a POV-Ray 3.7
 * include file of lit-table textures and, with a scene, a complete .pov. */
#include "config.h"

#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "export/pov/littable.h"
#include "export/pov/povexport.h"
#include "export/pov/scene.h"
#include "export/pov/scenespec.h"

static const char *CMD = "export pov";

static void help(FILE *fp)
{
	fprintf(fp,
	    "usage: skinbake export pov --bake [SKIN=]DIR [--textures [SKIN=]DIR]\n"
	    "                           (--scene FILE | --light SPEC [--light SPEC ...] --camera SPEC)\n"
	    "                           --out DIR [options]\n"
	    "\n"
	    "Write POV-Ray 3.7 SDL that evaluates a baked skin BRDF as 'lit tables'\n"
	    "(pigment = pi*f_r over slope/aoi blend maps, finish diffuse 1 brilliance 1):\n"
	    "shadows, area lights and bump maps stay right.  See docs/pov.md.\n"
	    "\n"
	    "  --scene FILE           scene file (format: scenes/README.md); writes BASE.inc,\n"
	    "                         BASE.pov and BASE.ini (+ BASE_combine.* for passes)\n"
	    "  --light SPEC           without --scene (repeat, 1 to %d): comma-separated\n"
	    "                         type=parallel|point (default parallel), position=X:Y:Z\n"
	    "                         (required), point_at=X:Y:Z (default 0:0:0),\n"
	    "                         color=R:G:B (default 1:1:1, each in [0, 1e6]), name=NAME\n"
	    "  --camera SPEC          without --scene: type=orthographic|perspective,\n"
	    "                         location=X:Y:Z, look_at=X:Y:Z (default 0:0:0),\n"
	    "                         angle=DEG (perspective, [1, 170], default 40),\n"
	    "                         width=UNITS (orthographic, default 2.4); only the include\n"
	    "                         file is written\n"
	    "  --bake [SKIN=]DIR      bake directory from `skinbake bake` (repeat per skin; a bare\n"
	    "                         DIR serves every skin without one; default: the scene\n"
	    "                         skin's bake = DIR)\n"
	    "  --textures [SKIN=]DIR  micro-geometry directory from `skinbake texture`\n"
	    "                         (height.png, 16-bit); default: the skin's textures = DIR;\n"
	    "                         none: no bump map\n"
	    "  --out DIR              output directory, created if missing (required)\n"
	    "  --name BASE            base name of the output files (default: the scene file\n"
	    "                         name without .scene; 'skin' without a scene)\n"
	    "  --lights auto|key|mixture|passes|separable\n"
	    "                         light strategy (default: the scene's, else auto: key for\n"
	    "                         1 light; for 2 the mixture table if its estimated error\n"
	    "                         is below 0.5 %%, else passes; passes for more)\n"
	    "  --nodes N              key-table nodes in theta_i and theta_o [2, 255] (default 65)\n"
	    "  --gamma-nodes N        light-view angle nodes where it varies [1, 256] (default 17)\n"
	    "  --mix-nodes N          two-light mixture nodes per axis [2, 255] (default 25)\n"
	    "  --data-dir DIR         where skinbake_shapes.inc is (default: $SKINBAKE_DATADIR,\n"
	    "                         then %s, then ../exporters/pov next to the scene)\n"
	    "  --size WxH             image size [px], each in [16, 8192] (default: the scene's;\n"
	    "                         320x240 without one)\n"
	    "  --unit-mm MM           without --scene: one scene unit in mm, [0.001, 1e6]\n"
	    "                         (sets the bump map's size; default 10)\n"
	    "  --bump-filter auto|off box-filter the height map so its texels are at most half\n"
	    "                         an image pixel on the nearest skin object (default auto)\n"
	    "  --analytic             use an analytic skin-like BRDF instead of a bake (tests)\n"
	    "  --plan                 print the incidence angles and wavelengths the scene\n"
	    "                         needs from a bake, write nothing\n"
	    "  --help                 this text\n"
	    "\n"
	    "Renders are linear (assumed_gamma 1): a white Lambertian under a light of colour 1\n"
	    "at normal incidence shows 1, so pixel = pi * radiance.\n",
	    SCENE_MAX_LIGHTS, PKGDATADIR);
}

static int run(struct povexport_options *po)
{
	struct povexport_result r = { 0 };
	char *cause = NULL;
	po->plan_out = stdout;
	int e = povexport_run(po, &r, &cause);
	for (int i = 0; i < r.n_msgs; i++)
		fprintf(stderr, "skinbake %s: %s\n", CMD, r.msgs[i]);
	if (e == 0)
		for (int i = 0; i < r.n_files; i++)
			printf("%s\n", r.files[i]);
	else
		(e == -1 ? cli_usage_error : cli_fail)(CMD, "%s", cause);
	povexport_result_free(&r);
	free(cause);
	return e == 0 ? CLI_EXIT_OK : e == -1 ? CLI_EXIT_USAGE : CLI_EXIT_FAIL;
}

int cmd_export_pov(int argc, char **argv)
{
	enum { O_SCENE = 1, O_LIGHT, O_CAMERA, O_BAKE, O_TEXTURES, O_OUT, O_NAME, O_LIGHTS, O_NODES, O_GNODES, O_MNODES,
		O_DATA, O_ANALYTIC, O_PLAN, O_FILTER, O_SIZE, O_UNIT, O_HELP };
	static const struct option opts[] = {
		{ "scene", required_argument, NULL, O_SCENE }, { "light", required_argument, NULL, O_LIGHT },
		{ "camera", required_argument, NULL, O_CAMERA }, { "bake", required_argument, NULL, O_BAKE },
		{ "textures", required_argument, NULL, O_TEXTURES }, { "out", required_argument, NULL, O_OUT },
		{ "name", required_argument, NULL, O_NAME }, { "lights", required_argument, NULL, O_LIGHTS },
		{ "nodes", required_argument, NULL, O_NODES }, { "gamma-nodes", required_argument, NULL, O_GNODES },
		{ "mix-nodes", required_argument, NULL, O_MNODES }, { "data-dir", required_argument, NULL, O_DATA },
		{ "analytic", no_argument, NULL, O_ANALYTIC }, { "plan", no_argument, NULL, O_PLAN },
		{ "bump-filter", required_argument, NULL, O_FILTER }, { "size", required_argument, NULL, O_SIZE },
		{ "unit-mm", required_argument, NULL, O_UNIT },
		{ "help", no_argument, NULL, O_HELP }, { NULL, 0, NULL, 0 } };
	struct scene cl = { 0 }; /* lights and camera from the command line */
	struct povexport_options po = { .cmdline = &cl, .bump_filter = 1 };
	long nodes = 65, gnodes = 17, mnodes = 25;
	char *cause = NULL;
	int c;

	optind = 1;
	while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (c) {
		case O_SCENE:
			po.scene_path = optarg;
			break;
		case O_LIGHT:
		case O_CAMERA:
			if ((c == O_LIGHT ? scenespec_add_light : scenespec_set_camera)(&cl, optarg, &cause) != 0) {
				cli_usage_error(CMD, "%s", cause);
				free(cause);
				return CLI_EXIT_USAGE;
			}
			po.have_camera |= c == O_CAMERA;
			break;
		case O_BAKE:
		case O_TEXTURES:
			if ((c == O_BAKE ? po.n_bakes : po.n_texs) > SCENE_MAX_SKINS)
				return cli_usage_error(CMD, "too many --%s options", c == O_BAKE ? "bake" : "textures");
			if (c == O_BAKE)
				po.bakes[po.n_bakes++] = optarg;
			else
				po.texs[po.n_texs++] = optarg;
			break;
		case O_OUT:
			po.out = optarg;
			break;
		case O_NAME:
			po.name = optarg;
			break;
		case O_LIGHTS:
			po.lights = optarg;
			break;
		case O_NODES:
			if (cli_long(CMD, "--nodes", optarg, 2, LITTABLE_MAX_NODES, &nodes) != 0)
				return CLI_EXIT_USAGE;
			break;
		case O_GNODES:
			if (cli_long(CMD, "--gamma-nodes", optarg, 1, 256, &gnodes) != 0)
				return CLI_EXIT_USAGE;
			break;
		case O_MNODES:
			if (cli_long(CMD, "--mix-nodes", optarg, 2, LITTABLE_MAX_NODES, &mnodes) != 0)
				return CLI_EXIT_USAGE;
			break;
		case O_DATA:
			po.data_dir = optarg;
			break;
		case O_ANALYTIC:
			po.analytic = 1;
			break;
		case O_PLAN:
			po.plan = 1;
			break;
		case O_FILTER:
			if (strcmp(optarg, "auto") && strcmp(optarg, "off"))
				return cli_usage_error(CMD, "--bump-filter = '%s' is not auto or off", optarg);
			po.bump_filter = !strcmp(optarg, "auto");
			break;
		case O_SIZE: {
			int w, h, end = 0;
			if (sscanf(optarg, "%dx%d%n", &w, &h, &end) != 2 || optarg[end] != '\0' || w < 16 || w > 8192 || h < 16
			    || h > 8192)
				return cli_usage_error(CMD, "--size = '%s' is not WxH with W and H in [16, 8192] pixels", optarg);
			po.width = w, po.height = h;
			break;
		}
		case O_UNIT:
			if (cli_double(CMD, "--unit-mm", optarg, 1e-3, 1e6, &po.unit_mm) != 0)
				return CLI_EXIT_USAGE;
			break;
		case O_HELP:
		case 'h':
			help(stdout);
			return CLI_EXIT_OK;
		default:
			help(stderr);
			return CLI_EXIT_USAGE;
		}
	}
	if (optind < argc)
		return cli_usage_error(CMD, "unexpected argument '%s'", argv[optind]);
	po.n_theta = (int)nodes, po.n_gamma = (int)gnodes, po.n_mix = (int)mnodes;
	return run(&po);
}
