/* skinbake simulate: one Monte Carlo run on a layer stack given on the
 * command line; a readable table or one JSON object on stdout. */
#include "config.h"

#include <json-c/json.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "engine/sim.h"
#include "base/util.h"

/* --layer d=CM,n=N,mua=1/CM,mus=1/CM,g=G, top layer first. */
static const struct opt_key layer_keys[] = {
	{ "d", OPT_DOUBLE, offsetof(struct layer, d), .lo = 0, .hi = INFINITY, .unit = "cm",
	  .flags = OPT_REQUIRED | OPT_LO_OPEN | OPT_HI_OPEN | OPT_INF, .help = "thickness (the last layer may be inf)" },
	{ "n", OPT_DOUBLE, offsetof(struct layer, n), "1", .lo = 1, .hi = 10, .help = "refractive index" },
	{ "mua", OPT_DOUBLE, offsetof(struct layer, mu_a), .lo = 0, .hi = 1e8, .unit = "1/cm", .flags = OPT_REQUIRED,
	  .help = "absorption coefficient" },
	{ "mus", OPT_DOUBLE, offsetof(struct layer, mu_s), .lo = 0, .hi = 1e8, .unit = "1/cm", .flags = OPT_REQUIRED,
	  .help = "scattering coefficient" },
	{ "g", OPT_DOUBLE, offsetof(struct layer, g), "0", .lo = -1, .hi = 1, .flags = OPT_LO_OPEN | OPT_HI_OPEN,
	  .help = "Henyey-Greenstein anisotropy" },
	{ NULL },
};

struct layers {
	int n;
	struct layer l[SLAB_MAX_LAYERS];
};

static int add_layer(struct opt_ctx *x, const struct opt *o, const char *spec)
{
	struct layers *ls = o->dest;
	char label[32];
	snprintf(label, sizeof label, "--layer %d", ls->n + 1);
	ls->l[ls->n] = (struct layer){ 0 };
	if (opt_keys(x, label, spec, layer_keys, &ls->l[ls->n]) != 0)
		return -1;
	ls->n++;
	return 0;
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
	struct sim_config c;
	sim_config_default(&c);
	struct layers ls = { 0 };
	double na, nbw, th, tos, phs;
	long seed;
	int json = 0, fresnel;
	char *cause = NULL;
	const struct opt opts[] = {
		{ "layer", OPT_CUSTOM, &ls, "SPEC", .fn = add_layer, .keys = layer_keys, .max = SLAB_MAX_LAYERS,
		  .flags = OPT_REQUIRED | OPT_REPEAT, .help = "one layer, top layer first: KEY=VALUE,... with these keys" },
		{ "n-above", OPT_DOUBLE, &na, "N", "1", .lo = 1, .hi = 10, .help = "index of the medium above" },
		{ "n-below", OPT_DOUBLE, &nbw, "N", "1", .lo = 1, .hi = 10, .help = "index of the medium below" },
		{ "theta-in", OPT_DOUBLE, &th, "DEG", "0", .lo = 0, .hi = 90, .flags = OPT_HI_OPEN, .unit = "deg",
		  .help = "incidence angle" },
		{ "photons", OPT_LONG, &c.photons, "N", "1e6", .lo = 1, .hi = 1e12, .help = "photons" },
		{ "seed", OPT_LONG, &seed, "N", "1", .lo = 0, .hi = (double)LONG_MAX, .help = "random seed" },
		{ "threads", OPT_INT, &c.threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "batches", OPT_INT, &c.batches, "N", "32", .lo = 2, .hi = 100000,
		  .help = "independent batches for standard errors" },
		{ "fresnel", OPT_ENUM, &fresnel, .def = "exact", .choices = "exact|schlick",
		  .help = "reflectance model at every boundary" },
		{ "theta-out-step", OPT_DOUBLE, &tos, "DEG", "5", .lo = 0.01, .hi = 90, .unit = "deg",
		  .help = "width of theta_out bands (must divide 90)" },
		{ "phi-step", OPT_DOUBLE, &phs, "DEG", "5", .lo = 0.01, .hi = 180, .unit = "deg",
		  .help = "width of delta_phi bins (must divide 180)" },
		{ "r-step", OPT_DOUBLE, &c.grid.dr, "CM", "0.005", .lo = 1e-7, .hi = 100, .unit = "cm",
		  .help = "radial bin width of Rd(r)" },
		{ "r-bins", OPT_INT, &c.grid.n_r, "N", "100", .lo = 0, .hi = 100000, .help = "radial bins of Rd(r) (0 = off)" },
		{ "roulette-w", OPT_DOUBLE, &c.opts.roulette_w, "W", "0.2", .lo = 0, .hi = 1,
		  .help = "weight threshold for roulette" },
		{ "roulette-chance", OPT_DOUBLE, &c.opts.roulette_chance, "P", "0.3", .lo = 0, .hi = 1,
		  .flags = OPT_LO_OPEN, .help = "roulette survival probability" },
		{ "max-steps", OPT_LONG, &c.opts.max_steps, "N", "1e6", .lo = 1, .hi = 1e12,
		  .help = "interactions per photon before the guard ends it (booked as 'lost')" },
		{ "json", OPT_FLAG, &json, .help = "one JSON object on stdout instead of a table" },
		OPT_END
	};
	const struct opt_cmd cmd = { "simulate", "--layer SPEC [--layer SPEC ...] [options]",
		"Monte Carlo light transport (MCML with oblique incidence) in a stack of\n"
		"plane-parallel layers, top layer first.  mua = mus = 0 makes a clear layer\n"
		"(e.g. sebum).", opts,
		"Rd excludes the specular reflection Rsp (MCML convention); Tt includes\n"
		"unscattered light.  BRDF values are in 1/sr: the fraction of incident power\n"
		"leaving through a band divided by the band's integral of cos(theta) d(omega).\n"
		"delta_phi = 0 points back toward the source, 180 to the mirror side.", 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (!divides(90.0, tos))
		return opt_error(&x, "--theta-out-step = %g does not divide 90 degrees", tos);
	if (!divides(180.0, phs))
		return opt_error(&x, "--phi-step = %g does not divide 180 degrees", phs);
	c.seed = (uint64_t)seed;
	c.opts.fresnel = fresnel == 0 ? OPTICS_FRESNEL_EXACT : OPTICS_FRESNEL_SCHLICK;

	slab_init(&c.slab, na, nbw);
	for (int i = 0; i < ls.n; i++)
		slab_add(&c.slab, &ls.l[i], &cause);
	if (slab_check(&c.slab, &cause) != 0) {
		int rc = opt_error(&x, "--%s", cause);
		free(cause);
		return rc;
	}
	slab_prepare(&c.slab);
	c.theta_in = th * M_PI / 180.0;
	c.grid.n_theta = (int)round(90.0 / tos);
	c.grid.n_phi = (int)round(180.0 / phs);
	if ((long)c.grid.n_theta * c.grid.n_phi > 1000000)
		return opt_error(&x, "--theta-out-step %g and --phi-step %g give %ld bins; at most 1e6 are allowed",
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
