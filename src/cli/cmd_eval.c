/* skinbake eval: the interpolated baked BRDF at given angles. */
#include "config.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"
#include "cli/cli.h"
#include "cli/opt.h"
#include "base/util.h"
#include "io/json.h"

int cmd_eval(int argc, char **argv)
{
	const char *dir;
	double ti, to, ph;
	int json = 0;
	const struct opt opts[] = {
		{ "bake", OPT_PATH_IN, &dir, "DIR", .flags = OPT_REQUIRED | OPT_DIR,
		  .help = "a directory written by skinbake bake" },
		{ "theta-in", OPT_DOUBLE, &ti, "DEG", .lo = 0, .hi = 90, .unit = "deg", .flags = OPT_REQUIRED,
		  .help = "incidence angle" },
		{ "theta-out", OPT_DOUBLE, &to, "DEG", .lo = 0, .hi = 90, .unit = "deg", .flags = OPT_REQUIRED,
		  .help = "exit angle" },
		{ "phi", OPT_DOUBLE, &ph, "DEG", .lo = 0, .hi = 360, .unit = "deg", .flags = OPT_REQUIRED,
		  .help = "azimuth difference: 0 back toward the light, 180 the mirror side" },
		{ "json", OPT_FLAG, &json, .help = "one JSON object: wavelengths_nm, diffuse, diffuse_err, "
		  "specular, total (arrays), and rgb_total" },
		OPT_END
	};
	const struct opt_cmd cmd = { "eval", "--bake DIR --theta-in DEG --theta-out DEG --phi DEG [--json]",
		"Print the baked BRDF [1/sr] per wavelength: the diffuse (subsurface) part\n"
		"interpolated from the table with its standard error, the analytic specular\n"
		"part and their total.", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	char *cause = NULL;
	struct bake *b = bake_load(dir, &cause);
	if (b == NULL) {
		int rc = cli_usage_error(cmd.name, "--bake: %s", cause);
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
				json_object_array_add(a, json_num(vals[k][i]));
			json_object_object_add(o, keys[k], a);
		}
		json_object *a = json_object_new_array();
		for (int c = 0; c < 3; c++)
			json_object_array_add(a, json_num(rgb[c]));
		json_object_object_add(o, "rgb_total", a);
		char *text = json_text(o, JSON_PLAIN);
		printf("%s\n", text);
		free(text);
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
