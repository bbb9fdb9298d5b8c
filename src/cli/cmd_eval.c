/* skinbake eval: the interpolated baked BRDF at given angles. */
#include "config.h"

#include <getopt.h>
#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"
#include "cli/cli.h"
#include "base/util.h"

static const char *CMD = "eval";

static void help(FILE *fp)
{
	fprintf(fp,
	    "usage: skinbake eval --bake DIR --theta-in DEG --theta-out DEG --phi DEG [--json]\n"
	    "\n"
	    "Print the baked BRDF [1/sr] per wavelength: the diffuse (subsurface) part\n"
	    "interpolated from the table with its standard error, the analytic specular\n"
	    "part and their total.\n"
	    "\n"
	    "  --bake DIR         a directory written by skinbake bake\n"
	    "  --theta-in DEG     incidence angle [0, 90] degrees\n"
	    "  --theta-out DEG    exit angle [0, 90] degrees\n"
	    "  --phi DEG          azimuth difference [0, 360] degrees: 0 back toward the light,\n"
	    "                     180 the mirror side\n"
	    "  --json             one JSON object: wavelengths_nm, diffuse, diffuse_err,\n"
	    "                     specular, total (arrays), and rgb_total\n"
	    "  --help             this text\n");
}

int cmd_eval(int argc, char **argv)
{
	enum { O_BAKE = 256, O_TI, O_TO, O_PHI, O_JSON, O_HELP };
	static const struct option opts[] = {
		{ "bake", required_argument, 0, O_BAKE }, { "theta-in", required_argument, 0, O_TI },
		{ "theta-out", required_argument, 0, O_TO }, { "phi", required_argument, 0, O_PHI },
		{ "json", no_argument, 0, O_JSON }, { "help", no_argument, 0, O_HELP }, { 0, 0, 0, 0 }
	};
	const char *dir = NULL;
	double ti = NAN, to = NAN, ph = NAN;
	int json = 0, ch;
	opterr = 0;
	optind = 1;
	while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (ch) {
		case O_BAKE: dir = optarg; break;
		case O_TI: if (cli_double(CMD, "--theta-in", optarg, 0, 90, &ti)) return CLI_EXIT_USAGE; break;
		case O_TO: if (cli_double(CMD, "--theta-out", optarg, 0, 90, &to)) return CLI_EXIT_USAGE; break;
		case O_PHI: if (cli_double(CMD, "--phi", optarg, 0, 360, &ph)) return CLI_EXIT_USAGE; break;
		case O_JSON: json = 1; break;
		case 'h':
		case O_HELP: help(stdout); return CLI_EXIT_OK;
		default:
			return cli_usage_error(CMD, "unknown or incomplete option '%s' (see skinbake eval --help)", argv[optind - 1]);
		}
	}
	if (optind < argc)
		return cli_usage_error(CMD, "unexpected argument '%s'", argv[optind]);
	if (dir == NULL || isnan(ti) || isnan(to) || isnan(ph))
		return cli_usage_error(CMD, "--bake, --theta-in, --theta-out and --phi are required");
	char *cause = NULL;
	struct bake *b = bake_load(dir, &cause);
	if (b == NULL) {
		int rc = cli_usage_error(CMD, "--bake: %s", cause);
		free(cause);
		return rc;
	}
	int n = b->n_wl;
	double *f = xmalloc(sizeof(double) * 4 * (size_t)n), *e = f + n, *sp = f + 2 * n, *tot = f + 3 * n;
	double d2r = M_PI / 180.0, rgb[3];
	bake_eval_diffuse(b, ti * d2r, to * d2r, ph * d2r, f, e);
	bake_eval_specular(b, ti * d2r, to * d2r, ph * d2r, sp);
	bake_eval_rgb(b, ti * d2r, to * d2r, ph * d2r, rgb);
	for (int i = 0; i < n; i++)
		tot[i] = f[i] + sp[i];
	if (json) {
		json_object *o = json_object_new_object();
		const char *keys[] = { "wavelengths_nm", "diffuse", "diffuse_err", "specular", "total" };
		const double *vals[] = { b->wl_nm, f, e, sp, tot };
		for (int k = 0; k < 5; k++) {
			json_object *a = json_object_new_array();
			for (int i = 0; i < n; i++)
				json_object_array_add(a, json_object_new_double(vals[k][i]));
			json_object_object_add(o, keys[k], a);
		}
		json_object *a = json_object_new_array();
		for (int c = 0; c < 3; c++)
			json_object_array_add(a, json_object_new_double(rgb[c]));
		json_object_object_add(o, "rgb_total", a);
		printf("%s\n", json_object_to_json_string_ext(o, JSON_C_TO_STRING_PLAIN));
		json_object_put(o);
	} else {
		printf("skinbake eval: %s at theta_in %g, theta_out %g, delta_phi %g degrees [1/sr]\n", dir, ti, to, ph);
		printf("  %8s %12s %12s %12s %12s\n", "wl [nm]", "diffuse", "std.err", "specular", "total");
		for (int i = 0; i < n; i++)
			printf("  %8.0f %12.6f %12.2e %12.6f %12.6f\n", b->wl_nm[i], f[i], e[i], sp[i], tot[i]);
		printf("  linear sRGB total: %.6f %.6f %.6f\n", rgb[0], rgb[1], rgb[2]);
	}
	free(f);
	bake_free(b);
	return CLI_EXIT_OK;
}
