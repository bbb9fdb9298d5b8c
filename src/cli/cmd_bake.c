/* skinbake bake: preset -> per-wavelength layer stacks -> Monte Carlo
 * tables -> bake directory. */
#include "config.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bake.h"
#include "bake/bakefile.h"
#include "cli/cli.h"
#include "skin/colour.h"
#include "skin/preset.h"
#include "skin/tissue.h"
#include "base/util.h"

static const char *CMD = "bake";

static void help(FILE *fp)
{
	fprintf(fp,
	    "usage: skinbake bake (--preset NAME | --preset-file F) --out DIR [options]\n"
	    "\n"
	    "Bake a skin preset's subsurface BRDF f(theta_i, theta_o, delta_phi) per wavelength\n"
	    "into OpenEXR tables with their standard errors (see README, 'Bake outputs').\n"
	    "\n"
	    "  --preset NAME          a shipped preset (skinbake presets lists them)\n"
	    "  --preset-file F        an INI preset file (docs/presets.md)\n"
	    "  --out DIR              output directory (created; files replaced atomically)\n"
	    "  --wavelengths LIST     wavelengths [nm], integers in [380, 780], comma-separated\n"
	    "                         (default: the preset's, e.g. 470,550,656 for 'paper')\n"
	    "  --spectral A:B:S       wavelengths A, A+S, ... <= B [nm] (instead of --wavelengths)\n"
	    "  --theta-in LIST|N      incidence angles [deg] in [0, 90): a comma list (a single angle\n"
	    "                         needs a decimal point or a trailing comma, e.g. 30.0 or 30,),\n"
	    "                         or a node count N in [1, %d] for nodes 90*k/N (default 10)\n"
	    "  --resolution TxP       theta_o bands x delta_phi bins over [0, 90] x [0, 180] deg,\n"
	    "                         each in [1, 360] (default 18x18: 5 x 10 degrees)\n"
	    "  --target-error E       add photons until the solid-angle-weighted RMS relative\n"
	    "                         error of the table is below E, in [0.001, 1]; 0 = spend\n"
	    "                         --max-photons (default 0.02)\n"
	    "  --max-photons N        photon budget of the whole bake [1e3, 1e13] (default 2e8)\n"
	    "  --batch-photons N      photons per batch [100, 1e9] (default 4000)\n"
	    "  --r-step CM            radial bin of Rd(r) [cm] (default 0.002)\n"
	    "  --r-bins N             radial bins [1, 100000] (default 250)\n"
	    "  --fresnel exact|schlick  boundary reflectance model (default exact)\n"
	    "  --estimator nee|bins   how the table is scored: next-event estimation toward every\n"
	    "                         bin (nee), or binning the escaping photons (bins), both\n"
	    "                         unbiased for the bin means (default nee)\n"
	    "  --seed N               random seed [0, 2^63-1] (default 1)\n"
	    "  --threads N            OpenMP threads [0, 1024], 0 = all cores (default 0)\n"
	    "  --quiet                no summary on stdout\n"
	    "  --help                 this text\n",
	    BAKE_MAX_TI);
}

static int parse_wl_list(const char *s, double *wl, int *n)
{
	char *c = xstrdup(s), *save = NULL;
	*n = 0;
	for (char *t = strtok_r(c, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		long v;
		if (*n >= BAKE_MAX_WL) {
			free(c);
			return cli_usage_error(CMD, "--wavelengths: at most %d wavelengths", BAKE_MAX_WL), -1;
		}
		if (util_parse_long(t, &v) != 0 || v < 380 || v > 780) {
			cli_usage_error(CMD, "--wavelengths: '%s' is not an integer wavelength in [380, 780] nm", t);
			free(c);
			return -1;
		}
		for (int i = 0; i < *n; i++)
			if (wl[i] == (double)v) {
				cli_usage_error(CMD, "--wavelengths: %ld nm is listed twice", v);
				free(c);
				return -1;
			}
		wl[(*n)++] = (double)v;
	}
	free(c);
	if (*n == 0)
		return cli_usage_error(CMD, "--wavelengths: empty list"), -1;
	return 0;
}

static int parse_spectral(const char *s, double *wl, int *n)
{
	long a, b, st;
	char *c = xstrdup(s), *p1 = strchr(c, ':'), *p2 = p1 ? strchr(p1 + 1, ':') : NULL;
	if (!p1 || !p2) {
		free(c);
		return cli_usage_error(CMD, "--spectral = '%s' is not A:B:STEP (nm)", s), -1;
	}
	*p1 = *p2 = '\0';
	int bad = util_parse_long(c, &a) || util_parse_long(p1 + 1, &b) || util_parse_long(p2 + 1, &st);
	free(c);
	if (bad || a < 380 || b > 780 || a > b || st < 1)
		return cli_usage_error(CMD, "--spectral = '%s': need integers 380 <= A <= B <= 780 and STEP >= 1 (nm)", s), -1;
	*n = 0;
	for (long w = a; w <= b; w += st) {
		if (*n >= BAKE_MAX_WL)
			return cli_usage_error(CMD, "--spectral = '%s' gives more than %d wavelengths", s, BAKE_MAX_WL), -1;
		wl[(*n)++] = (double)w;
	}
	return 0;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

static int parse_theta(const char *s, double *th, int *n)
{
	if (strchr(s, ',') == NULL && strchr(s, '.') == NULL) {
		long v;
		if (util_parse_long(s, &v) != 0 || v < 1 || v > BAKE_MAX_TI)
			return cli_usage_error(CMD, "--theta-in = '%s': a node count must be an integer in [1, %d] "
			    "(a single angle needs a decimal point, e.g. 30.0)", s, BAKE_MAX_TI), -1;
		*n = (int)v;
		for (int k = 0; k < *n; k++)
			th[k] = 0.5 * M_PI * k / *n;
		return 0;
	}
	char *c = xstrdup(s), *save = NULL;
	*n = 0;
	for (char *t = strtok_r(c, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		double v;
		if (*n >= BAKE_MAX_TI || util_parse_double(t, &v) != 0 || !(v >= 0.0 && v < 90.0)) {
			cli_usage_error(CMD, "--theta-in: '%s' is not an angle in [0, 90) degrees (at most %d angles)", t, BAKE_MAX_TI);
			free(c);
			return -1;
		}
		th[(*n)++] = v * M_PI / 180.0;
	}
	free(c);
	if (*n == 0)
		return cli_usage_error(CMD, "--theta-in: empty list"), -1;
	qsort(th, (size_t)*n, sizeof *th, cmp_double);
	for (int i = 1; i < *n; i++)
		if (th[i] == th[i - 1])
			return cli_usage_error(CMD, "--theta-in: %g degrees is listed twice", th[i] * 180 / M_PI), -1;
	return 0;
}

int cmd_bake(int argc, char **argv)
{
	enum { O_PRESET = 256, O_PFILE, O_OUT, O_WL, O_SPEC, O_TH, O_RES, O_TE, O_MAXP, O_BATCH, O_RS, O_RB, O_FR,
		O_SEED, O_THR, O_QUIET, O_EST, O_HELP };
	static const struct option opts[] = {
		{ "preset", required_argument, 0, O_PRESET }, { "preset-file", required_argument, 0, O_PFILE },
		{ "out", required_argument, 0, O_OUT }, { "wavelengths", required_argument, 0, O_WL },
		{ "spectral", required_argument, 0, O_SPEC }, { "theta-in", required_argument, 0, O_TH },
		{ "resolution", required_argument, 0, O_RES }, { "target-error", required_argument, 0, O_TE },
		{ "max-photons", required_argument, 0, O_MAXP }, { "batch-photons", required_argument, 0, O_BATCH },
		{ "r-step", required_argument, 0, O_RS }, { "r-bins", required_argument, 0, O_RB },
		{ "fresnel", required_argument, 0, O_FR }, { "seed", required_argument, 0, O_SEED },
		{ "threads", required_argument, 0, O_THR }, { "quiet", no_argument, 0, O_QUIET },
		{ "estimator", required_argument, 0, O_EST }, { "help", no_argument, 0, O_HELP }, { 0, 0, 0, 0 }
	};
	static struct bake_spec s;
	memset(&s, 0, sizeof s);
	const char *preset = NULL, *pfile = NULL, *out = NULL;
	int have_wl = 0, quiet = 0, ch;
	long lv;
	s.n_ti = 10;
	for (int k = 0; k < s.n_ti; k++)
		s.theta_i[k] = 0.5 * M_PI * k / s.n_ti;
	s.n_to = 18;
	s.n_phi = 18;
	s.n_r = 250;
	s.dr = 0.002;
	transport_opts_default(&s.opts);
	s.seed = 1;
	s.batch_photons = 4000;
	s.min_batches = 8;
	s.target_error = 0.02;
	s.max_photons = 200000000L;
	s.n_ranks = 1;
	s.nee = 1;

	opterr = 0;
	optind = 1;
	while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (ch) {
		case O_PRESET: preset = optarg; break;
		case O_PFILE: pfile = optarg; break;
		case O_OUT: out = optarg; break;
		case O_WL: if (parse_wl_list(optarg, s.wl_nm, &s.n_wl)) return CLI_EXIT_USAGE; have_wl = 1; break;
		case O_SPEC: if (parse_spectral(optarg, s.wl_nm, &s.n_wl)) return CLI_EXIT_USAGE; have_wl = 1; break;
		case O_TH: if (parse_theta(optarg, s.theta_i, &s.n_ti)) return CLI_EXIT_USAGE; break;
		case O_RES: {
			long a, b;
			char *c = xstrdup(optarg), *x = strchr(c, 'x');
			int bad = x == NULL;
			if (!bad) {
				*x = '\0';
				bad = util_parse_long(c, &a) || util_parse_long(x + 1, &b) || a < 1 || a > 360 || b < 1 || b > 360;
			}
			free(c);
			if (bad)
				return cli_usage_error(CMD, "--resolution = '%s' is not TxP with T, P integers in [1, 360]", optarg);
			s.n_to = (int)a;
			s.n_phi = (int)b;
			break;
		}
		case O_TE:
			if (cli_double(CMD, "--target-error", optarg, 0, 1, &s.target_error)) return CLI_EXIT_USAGE;
			if (s.target_error > 0 && s.target_error < 0.001)
				return cli_usage_error(CMD, "--target-error = %g is out of range [0.001, 1] (or 0)", s.target_error);
			break;
		case O_MAXP: if (cli_long(CMD, "--max-photons", optarg, 1000, 10000000000000L, &s.max_photons)) return CLI_EXIT_USAGE; break;
		case O_BATCH: if (cli_long(CMD, "--batch-photons", optarg, 100, 1000000000L, &s.batch_photons)) return CLI_EXIT_USAGE; break;
		case O_RS: if (cli_double(CMD, "--r-step", optarg, 1e-6, 10, &s.dr)) return CLI_EXIT_USAGE; break;
		case O_RB: if (cli_long(CMD, "--r-bins", optarg, 1, 100000, &lv)) return CLI_EXIT_USAGE; s.n_r = (int)lv; break;
		case O_FR: {
			int m;
			if (cli_fresnel(CMD, optarg, &m))
				return CLI_EXIT_USAGE;
			s.opts.fresnel = (enum optics_fresnel)m;
			break;
		}
		case O_SEED: if (cli_long(CMD, "--seed", optarg, 0, 9223372036854775807L, &lv)) return CLI_EXIT_USAGE; s.seed = (uint64_t)lv; break;
		case O_THR: if (cli_long(CMD, "--threads", optarg, 0, 1024, &lv)) return CLI_EXIT_USAGE; s.threads = (int)lv; break;
		case O_QUIET: quiet = 1; break;
		case O_EST:
			if (strcmp(optarg, "nee") == 0) s.nee = 1;
			else if (strcmp(optarg, "bins") == 0) s.nee = 0;
			else return cli_usage_error(CMD, "--estimator = '%s' is not one of nee, bins", optarg);
			break;
		case 'h':
		case O_HELP: help(stdout); return CLI_EXIT_OK;
		default:
			return cli_usage_error(CMD, "unknown or incomplete option '%s' (see skinbake bake --help)", argv[optind - 1]);
		}
	}
	if (optind < argc)
		return cli_usage_error(CMD, "unexpected argument '%s'", argv[optind]);
	if ((preset == NULL) == (pfile == NULL))
		return cli_usage_error(CMD, "give exactly one of --preset NAME or --preset-file F");
	if (out == NULL)
		return cli_usage_error(CMD, "--out DIR is required");

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
			    "(choose with --wavelengths or --spectral)", preset ? preset : pfile, p->n_wl, BAKE_MAX_WL);
			preset_free(p);
			return rc;
		}
		s.n_wl = preset_default_wavelengths(p, s.wl_nm, BAKE_MAX_WL);
	}
	if ((long)s.n_wl * s.n_ti * s.min_batches * s.batch_photons > s.max_photons) {
		preset_free(p);
		return cli_usage_error(CMD, "--max-photons = %ld is below the first round of the bake "
		    "(%d wavelengths x %d angles x %d batches x %ld photons)", s.max_photons, s.n_wl, s.n_ti,
		    s.min_batches, s.batch_photons);
	}
	for (int w = 0; w < s.n_wl; w++) {
		if (tissue_slab(p, s.wl_nm[w], &s.slab[w], &cause) != 0) {
			int rc = cli_usage_error(CMD, "%s at %.0f nm: %s", preset ? preset : pfile, s.wl_nm[w], cause);
			free(cause);
			preset_free(p);
			return rc;
		}
	}
	double *m = xmalloc(sizeof(double) * 3 * (size_t)s.n_wl);
	colour_rgb_weights(s.n_wl, s.wl_nm, m);
	s.rank = cli_par.rank;
	s.n_ranks = cli_par.size;
	s.allreduce = cli_par.allreduce;
	struct cli_progress pr;
	cli_progress_start(&pr, "bake");
	if (cli_par.rank != 0)
		pr.tty = 0;
	s.progress = cli_progress_update;
	s.progress_user = &pr;
	struct bake_result r;
	bake_run(&s, &r);
	cli_progress_end(&pr);

	char *cmdline = xstrdup("skinbake");
	for (int i = 0; i < argc; i++) {
		char *t = xasprintf("%s %s", cmdline, argv[i]);
		free(cmdline);
		cmdline = t;
	}
	int three = s.n_wl == 3 && s.wl_nm[0] == 470 && s.wl_nm[1] == 550 && s.wl_nm[2] == 656;
	struct bake_meta meta = {
		.preset = preset ? preset : pfile,
		.ior = preset_surface_ior(p),
		.roughness = preset_surface_roughness(p),
		.rgb_from_wl = m,
		.rgb_note = three ? "the paper's three wavelengths map directly: 656 nm -> R, 550 nm -> G, 470 nm -> B"
				  : "CIE 1931 2-degree colour matching under D65, reflectance normalised to the perfect white",
		.command = cmdline,
	};
	int rc = CLI_EXIT_OK;
	if (cli_par.rank != 0) {
		/* Every rank holds the whole result; rank 0 writes it. */
	} else if (bake_write(out, &s, &r, &meta, &cause) != 0) {
		rc = cli_fail(CMD, "%s", cause);
		free(cause);
	} else if (!quiet) {
		printf("skinbake bake: %s -> %s\n  %d wavelengths x %d incidence angles, table %d x %d\n"
		    "  photons %ld, %.2f s, RMS relative error %.4f (target %g: %s)\n",
		    meta.preset, out, s.n_wl, s.n_ti, s.n_to, s.n_phi, r.photons, r.seconds, r.rms_rel_err,
		    s.target_error, s.target_error <= 0 ? "none" : r.target_met ? "met" : "NOT met, photon budget spent");
	}
	free(cmdline);
	free(m);
	bake_result_free(&r);
	preset_free(p);
	return rc;
}
