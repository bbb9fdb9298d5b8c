/* skinbake simulate: one Monte Carlo run on a layer stack given on the
 * command line; a readable table or one JSON object on stdout. */
#include "config.h"

#include <getopt.h>
#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "engine/sim.h"
#include "base/util.h"

static const char *CMD = "simulate";

static void help(FILE *fp)
{
	fprintf(fp,
	    "usage: skinbake simulate --layer SPEC [--layer SPEC ...] [options]\n"
	    "\n"
	    "Monte Carlo light transport (MCML with oblique incidence) in a stack of\n"
	    "plane-parallel layers, top layer first.\n"
	    "\n"
	    "  --layer d=CM,n=N,mua=1/CM,mus=1/CM,g=G\n"
	    "                         one layer (repeat, 1 to %d): d thickness [cm] in (0, inf),\n"
	    "                         'inf' allowed for the last layer; n refractive index [1, 10]\n"
	    "                         (default 1); mua, mus absorption and scattering coefficients\n"
	    "                         [1/cm] in [0, 1e8]; g HG anisotropy in (-1, 1) (default 0).\n"
	    "                         mua = mus = 0 makes a clear layer (e.g. sebum).\n"
	    "  --n-above N            index of the medium above [1, 10] (default 1)\n"
	    "  --n-below N            index of the medium below [1, 10] (default 1)\n"
	    "  --theta-in DEG         incidence angle [0, 90) degrees (default 0)\n"
	    "  --photons N            photons [1, 1e12] (default 1e6)\n"
	    "  --seed N               random seed [0, 2^63-1] (default 1)\n"
	    "  --threads N            OpenMP threads [0, 1024], 0 = all cores (default 0)\n"
	    "  --batches N            independent batches for standard errors [2, 100000] (default 32)\n"
	    "  --fresnel exact|schlick  reflectance model at every boundary (default exact)\n"
	    "  --theta-out-step DEG   width of theta_out bands, must divide 90 (default 5)\n"
	    "  --phi-step DEG         width of delta_phi bins, must divide 180 (default 5)\n"
	    "  --r-step CM            radial bin width of Rd(r) [cm] in [1e-7, 100] (default 0.005)\n"
	    "  --r-bins N             radial bins of Rd(r) [0, 100000], 0 = off (default 100)\n"
	    "  --roulette-w W         weight threshold for roulette [0, 1] (default 0.2)\n"
	    "  --roulette-chance P    roulette survival probability (0, 1] (default 0.3)\n"
	    "  --max-steps N          interactions per photon before the guard ends it,\n"
	    "                         booked as 'lost' [1, 1e12] (default 1e6)\n"
	    "  --json                 one JSON object on stdout instead of a table\n"
	    "  --help                 this text\n"
	    "\n"
	    "Rd excludes the specular reflection Rsp (MCML convention); Tt includes\n"
	    "unscattered light.  BRDF values are in 1/sr: the fraction of incident power\n"
	    "leaving through a band divided by the band's integral of cos(theta) d(omega).\n"
	    "delta_phi = 0 points back toward the source, 180 to the mirror side.\n",
	    SLAB_MAX_LAYERS);
}

/* Parse "d=0.02,n=1,mua=10,mus=90,g=0.75". */
static int parse_layer(const char *spec, int idx, struct layer *l)
{
	char *s = xstrdup(spec), *save = NULL;
	int have_d = 0, have_a = 0, have_s = 0, rc = -1;
	*l = (struct layer){ .n = 1.0 };
	for (char *tok = strtok_r(s, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
		char *eq = strchr(tok, '=');
		if (eq == NULL) {
			cli_usage_error(CMD, "--layer %d: '%s' is not key=value (keys d, n, mua, mus, g)", idx, tok);
			goto out;
		}
		*eq = '\0';
		const char *k = tok, *v = eq + 1;
		double x;
		if (strcmp(k, "d") == 0 && (strcmp(v, "inf") == 0 || strcmp(v, "INF") == 0)) {
			l->d = INFINITY;
			have_d = 1;
			continue;
		}
		if (util_parse_double(v, &x) != 0) {
			static const char *const keys[] = { "d", "n", "mua", "mus", "g" };
			static const char *const ranges[] = { "(0, inf) cm, or inf for the last layer", "[1, 10]",
				"[0, 1e8] 1/cm", "[0, 1e8] 1/cm", "(-1, 1)" };
			const char *range = NULL;
			for (int i = 0; i < 5; i++)
				if (strcmp(k, keys[i]) == 0)
					range = ranges[i];
			if (range == NULL)
				cli_usage_error(CMD, "--layer %d: unknown key '%s' (keys d, n, mua, mus, g)", idx, k);
			else
				cli_usage_error(CMD, "--layer %d: %s = '%s' is not a number (allowed range %s)", idx, k, v, range);
			goto out;
		}
		if (strcmp(k, "d") == 0)
			l->d = x, have_d = 1;
		else if (strcmp(k, "n") == 0)
			l->n = x;
		else if (strcmp(k, "mua") == 0)
			l->mu_a = x, have_a = 1;
		else if (strcmp(k, "mus") == 0)
			l->mu_s = x, have_s = 1;
		else if (strcmp(k, "g") == 0)
			l->g = x;
		else {
			cli_usage_error(CMD, "--layer %d: unknown key '%s' (keys d, n, mua, mus, g)", idx, k);
			goto out;
		}
	}
	if (!have_d || !have_a || !have_s) {
		cli_usage_error(CMD, "--layer %d: '%s' lacks %s (required keys d, mua, mus)", idx, spec,
		    !have_d ? "d" : !have_a ? "mua" : "mus");
		goto out;
	}
	rc = 0;
out:
	free(s);
	return rc;
}

static int divides(double whole, double step)
{
	double n = whole / step;
	return fabs(n - round(n)) < 1e-9 && round(n) >= 1 && round(n) <= 10000;
}

/* JSON has no NaN: a value that cannot be estimated (e.g. the error of a
 * single batch) is null. */
static json_object *jnum(double v)
{
	return isfinite(v) ? json_object_new_double(v) : NULL;
}

static json_object *jarray(const double *v, int n)
{
	json_object *a = json_object_new_array_ext(n);
	for (int i = 0; i < n; i++)
		json_object_array_add(a, jnum(v[i]));
	return a;
}

static void print_json(const struct sim_config *c, const struct sim_result *r)
{
	const struct tally_grid *g = &r->grid;
	json_object *o = json_object_new_object();
	json_object_object_add(o, "photons", json_object_new_int64(r->photons));
	json_object_object_add(o, "seconds", jnum(r->seconds));
	json_object_object_add(o, "theta_in_deg", jnum(c->theta_in * 180.0 / M_PI));
	json_object_object_add(o, "seed", json_object_new_int64((int64_t)c->seed));
	json_object_object_add(o, "Rsp", jnum(r->rsp));
	json_object_object_add(o, "Rd", jnum(r->rd.v));
	json_object_object_add(o, "Rd_err", jnum(r->rd.err));
	json_object_object_add(o, "Rd_unscattered", jnum(r->rd_unscat.v));
	json_object_object_add(o, "Rd_unscattered_err", jnum(r->rd_unscat.err));
	json_object_object_add(o, "Tt", jnum(r->tt.v));
	json_object_object_add(o, "Tt_err", jnum(r->tt.err));
	json_object_object_add(o, "Tt_unscattered", jnum(r->tt_unscat.v));
	double a[SLAB_MAX_LAYERS], ae[SLAB_MAX_LAYERS];
	for (int i = 0; i < r->n_layers; i++)
		a[i] = r->a[i + 1].v, ae[i] = r->a[i + 1].err;
	json_object_object_add(o, "A", jarray(a, r->n_layers));
	json_object_object_add(o, "A_err", jarray(ae, r->n_layers));
	json_object_object_add(o, "lost", jnum(r->lost.v));
	json_object_object_add(o, "balance", jnum(r->balance));
	json_object_object_add(o, "scattering_events", jnum(r->events));
	json_object_object_add(o, "photons_per_second", jnum(r->photons / r->seconds));
	json_object_object_add(o, "events_per_second", jnum(r->events / r->seconds));

	double *edges = xmalloc(sizeof(double) * (size_t)(g->n_theta + 1));
	for (int i = 0; i <= g->n_theta; i++)
		edges[i] = 90.0 * i / g->n_theta;
	json_object *bz = json_object_new_object();
	json_object_object_add(bz, "theta_out_edges_deg", jarray(edges, g->n_theta + 1));
	json_object_object_add(bz, "fr", jarray(r->fr_az, g->n_theta));
	json_object_object_add(bz, "fr_err", jarray(r->fr_az_err, g->n_theta));
	json_object_object_add(o, "brdf_az", bz);

	double *pe = xmalloc(sizeof(double) * (size_t)(g->n_phi + 1));
	for (int i = 0; i <= g->n_phi; i++)
		pe[i] = 180.0 * i / g->n_phi;
	json_object *b2 = json_object_new_object();
	json_object_object_add(b2, "theta_out_edges_deg", jarray(edges, g->n_theta + 1));
	json_object_object_add(b2, "delta_phi_edges_deg", jarray(pe, g->n_phi + 1));
	json_object_object_add(b2, "layout", json_object_new_string("row-major [theta_out][delta_phi]"));
	json_object_object_add(b2, "fr", jarray(r->fr, g->n_theta * g->n_phi));
	json_object_object_add(b2, "fr_err", jarray(r->fr_err, g->n_theta * g->n_phi));
	json_object_object_add(o, "brdf", b2);
	free(pe);
	free(edges);

	if (g->n_r > 0) {
		double *re = xmalloc(sizeof(double) * (size_t)(g->n_r + 1));
		for (int i = 0; i <= g->n_r; i++)
			re[i] = g->dr * i;
		json_object *rr = json_object_new_object();
		json_object_object_add(rr, "r_edges_cm", jarray(re, g->n_r + 1));
		json_object_object_add(rr, "rd_per_cm2", jarray(r->rd_r, g->n_r));
		json_object_object_add(rr, "rd_err", jarray(r->rd_r_err, g->n_r));
		json_object_object_add(o, "Rd_r", rr);
		free(re);
	}
	printf("%s\n", json_object_to_json_string_ext(o, JSON_C_TO_STRING_PLAIN | JSON_C_TO_STRING_NOSLASHESCAPE));
	json_object_put(o);
}

static void print_table(const struct sim_config *c, const struct sim_result *r)
{
	printf("skinbake simulate: %ld photons, theta_in %.4g deg, seed %llu, %.3f s "
	    "(%.3g photons/s, %.3g events/s)\n\n", r->photons, c->theta_in * 180.0 / M_PI,
	    (unsigned long long)c->seed, r->seconds, r->photons / r->seconds, r->events / r->seconds);
	printf("  %-18s %12s %12s\n", "quantity", "value", "std.err");
	printf("  %-18s %12.6f %12s\n", "Rsp", r->rsp, "exact");
	printf("  %-18s %12.6f %12.2e\n", "Rd", r->rd.v, r->rd.err);
	printf("  %-18s %12.6f %12.2e\n", "  unscattered", r->rd_unscat.v, r->rd_unscat.err);
	printf("  %-18s %12.6f %12.2e\n", "Tt", r->tt.v, r->tt.err);
	printf("  %-18s %12.6f %12.2e\n", "  unscattered", r->tt_unscat.v, r->tt_unscat.err);
	for (int i = 1; i <= r->n_layers; i++) {
		char name[32];
		snprintf(name, sizeof name, "A layer %d", i);
		printf("  %-18s %12.6f %12.2e\n", name, r->a[i].v, r->a[i].err);
	}
	printf("  %-18s %12.3g\n", "lost", r->lost.v);
	printf("  %-18s %12.3g\n", "balance - 1", r->balance);
	printf("\n  azimuth-averaged diffuse BRDF [1/sr]\n  %-18s %12s %12s\n", "theta_out [deg]", "fr", "std.err");
	for (int i = 0; i < r->grid.n_theta; i++) {
		char band[32];
		snprintf(band, sizeof band, "%5.1f - %5.1f", 90.0 * i / r->grid.n_theta, 90.0 * (i + 1) / r->grid.n_theta);
		printf("  %-18s %12.6f %12.2e\n", band, r->fr_az[i], r->fr_az_err[i]);
	}
}

int cmd_simulate(int argc, char **argv)
{
	enum { O_LAYER = 256, O_NA, O_NB, O_TH, O_PH, O_SEED, O_THR, O_BAT, O_FR, O_TOS, O_PHS, O_RS, O_RB,
		O_RW, O_RC, O_MS, O_JSON, O_HELP };
	static const struct option opts[] = {
		{ "layer", required_argument, 0, O_LAYER }, { "n-above", required_argument, 0, O_NA },
		{ "n-below", required_argument, 0, O_NB }, { "theta-in", required_argument, 0, O_TH },
		{ "photons", required_argument, 0, O_PH }, { "seed", required_argument, 0, O_SEED },
		{ "threads", required_argument, 0, O_THR }, { "batches", required_argument, 0, O_BAT },
		{ "fresnel", required_argument, 0, O_FR }, { "theta-out-step", required_argument, 0, O_TOS },
		{ "phi-step", required_argument, 0, O_PHS }, { "r-step", required_argument, 0, O_RS },
		{ "r-bins", required_argument, 0, O_RB }, { "roulette-w", required_argument, 0, O_RW },
		{ "roulette-chance", required_argument, 0, O_RC }, { "max-steps", required_argument, 0, O_MS },
		{ "json", no_argument, 0, O_JSON }, { "help", no_argument, 0, O_HELP }, { 0, 0, 0, 0 }
	};
	struct sim_config c;
	sim_config_default(&c);
	struct layer layers[SLAB_MAX_LAYERS];
	int nl = 0, json = 0, ch;
	double na = 1.0, nbw = 1.0, th = 0.0, tos = 5.0, phs = 5.0, v;
	long lv;
	char *cause = NULL;

	opterr = 0;
	optind = 1;
	while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (ch) {
		case O_LAYER:
			if (nl >= SLAB_MAX_LAYERS)
				return cli_usage_error(CMD, "--layer: at most %d layers are allowed", SLAB_MAX_LAYERS);
			if (parse_layer(optarg, nl + 1, &layers[nl]) != 0)
				return CLI_EXIT_USAGE;
			nl++;
			break;
		case O_NA: if (cli_double(CMD, "--n-above", optarg, 1, 10, &na)) return CLI_EXIT_USAGE; break;
		case O_NB: if (cli_double(CMD, "--n-below", optarg, 1, 10, &nbw)) return CLI_EXIT_USAGE; break;
		case O_TH:
			if (cli_double(CMD, "--theta-in", optarg, 0, 90, &th)) return CLI_EXIT_USAGE;
			if (th >= 90.0)
				return cli_usage_error(CMD, "--theta-in = %g is out of range [0, 90) degrees", th);
			break;
		case O_PH: if (cli_long(CMD, "--photons", optarg, 1, 1000000000000L, &c.photons)) return CLI_EXIT_USAGE; break;
		case O_SEED: if (cli_long(CMD, "--seed", optarg, 0, 9223372036854775807L, &lv)) return CLI_EXIT_USAGE;
			c.seed = (uint64_t)lv; break;
		case O_THR: if (cli_long(CMD, "--threads", optarg, 0, 1024, &lv)) return CLI_EXIT_USAGE;
			c.threads = (int)lv; break;
		case O_BAT: if (cli_long(CMD, "--batches", optarg, 2, 100000, &lv)) return CLI_EXIT_USAGE;
			c.batches = (int)lv; break;
		case O_FR: {
			int m;
			if (cli_fresnel(CMD, optarg, &m))
				return CLI_EXIT_USAGE;
			c.opts.fresnel = (enum optics_fresnel)m;
			break;
		}
		case O_TOS:
			if (cli_double(CMD, "--theta-out-step", optarg, 0.01, 90, &tos)) return CLI_EXIT_USAGE;
			if (!divides(90.0, tos))
				return cli_usage_error(CMD, "--theta-out-step = %g does not divide 90 degrees", tos);
			break;
		case O_PHS:
			if (cli_double(CMD, "--phi-step", optarg, 0.01, 180, &phs)) return CLI_EXIT_USAGE;
			if (!divides(180.0, phs))
				return cli_usage_error(CMD, "--phi-step = %g does not divide 180 degrees", phs);
			break;
		case O_RS: if (cli_double(CMD, "--r-step", optarg, 1e-7, 100, &c.grid.dr)) return CLI_EXIT_USAGE; break;
		case O_RB: if (cli_long(CMD, "--r-bins", optarg, 0, 100000, &lv)) return CLI_EXIT_USAGE;
			c.grid.n_r = (int)lv; break;
		case O_RW: if (cli_double(CMD, "--roulette-w", optarg, 0, 1, &c.opts.roulette_w)) return CLI_EXIT_USAGE; break;
		case O_RC:
			if (cli_double(CMD, "--roulette-chance", optarg, 0, 1, &v)) return CLI_EXIT_USAGE;
			if (v <= 0.0)
				return cli_usage_error(CMD, "--roulette-chance = %g is out of range (0, 1]", v);
			c.opts.roulette_chance = v;
			break;
		case O_MS: if (cli_long(CMD, "--max-steps", optarg, 1, 1000000000000L, &c.opts.max_steps)) return CLI_EXIT_USAGE; break;
		case O_JSON: json = 1; break;
		case 'h':
		case O_HELP: help(stdout); return CLI_EXIT_OK;
		default:
			return cli_usage_error(CMD, "unknown or incomplete option '%s' (see skinbake simulate --help)",
			    argv[optind - 1]);
		}
	}
	if (optind < argc)
		return cli_usage_error(CMD, "unexpected argument '%s'", argv[optind]);
	if (nl == 0)
		return cli_usage_error(CMD, "at least one --layer is required (see skinbake simulate --help)");
	(void)v;

	slab_init(&c.slab, na, nbw);
	for (int i = 0; i < nl; i++)
		slab_add(&c.slab, &layers[i], &cause);
	if (slab_check(&c.slab, &cause) != 0) {
		int rc = cli_usage_error(CMD, "--%s", cause);
		free(cause);
		return rc;
	}
	slab_prepare(&c.slab);
	c.theta_in = th * M_PI / 180.0;
	c.grid.n_theta = (int)round(90.0 / tos);
	c.grid.n_phi = (int)round(180.0 / phs);
	if ((long)c.grid.n_theta * c.grid.n_phi > 1000000)
		return cli_usage_error(CMD, "--theta-out-step %g and --phi-step %g give %ld bins; at most 1e6 are allowed",
		    tos, phs, (long)c.grid.n_theta * c.grid.n_phi);

	struct sim_result r;
	struct cli_progress pr;
	cli_progress_start(&pr, "simulate");
	sim_run(&c, &r, cli_progress_update, &pr);
	cli_progress_end(&pr);
	if (json)
		print_json(&c, &r);
	else
		print_table(&c, &r);
	sim_result_free(&r);
	return CLI_EXIT_OK;
}
