/* verify: recompute a sample of a bake's cells by Monte Carlo and judge the
 * agreement by z-scores (see verify.h). */
#include "config.h"
#include "bake/verify.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"
#include "bake/bakeinterp.h"
#include "bake/manifest.h"
#include "base/check.h"
#include "base/util.h"
#include "engine/ad_quad.h"
#include "engine/mc.h"
#include "io/json.h"

enum { MC_BATCHES = 32 };

void verify_opts_default(struct verify_opts *o)
{
	*o = (struct verify_opts){ .cells = 32, .cells_per_pair = 1, .photons = 50000, .seed = 20261, .threads = 0 };
}

/* ---- statistics ---- */

/* Continued fraction of the incomplete beta function (modified Lentz;
 * DLMF 8.17.22). */
static double beta_cf(double a, double b, double x)
{
	const double tiny = 1e-300;
	double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
	d = 1.0 / (fabs(d) < tiny ? tiny : d);
	double h = d;
	for (int m = 1; m <= 500; m++) {
		for (int odd = 0; odd < 2; odd++) {
			double num = odd ? -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))
					 : m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
			d = 1.0 + num * d;
			d = 1.0 / (fabs(d) < tiny ? tiny : d);
			c = 1.0 + num / c;
			c = fabs(c) < tiny ? tiny : c;
			h *= d * c;
			if (odd && fabs(d * c - 1.0) < 1e-15)
				return h;
		}
	}
	return h;
}

/* Regularized incomplete beta function I_x(a, b). */
static double beta_inc(double a, double b, double x)
{
	if (x <= 0.0)
		return 0.0;
	if (x >= 1.0)
		return 1.0;
	double lbt = lgamma(a + b) - lgamma(a) - lgamma(b) + a * log(x) + b * log1p(-x);
	if (x < (a + 1.0) / (a + b + 2.0))
		return exp(lbt) * beta_cf(a, b, x) / a;
	return 1.0 - exp(lbt) * beta_cf(b, a, 1.0 - x) / b;
}

/* The z > 0 with P(|N(0,1)| > z) = p. */
static double normal_two_sided(double p)
{
	if (p <= 1e-300)
		return 37.0;
	double lo = 0.0, hi = 38.0;
	for (int i = 0; i < 200; i++) {
		double mid = 0.5 * (lo + hi);
		if (erfc(mid / M_SQRT2) > p)
			lo = mid;
		else
			hi = mid;
	}
	return 0.5 * (lo + hi);
}

/* t with dof degrees of freedom as the normal quantile of the same tail. */
static double t_to_normal(double t, double dof)
{
	if (!isfinite(dof) || dof > 1e7)
		return t;
	double p = beta_inc(0.5 * dof, 0.5, dof / (dof + t * t));	/* P(|T| > |t|) */
	if (p <= 1e-300)
		return t;	/* beyond any limit either way */
	return copysign(normal_two_sided(p), t);
}

/* ---- cells ---- */

static long gcd(long a, long b)
{
	while (b) {
		long t = a % b;
		a = b;
		b = t;
	}
	return a;
}

/* Bin j of pair k: a golden-ratio stride through the nb bins (coprime, so
 * distinct for j < nb), starting at a place of its own for each pair. */
static long pair_bin(int k, int j, long nb)
{
	long s = lround(0.6180339887498949 * (double)nb);
	while (s > 1 && gcd(s, nb) != 1)
		s++;
	if (s < 1)
		s = 1;
	return ((long)k * 7919 + (long)j * s) % nb;
}

/* One pair's re-run: entry (w, ti) of the bake on its own grid. */
static int rerun(const struct bake_provenance *pv, const struct bake *b, int w, int ti, const struct verify_opts *o,
    int k, struct brdf_table *t, char **cause)
{
	struct mc_settings mc;
	mc_settings_default(&mc);
	mc.seed = o->seed + (uint64_t)k;
	mc.batch_photons = (o->photons + MC_BATCHES - 1) / MC_BATCHES;
	mc.min_batches = MC_BATCHES;
	mc.max_photons = MC_BATCHES * mc.batch_photons;
	struct solver_problem p = { .n_wl = 1, .wl_nm = &b->wl_nm[w], .slab = &pv->slab[w], .n_ti = 1,
		.theta_i = &b->theta_i[ti], .grid = { .n_theta = b->n_to, .n_phi = b->n_phi }, .fresnel = pv->fresnel };
	struct solver_run run = { .threads = o->threads, .n_ranks = 1 };
	return solver_solve(&mc_solver, &mc, &p, &run, t, cause);
}

/* The bake's bin mean of entry (w, ti) and its error: the table's value
 * (bin means), or for point values the mean of the interpolated function
 * over the bin (Gauss-Legendre in theta_o weighted by cos sin, uniform in
 * delta_phi) with the mean of its error bound. */
static void bake_cell(const struct bake *b, int w, int ti, long bin, double *f, double *e)
{
	size_t idx = ((size_t)w * b->n_ti + (size_t)ti) * (size_t)b->n_to * b->n_phi + (size_t)bin;
	if (!b->points || !b->points[w]) {
		*f = b->fr[idx];
		*e = b->fr_err[idx];
		return;
	}
	enum { NG = 8 };
	int it = (int)(bin / b->n_phi), ip = (int)(bin % b->n_phi);
	double t0 = 0.5 * M_PI * it / b->n_to, t1 = 0.5 * M_PI * (it + 1) / b->n_to;
	double p0 = M_PI * ip / b->n_phi, p1 = M_PI * (ip + 1) / b->n_phi;
	double xt[NG], wt[NG], xp[NG], wp[NG], num = 0.0, err = 0.0, den = 0.0;
	ad_gauss_legendre(NG, t0, t1, xt, wt);
	ad_gauss_legendre(NG, p0, p1, xp, wp);
	for (int a = 0; a < NG; a++)
		for (int c = 0; c < NG; c++) {
			double g = wt[a] * wp[c] * cos(xt[a]) * sin(xt[a]), ev;
			num += g * bake_interp_eval(b, w, b->theta_i[ti], xt[a], xp[c], &ev);
			err += g * ev;
			den += g;
		}
	*f = num / den;
	*e = err / den;
}

static void summarize(struct verify_result *r)
{
	int n = r->n_cells, beyond = 0;
	double s = 0.0, sn = 0.0;
	for (int i = 0; i < n; i++) {
		const struct verify_cell *c = &r->cell[i];
		s += c->z * c->z;
		sn += c->z_n * c->z_n;
		r->max_abs_z = fmax(r->max_abs_z, fabs(c->z));
		r->max_abs_zn = fmax(r->max_abs_zn, fabs(c->z_n));
		beyond += fabs(c->z) > 3.0;
	}
	r->mean_z2 = n ? s / n : 0.0;
	r->mean_zn2 = n ? sn / n : 0.0;
	r->frac_3sigma = n ? (double)beyond / n : 0.0;
	/* Wilson-Hilferty: chi^2_n quantile = n (1 - 2/(9n) + z sqrt(2/(9n)))^3, z(99.9%) = 3.0902. */
	double h = 2.0 / (9.0 * (n > 0 ? n : 1));
	r->mean_z2_limit = pow(1.0 - h + 3.0902 * sqrt(h), 3.0);
	r->max_z_limit = normal_two_sided(0.001 / (n > 0 ? n : 1));
	r->consistent = n > 0 && r->mean_zn2 <= r->mean_z2_limit && r->max_abs_zn <= r->max_z_limit;
}

int verify_bake(const char *dir, const struct verify_opts *o, struct verify_result *r, char **cause)
{
	CHECK(o->cells >= 1 && o->cells_per_pair >= 1 && o->photons >= 1);
	memset(r, 0, sizeof *r);
	struct bake_provenance pv;
	struct bake *b = bake_load(dir, cause);
	if (b == NULL)
		return -1;
	if (bake_provenance_read(dir, &pv, cause) != 0) {
		bake_free(b);
		return -1;
	}
	snprintf(r->solver, sizeof r->solver, "%s", pv.solver);
	long nb = (long)b->n_to * b->n_phi, n_entries = (long)b->n_wl * b->n_ti;
	int cells = o->cells < n_entries * nb ? o->cells : (int)(n_entries * nb);
	/* One re-run of its own (seed) per cells_per_pair cells: cells of one
	 * run share photons and their errors move together. */
	int n_runs = (cells + o->cells_per_pair - 1) / o->cells_per_pair;
	r->cell = xcalloc((size_t)cells, sizeof *r->cell);
	r->n_pairs = n_runs;
	double t0 = util_now();
	for (int k = 0; k < n_runs; k++) {
		/* Angles stepped evenly, wavelengths cycled (runs beyond the
		 * entries repeat them with other seeds and bins). */
		int ti = (int)((long)(k % n_entries) * b->n_ti / (n_runs < n_entries ? n_runs : n_entries)), w = k % b->n_wl;
		struct brdf_table t;
		if (rerun(&pv, b, w, ti, o, k, &t, cause) != 0) {
			verify_result_free(r);
			break;
		}
		r->photons += t.photons;
		double nu_mc = (double)(t.entry[0].batches - 1);
		long bb = pv.entry_batches[w * b->n_ti + ti];
		double nu_b = pv.entry_mc[w * b->n_ti + ti] && bb > 1 ? (double)(bb - 1) : INFINITY;
		for (int j = 0; j < o->cells_per_pair && r->n_cells < cells; j++) {
			long bin = pair_bin(k, j, nb);
			struct verify_cell *v = &r->cell[r->n_cells];
			double fb, eb;
			bake_cell(b, w, ti, bin, &fb, &eb);
			*v = (struct verify_cell){ b->wl_nm[w], b->theta_i[ti] * 180.0 / M_PI, b->theta_o[bin / b->n_phi] * 180.0 / M_PI,
				b->phi[bin % b->n_phi] * 180.0 / M_PI, fb, eb, t.entry[0].fr[bin], t.entry[0].fr_err[bin],
				0.0, 0.0, 0.0 };
			double vb = v->e_bake * v->e_bake, vm = v->e_mc * v->e_mc, den = vb * vb / nu_b + vm * vm / nu_mc;
			if (vb + vm <= 0.0)
				continue;	/* both exact (no light here): nothing to compare */
			v->z = (v->f_bake - v->f_mc) / sqrt(vb + vm);
			v->dof = den > 0.0 ? (vb + vm) * (vb + vm) / den : INFINITY;
			v->z_n = t_to_normal(v->z, v->dof);
			r->n_cells++;
		}
		brdf_table_free(&t);
		if (o->progress)
			o->progress(o->progress_user, k + 1, n_runs);
	}
	r->seconds = util_now() - t0;
	bake_provenance_free(&pv);
	bake_free(b);
	if (r->cell == NULL)
		return -1;
	summarize(r);
	return 0;
}

void verify_result_free(struct verify_result *r)
{
	free(r->cell);
	memset(r, 0, sizeof *r);
}

/* ---- reports ---- */


char *verify_json(const char *dir, const struct verify_result *r)
{
	json_object *o = json_object_new_object(), *cells = json_object_new_array(), *s = json_object_new_object();
	json_object_object_add(o, "bake", json_object_new_string(dir));
	json_object_object_add(o, "solver", json_object_new_string(r->solver));
	for (int i = 0; i < r->n_cells; i++) {
		const struct verify_cell *c = &r->cell[i];
		json_object *jc = json_object_new_object();
		const char *k[] = { "wavelength_nm", "theta_i_deg", "theta_o_deg", "delta_phi_deg", "f_bake", "f_bake_err",
			"f_mc", "f_mc_err", "z", "dof", "z_normal" };
		const double v[] = { c->wl_nm, c->theta_i_deg, c->theta_o_deg, c->dphi_deg, c->f_bake, c->e_bake, c->f_mc,
			c->e_mc, c->z, c->dof, c->z_n };
		for (size_t j = 0; j < sizeof v / sizeof v[0]; j++)
			json_object_object_add(jc, k[j], json_num(v[j]));	/* dof: null when exact */
		json_object_array_add(cells, jc);
	}
	json_object_object_add(o, "cells", cells);
	json_object_object_add(s, "cells", json_object_new_int(r->n_cells));
	json_object_object_add(s, "pairs", json_object_new_int(r->n_pairs));
	json_object_object_add(s, "photons", json_object_new_int64(r->photons));
	json_object_object_add(s, "seconds", json_num(r->seconds));
	json_object_object_add(s, "mean_z2", json_num(r->mean_z2));
	json_object_object_add(s, "max_abs_z", json_num(r->max_abs_z));
	json_object_object_add(s, "frac_beyond_3sigma", json_num(r->frac_3sigma));
	json_object_object_add(s, "mean_z_normal2", json_num(r->mean_zn2));
	json_object_object_add(s, "max_abs_z_normal", json_num(r->max_abs_zn));
	json_object_object_add(s, "mean_z2_limit", json_num(r->mean_z2_limit));
	json_object_object_add(s, "max_abs_z_limit", json_num(r->max_z_limit));
	json_object_object_add(s, "consistent", json_object_new_boolean(r->consistent));
	json_object_object_add(o, "summary", s);
	char *text = json_text(o, JSON_PLAIN);
	json_object_put(o);
	return text;
}

void verify_table(FILE *fp, const char *dir, const struct verify_result *r)
{
	fprintf(fp, "skinbake verify: %s (solver %s) against Monte Carlo: %d cells in %d (wavelength, angle) pairs, "
	    "%ld photons, %.2f s\n\n", dir, r->solver, r->n_cells, r->n_pairs, r->photons, r->seconds);
	fprintf(fp, "  %6s %6s %6s %6s %12s %10s %12s %10s %7s %5s\n", "wl", "th_i", "th_o", "dphi", "bake", "error", mc_solver.name,
	    "std.err", "z", "dof");
	for (int i = 0; i < r->n_cells; i++) {
		const struct verify_cell *c = &r->cell[i];
		fprintf(fp, "  %6.0f %6.1f %6.1f %6.1f %12.6g %10.3g %12.6g %10.3g %7.2f %5.0f\n", c->wl_nm, c->theta_i_deg,
		    c->theta_o_deg, c->dphi_deg, c->f_bake, c->e_bake, c->f_mc, c->e_mc, c->z, isfinite(c->dof) ? c->dof : -1);
	}
	fprintf(fp, "\n  mean z^2 %.3f, max |z| %.2f, beyond 3 sigma %.1f%% (dof -1: the bake's error is exact)\n",
	    r->mean_z2, r->max_abs_z, 100.0 * r->frac_3sigma);
	fprintf(fp, "  verdict (z as normal quantiles through Student's t): mean %.3f (limit %.3f), "
	    "max %.2f (limit %.2f): %s\n",
	    r->mean_zn2, r->mean_z2_limit, r->max_abs_zn, r->max_z_limit,
	    r->consistent ? "consistent" : "NOT consistent");
}
