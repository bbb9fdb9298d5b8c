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

int cmd_bake(int argc, char **argv)
{
	static struct bake_spec s;
	static struct opt_list wl, th;
	static struct bake_vary vary;
	memset(&s, 0, sizeof s);
	vary.n = 0;
	const char *preset = NULL, *pfile = NULL, *out = NULL;
	int quiet = 0, nodes = 0, fresnel, est, solver;
	uint64_t seed;
	const struct opt opts[] = {
		{ "preset", OPT_STRING, &preset, "NAME", .flags = OPT_REQUIRED, .excl = "preset-file",
		  .help = "a shipped preset (skinbake presets lists them)" },
		{ "preset-file", OPT_PATH_IN, &pfile, "FILE", .flags = OPT_REQUIRED | OPT_FILE, .excl = "preset",
		  .help = "an INI preset file (docs/presets.md)" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED,
		  .help = "output directory (created; files replaced atomically)" },
		{ "wavelengths", OPT_LIST, &wl, "LIST", .lo = 380, .hi = 780, .unit = "nm", .max = BAKE_MAX_WL, .flags = OPT_WHOLE |
		  OPT_UNIQUE | OPT_STEPS, .excl = "spectral", .def_note = "the preset's, e.g. 470,550,656 for 'paper'",
		  .help = "wavelengths, whole numbers" },
		{ "spectral", OPT_LIST, &wl, "A:B:STEP", .lo = 380, .hi = 780, .unit = "nm", .max = BAKE_MAX_WL,
		  .flags = OPT_WHOLE | OPT_UNIQUE | OPT_STEPS, .excl = "wavelengths", .help = "as --wavelengths A:B:STEP" },
		{ "theta-in", OPT_LIST, &th, "LIST", .lo = 0, .hi = 90, .unit = "deg", .max = BAKE_MAX_TI,
		  .flags = OPT_HI_OPEN | OPT_UNIQUE | OPT_SORT, .excl = "theta-nodes", .help = "incidence angles" },
		{ "theta-nodes", OPT_INT, &nodes, "N", .lo = 1, .hi = BAKE_MAX_TI, .excl = "theta-in",
		  .help = "incidence angles 90*k/N deg (k = 0 .. N-1), N", .def_note = "the exit nodes below 90 deg: "
		  "T-1 angles 45 (1 - cos(180 k/(T-1))) deg for --resolution TxP (T >= 3; else N = 10)" },
		{ "resolution", OPT_CUSTOM, &s, "TxP", "18x18", .fn = parse_resolution,
		  .help = "theta_o bands x delta_phi bins over [0, 90] x [0, 180] deg, each in [1, 360]" },
		{ "solver", OPT_ENUM, &solver, .def = "auto", .choices = bake_method_choices(), .help = "adding-doubling (ad), Monte "
		  "Carlo (mc), or ad with mc, said on stderr, for the wavelengths where ad cannot meet --ad-tol (auto)" },
		{ "ad-tol", OPT_DOUBLE, &s.ad_tol, "E", "0.001", .lo = 1e-6, .hi = 0.1,
		  .help = "ad: estimated RMS relative error of the table to reach (or --target-error when smaller)" },
		{ "ad-quad", OPT_INT, &s.ad_quad, "N", .lo = 4, .hi = 1024, .help = "ad: quadrature nodes per unit cosine",
		  .def_note = "the fewest from 16 up, doubling, that meet --ad-tol" },
		{ "ad-quad-max", OPT_INT, &s.ad_quad_max, "N", .lo = 16, .hi = 1024, .def_note = "256",
		  .help = "ad: the most nodes per unit cosine the automatic search tries before refusing (its cost bound)" },
		{ "radial-error", OPT_DOUBLE, &s.radial_error, "E", "0.02", .lo = 1e-4, .hi = 1, .help = "ad: relative error of "
		  "each mean exit radius (Rd(r) by Monte Carlo: 2000 photons per wavelength, more as E asks, up to "
		  "--radial-photons)" },
		{ "radial-photons", OPT_LONG, &s.radial_photons, "N", "1e6", .lo = 100, .hi = 1e10, .help = "ad: Rd(r) photons cap" },
		{ "target-error", OPT_DOUBLE, &s.target_error, "E", "0.02", .lo = 0, .hi = 1, .help = "mc: add photons until the "
		  "solid-angle-weighted RMS relative error of the table is below E (at least 0.001; 0 = spend --max-photons);"
		  " without --batch-photons a pilot of 8 x 250 photons per (wavelength, angle) measures the error E_p, then "
		  "the first round is 32 batches of N/32 photons, N = 2000 (E_p/E)^2 x 1.1," },
		{ "max-photons", OPT_LONG, &s.max_photons, "N", "2e8", .lo = 1e3, .hi = 1e13, .help = "mc: photon budget" },
		{ "batch-photons", OPT_LONG, &s.batch_photons, "N", .lo = 100, .hi = 1e9, .help = "mc: photons per batch, 8 "
		  "batches in the first round", .def_note = "sized from --target-error; 4000 with --target-error 0" },
		{ "r-step", OPT_DOUBLE, &s.dr, "CM", "0.002", .lo = 1e-6, .hi = 10, .unit = "cm", .help = "radial bin of Rd(r)" },
		{ "r-bins", OPT_INT, &s.n_r, "N", "250", .lo = 1, .hi = 100000, .help = "radial bins of Rd(r)" },
		{ "fresnel", OPT_ENUM, &fresnel, .def = "exact", .choices = "exact|schlick", .help = "boundary reflectance model" },
		{ "estimator", OPT_ENUM, &est, .def = "nee", .choices = "nee|bins", .help = "mc: how the table is scored: "
		  "next-event estimation toward every bin (nee), or binning the escaping photons (bins), both unbiased" },
		{ "seed", OPT_U64, &seed, "N", "1", .help = "mc: random seed (exact)" },
		{ "threads", OPT_INT, &s.threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		{ "resume", OPT_FLAG, &s.resume, .help = "go on from DIR.checkpoint (none: from the start; a "
		  "family bake from its finished members, whole members only); not under MPI" },
		{ "checkpoint-seconds", OPT_DOUBLE, &s.checkpoint_s, "S", "5", .lo = 0, .hi = 1e6, .unit = "s",
		  .help = "write DIR.checkpoint at most every S seconds (0: after every step)" },
		{ "vary", OPT_CUSTOM, &vary, "KEY=LO:HI:N[:SPACING]", .fn = bake_vary_parse, .flags = OPT_REPEAT,
		  .max = FAMILY_MAX_AXES, .help = BAKE_VARY_HELP },
		OPT_END
	};
	const struct opt_cmd cmd = { "bake", "(--preset NAME | --preset-file FILE) --out DIR [options]",
		"Bake a skin preset's subsurface BRDF f(theta_i, theta_o, delta_phi) per wavelength into OpenEXR\n"
		"tables with their errors (README, 'Bake outputs').  ad: and mc: options apply to that method.",
		opts, NULL, 0, 0 };
	struct opt_ctx x;
	wl.n = th.n = 0;
	transport_opts_default(&s.opts);
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (s.target_error > 0 && s.target_error < 0.001)
		return opt_error(&x, "--target-error = %g is out of range [0.001, 1] (or 0)", s.target_error);
	bake_spec_axes(&s, wl.v, wl.n, th.v, th.n, nodes);
	s.opts.fresnel = fresnel == 0 ? OPTICS_FRESNEL_EXACT : OPTICS_FRESNEL_SCHLICK;
	s.method = bake_method_at(solver)->id;
	s.nee = est == 0;
	s.seed = seed;
	s.min_batches = 8;
	s.n_ranks = 1;
	return bake_cmd_run(&s, preset, pfile, out, quiet, &vary, argc, argv);
}
