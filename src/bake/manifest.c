/* manifest: write manifest.json of a bake directory (io/json); the reader
 * is manifest_read.c. */
#include "config.h"
#include "bake/manifest.h"

#include <errno.h>
#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/check.h"
#include "base/util.h"
#include "engine/solvers.h"
#include "io/json.h"

static json_object *jarr(const double *v, int n)
{
	return json_num_array(v, n);
}

static json_object *jarr_deg(const double *v, int n)
{
	json_object *a = json_object_new_array_ext(n);
	for (int i = 0; i < n; i++)
		json_object_array_add(a, json_num(v[i] * 180.0 / M_PI));
	return a;
}

static void add(json_object *o, const char *key, json_object *v)
{
	json_object_object_add(o, key, v);
}

static json_object *jstr(const char *s)
{
	return json_object_new_string(s);
}

/* Wavelengths, incidence nodes, and the exit bins' edges and centres [deg]. */
static void add_axes(json_object *o, const struct bake_spec *s)
{
	int nto = s->n_to, np = s->n_phi;
	add(o, "wavelengths_nm", jarr(s->wl_nm, s->n_wl));
	add(o, "theta_i_deg", jarr_deg(s->theta_i, s->n_ti));
	double *e = xmalloc(sizeof(double) * (size_t)(nto + np + 2));
	for (int i = 0; i <= nto; i++)
		e[i] = 90.0 * i / nto;
	add(o, "theta_o_edges_deg", jarr(e, nto + 1));
	for (int i = 0; i < nto; i++)
		e[i] = 90.0 * (i + 0.5) / nto;
	add(o, "theta_o_centres_deg", jarr(e, nto));
	for (int i = 0; i <= np; i++)
		e[i] = 180.0 * i / np;
	add(o, "delta_phi_edges_deg", jarr(e, np + 1));
	for (int i = 0; i < np; i++)
		e[i] = 180.0 * (i + 0.5) / np;
	add(o, "delta_phi_centres_deg", jarr(e, np));
	if (bake_spec_points(s)) {	/* where adding-doubling entries hold point values */
		bake_nodes_theta(nto, e);
		add(o, "theta_o_nodes_deg", jarr_deg(e, nto));
		bake_nodes_phi(np, e);
		add(o, "delta_phi_nodes_deg", jarr_deg(e, np));
	}
	free(e);
}

static json_object *table_info(const struct bake_spec *s, const struct bake_result *r)
{
	json_object *t = json_object_new_object();
	add(t, "file", jstr("brdf.exr"));
	add(t, "width", json_object_new_int(s->n_phi));
	add(t, "height", json_object_new_int(s->n_ti * s->n_to));
	add(t, "row", jstr("theta_i_index * n_theta_o + theta_o_index, row 0 at the top"));
	add(t, "column", jstr("delta_phi bin index"));
	add(t, "value", jstr("diffuse (subsurface) BRDF [1/sr]: mean over the (theta_o, delta_phi) "
	    "bin at the theta_i node; delta_phi = 0 back toward the light, 180 the mirror side"));
	json_object *vals = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++) {	/* "points" at the nodes
						 * (adding-doubling) or "bins" (means) */
		const struct solver_ops *m = solvers_find(r->table.entry[w * s->n_ti].method);
		int points = bake_spec_points(s) && m && (m->traits & SOLVER_POINTS);
		json_object_array_add(vals, jstr(points ? "points" : "bins"));
	}
	add(t, "values", vals);
	add(t, "values_note", jstr("per wavelength: 'bins' as 'value' says; 'points': the BRDF at "
	    "the theta_i node, theta_o_nodes_deg[row], delta_phi_nodes_deg[column]; at theta_i 90 "
	    "deg it is 0 (nothing enters at grazing)"));
	const struct solver_ops *so = solvers_find(r->solver);
	add(t, "channels", jstr(so && (so->traits & SOLVER_SAMPLED) ?
	    "fr.<WL>nm and fr_err.<WL>nm (standard error)"
	    : "fr.<WL>nm and fr_err.<WL>nm (its error estimate: see solver.error)"));
	return t;
}

static json_object *rgb_info(const struct bake_spec *s, const struct bake_meta *m)
{
	json_object *rgb = json_object_new_object();
	add(rgb, "file", jstr("brdf_rgb.exr"));
	add(rgb, "colour_space",
	    jstr("linear sRGB (Rec. 709 primaries), D65 white, CIE 1931 2-degree observer"));
	json_object *mm = json_object_new_array();
	for (int c = 0; c < 3; c++)
		json_object_array_add(mm, jarr(m->rgb_from_wl + c * s->n_wl, s->n_wl));
	add(rgb, "rgb_from_wl", mm);
	if (m->rgb_note)
		add(rgb, "note", jstr(m->rgb_note));
	return rgb;
}

static json_object *specular_info(const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m)
{
	json_object *sp = json_object_new_object();
	add(sp, "model", jstr(
	    "GGX microfacet (Walter et al. 2007), Smith masking, facet reflectance of the clear "
	    "top stack"));
	add(sp, "alpha", json_num(m->roughness));
	add(sp, "ior", json_num(m->ior));
	if (m->macro_slope > 0.0) {
		add(sp, "macro_slope", json_num(m->macro_slope));
		add(sp, "macro", jstr("mm-scale relief (engine/macro.h): eval and the exporters "
		    "integrate the table and this lobe together over Beckmann facets of this RMS "
		    "slope with height-correlated Smith shadowing; the table and albedo here are "
		    "the facets' own"));
	}
	add(sp, "fresnel", jstr(s->opts.fresnel == OPTICS_FRESNEL_SCHLICK ? "schlick" : "exact"));
	json_object *stacks = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++)
		json_object_array_add(stacks, jarr(r->stack[w].n_list, r->stack[w].n));
	add(sp, "stack_n", stacks);
	int rough = 0;
	for (int w = 0; w < s->n_wl; w++)
		rough |= s->slab[w].rough_top;
	if (rough && s->slab[0].rough_ms && m->roughness > 0.0)
		add(sp, "multiple_scattering", json_num(1));
	if (rough)
		add(sp, "split", jstr("rough top: this lobe is the surface's own reflection (Rsp "
		    "of both solvers, light that never entered a turbid layer); the table holds "
		    "only light that entered, so eval and the exporters add the two once each"));
	return sp;
}

static json_object *layers_info(const struct bake_spec *s)
{
	json_object *layers = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++) {
		json_object *lw = json_object_new_object();
		add(lw, "wavelength_nm", json_num(s->wl_nm[w]));
		add(lw, "n_above", json_num(s->slab[w].n_above));
		add(lw, "n_below", json_num(s->slab[w].n_below));
		json_object *ls = json_object_new_array();
		for (int i = 1; i <= s->slab[w].n_layers; i++) {
			const struct layer *l = &s->slab[w].layer[i];
			json_object *lo = json_object_new_object();
			add(lo, "d_cm", isinf(l->d) ? jstr("inf") : json_num(l->d));
			add(lo, "n", json_num(l->n));
			add(lo, "mua_per_cm", json_num(l->mu_a));
			add(lo, "mus_per_cm", json_num(l->mu_s));
			add(lo, "g", json_num(l->g));
			if (l->rough > 0.0) {
				add(lo, "rough_top", json_num(l->rough));
				add(lo, "rough_multiple", json_num(s->slab[w].rough_ms));
			}
			json_object_array_add(ls, lo);
		}
		add(lw, "layers", ls);
		json_object_array_add(layers, lw);
	}
	return layers;
}

/* Radial profile and subsurface radius at the node nearest normal incidence. */
static json_object *radial_info(const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m)
{
	json_object *rad = json_object_new_object();
	add(rad, "dr_cm", json_num(s->dr));
	add(rad, "n_r", json_object_new_int(s->n_r));
	add(rad, "theta_i_deg", json_num(s->theta_i[0] * 180.0 / M_PI));
	add(rad, "units", jstr("Rd(r) [1/cm^2]; radius [cm]"));
	json_object *prof = json_object_new_array(), *prof_e = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++) {
		const struct brdf_entry *jb = &r->table.entry[w * s->n_ti];
		json_object_array_add(prof, jarr(jb->rd_r, s->n_r));
		json_object_array_add(prof_e, jarr(jb->rd_r_err, s->n_r));
	}
	add(rad, "rd_r", prof);
	add(rad, "rd_r_err", prof_e);
	add(rad, "mean_radius_cm", jarr(r->mean_radius_cm, s->n_wl));
	add(rad, "mean_radius_err_cm", jarr(r->mean_radius_err_cm, s->n_wl));
	if (r->radial_shared > 0)
		add(rad, "method", jstr("white Monte Carlo at theta_i_deg, exit bins by escapes, "
		    "apart from the table: one run per wavelength shared by the family's members "
		    "(they differ only in absorption; each escape counts for a member with its "
		    "weight times exp(-sum over layers of the member's extra mu_a times the path "
		    "length there)), sized so that every member's mean radius reaches "
		    "target_rel_err (a member it cannot reach within the photon cap runs its own); "
		    "photons are the shared runs'"));
	else
		add(rad, "method", jstr(r->radial_photons > 0 ?
		    "Monte Carlo at theta_i_deg, exit bins by escapes, apart from the table (its "
		    "method gives no Rd(r)), each escape also scored as exp(-2/cm x its path "
		    "length in the turbid layers): profile and mean radius regressed on that and "
		    "on the escape weight, whose means adding-doubling gives (control variates; "
		    "src/bake/radial.h); a pilot of 1024 photons per wavelength, then more (up to "
		    "4 rounds) where the mean radius's relative error is above target_rel_err" :
		    "Monte Carlo, the table's jobs at theta_i_deg"));
	add(rad, "photons", json_object_new_int64(r->radial_photons > 0 ? r->radial_photons
	    : r->table.entry[0].photons));
	if (r->radial_photons > 0)
		add(rad, "target_rel_err",
		    json_num(s->radial_error > 0.0 ? s->radial_error : BAKE_RADIAL_ERROR));
	add(rad, "seconds", json_num(r->radial_seconds));
	/* Per RGB channel: the wavelengths' radii weighted by |rgb_from_wl|. */
	double rr[3];
	for (int c = 0; c < 3; c++) {
		double num = 0.0, den = 0.0;
		for (int w = 0; w < s->n_wl; w++) {
			double k = fabs(m->rgb_from_wl[c * s->n_wl + w]);
			num += k * r->mean_radius_cm[w];
			den += k;
		}
		rr[c] = den > 0 ? num / den : 0.0;
	}
	add(rad, "mean_radius_rgb_cm", jarr(rr, 3));
	add(rad, "definition", jstr(
	    "mean lateral distance between entry and exit of the diffusely reflected light (first "
	    "moment of Rd(r) r dr), from the profile's bins (light beyond the last bin is not "
	    "counted)"));
	return rad;
}

/* What the errors of entries made by each method are. */
static char *error_doc(void)
{
	char *t = xstrdup("fr_err, albedo_err and rms_rel_err of entries made ");
	for (int i = 0; solvers[i] != NULL; i++) {
		char *u = xasprintf("%sby %s: %s; ", t, solvers[i]->name, solvers[i]->error_doc);
		free(t);
		t = u;
	}
	char *u = xasprintf("%srms_rel_err: solid-angle-weighted RMS relative error of the table",
	    t);
	free(t);
	return u;
}

/* Which method made the table, how, and what its errors mean. */
static json_object *solver_info(const struct bake_spec *s, const struct bake_result *r)
{
	json_object *so = json_object_new_object();
	add(so, "name", jstr(r->solver));
	add(so, "requested", jstr(bake_method_name(s->method)));
	add(so, "rms_rel_err", json_num(r->table.rms_rel_err));
	char *doc = error_doc();
	add(so, "error", jstr(doc));
	free(doc);
	const struct solver_ops *ops = bake_method_ops(s->method);
	if (r->tol > 0.0 && ops->manifest) {
		struct solver_knobs k = {
			.tol = s->ad_tol, .n_quad = s->ad_quad, .n_quad_max = s->ad_quad_max,
			.n_orders = s->ad_orders,
		};
		add(so, ops->name, ops->manifest(&k, r->tol));
	}
	json_object *fb = json_object_new_array();
	for (int w = 0; r->fallback_cause && w < s->n_wl; w++)
		if (r->fallback_cause[w]) {
			json_object *f = json_object_new_object();
			add(f, "wavelength_nm", json_num(s->wl_nm[w]));
			add(f, "cause", jstr(r->fallback_cause[w]));
			json_object_array_add(fb, f);
		}
	add(so, "fallback_to_mc", fb);
	return so;
}

static json_object *settings_info(const struct bake_spec *s, const struct bake_result *r)
{
	json_object *st = json_object_new_object();
	add(st, "seed", json_object_new_uint64(s->seed));
	const struct brdf_entry *e = &r->table.entry[0];
	long bp = s->batch_photons > 0 || e->batches == 0 ? s->batch_photons
	    : e->photons / e->batches;
	add(st, "batch_photons", json_object_new_int64(bp));
	add(st, "min_batches", json_object_new_int(s->min_batches));
	add(st, "target_error", json_num(s->target_error));
	add(st, "max_photons", json_object_new_int64(s->max_photons));
	add(st, "roulette_w", json_num(s->opts.roulette_w));
	add(st, "roulette_chance", json_num(s->opts.roulette_chance));
	add(st, "max_steps", json_object_new_int64(s->opts.max_steps));
	return st;
}

static json_object *result_info(const struct bake_result *r)
{
	json_object *res = json_object_new_object();
	add(res, "photons", json_object_new_int64(r->table.photons));
	add(res, "pilot_photons", json_object_new_int64(r->table.pilot_photons));
	add(res, "seconds", json_num(r->table.seconds));
	add(res, "rms_rel_err", json_num(r->table.rms_rel_err));
	add(res, "target_met", json_object_new_boolean(r->table.target_met));
	return res;
}

static json_object *entries_info(const struct bake_result *r)
{
	json_object *jobs = json_object_new_array();
	for (int j = 0; j < r->table.n_wl * r->table.n_ti; j++) {
		const struct brdf_entry *b = &r->table.entry[j];
		json_object *jo = json_object_new_object();
		add(jo, "wavelength_nm", json_num(b->wl_nm));
		add(jo, "theta_i_deg", json_num(b->theta_i * 180.0 / M_PI));
		add(jo, "solver", jstr(b->method ? b->method : ""));
		add(jo, "photons", json_object_new_int64(b->photons));
		add(jo, "batches", json_object_new_int64(b->batches));
		if (b->n_quad > 0) {
			add(jo, "n_quad", json_object_new_int(b->n_quad));
			add(jo, "fourier_orders", json_object_new_int(b->n_orders));
		}
		add(jo, "Rsp", json_num(b->rsp));
		add(jo, "albedo", json_num(b->albedo.v));
		add(jo, "albedo_err", json_num(b->albedo.err));
		add(jo, "Rd_unscattered", json_num(b->rd_unscat.v));
		add(jo, "Tt", json_num(b->tt.v));
		add(jo, "A", json_num(b->a_total.v));
		add(jo, "lost", json_num(b->lost.v));
		if (b->facet_loss.v > 0.0)
			add(jo, "facet_loss", json_num(b->facet_loss.v));
		add(jo, "rms_rel_err", json_num(b->rms_rel_err));
		json_object_array_add(jobs, jo);
	}
	return jobs;
}

char *bake_manifest_text(const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m)
{
	CHECK(r->table.n_wl == s->n_wl && r->table.n_ti == s->n_ti);
	json_object *o = json_object_new_object();
	add(o, "format", jstr("skinbake-bake"));
	add(o, "format_version", json_object_new_int(BAKE_FORMAT_VERSION));
	add(o, "skinbake_version", jstr(PACKAGE_VERSION));
	add(o, "preset", jstr(m->preset ? m->preset : ""));
	if (m->command)
		add(o, "command", jstr(m->command));
	add_axes(o, s);
	add(o, "table", table_info(s, r));
	add(o, "solver", solver_info(s, r));
	add(o, "rgb", rgb_info(s, m));
	add(o, "specular", specular_info(s, r, m));
	add(o, "layers", layers_info(s));
	add(o, "radial", radial_info(s, r, m));
	add(o, "settings", settings_info(s, r));
	add(o, "result", result_info(r));
	add(o, "jobs", entries_info(r));
	char *text = json_text(o, JSON_PRETTY);
	json_object_put(o);
	return text;
}
