/* skinbake maps fit: per texel, the family parameters whose diffuse albedo
 * matches an albedo texture (maps/fit.c), with an error and a status map. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "cli/cmd_maps.h"
#include "maps/fit.h"
#include "maps/image.h"

int cmd_maps_fit(int argc, char **argv)
{
	const char *fam = NULL, *alb = NULL, *mask = NULL, *out = NULL;
	int input = 0, exr = 0, quiet = 0;
	struct maps_fit_opts fo = { 0 };
	const struct opt opts[] = {
		{ "family", OPT_PATH_IN, &fam, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "a family directory (bake --vary)" },
		{ "albedo", OPT_PATH_IN, &alb, "IMAGE", .flags = OPT_REQUIRED | OPT_FILE,
		  .help = "the albedo texture: PNG (8 or 16 bit) or EXR, RGB or grey, alpha < 0.5 not fitted" },
		{ "input", OPT_ENUM, &input, .def = "auto", .choices = "auto|srgb|linear",
		  .help = "how the albedo's values are encoded: auto = sRGB for PNG, linear for EXR" },
		{ "mask", OPT_PATH_IN, &mask, "IMAGE", .flags = OPT_FILE,
		  .help = "fit only where this grey image is >= 0.5 (the albedo's size)" },
		{ "max-de", OPT_DOUBLE, &fo.max_de, "E", "2.5", .lo = 0, .hi = 100, .flags = OPT_LO_OPEN,
		  .help = "CIEDE2000 beyond which a texel is flagged unmatched (status 255)" },
		{ "format", OPT_ENUM, &exr, .def = "png", .choices = "png|exr", .help = "16-bit PNG or float EXR maps" },
		{ "threads", OPT_INT, &fo.threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED, .help = "maps directory (created or replaced)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		OPT_END
	};
	const struct opt_cmd cmd = { "maps fit", "--family DIR --albedo IMAGE --out DIR [options]",
		"Per texel, the family parameters whose diffuse albedo matches the texture's colour\n"
		"(CIELAB D65, CIEDE2000 reported), with an error map and a status map (docs/maps.md).", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	int w, h, mw, mh;
	if (cmd_maps_image_arg(&x, "albedo", alb, &w, &h) || (mask && cmd_maps_image_arg(&x, "mask", mask, &mw, &mh)) || cmd_maps_check_out_dir(&x, out, fam, alb))
		return CLI_EXIT_USAGE;
	if (mask && (mw != w || mh != h))
		return opt_error(&x, "--mask %s is %d x %d texels, but --albedo %s is %d x %d", mask, mw, mh, alb, w, h);
	struct family *f = cmd_maps_load_family(&x, fam);
	if (f == NULL)
		return CLI_EXIT_USAGE;
	char *cause = NULL;
	double texels = (double)w * h;
	double disk = ((exr ? 4.0 : 2.0) * (f->n_axes + 1) + 1.0) * texels;
	char what[96];
	snprintf(what, sizeof what, "a fit of the %d x %d texel --albedo", w, h);
	double mem = MAPS_FIT_MEM_PER_TEXEL * texels + MAPS_FIT_MEM_FIXED;
	if (cmd_maps_budget(&x, what, mem, disk, out,
		"use a smaller --albedo texture (fit its tiles one by one)")) {
		family_free(f);
		return CLI_EXIT_USAGE;
	}
	fo.input_linear = input == 2 || (input == 0 && image_kind(alb, &cause) == IMAGE_EXR);
	struct maps_fit_summary s;
	char *cl = mapset_command_line("fit", argc, argv);
	int input_error = 0, rc = CLI_EXIT_OK;
	if (maps_fit_files(f, alb, mask, &fo, out, exr, cl, &s, &input_error, &cause) != 0) {
		if (input_error)
			rc = opt_error(&x, "%s", cause);
		else {
			fprintf(stderr, "skinbake %s: %s\n", x.cmd->name, cause);
			rc = CLI_EXIT_FAIL;
		}
		free(cause);
	} else if (!quiet)
		printf("skinbake maps fit: %s (%d x %d, %s) with %s -> %s\n"
		    "  %ld texels fitted (%ld distinct colours), %ld not fitted; %ld matched, %ld unmatched "
		    "(CIEDE2000 > %g, %.2f %%)\n  CIEDE2000 median %.3f, 95th percentile %.3f, max %.3f; %.2f s\n", alb, w,
		    h, fo.input_linear ? "linear" : "sRGB", fam, out, s.fitted, s.unique, s.texels - s.fitted, s.matched,
		    s.unmatched, fo.max_de, s.fitted ? 100.0 * s.unmatched / s.fitted : 0.0, s.de_median, s.de_p95,
		    s.de_max, s.seconds);
	free(cl);
	family_free(f);
	return rc;
}
