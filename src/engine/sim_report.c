/* sim_report: one stack's results as JSON or a table, for either method
 * (see sim_report.h). */
#include "config.h"
#include "engine/sim_report.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "io/json.h"

/* JSON has no NaN: a value that cannot be estimated (e.g. the error of a
 * single batch) is null. */

static json_object *jarray(const double *v, int n)
{
	json_object *a = json_object_new_array_ext(n);
	for (int i = 0; i < n; i++)
		json_object_array_add(a, json_num(v[i]));
	return a;
}

static void add(json_object *o, const char *key, json_object *v)
{
	json_object_object_add(o, key, v);
}

/* The totals, Rsp to the balance. */
static void add_totals(json_object *o, const struct sim_result *r)
{
	add(o, "Rsp", json_num(r->rsp));
	add(o, "Rd", json_num(r->rd.v));
	add(o, "Rd_err", json_num(r->rd.err));
	add(o, "Rd_unscattered", json_num(r->rd_unscat.v));
	add(o, "Rd_unscattered_err", json_num(r->rd_unscat.err));
	add(o, "Tt", json_num(r->tt.v));
	add(o, "Tt_err", json_num(r->tt.err));
	add(o, "Tt_unscattered", json_num(r->tt_unscat.v));
	double a[SLAB_MAX_LAYERS], ae[SLAB_MAX_LAYERS];
	for (int i = 0; i < r->n_layers; i++) {
		a[i] = r->a[i + 1].v;
		ae[i] = r->a[i + 1].err;
	}
	add(o, "A", jarray(a, r->n_layers));
	add(o, "A_err", jarray(ae, r->n_layers));
	add(o, "lost", json_num(r->lost.v));
	if (r->rsp_err > 0.0 || r->facet_loss.v > 0.0) {
		/* Rough boundaries only, so smooth stacks' reports stay as they were. */
		add(o, "Rsp_err", json_num(r->rsp_err));
		add(o, "facet_loss", json_num(r->facet_loss.v));
		add(o, "facet_loss_err", json_num(r->facet_loss.err));
	}
	add(o, "balance", json_num(r->balance));
}

/* brdf_az, brdf and Rd_r. */
static void add_tables(json_object *o, const struct sim_result *r)
{
	const struct tally_grid *g = &r->grid;
	double *edges = xmalloc(sizeof(double) * (size_t)(g->n_theta + 1));
	for (int i = 0; i <= g->n_theta; i++)
		edges[i] = 90.0 * i / g->n_theta;
	json_object *bz = json_object_new_object();
	add(bz, "theta_out_edges_deg", jarray(edges, g->n_theta + 1));
	add(bz, "fr", jarray(r->fr_az, g->n_theta));
	add(bz, "fr_err", jarray(r->fr_az_err, g->n_theta));
	add(o, "brdf_az", bz);
	double *pe = xmalloc(sizeof(double) * (size_t)(g->n_phi + 1));
	for (int i = 0; i <= g->n_phi; i++)
		pe[i] = 180.0 * i / g->n_phi;
	json_object *b2 = json_object_new_object();
	add(b2, "theta_out_edges_deg", jarray(edges, g->n_theta + 1));
	add(b2, "delta_phi_edges_deg", jarray(pe, g->n_phi + 1));
	add(b2, "layout", json_object_new_string("row-major [theta_out][delta_phi]"));
	add(b2, "fr", jarray(r->fr, g->n_theta * g->n_phi));
	add(b2, "fr_err", jarray(r->fr_err, g->n_theta * g->n_phi));
	add(o, "brdf", b2);
	free(pe);
	free(edges);
	if (g->n_r > 0) {
		double *re = xmalloc(sizeof(double) * (size_t)(g->n_r + 1));
		for (int i = 0; i <= g->n_r; i++)
			re[i] = g->dr * i;
		json_object *rr = json_object_new_object();
		add(rr, "r_edges_cm", jarray(re, g->n_r + 1));
		add(rr, "rd_per_cm2", jarray(r->rd_r, g->n_r));
		add(rr, "rd_err", jarray(r->rd_r_err, g->n_r));
		add(o, "Rd_r", rr);
		free(re);
	}
}

char *sim_report_json(const struct sim_config *c, const struct sim_result *r, const struct sim_solve_info *ad)
{
	json_object *o = json_object_new_object();
	if (ad) {
		add(o, "solver", json_object_new_string(ad->method));
		add(o, "seconds", json_num(r->seconds));
		add(o, "theta_in_deg", json_num(c->theta_in * 180.0 / M_PI));
		add_totals(o, r);
		add(o, "tol", json_num(ad->tol));
		add(o, "n_quad", json_object_new_int(ad->n_quad));
		add(o, "fourier_orders", json_object_new_int(ad->n_orders));
		add(o, "rms_rel_err", json_num(ad->rms_rel_err));
	} else {
		add(o, "photons", json_object_new_int64(r->photons));
		add(o, "seconds", json_num(r->seconds));
		add(o, "theta_in_deg", json_num(c->theta_in * 180.0 / M_PI));
		add(o, "seed", json_object_new_int64((int64_t)c->seed));
		add_totals(o, r);
		add(o, "scattering_events", json_num(r->events));
		add(o, "photons_per_second", json_num(r->photons / r->seconds));
		add(o, "events_per_second", json_num(r->events / r->seconds));
	}
	add_tables(o, r);
	char *s = json_text(o, JSON_PLAIN);
	json_object_put(o);
	return s;
}

void sim_report_table(FILE *fp, const struct sim_config *c, const struct sim_result *r, const struct sim_solve_info *ad)
{
	if (ad)
		fprintf(fp, "skinbake simulate: adding-doubling, theta_in %.4g deg, tolerance %g, %d nodes per unit cosine, "
		    "%d Fourier orders, %.3f s\n\n", c->theta_in * 180.0 / M_PI, ad->tol, ad->n_quad, ad->n_orders, r->seconds);
	else
		fprintf(fp, "skinbake simulate: %ld photons, theta_in %.4g deg, seed %llu, %.3f s "
		    "(%.3g photons/s, %.3g events/s)\n\n", r->photons, c->theta_in * 180.0 / M_PI,
		    (unsigned long long)c->seed, r->seconds, r->photons / r->seconds, r->events / r->seconds);
	const char *err = ad ? "error est." : "std.err";
	fprintf(fp, "  %-18s %12s %12s\n", "quantity", "value", err);
	if (r->rsp_err > 0.0)
		fprintf(fp, "  %-18s %12.6f %12.2e\n", "Rsp", r->rsp, r->rsp_err);
	else
		fprintf(fp, "  %-18s %12.6f %12s\n", "Rsp", r->rsp, "exact");
	fprintf(fp, "  %-18s %12.6f %12.2e\n", "Rd", r->rd.v, r->rd.err);
	fprintf(fp, "  %-18s %12.6f %12.2e\n", "  unscattered", r->rd_unscat.v, r->rd_unscat.err);
	fprintf(fp, "  %-18s %12.6f %12.2e\n", "Tt", r->tt.v, r->tt.err);
	fprintf(fp, "  %-18s %12.6f %12.2e\n", "  unscattered", r->tt_unscat.v, r->tt_unscat.err);
	for (int i = 1; i <= r->n_layers; i++) {
		char name[32];
		snprintf(name, sizeof name, "A layer %d", i);
		fprintf(fp, "  %-18s %12.6f %12.2e\n", name, r->a[i].v, r->a[i].err);
	}
	fprintf(fp, "  %-18s %12.3g\n", "lost", r->lost.v);
	if (r->facet_loss.v > 0.0)
		fprintf(fp, "  %-18s %12.6f %12.2e\n", "facet loss", r->facet_loss.v, r->facet_loss.err);
	fprintf(fp, "  %-18s %12.3g\n", "balance - 1", r->balance);
	fprintf(fp, "\n  azimuth-averaged diffuse BRDF [1/sr]\n  %-18s %12s %12s\n", "theta_out [deg]", "fr", err);
	for (int i = 0; i < r->grid.n_theta; i++) {
		char band[32];
		snprintf(band, sizeof band, "%5.1f - %5.1f", 90.0 * i / r->grid.n_theta, 90.0 * (i + 1) / r->grid.n_theta);
		fprintf(fp, "  %-18s %12.6f %12.2e\n", band, r->fr_az[i], r->fr_az_err[i]);
	}
}
