/* manifest: write and read manifest.json of a bake directory (json-c).
 * Over 600 lines because it writes and reads every section of the one format. */
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
#include "engine/ad_solver.h"
#include "io/json.h"

/* ---- writer ---- */
#define jarr json_num_array	/* a number array */

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
	add(t, "value", jstr("diffuse (subsurface) BRDF [1/sr]: mean over the (theta_o, delta_phi) bin at the theta_i node; "
	    "delta_phi = 0 back toward the light, 180 the mirror side"));
	json_object *vals = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++) {	/* "points" at the nodes (adding-doubling) or "bins" (means) */
		const char *m = r->table.entry[w * s->n_ti].method;
		json_object_array_add(vals, jstr(bake_spec_points(s) && m && strcmp(m, "ad") == 0 ? "points" : "bins"));
	}
	add(t, "values", vals);
	add(t, "values_note", jstr("per wavelength: 'bins' as 'value' says; 'points': the BRDF at the theta_i node, "
	    "theta_o_nodes_deg[row], delta_phi_nodes_deg[column]; at theta_i 90 deg it is 0 (nothing enters at grazing)"));
	add(t, "channels", jstr(strcmp(r->solver, "mc") == 0 ? "fr.<WL>nm and fr_err.<WL>nm (standard error)"
	    : "fr.<WL>nm and fr_err.<WL>nm (its error estimate: see solver.error)"));
	return t;
}

static json_object *rgb_info(const struct bake_spec *s, const struct bake_meta *m)
{
	json_object *rgb = json_object_new_object();
	add(rgb, "file", jstr("brdf_rgb.exr"));
	add(rgb, "colour_space", jstr("linear sRGB (Rec. 709 primaries), D65 white, CIE 1931 2-degree observer"));
	json_object *mm = json_object_new_array();
	for (int c = 0; c < 3; c++)
		json_object_array_add(mm, jarr(m->rgb_from_wl + c * s->n_wl, s->n_wl));
	add(rgb, "rgb_from_wl", mm);
	if (m->rgb_note)
		add(rgb, "note", jstr(m->rgb_note));
	return rgb;
}

static json_object *specular_info(const struct bake_spec *s, const struct bake_result *r, const struct bake_meta *m)
{
	json_object *sp = json_object_new_object();
	add(sp, "model", jstr("GGX microfacet (Walter et al. 2007), Smith masking, facet reflectance of the clear top stack"));
	add(sp, "alpha", json_num(m->roughness));
	add(sp, "ior", json_num(m->ior));
	add(sp, "fresnel", jstr(s->opts.fresnel == OPTICS_FRESNEL_SCHLICK ? "schlick" : "exact"));
	json_object *stacks = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++)
		json_object_array_add(stacks, jarr(r->stack[w].n_list, r->stack[w].n));
	add(sp, "stack_n", stacks);
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
static json_object *radial_info(const struct bake_spec *s, const struct bake_result *r, const struct bake_meta *m)
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
	add(rad, "method", jstr(r->radial_photons > 0 ? "Monte Carlo at theta_i_deg, exit bins by escapes, apart from the "
	    "table (its method gives no Rd(r)): a pilot of 2000 photons per wavelength, then more where the mean radius's "
	    "relative error is above target_rel_err" : "Monte Carlo, the table's jobs at theta_i_deg"));
	add(rad, "photons", json_object_new_int64(r->radial_photons > 0 ? r->radial_photons : r->table.entry[0].photons));
	if (r->radial_photons > 0)
		add(rad, "target_rel_err", json_num(s->radial_error > 0.0 ? s->radial_error : BAKE_RADIAL_ERROR));
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
	    "mean lateral distance between entry and exit of the diffusely reflected light (first moment of Rd(r) r dr), "
	    "from the profile's bins (light beyond the last bin is not counted)"));
	return rad;
}

/* Which method made the table, how, and what its errors mean. */
static json_object *solver_info(const struct bake_spec *s, const struct bake_result *r)
{
	json_object *so = json_object_new_object();
	add(so, "name", jstr(r->solver));
	add(so, "requested", jstr(bake_method_of(s->method)->name));
	add(so, "rms_rel_err", json_num(r->table.rms_rel_err));
	add(so, "error", jstr("fr_err, albedo_err and rms_rel_err of entries made by mc: standard errors (batch means); "
	    "by ad: the adding-doubling error estimates (|X_N - X_N/2| from a solve at half the quadrature nodes, scaled up "
	    "where convergence is slow, plus the Fourier series' tail: bounds, not standard errors; src/engine/ad.h); "
	    "rms_rel_err: solid-angle-weighted RMS relative error of the table"));
	if (r->ad_tol > 0.0) {
		struct ad_solver_settings d;
		ad_solver_settings_default(&d);
		json_object *ad = json_object_new_object();
		add(ad, "method", jstr("adding-doubling, Fourier series in delta_phi (src/engine/ad.h)"));
		add(ad, "tol", json_num(r->ad_tol));
		add(ad, "n_quad", s->ad_quad > 0 ? json_object_new_int(s->ad_quad) : jstr("auto"));
		add(ad, "n_quad_max", json_object_new_int(d.ad.n_quad_max));
		add(ad, "dtau_frac", json_num(d.ad.dtau_frac));
		add(ad, "dm_terms", json_num(d.ad.dm_terms));
		add(ad, "max_orders", json_object_new_int(d.ad.max_orders));
		add(so, "ad", ad);
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
	add(st, "seed", json_object_new_int64((int64_t)s->seed));
	const struct brdf_entry *e = &r->table.entry[0];
	long bp = s->batch_photons > 0 || e->batches == 0 ? s->batch_photons : e->photons / e->batches;
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

char *bake_manifest_text(const struct bake_spec *s, const struct bake_result *r, const struct bake_meta *m)
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

/* ---- reader ---- */

static int jnum_array(json_object *o, const char *key, double **out, int *n, char **cause, const char *path)
{
	json_object *a;
	if (!json_object_object_get_ex(o, key, &a) || !json_object_is_type(a, json_type_array)) {
		*cause = xasprintf("%s: missing array '%s'", path, key);
		return -1;
	}
	*n = (int)json_object_array_length(a);
	*out = xcalloc((size_t)(*n > 0 ? *n : 1), sizeof(double));
	for (int i = 0; i < *n; i++)
		if (json_to_num(json_object_array_get_idx(a, (size_t)i), &(*out)[i]) != 0) {
			*cause = xasprintf("%s: '%s'[%d] is not a number", path, key, i);
			free(*out);
			*out = NULL;
			return -1;
		}
	return 0;
}

/* Member KEY of O, or DFLT when it is missing or not a finite number. */
static double jnum(json_object *o, const char *key, double dflt)
{
	double x;
	if (json_get_num(o, key, &x) != 0)
		return dflt;
	return x;
}

/* The N numbers of array ROW into OUT; -1 when one is not a finite number. */
static int jrow(json_object *row, double *out, int n)
{
	for (int i = 0; i < n; i++)
		if (json_to_num(json_object_array_get_idx(row, (size_t)i), &out[i]) != 0)
			return -1;
	return 0;
}

/* The table axes, converted to radians. */
static int read_axes(json_object *o, struct bake *b, const char *mpath, char **cause)
{
	if (jnum_array(o, "wavelengths_nm", &b->wl_nm, &b->n_wl, cause, mpath) ||
	    jnum_array(o, "theta_i_deg", &b->theta_i, &b->n_ti, cause, mpath) ||
	    jnum_array(o, "theta_o_centres_deg", &b->theta_o, &b->n_to, cause, mpath) ||
	    jnum_array(o, "delta_phi_centres_deg", &b->phi, &b->n_phi, cause, mpath))
		return -1;
	if (b->n_wl < 1 || b->n_ti < 1 || b->n_to < 1 || b->n_phi < 1) {
		*cause = xasprintf("%s: empty table axes", mpath);
		return -1;
	}
	if (b->n_wl > BAKE_MAX_WL) {
		*cause = xasprintf("%s: %d wavelengths, more than a bake holds (%d)", mpath, b->n_wl, BAKE_MAX_WL);
		return -1;
	}
	for (int i = 0; i < b->n_ti; i++)
		b->theta_i[i] *= M_PI / 180.0;
	for (int i = 0; i < b->n_to; i++)
		b->theta_o[i] *= M_PI / 180.0;
	for (int i = 0; i < b->n_phi; i++)
		b->phi[i] *= M_PI / 180.0;
	return 0;
}

static int read_rgb(json_object *o, struct bake *b, const char *mpath, char **cause)
{
	json_object *rgb, *v;
	if (!json_object_object_get_ex(o, "rgb", &rgb) || !json_object_object_get_ex(rgb, "rgb_from_wl", &v) ||
	    json_object_array_length(v) != 3) {
		*cause = xasprintf("%s: missing rgb.rgb_from_wl", mpath);
		return -1;
	}
	b->rgb_from_wl = xcalloc(3 * (size_t)b->n_wl, sizeof(double));
	for (int c = 0; c < 3; c++) {
		json_object *row = json_object_array_get_idx(v, (size_t)c);
		if ((int)json_object_array_length(row) != b->n_wl) {
			*cause = xasprintf("%s: rgb_from_wl row %d has the wrong length", mpath, c);
			return -1;
		}
		if (jrow(row, &b->rgb_from_wl[c * b->n_wl], b->n_wl) != 0) {
			*cause = xasprintf("%s: rgb_from_wl row %d holds a value that is not a number", mpath, c);
			return -1;
		}
	}
	return 0;
}

static int read_specular(json_object *o, struct bake *b, const char *mpath, char **cause)
{
	json_object *sp, *v, *fr;
	if (!json_object_object_get_ex(o, "specular", &sp)) {
		*cause = xasprintf("%s: missing specular", mpath);
		return -1;
	}
	b->ior = jnum(sp, "ior", 1.5);
	b->roughness = jnum(sp, "alpha", 0.3);
	b->stack = xcalloc((size_t)b->n_wl, sizeof *b->stack);
	enum optics_fresnel model = OPTICS_FRESNEL_EXACT;
	if (json_object_object_get_ex(sp, "fresnel", &fr) && json_object_is_type(fr, json_type_string) &&
	    strcmp(json_object_get_string(fr), "schlick") == 0)
		model = OPTICS_FRESNEL_SCHLICK;
	if (!json_object_object_get_ex(sp, "stack_n", &v) || (int)json_object_array_length(v) != b->n_wl) {
		*cause = xasprintf("%s: missing specular.stack_n", mpath);
		return -1;
	}
	for (int w = 0; w < b->n_wl; w++) {
		json_object *row = json_object_array_get_idx(v, (size_t)w);
		int k = (int)json_object_array_length(row);
		if (k < 2 || k > SPECULAR_MAX_IFACES) {
			*cause = xasprintf("%s: specular.stack_n[%d] has %d entries", mpath, w, k);
			return -1;
		}
		b->stack[w].n = k;
		b->stack[w].model = model;
		if (jrow(row, b->stack[w].n_list, k) != 0) {
			*cause = xasprintf("%s: specular.stack_n[%d] holds a value that is not a number", mpath, w);
			return -1;
		}
	}
	return 0;
}

/* The radial profile in linear sRGB (rgb_from_wl applied to Rd(r) per
 * wavelength); left NULL when the manifest has none or it is malformed. */
static void read_radial_profile(json_object *rad, struct bake *b)
{
	json_object *prof;
	int n_r = (int)jnum(rad, "n_r", 0);
	double dr = jnum(rad, "dr_cm", 0);
	if (!json_object_object_get_ex(rad, "rd_r", &prof) || !json_object_is_type(prof, json_type_array) ||
	    (int)json_object_array_length(prof) != b->n_wl || n_r < 1 || n_r > 100000 || !(dr > 0 && dr < 100))
		return;
	double *rgb = xcalloc((size_t)(3 * n_r), sizeof(double));
	for (int w = 0; w < b->n_wl; w++) {
		json_object *row = json_object_array_get_idx(prof, (size_t)w);
		if (!json_object_is_type(row, json_type_array) || (int)json_object_array_length(row) != n_r) {
			free(rgb);
			return;
		}
		for (int i = 0; i < n_r; i++) {
			double v = json_object_get_double(json_object_array_get_idx(row, (size_t)i));
			for (int c = 0; c < 3; c++)
				rgb[c * n_r + i] += b->rgb_from_wl[c * b->n_wl + w] * v;
		}
	}
	b->n_r = n_r;
	b->dr_cm = dr;
	b->rd_r_rgb = rgb;
}

/* Subsurface radii: optional (0 when the manifest has none). */
static void read_radial(json_object *o, struct bake *b, const char *mpath)
{
	json_object *rad;
	char *ignored = NULL;
	double *tmp;
	int n;
	b->sss_radius_cm = xcalloc((size_t)b->n_wl, sizeof(double));
	if (!json_object_object_get_ex(o, "radial", &rad))
		return;
	if (jnum_array(rad, "mean_radius_cm", &tmp, &n, &ignored, mpath) == 0) {
		for (int w = 0; w < b->n_wl && w < n; w++)
			b->sss_radius_cm[w] = tmp[w];
		free(tmp);
	}
	free(ignored);
	ignored = NULL;
	if (jnum_array(rad, "mean_radius_rgb_cm", &tmp, &n, &ignored, mpath) == 0) {
		for (int c = 0; c < 3 && c < n; c++)
			b->sss_radius_rgb_cm[c] = tmp[c];
		free(tmp);
	}
	free(ignored);
	read_radial_profile(rad, b);
}

/* Point values (issue 26; absent in older bakes: all bin means). */
static int read_points(json_object *o, struct bake *b, const char *mpath, char **cause)
{
	json_object *t, *vals;
	int nt = 0, np = 0, any = 0, bad = -1;
	if (!json_object_object_get_ex(o, "table", &t) || !json_object_object_get_ex(t, "values", &vals))
		return 0;
	b->points = xcalloc((size_t)b->n_wl, sizeof(int));
	for (int w = 0; w < b->n_wl && bad < 0; w++) {
		const char *v = json_object_get_string(json_object_array_get_idx(vals, (size_t)w));
		b->points[w] = v && strcmp(v, "points") == 0;
		bad = b->points[w] || (v && strcmp(v, "bins") == 0) ? -1 : w;
		any |= b->points[w];
	}
	if (bad >= 0 || (int)json_object_array_length(vals) != b->n_wl) {
		*cause = xasprintf("%s: table.values must list 'points' or 'bins' for each of the %d wavelengths", mpath, b->n_wl);
		return -1;
	}
	if (any && (jnum_array(o, "theta_o_nodes_deg", &b->theta_o_nodes, &nt, cause, mpath) ||
	    jnum_array(o, "delta_phi_nodes_deg", &b->phi_nodes, &np, cause, mpath)))
		return -1;
	if (any && (nt != b->n_to || np != b->n_phi)) {
		*cause = xasprintf("%s: %d x %d nodes for a %d x %d table", mpath, nt, np, b->n_to, b->n_phi);
		return -1;
	}
	for (int i = 0; i < nt + np; i++)
		*(i < nt ? &b->theta_o_nodes[i] : &b->phi_nodes[i - nt]) *= M_PI / 180.0;
	return 0;
}

int bake_manifest_read(const char *dir, struct bake *b, char **cause)
{
	char *mpath = xasprintf("%s/manifest.json", dir);
	json_object *o = NULL, *v;
	int rc = -1;
	if (access(mpath, R_OK) != 0) {
		*cause = xasprintf("%s: not a bake directory (%s: %s)", dir, mpath, strerror(errno));
		goto out;
	}
	o = json_load(mpath);
	if (o == NULL || !json_object_object_get_ex(o, "format", &v) || !json_object_is_type(v, json_type_string) ||
	    strcmp(json_object_get_string(v), "skinbake-bake") != 0) {
		*cause = xasprintf("%s: not a skinbake bake manifest (corrupt JSON or wrong format)", mpath);
		goto out;
	}
	if (jnum(o, "format_version", 0) != BAKE_FORMAT_VERSION) {	/* a double: (int)1e999 is undefined */
		*cause = xasprintf("%s: format_version %g is not %d", mpath, jnum(o, "format_version", 0), BAKE_FORMAT_VERSION);
		goto out;
	}
	if (json_object_object_get_ex(o, "preset", &v) && json_object_is_type(v, json_type_string))
		b->preset = xstrdup(json_object_get_string(v));
	if (read_axes(o, b, mpath, cause) || read_rgb(o, b, mpath, cause) || read_specular(o, b, mpath, cause) ||
	    read_points(o, b, mpath, cause))
		goto out;
	read_radial(o, b, mpath);
	rc = 0;
out:
	if (o)
		json_object_put(o);
	free(mpath);
	return rc;
}

/* ---- provenance (for verify) ---- */

static int read_stack(json_object *lw, struct slab *s, int w, const char *mpath, char **cause)
{
	json_object *ls;
	slab_init(s, jnum(lw, "n_above", 1.0), jnum(lw, "n_below", 1.0));
	if (!json_object_object_get_ex(lw, "layers", &ls) || !json_object_is_type(ls, json_type_array)) {
		*cause = xasprintf("%s: layers[%d] has no layer list", mpath, w);
		return -1;
	}
	for (size_t i = 0; i < json_object_array_length(ls); i++) {
		json_object *lo = json_object_array_get_idx(ls, i), *d;
		struct layer l = { INFINITY, jnum(lo, "n", 1.0), jnum(lo, "mua_per_cm", 0.0), jnum(lo, "mus_per_cm", 0.0),
			jnum(lo, "g", 0.0), jnum(lo, "rough_top", 0.0) };
		if (jnum(lo, "rough_multiple", 0.0) == 1.0)
			s->rough_ms = 1;
		if (json_object_object_get_ex(lo, "d_cm", &d) && !json_object_is_type(d, json_type_string))
			l.d = json_object_get_double(d);
		char *why = NULL;
		if (slab_add(s, &l, &why) != 0) {
			*cause = xasprintf("%s: layers[%d]: %s", mpath, w, why);
			free(why);
			return -1;
		}
	}
	char *why = NULL;
	if (slab_check(s, &why) != 0) {
		*cause = xasprintf("%s: layers[%d]: %s", mpath, w, why);
		free(why);
		return -1;
	}
	slab_prepare(s);
	return 0;
}

/* Per entry: its method and batches (manifests from before the solver
 * choice are Monte Carlo with batches = photons / settings.batch_photons). */
static void read_entries(json_object *o, struct bake_provenance *p)
{
	json_object *jobs, *st, *v;
	long bp = 0;
	if (json_object_object_get_ex(o, "settings", &st))
		bp = (long)jnum(st, "batch_photons", 0.0);
	if (!json_object_object_get_ex(o, "jobs", &jobs))
		return;
	for (int j = 0; j < p->n_wl * p->n_ti && j < (int)json_object_array_length(jobs); j++) {
		json_object *jo = json_object_array_get_idx(jobs, (size_t)j);
		int mc = !json_object_object_get_ex(jo, "solver", &v) || strcmp(json_object_get_string(v), "mc") == 0;
		long photons = (long)jnum(jo, "photons", 0.0);
		p->entry_mc[j] = mc;
		p->entry_batches[j] = !mc ? 0 : json_object_object_get_ex(jo, "batches", &v) ? json_object_get_int64(v)
				    : bp > 0 ? photons / bp : 0;
	}
}

int bake_provenance_read(const char *dir, struct bake_provenance *p, char **cause)
{
	memset(p, 0, sizeof *p);
	struct bake *b = xcalloc(1, sizeof *b);
	char *mpath = xasprintf("%s/manifest.json", dir);
	json_object *o = NULL, *v, *so, *sp, *layers;
	int rc = -1;
	if (bake_manifest_read(dir, b, cause) != 0 || (o = json_load(mpath)) == NULL)
		goto out;
	p->n_wl = b->n_wl;
	p->n_ti = b->n_ti;
	snprintf(p->solver, sizeof p->solver, "mc");
	if (json_object_object_get_ex(o, "solver", &so) && json_object_object_get_ex(so, "name", &v))
		snprintf(p->solver, sizeof p->solver, "%s", json_object_get_string(v));
	p->fresnel = OPTICS_FRESNEL_EXACT;
	if (json_object_object_get_ex(o, "specular", &sp) && json_object_object_get_ex(sp, "fresnel", &v) &&
	    strcmp(json_object_get_string(v), "schlick") == 0)
		p->fresnel = OPTICS_FRESNEL_SCHLICK;
	if (json_object_object_get_ex(o, "settings", &v))
		p->seed = (uint64_t)jnum(v, "seed", 1.0);
	if (!json_object_object_get_ex(o, "layers", &layers) || (int)json_object_array_length(layers) != p->n_wl) {
		*cause = xasprintf("%s: layers do not match the wavelengths", mpath);
		goto out;
	}
	p->slab = xcalloc((size_t)p->n_wl, sizeof *p->slab);
	p->entry_mc = xcalloc((size_t)(p->n_wl * p->n_ti), sizeof *p->entry_mc);
	p->entry_batches = xcalloc((size_t)(p->n_wl * p->n_ti), sizeof *p->entry_batches);
	for (int w = 0; w < p->n_wl; w++)
		if (read_stack(json_object_array_get_idx(layers, (size_t)w), &p->slab[w], w, mpath, cause) != 0)
			goto out;
	read_entries(o, p);
	rc = 0;
out:
	if (o)
		json_object_put(o);
	bake_free(b);
	free(mpath);
	if (rc != 0)
		bake_provenance_free(p);
	return rc;
}

void bake_provenance_free(struct bake_provenance *p)
{
	free(p->slab);
	free(p->entry_mc);
	free(p->entry_batches);
	memset(p, 0, sizeof *p);
}
