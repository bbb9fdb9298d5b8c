/* skinbake bake: preset -> per-wavelength layer stacks -> Monte Carlo
 * tables -> bake directory. */
#include "config.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bake.h"
#include "bake/bakefile.h"
#include "cli/cli.h"
#include "cli/opt.h"
#include "skin/preset.h"
#include "base/util.h"

static const char *CMD = "bake";

/* --resolution TxP. */
static int parse_resolution(struct opt_ctx *x, const struct opt *o, const char *v)
{
	struct bake_spec *s = o->dest;
	long a, b;
	char *c = xstrdup(v), *p = strchr(c, 'x');
	int rc = -1;
	if (p == NULL)
		opt_error(x, "--resolution = '%s' is not TxP (theta_o bands x delta_phi bins)", v);
	else {
		*p = '\0';
		rc = opt_long(x, "--resolution: T", c, 1, 360, 0, NULL, &a) || opt_long(x, "--resolution: P", p + 1, 1, 360, 0,
		    NULL, &b) ? -1 : 0;
	}
	free(c);
	if (rc == 0)
		s->n_to = (int)a, s->n_phi = (int)b;
	return rc;
}

/* "skinbake ARGS...", for the manifest.  Caller frees. */
static char *command_line(int argc, char **argv)
{
	char *cmdline = xstrdup("skinbake");
	for (int i = 0; i < argc; i++) {
		char *t = xasprintf("%s %s", cmdline, argv[i]);
		free(cmdline);
		cmdline = t;
	}
	return cmdline;
}

/* After the options: the preset's layer stacks, the bake, the directory. */
static int run(struct bake_spec *s, const char *preset, const char *pfile, const char *out, int have_wl, int quiet,
    int argc, char **argv)
{
	const char *label = preset ? preset : pfile;
	char *cause = NULL;
	struct skin_params *p = preset ? preset_load_builtin(preset, &cause) : preset_load_file(pfile, &cause);
	if (p == NULL) {
		int rc = cli_usage_error(CMD, "%s", cause);
		free(cause);
		return rc;
	}
	if (!have_wl) {
		if (p->n_wl > BAKE_MAX_WL) {
			int rc = cli_usage_error(CMD, "preset %s lists %d wavelengths; a bake takes at most %d "
			    "(choose with --wavelengths or --spectral)", label, p->n_wl, BAKE_MAX_WL);
			preset_free(p);
			return rc;
		}
		s->n_wl = preset_default_wavelengths(p, s->wl_nm, BAKE_MAX_WL);
	}
	if ((long)s->n_wl * s->n_ti * s->min_batches * s->batch_photons > s->max_photons) {
		preset_free(p);
		return cli_usage_error(CMD, "--max-photons = %ld is below the first round of the bake "
		    "(%d wavelengths x %d angles x %d batches x %ld photons)", s->max_photons, s->n_wl, s->n_ti,
		    s->min_batches, s->batch_photons);
	}
	if (bake_spec_layers(s, p, label, &cause) != 0) {
		int rc = cli_usage_error(CMD, "%s", cause);
		free(cause);
		preset_free(p);
		return rc;
	}
	double *m = xmalloc(sizeof(double) * 3 * (size_t)s->n_wl);
	char *cmdline = command_line(argc, argv);
	struct bake_meta meta = {
		.preset = label,
		.ior = preset_surface_ior(p),
		.roughness = preset_surface_roughness(p),
		.rgb_from_wl = m,
		.rgb_note = bake_rgb_weights(s, m),
		.command = cmdline,
	};
	s->rank = cli_par.rank;
	s->n_ranks = cli_par.size;
	s->allreduce = cli_par.allreduce;
	struct cli_progress pr;
	cli_progress_start(&pr, "bake");
	if (cli_par.rank != 0)
		pr.tty = 0;
	s->progress = cli_progress_update;
	s->progress_user = &pr;
	struct bake_result r;
	int ok = bake_run(s, &r, &cause) == 0, rc = CLI_EXIT_OK;
	cli_progress_end(&pr);
	if (!ok) {
		rc = cli_usage_error(CMD, "%s", cause);
		free(cause);
	} else if (cli_par.rank != 0) {
		/* Every rank holds the whole result; rank 0 writes it. */
	} else if (bake_write(out, s, &r, &meta, &cause) != 0) {
		rc = cli_fail(CMD, "%s", cause);
		free(cause);
	} else if (!quiet) {
		printf("skinbake bake: %s -> %s\n  %d wavelengths x %d incidence angles, table %d x %d\n"
		    "  photons %ld, %.2f s, RMS relative error %.4f (target %g: %s)\n",
		    meta.preset, out, s->n_wl, s->n_ti, s->n_to, s->n_phi, r.table.photons, r.table.seconds,
		    r.table.rms_rel_err, s->target_error, s->target_error <= 0 ? "none"
		    : r.table.target_met ? "met" : "NOT met, photon budget spent");
	}
	if (ok)
		bake_result_free(&r);
	free(cmdline);
	free(m);
	preset_free(p);
	return rc;
}

int cmd_bake(int argc, char **argv)
{
	static struct bake_spec s;
	static struct opt_list wl, th;
	memset(&s, 0, sizeof s);
	const char *preset = NULL, *pfile = NULL, *out = NULL;
	int quiet = 0, nodes, fresnel, est;
	long seed;
	const struct opt opts[] = {
		{ "preset", OPT_STRING, &preset, "NAME", .flags = OPT_REQUIRED, .excl = "preset-file",
		  .help = "a shipped preset (skinbake presets lists them)" },
		{ "preset-file", OPT_PATH_IN, &pfile, "FILE", .flags = OPT_REQUIRED | OPT_FILE, .excl = "preset",
		  .help = "an INI preset file (docs/presets.md)" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED,
		  .help = "output directory (created; files replaced atomically)" },
		{ "wavelengths", OPT_LIST, &wl, "LIST", .lo = 380, .hi = 780, .unit = "nm", .max = BAKE_MAX_WL,
		  .flags = OPT_WHOLE | OPT_UNIQUE | OPT_STEPS, .excl = "spectral",
		  .def_note = "the preset's, e.g. 470,550,656 for 'paper'", .help = "wavelengths, whole numbers" },
		{ "spectral", OPT_LIST, &wl, "A:B:STEP", .lo = 380, .hi = 780, .unit = "nm", .max = BAKE_MAX_WL,
		  .flags = OPT_WHOLE | OPT_UNIQUE | OPT_STEPS, .excl = "wavelengths", .help = "as --wavelengths A:B:STEP" },
		{ "theta-in", OPT_LIST, &th, "LIST", .lo = 0, .hi = 90, .unit = "deg", .max = BAKE_MAX_TI,
		  .flags = OPT_HI_OPEN | OPT_UNIQUE | OPT_SORT, .excl = "theta-nodes", .help = "incidence angles" },
		{ "theta-nodes", OPT_INT, &nodes, "N", "10", .lo = 1, .hi = BAKE_MAX_TI, .excl = "theta-in",
		  .help = "incidence angles 90*k/N deg (k = 0 .. N-1), N" },
		{ "resolution", OPT_CUSTOM, &s, "TxP", "18x18", .fn = parse_resolution,
		  .help = "theta_o bands x delta_phi bins over [0, 90] x [0, 180] deg, each in [1, 360]" },
		{ "target-error", OPT_DOUBLE, &s.target_error, "E", "0.02", .lo = 0, .hi = 1,
		  .help = "add photons until the solid-angle-weighted RMS relative error of the table is below E "
		  "(at least 0.001; 0 = spend --max-photons)," },
		{ "max-photons", OPT_LONG, &s.max_photons, "N", "2e8", .lo = 1e3, .hi = 1e13,
		  .help = "photon budget of the whole bake" },
		{ "batch-photons", OPT_LONG, &s.batch_photons, "N", "4000", .lo = 100, .hi = 1e9, .help = "photons per batch" },
		{ "r-step", OPT_DOUBLE, &s.dr, "CM", "0.002", .lo = 1e-6, .hi = 10, .unit = "cm", .help = "radial bin of Rd(r)" },
		{ "r-bins", OPT_INT, &s.n_r, "N", "250", .lo = 1, .hi = 100000, .help = "radial bins of Rd(r)" },
		{ "fresnel", OPT_ENUM, &fresnel, .def = "exact", .choices = "exact|schlick",
		  .help = "boundary reflectance model" },
		{ "estimator", OPT_ENUM, &est, .def = "nee", .choices = "nee|bins",
		  .help = "how the table is scored: next-event estimation toward every bin (nee), or binning the "
		  "escaping photons (bins), both unbiased for the bin means" },
		{ "seed", OPT_LONG, &seed, "N", "1", .lo = 0, .hi = (double)LONG_MAX, .help = "random seed" },
		{ "threads", OPT_INT, &s.threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		OPT_END
	};
	const struct opt_cmd cmd = { "bake", "(--preset NAME | --preset-file FILE) --out DIR [options]",
		"Bake a skin preset's subsurface BRDF f(theta_i, theta_o, delta_phi) per wavelength\n"
		"into OpenEXR tables with their standard errors (see README, 'Bake outputs').", opts, NULL, 0, 0 };
	struct opt_ctx x;
	wl.n = th.n = 0;
	transport_opts_default(&s.opts);
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (s.target_error > 0 && s.target_error < 0.001)
		return opt_error(&x, "--target-error = %g is out of range [0.001, 1] (or 0)", s.target_error);
	s.n_ti = th.n > 0 ? th.n : nodes;
	for (int k = 0; k < s.n_ti; k++)
		s.theta_i[k] = th.n > 0 ? th.v[k] * M_PI / 180.0 : 0.5 * M_PI * k / s.n_ti;
	s.n_wl = wl.n;
	memcpy(s.wl_nm, wl.v, sizeof(double) * (size_t)wl.n);
	s.opts.fresnel = fresnel == 0 ? OPTICS_FRESNEL_EXACT : OPTICS_FRESNEL_SCHLICK;
	s.nee = est == 0;
	s.seed = (uint64_t)seed;
	s.min_batches = 8;
	s.n_ranks = 1;
	int have_wl = wl.n > 0;
	return run(&s, preset, pfile, out, have_wl, quiet, argc, argv);
}
