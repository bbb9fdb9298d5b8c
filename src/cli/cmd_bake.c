/* skinbake bake: preset -> per-wavelength layer stacks -> BRDF tables (adding-
 * doubling or Monte Carlo) -> bake directory. */
#include "config.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bake.h"
#include "bake/bakefile.h"
#include "bake/summary.h"
#include "cli/bake_cmd.h"
#include "cli/bake_opts.h"
#include "cli/cli.h"
#include "cli/cmd_bake_family.h"
#include "cli/opt.h"
#include "skin/preset.h"
#include "base/util.h"

/* --resolution TxP. */
static int parse_resolution(struct opt_ctx *x, const struct opt *o, const char *v)
{
	struct bake_spec *s = o->dest;
	long a, b;
	char *c = xstrdup(v), *p = strchr(c, 'x');
	int rc = -1;
	if (p == NULL) {
		opt_error(x, "--resolution = '%s' is not TxP (theta_o bands x delta_phi bins)", v);
		free(c);
		return -1;
	}
	*p = '\0';
	if (opt_long(x, "--resolution: T", c, 1, 360, 0, NULL, &a) == 0 &&
	    opt_long(x, "--resolution: P", p + 1, 1, 360, 0, NULL, &b) == 0) {
		s->n_to = (int)a;
		s->n_phi = (int)b;
		rc = 0;
	}
	free(c);
	return rc;
}

/* The options of the input, the table's grid and the run; the transport
 * options (bake_opts.h) go between the grid's and the run's. */
int cmd_bake(int argc, char **argv)
{
	static struct bake_spec s;
	static struct opt_list wl, th;
	static struct bake_vary vary;
	memset(&s, 0, sizeof s);
	vary.n = 0;
	const char *preset = NULL, *pfile = NULL, *out = NULL;
	int quiet = 0, nodes = 0;
	struct bake_opts b = { .s = &s };
	const struct opt head[] = {
		{ "preset", OPT_STRING, &preset, "NAME", .flags = OPT_REQUIRED,
		  .excl = "preset-file", .help = "a shipped preset (skinbake presets lists them)" },
		{ "preset-file", OPT_PATH_IN, &pfile, "FILE", .flags = OPT_REQUIRED | OPT_FILE,
		  .excl = "preset", .help = "an INI preset file (docs/presets.md)" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED,
		  .help = "output directory (created; files replaced atomically)" },
		{ "wavelengths", OPT_LIST, &wl, "LIST", .lo = 380, .hi = 780, .unit = "nm",
		  .max = BAKE_MAX_WL, .flags = OPT_WHOLE | OPT_UNIQUE | OPT_STEPS,
		  .excl = "spectral",
		  .def_note = "the preset's, e.g. 470,550,656 for 'paper'",
		  .help = "wavelengths, whole numbers" },
		{ "spectral", OPT_LIST, &wl, "A:B:STEP", .lo = 380, .hi = 780, .unit = "nm",
		  .max = BAKE_MAX_WL, .flags = OPT_WHOLE | OPT_UNIQUE | OPT_STEPS,
		  .excl = "wavelengths",
		  .help = "as --wavelengths A:B:STEP" },
		{ "theta-in", OPT_LIST, &th, "LIST", .lo = 0, .hi = 90, .unit = "deg",
		  .max = BAKE_MAX_TI, .flags = OPT_HI_OPEN | OPT_UNIQUE | OPT_SORT,
		  .excl = "theta-nodes",
		  .help = "incidence angles" },
		{ "theta-nodes", OPT_INT, &nodes, "N", .lo = 1, .hi = BAKE_MAX_TI,
		  .excl = "theta-in", .help = "incidence angles 90*k/N deg (k = 0 .. N-1), N",
		  .def_note = "the exit nodes below 90 deg: "
		  "T-1 angles 45 (1 - cos(180 k/(T-1))) deg for --resolution TxP "
		  "(T >= 3; else N = 10)" },
		{ "resolution", OPT_CUSTOM, &s, "TxP", "18x18", .fn = parse_resolution,
		  .help = "theta_o bands x delta_phi bins over [0, 90] x [0, 180] deg, "
		  "each in [1, 360]" },
	};
	const struct opt tail[] = {
		{ "threads", OPT_INT, &s.threads, "N", "0", .lo = 0, .hi = 1024,
		  .help = "OpenMP threads (0 = all cores)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		{ "resume", OPT_FLAG, &s.resume,
		  .help = "go on from DIR.checkpoint (none: from the start; a family bake "
		  "from its finished members, whole members only); not under MPI" },
		{ "checkpoint-seconds", OPT_DOUBLE, &s.checkpoint_s, "S", "5", .lo = 0, .hi = 1e6,
		  .unit = "s",
		  .help = "write DIR.checkpoint at most every S seconds (0: after every step)" },
		{ "vary", OPT_CUSTOM, &vary, "KEY=LO:HI:N[:SPACING]", .fn = bake_vary_parse,
		  .flags = OPT_REPEAT, .max = FAMILY_MAX_AXES, .help = BAKE_VARY_HELP },
		OPT_END
	};
	struct opt opts[OPT_MAX];
	memcpy(opts, head, sizeof head);
	int n = (int)(sizeof head / sizeof head[0]);
	n += bake_opts_transport(opts + n, &b);
	memcpy(opts + n, tail, sizeof tail);
	const struct opt_cmd cmd = {
		.name = "bake",
		.usage = "(--preset NAME | --preset-file FILE) --out DIR [options]",
		.about = "Bake a skin preset's subsurface BRDF f(theta_i, theta_o, delta_phi) "
		"per wavelength into OpenEXR\ntables with their errors (README, 'Bake outputs').  "
		"ad: and mc: options apply to that method.",
		.opts = opts,
	};
	struct opt_ctx x;
	wl.n = th.n = 0;
	transport_opts_default(&s.opts);
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (s.target_error > 0 && s.target_error < 0.001)
		return opt_error(&x, "--target-error = %g is out of range [0.001, 1] (or 0)",
		    s.target_error);
	bake_spec_axes(&s, wl.v, wl.n, th.v, th.n, nodes);
	s.opts.fresnel = b.fresnel == 0 ? OPTICS_FRESNEL_EXACT : OPTICS_FRESNEL_SCHLICK;
	s.method = bake_method_at(b.solver);
	s.nee = b.estimator == 0;
	s.seed = b.seed;
	s.min_batches = 8;
	s.n_ranks = 1;
	return bake_cmd_run(&s, preset, pfile, out, quiet, &vary, argc, argv);
}
