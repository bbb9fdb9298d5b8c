/* skinbake maps render-albedo: the family's diffuse albedo (and subsurface
 * radius) per texel from parameter maps (maps/render.c). */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "cli/cmd_maps.h"
#include "maps/image.h"
#include "maps/render.h"

int cmd_maps_render(int argc, char **argv)
{
	const char *fam = NULL, *in = NULL, *out = NULL, *radius = NULL;
	int bits = 16, enc = 0, threads = 0, quiet = 0, exr, rexr;
	const struct opt opts[] = {
		{ "family", OPT_PATH_IN, &fam, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "a family directory (bake --vary)" },
		{ "maps", OPT_PATH_IN, &in, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "its parameter maps" },
		{ "out", OPT_STRING, &out, "FILE", .flags = OPT_REQUIRED,
		  .help = "the albedo: FILE.png (sRGB-encoded unless --encoding linear) or FILE.exr (linear float)" },
		{ "bits", OPT_INT, &bits, "N", "16", .lo = 8, .hi = 16, .help = "PNG bits, 8 or 16" },
		{ "encoding", OPT_ENUM, &enc, .def = "srgb", .choices = "srgb|linear", .help = "PNG encoding" },
		{ "radius", OPT_STRING, &radius, "FILE.exr",
		  .help = "also the subsurface radius per R, G, B [cm] as a float EXR" },
		{ "threads", OPT_INT, &threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		OPT_END
	};
	const struct opt_cmd cmd = { "maps render-albedo", "--family DIR --maps DIR --out FILE [options]",
		"The family's diffuse albedo per texel from parameter maps (the fit's forward direction).", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (bits != 8 && bits != 16)
		return opt_error(&x, "--bits = %d is not 8 or 16", bits);
	if (cmd_maps_check_out_file(&x, "out", out, &exr) || (radius && cmd_maps_check_out_file(&x, "radius", radius, &rexr)))
		return CLI_EXIT_USAGE;
	if (radius && !rexr)
		return opt_error(&x, "--radius = '%s' must be an .exr file (radii in cm)", radius);
	/* Before the maps are read, from the size maps.json states (reading it
	 * says what is wrong with it).  Disk: the albedo (3 channels of 1, 2 or
	 * 4 bytes), the radius 12 bytes. */
	int w, h, n;
	char what[160], *cause = NULL;
	if (mapset_read_size(in, &w, &h, &n, &cause) == 0) {
		double texels = (double)w * h, disk = exr ? 12.0 : 3.0 * bits / 8;
		double per = MAPS_MEM_PER_TEXEL_MAP * n + MAPS_RENDER_MEM_PER_TEXEL;
		if (radius) {
			disk += 12.0;
			per += MAPS_RENDER_MEM_PER_TEXEL;
		}
		snprintf(what, sizeof what, "maps render-albedo of %d x %d texels (--maps %s)",
		    w, h, in);
		if (cmd_maps_budget(&x, what, per * texels + MAPS_MEM_FIXED, disk * texels, out,
			"render smaller maps (tiles one by one)"))
			return CLI_EXIT_USAGE;
	}
	free(cause);
	cause = NULL;
	struct family *f = cmd_maps_load_family(&x, fam);
	struct mapset *m = f ? cmd_maps_load_maps(&x, in) : NULL;
	int rc = CLI_EXIT_OK;
	if (f == NULL || m == NULL)
		rc = CLI_EXIT_USAGE;
	else if (mapset_check_family(m, in, f, &cause) != 0) {
		rc = opt_error(&x, "%s", cause);
		free(cause);
	}
	if (rc == CLI_EXIT_OK) {
		struct image *rad = NULL, *im = maps_render_albedo(f, m, radius ? &rad : NULL, threads);
		rc = maps_render_write(out, exr, bits, enc == 0, im, radius, rad, &cause);
		if (rc != 0) {
			fprintf(stderr, "skinbake maps render-albedo: %s\n", cause);
			free(cause);
			rc = CLI_EXIT_FAIL;
		} else if (!quiet)
			printf("skinbake maps render-albedo: %s with %s -> %s%s%s\n", in, fam, out, rad ? " and " : "",
			    rad ? radius : "");
		image_free(im);
		image_free(rad);
	}
	mapset_free(m);
	family_free(f);
	return rc;
}
