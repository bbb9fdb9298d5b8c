/* skinbake export blender: a bake directory (and optional texture maps) to
 * the image set that exporters/blender/import_skin.py imports. */
#include "config.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"
#include "export/blender/blender.h"
#include "cli/cli.h"
#include "base/util.h"

static const char *CMD = "export blender";

static void help(FILE *fp)
{
	fprintf(fp,
	    "usage: skinbake export blender --bake DIR --out DIR [options]\n"
	    "\n"
	    "Write an image set for Blender (import it with import_skin.py, installed in\n"
	    "%s): albedo.exr, brdf_lut.exr (pi * f_r for the exact\n"
	    "one-sun mode), roughness/height/normal 16-bit PNGs and manifest.json.\n"
	    "\n"
	    "  --bake DIR             bake directory written by `skinbake bake` (required)\n"
	    "  --out DIR              output directory, created if needed (required)\n"
	    "  --textures DIR         `skinbake texture` output (height.png, normal.png);\n"
	    "                         default: flat maps, noted in the manifest\n"
	    "  --sun-elevation DEG    default sun for the exact mode, above the horizon\n"
	    "                         (0, 90] degrees (default 45)\n"
	    "  --sun-azimuth DEG      default sun azimuth from +X toward +Y [-360, 360]\n"
	    "                         degrees (default -45)\n"
	    "  --sun-strength E       sun irradiance for the importer's demo scene\n"
	    "                         (0, 1e6] W/m^2 (default 3)\n"
	    "  --view-elevation DEG   camera of the manifest's reference value (0, 90]\n"
	    "                         degrees (default 60)\n"
	    "  --view-azimuth DEG     its azimuth [-360, 360] degrees (default -90)\n"
	    "  --lut-cos N            cosine nodes per axis of brdf_lut.exr [%d, %d] (default 64)\n"
	    "  --lut-phi N            delta_phi nodes over [0, 180] degrees [%d, %d] (default 37)\n"
	    "  --map-size PX          side of albedo.exr, roughness.png and the flat detail\n"
	    "                         maps [%d, %d] px (default 16)\n"
	    "  --help                 this text\n"
	    "\n"
	    "World axes as in Blender: +Z up.  brdf_lut.exr holds delta_phi tiles side by\n"
	    "side; in a tile the column is cos(view) 0..1 and the file row from the top is\n"
	    "cos(light) 1..0, so Blender's v = 0 (bottom row) is grazing light.\n",
	    PKGDATADIR, BLENDER_LUT_COS_MIN, BLENDER_LUT_COS_MAX, BLENDER_LUT_PHI_MIN, BLENDER_LUT_PHI_MAX,
	    BLENDER_MAP_MIN, BLENDER_MAP_MAX);
}

static void bake_f(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	bake_eval_rgb(ctx, ti, to, dphi, rgb);
}

int cmd_export_blender(int argc, char **argv)
{
	enum { O_BAKE = 256, O_OUT, O_TEX, O_SE, O_SA, O_SS, O_VE, O_VA, O_LC, O_LP, O_MS, O_HELP };
	static const struct option opts[] = {
		{ "bake", required_argument, 0, O_BAKE }, { "out", required_argument, 0, O_OUT },
		{ "textures", required_argument, 0, O_TEX }, { "sun-elevation", required_argument, 0, O_SE },
		{ "sun-azimuth", required_argument, 0, O_SA }, { "sun-strength", required_argument, 0, O_SS },
		{ "view-elevation", required_argument, 0, O_VE }, { "view-azimuth", required_argument, 0, O_VA },
		{ "lut-cos", required_argument, 0, O_LC }, { "lut-phi", required_argument, 0, O_LP },
		{ "map-size", required_argument, 0, O_MS }, { "help", no_argument, 0, O_HELP }, { 0, 0, 0, 0 }
	};
	struct blender_options o;
	const char *bake_dir = NULL, *out = NULL;
	double deg;
	long lv;
	int ch;

	blender_options_default(&o);
	opterr = 0;
	optind = 1;
	while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (ch) {
		case O_BAKE: bake_dir = optarg; break;
		case O_OUT: out = optarg; break;
		case O_TEX: o.textures = optarg; break;
		case O_SE:
		case O_VE:
			if (cli_double(CMD, ch == O_SE ? "--sun-elevation" : "--view-elevation", optarg, 0, 90, &deg))
				return CLI_EXIT_USAGE;
			if (deg <= 0)
				return cli_usage_error(CMD, "%s = %g is out of range (0, 90] degrees",
				    ch == O_SE ? "--sun-elevation" : "--view-elevation", deg);
			*(ch == O_SE ? &o.sun_elevation : &o.view_elevation) = deg * M_PI / 180.0;
			break;
		case O_SA:
		case O_VA:
			if (cli_double(CMD, ch == O_SA ? "--sun-azimuth" : "--view-azimuth", optarg, -360, 360, &deg))
				return CLI_EXIT_USAGE;
			*(ch == O_SA ? &o.sun_azimuth : &o.view_azimuth) = deg * M_PI / 180.0;
			break;
		case O_SS:
			if (cli_double(CMD, "--sun-strength", optarg, 0, 1e6, &o.sun_strength))
				return CLI_EXIT_USAGE;
			if (o.sun_strength <= 0)
				return cli_usage_error(CMD, "--sun-strength = %g is out of range (0, 1e6] W/m^2",
				    o.sun_strength);
			break;
		case O_LC:
			if (cli_long(CMD, "--lut-cos", optarg, BLENDER_LUT_COS_MIN, BLENDER_LUT_COS_MAX, &lv))
				return CLI_EXIT_USAGE;
			o.lut_cos = (int)lv;
			break;
		case O_LP:
			if (cli_long(CMD, "--lut-phi", optarg, BLENDER_LUT_PHI_MIN, BLENDER_LUT_PHI_MAX, &lv))
				return CLI_EXIT_USAGE;
			o.lut_phi = (int)lv;
			break;
		case O_MS:
			if (cli_long(CMD, "--map-size", optarg, BLENDER_MAP_MIN, BLENDER_MAP_MAX, &lv))
				return CLI_EXIT_USAGE;
			o.map_size = (int)lv;
			break;
		case 'h':
		case O_HELP: help(stdout); return CLI_EXIT_OK;
		default:
			return cli_usage_error(CMD, "unknown or incomplete option '%s' (see skinbake export blender --help)",
			    argv[optind - 1]);
		}
	}
	if (optind < argc)
		return cli_usage_error(CMD, "unexpected argument '%s'", argv[optind]);
	if (bake_dir == NULL || out == NULL)
		return cli_usage_error(CMD, "--bake DIR and --out DIR are required (see skinbake export blender --help)");

	char *cause = NULL;
	struct bake *b = bake_load(bake_dir, &cause);
	if (b == NULL) {
		int rc = cli_usage_error(CMD, "--bake: %s", cause);
		free(cause);
		return rc;
	}
	struct blender_model m = {
		.f_rgb = bake_f,
		.ctx = b,
		.n_albedo = b->n_ti,
		.theta_albedo = b->theta_i,
		.albedo_rgb = b->albedo_rgb,
		.ior = b->ior,
		.roughness = b->roughness,
		.sss_radius_cm = { b->sss_radius_rgb_cm[0], b->sss_radius_rgb_cm[1], b->sss_radius_rgb_cm[2] },
		.source = b->dir,
		.preset = b->preset,
	};
	struct blender_set *s = blender_prepare(&m, &o, &cause);
	if (s == NULL) {
		int rc = cli_usage_error(CMD, "%s", cause);
		free(cause);
		bake_free(b);
		return rc;
	}
	int rc = CLI_EXIT_OK;
	if (blender_write(s, out, &cause) != 0) {
		rc = cli_fail(CMD, "%s", cause);
		free(cause);
	}
	blender_set_free(s);
	bake_free(b);
	return rc;
}
