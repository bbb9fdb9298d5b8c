/* skinbake export blender: a bake directory (and optional texture maps) to
 * the image set that exporters/blender/import_skin.py imports. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export/blender/blender.h"
#include "export/blender/blender_family.h"
#include "export/blender/blender_sss.h"
#include "maps/mapset.h"
#include "export/source.h"
#include "cli/cli.h"
#include "cli/opt.h"
#include "base/util.h"

static const char *CMD = "export blender";

enum { MODE_EXACT, MODE_TRANSLUCENT, MODE_AUTO };	/* --mode, in its choices' order */

/* After the options: the bake (and textures) as a BRDF source, the image set;
 * translucent: Cycles' subsurface node fitted to Rd(r), the table the rest. */
static int run(const char *bake_dir, const char *tex_dir, const char *out, const struct blender_options *o,
    int mode)
{
	char *cause = NULL;
	struct brdf_source *src = brdf_source_open(bake_dir, &cause);
	if (src == NULL) {
		int rc = cli_usage_error(CMD, "--bake: %s", cause);
		free(cause);
		return rc;
	}
	struct blender_set *s = NULL;
	struct blender_sss w;
	int rc = CLI_EXIT_OK, translucent = mode == MODE_TRANSLUCENT;
	char *note = NULL;
	if (blender_check(src, o, &cause) != 0 ||
	    (tex_dir && brdf_source_add_textures(src, tex_dir, &cause) != 0) ||
	    (translucent && blender_sss_wrap(src, &w, &cause) != 0))
		rc = cli_usage_error(CMD, "%s", cause);
	else if (mode == MODE_AUTO && (translucent = blender_sss_auto(src, tex_dir != NULL, &w, &note)) >= 0)
		fprintf(stderr, "skinbake %s: %s\n", CMD, note);
	if (rc == CLI_EXIT_OK && (s = blender_prepare(src, o, &cause)) == NULL)
		rc = cli_usage_error(CMD, "%s", cause);
	else if (rc == CLI_EXIT_OK) {
		if (translucent) {
			char *j = blender_sss_json(&w, NULL);
			blender_set_add_section(s, "translucent", j);
			free(j);
		}
		if ((rc = blender_write(s, out, &cause)) != 0)
			rc = rc == -1 ? cli_usage_error(CMD, "%s", cause) : cli_fail(CMD, "%s", cause);
	}
	free(cause);
	free(note);
	blender_set_free(s);
	brdf_source_free(src);
	return rc;
}

/* --family and --maps: the family's image set with per-texel maps. */
static int run_family(const char *fam_dir, const char *maps_dir, const char *tex_dir, const char *out, int sub,
    const struct blender_options *o, int translucent)
{
	char *cause = NULL;
	struct brdf_family *f = brdf_family_open(fam_dir, &cause);
	struct mapset *m = f ? mapset_read(maps_dir, &cause) : NULL;
	int rc = CLI_EXIT_OK, e;
	if (f == NULL || m == NULL)
		rc = cli_usage_error(CMD, "%s %s: %s", f ? "--maps" : "--family", f ? maps_dir : fam_dir, cause);
	else if ((e = blender_family_export(f, m, o, sub, tex_dir, translucent, out, &cause)) != 0)
		rc = e == -1 ? cli_usage_error(CMD, "%s", cause) : cli_fail(CMD, "%s", cause);
	free(cause);
	mapset_free(m);
	brdf_family_free(f);
	return rc;
}

int cmd_export_blender(int argc, char **argv)
{
	struct blender_options o;
	const char *bake_dir = NULL, *out, *tex_dir = NULL, *fam_dir = NULL, *maps_dir = NULL;
	double se, sa, ve, va;
	int sub, mode = MODE_AUTO;
	blender_options_default(&o);
	const struct opt opts[] = {
		{ "bake", OPT_PATH_IN, &bake_dir, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .excl = "family",
		  .help = "bake directory written by `skinbake bake`" },
		{ "family", OPT_PATH_IN, &fam_dir, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .excl = "bake",
		  .help = "a family directory (`skinbake bake --vary`), with --maps: per-texel skin (docs/maps.md)" },
		{ "maps", OPT_PATH_IN, &maps_dir, "DIR", .flags = OPT_DIR,
		  .help = "the family's parameter maps (`skinbake maps`), for --family" },
		{ "family-sub", OPT_INT, &sub, "N", "4", .lo = BLENDER_FAMILY_SUB_MIN, .hi = BLENDER_FAMILY_SUB_MAX,
		  .help = "exact-mode tables per varying axis over the maps' range, for --family" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED, .help = "output directory, created if needed" },
		{ "textures", OPT_PATH_IN, &tex_dir, "DIR", .flags = OPT_DIR, .def_note = "flat maps, noted in the manifest",
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
		{ "mode", OPT_ENUM, &mode, .choices = "exact|translucent|auto", .def = "auto",
		  .help = "translucent: Cycles' subsurface fitted to Rd(r) beside the rest of the table "
		  "(docs/translucency.md; with --family: per texel, docs/maps.md); auto: translucent "
		  "for a --bake without --textures, else exact, saying why" },
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
	if (fam_dir && !maps_dir)
		return opt_error(&x, "--family needs --maps (the parameter maps to export)");
	if (maps_dir && !fam_dir)
		return opt_error(&x, "--maps goes with --family, not --bake");
	const char *in[] = { bake_dir, tex_dir, fam_dir, maps_dir };
	if (opt_out_check(&x, out, &blender_outdir_kind, in, 4) != 0)
		return CLI_EXIT_USAGE;
	if (fam_dir && mode == MODE_AUTO)
		fprintf(stderr, "skinbake %s: exact (--mode auto: a --family)\n", CMD);
	if (fam_dir)
		return run_family(fam_dir, maps_dir, tex_dir, out, sub, &o,
		    mode == MODE_TRANSLUCENT);
	return run(bake_dir, tex_dir, out, &o, mode);
}
