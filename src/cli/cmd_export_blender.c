/* skinbake export blender: a bake directory (and optional texture maps) to
 * the image set that exporters/blender/import_skin.py imports. */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"
#include "export/blender/blender.h"
#include "cli/cli.h"
#include "cli/opt.h"
#include "base/util.h"

static void bake_f(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	bake_eval_rgb(ctx, ti, to, dphi, rgb);
}

int cmd_export_blender(int argc, char **argv)
{
	struct blender_options o;
	const char *bake_dir, *out;
	double se, sa, ve, va;
	blender_options_default(&o);
	const struct opt opts[] = {
		{ "bake", OPT_PATH_IN, &bake_dir, "DIR", .flags = OPT_REQUIRED | OPT_DIR,
		  .help = "bake directory written by `skinbake bake`" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED, .help = "output directory, created if needed" },
		{ "textures", OPT_PATH_IN, &o.textures, "DIR", .flags = OPT_DIR, .def_note = "flat maps, noted in the manifest",
		  .help = "`skinbake texture` output (height.png, normal.png)" },
		{ "sun-elevation", OPT_DOUBLE, &se, "DEG", "45", .lo = 0, .hi = 90, .flags = OPT_LO_OPEN, .unit = "deg",
		  .help = "default sun for the exact mode, above the horizon," },
		{ "sun-azimuth", OPT_DOUBLE, &sa, "DEG", "-45", .lo = -360, .hi = 360, .unit = "deg",
		  .help = "default sun azimuth from +X toward +Y," },
		{ "sun-strength", OPT_DOUBLE, &o.sun_strength, "E", "3", .lo = 0, .hi = 1e6, .flags = OPT_LO_OPEN,
		  .unit = "W/m^2", .help = "sun irradiance for the importer's demo scene," },
		{ "view-elevation", OPT_DOUBLE, &ve, "DEG", "60", .lo = 0, .hi = 90, .flags = OPT_LO_OPEN, .unit = "deg",
		  .help = "camera of the manifest's reference value," },
		{ "view-azimuth", OPT_DOUBLE, &va, "DEG", "-90", .lo = -360, .hi = 360, .unit = "deg",
		  .help = "its azimuth," },
		{ "lut-cos", OPT_INT, &o.lut_cos, "N", "64", .lo = BLENDER_LUT_COS_MIN, .hi = BLENDER_LUT_COS_MAX,
		  .help = "cosine nodes per axis of brdf_lut.exr," },
		{ "lut-phi", OPT_INT, &o.lut_phi, "N", "37", .lo = BLENDER_LUT_PHI_MIN, .hi = BLENDER_LUT_PHI_MAX,
		  .help = "delta_phi nodes over [0, 180] degrees," },
		{ "map-size", OPT_INT, &o.map_size, "PX", "16", .lo = BLENDER_MAP_MIN, .hi = BLENDER_MAP_MAX, .unit = "px",
		  .help = "side of albedo.exr, roughness.png and the flat detail maps," },
		OPT_END
	};
	const struct opt_cmd cmd = { "export blender", "--bake DIR --out DIR [options]",
		"Write an image set for Blender (import it with import_skin.py, installed in\n"
		PKGDATADIR "): albedo.exr, brdf_lut.exr (pi * f_r for the exact one-sun mode),\n"
		"roughness/height/normal 16-bit PNGs and manifest.json.", opts,
		"World axes as in Blender: +Z up.  brdf_lut.exr holds delta_phi tiles side by\n"
		"side; in a tile the column is cos(view) 0..1 and the file row from the top is\n"
		"cos(light) 1..0, so Blender's v = 0 (bottom row) is grazing light.", 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	o.sun_elevation = se * M_PI / 180.0;
	o.sun_azimuth = sa * M_PI / 180.0;
	o.view_elevation = ve * M_PI / 180.0;
	o.view_azimuth = va * M_PI / 180.0;
	const char *CMD = cmd.name;

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
