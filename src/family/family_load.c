/* family_load: family.json read back (family.h), with a message that names
 * the file, the field, the value and what was expected for anything
 * missing, corrupt or of another format version; the member tables. */
#include "config.h"
#include "family/family.h"

#include <errno.h>
#include <json-c/json.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/checksum.h"
#include "base/util.h"
#include "io/json.h"

/* Every read names the file and the field. */
struct rd {
	const char *path;
	char **cause;
};

static json_object *get(const struct rd *r, json_object *o, const char *field, const char *key, json_type t)
{
	json_object *v;
	if (!json_object_object_get_ex(o, key, &v) || !json_object_is_type(v, t)) {
		static const char *tn[] = { "null", "boolean", "number", "number", "object", "array", "string" };
		*r->cause = xasprintf("%s: field %s%s%s is missing or not a%s %s", r->path, field, *field ? "." : "", key,
		    t == json_type_array || t == json_type_object ? "n" : "", tn[t]);
		return NULL;
	}
	return v;
}

static int get_num(const struct rd *r, json_object *o, const char *field, const char *key, double *out)
{
	if (json_get_num(o, key, out) != 0) {
		*r->cause = xasprintf("%s: field %s%s%s is missing or not a number", r->path, field, *field ? "." : "", key);
		return -1;
	}
	return 0;
}

/* The numbers of array a, named LABEL in messages: exactly n of them, or
 * (n < 0) up to max, their count in *n_out. */
static int arr_nums(const struct rd *r, json_object *a, const char *label, double *out, int n, int max, int *n_out)
{
	int k = (int)json_object_array_length(a);
	if ((n >= 0 && k != n) || k > max) {
		*r->cause = xasprintf("%s: field %s has %d values, expected %s%d", r->path, label, k, n >= 0 ? "" : "at most ",
		    n >= 0 ? n : max);
		return -1;
	}
	for (int i = 0; i < k; i++) {
		if (json_to_num(json_object_array_get_idx(a, (size_t)i), &out[i]) != 0) {
			*r->cause = xasprintf("%s: field %s[%d] is not a number", r->path, label, i);
			return -1;
		}
	}
	if (n_out)
		*n_out = k;
	return 0;
}

static int get_arr(const struct rd *r, json_object *o, const char *field, const char *key, double *out, int n,
    int max, int *n_out)
{
	json_object *a = get(r, o, field, key, json_type_array);
	if (a == NULL)
		return -1;
	char label[96];
	snprintf(label, sizeof label, "%s%s%s", field, *field ? "." : "", key);
	return arr_nums(r, a, label, out, n, max, n_out);
}

static int read_axis(const struct rd *r, json_object *o, int a, struct family_axis *ax)
{
	char field[32];
	snprintf(field, sizeof field, "axes[%d]", a);
	json_object *k = get(r, o, field, "key", json_type_string), *sp, *lc;
	if (k == NULL)
		return -1;
	double rng[2];
	if (get_arr(r, o, field, "range", rng, 2, 2, NULL))
		return -1;
	sp = get(r, o, field, "spacing", json_type_string);
	lc = sp ? get(r, o, field, "log_coordinate", json_type_boolean) : NULL;
	if (lc == NULL)
		return -1;
	int spacing = -1;
	for (int s = 0; s <= FAMILY_SPACING_LIST; s++)
		if (strcmp(json_object_get_string(sp), family_spacing_name((enum family_spacing)s)) == 0)
			spacing = s;
	if (spacing < 0) {
		*r->cause = xasprintf("%s: field %s.spacing = '%s', expected lin, log, de or list", r->path, field,
		    json_object_get_string(sp));
		return -1;
	}
	double nodes[FAMILY_MAX_NODES];
	int n;
	if (get_arr(r, o, field, "nodes", nodes, -1, FAMILY_MAX_NODES, &n))
		return -1;
	char *why = NULL;
	if (family_axis_init(ax, json_object_get_string(k), rng[0], rng[1], n, FAMILY_SPACING_LIST, nodes, &why) != 0) {
		*r->cause = xasprintf("%s: field %s: %s", r->path, field, why);
		free(why);
		return -1;
	}
	ax->spacing = (enum family_spacing)spacing;
	ax->lo = rng[0];
	ax->hi = rng[1];
	ax->log_coord = json_object_get_boolean(lc);
	if (ax->log_coord && !(ax->node[0] > 0)) {
		*r->cause = xasprintf("%s: field %s.log_coordinate = true with a node %g <= 0", r->path, field, ax->node[0]);
		return -1;
	}
	return 0;
}

static int read_spec(const struct rd *r, json_object *o, struct family *f)
{
	json_object *b = get(r, o, "", "bake", json_type_object), *v;
	if (b == NULL)
		return -1;
	struct bake_spec *s = f->spec = xcalloc(1, sizeof *f->spec);
	double th[BAKE_MAX_TI], x[12];
	static const char *keys[] = { "n_theta_o", "n_delta_phi", "n_r", "dr_cm", "seed", "batch_photons", "min_batches",
		"target_error", "max_photons", "roulette_w", "roulette_chance", "max_steps" };
	if (get_arr(r, b, "bake", "theta_i_deg", th, -1, BAKE_MAX_TI, &s->n_ti))
		return -1;
	for (int i = 0; i < 12; i++)
		if (get_num(r, b, "bake", keys[i], &x[i]))
			return -1;
	for (int i = 0; i < s->n_ti; i++)
		s->theta_i[i] = th[i] * M_PI / 180.0;
	s->n_to = (int)x[0];
	s->n_phi = (int)x[1];
	s->n_r = (int)x[2];
	s->dr = x[3];
	s->seed = (uint64_t)x[4];
	json_object *sv;
	if (json_object_object_get_ex(b, "seed", &sv) && json_object_is_type(sv, json_type_int))
		s->seed = json_object_get_uint64(sv);	/* exact: seeds go to 2^64-1 */
	s->batch_photons = (long)x[5];
	s->min_batches = (int)x[6];
	s->target_error = x[7];
	s->max_photons = (long)x[8];
	transport_opts_default(&s->opts);
	s->opts.roulette_w = x[9];
	s->opts.roulette_chance = x[10];
	s->opts.max_steps = (long)x[11];
	if (s->n_ti < 1 || s->n_to < 1 || s->n_phi < 1) {
		*r->cause = xasprintf("%s: field bake has an empty table (theta_i, n_theta_o, n_delta_phi)", r->path);
		return -1;
	}
	if ((v = get(r, b, "bake", "fresnel", json_type_string)) == NULL)
		return -1;
	s->opts.fresnel = strcmp(json_object_get_string(v), "schlick") == 0 ? OPTICS_FRESNEL_SCHLICK : OPTICS_FRESNEL_EXACT;
	if ((v = get(r, b, "bake", "estimator", json_type_string)) == NULL)
		return -1;
	s->nee = strcmp(json_object_get_string(v), "nee") == 0;
	if ((v = get(r, b, "bake", "solver", json_type_string)) == NULL)
		return -1;
	f->solver = xstrdup(json_object_get_string(v));
	/* Families from before the adding-doubling solver have no "requested":
	 * Monte Carlo (solvers[0]). */
	s->method = 0;
	if (json_object_object_get_ex(b, "requested", &v) && json_object_is_type(v, json_type_string)) {
		const char *q = json_object_get_string(v);
		int m = bake_method_named(q);
		if (m == BAKE_SOLVER_NONE) {
			*r->cause = xasprintf("%s: field bake.requested = '%s' is not one of %s", r->path, q,
			    bake_method_choices());
			return -1;
		}
		s->method = m;
		double y[4] = { 0 };
		static const char *k2[] = { "ad_tol", "ad_quad", "radial_error", "radial_photons" };
		for (int i = 0; i < 4; i++)
			if (get_num(r, b, "bake", k2[i], &y[i]))
				return -1;
		s->ad_tol = y[0];
		s->ad_quad = (int)y[1];
		s->radial_error = y[2];
		s->radial_photons = (long)y[3];
	}
	s->n_wl = f->n_wl;
	memcpy(s->wl_nm, f->wl_nm, sizeof(double) * (size_t)f->n_wl);
	s->n_ranks = 1;
	return 0;
}

static int read_member(const struct rd *r, json_object *o, struct family *f, int m)
{
	char field[32];
	snprintf(field, sizeof field, "members[%d]", m);
	struct family_member *fm = &f->member[m];
	fm->albedo_wl = xcalloc((size_t)f->n_wl, sizeof(double));
	if (get_arr(r, o, field, "params", fm->param, f->n_axes, FAMILY_MAX_AXES, NULL) ||
	    get_arr(r, o, field, "albedo_wl", fm->albedo_wl, f->n_wl, BAKE_MAX_WL, NULL) ||
	    get_arr(r, o, field, "albedo_rgb", fm->albedo_rgb, 3, 3, NULL) ||
	    get_arr(r, o, field, "albedo_lab", fm->albedo_lab, 3, 3, NULL) ||
	    get_arr(r, o, field, "sss_radius_rgb_cm", fm->sss_radius_rgb_cm, 3, 3, NULL) ||
	    get_num(r, o, field, "rms_rel_err", &fm->rms_rel_err) || get_num(r, o, field, "seconds", &fm->seconds))
		return -1;
	int idx[FAMILY_MAX_AXES];
	family_member_index(f, m, idx);
	for (int a = 0; a < f->n_axes; a++)
		if (fm->param[a] != f->axis[a].node[idx[a]]) {
			*r->cause = xasprintf("%s: field %s.params[%d] = %.17g, expected node %d of axis %s (%.17g)", r->path,
			    field, a, fm->param[a], idx[a], f->axis[a].key, f->axis[a].node[idx[a]]);
			return -1;
		}
	for (int w = 0; w < f->n_wl; w++)
		if (!(fm->albedo_wl[w] >= 0 && fm->albedo_wl[w] <= 1)) {
			*r->cause = xasprintf("%s: field %s.albedo_wl[%d] = %g, expected a value in [0, 1]", r->path, field, w,
			    fm->albedo_wl[w]);
			return -1;
		}
	if (fm->rms_rel_err > f->rms_rel_err)
		f->rms_rel_err = fm->rms_rel_err;
	return 0;
}

/* The header: format, version, preset, axes, wavelengths, weights. */
static int read_head(const struct rd *r, json_object *o, struct family *f)
{
	json_object *v = get(r, o, "", "format", json_type_string);
	if (v == NULL)
		return -1;
	if (strcmp(json_object_get_string(v), "skinbake-family") != 0) {
		*r->cause = xasprintf("%s: field format = '%s', expected 'skinbake-family'", r->path, json_object_get_string(v));
		return -1;
	}
	double ver;
	if (get_num(r, o, "", "format_version", &ver))
		return -1;
	if (ver != FAMILY_FORMAT_VERSION) {
		*r->cause = xasprintf("%s: field format_version = %g, expected %d (the family format this skinbake reads; "
		    "bake the family again)", r->path, ver, FAMILY_FORMAT_VERSION);
		return -1;
	}
	if ((v = get(r, o, "", "preset", json_type_string)) == NULL)
		return -1;
	f->preset = xstrdup(json_object_get_string(v));
	json_object *ax = get(r, o, "", "axes", json_type_array);
	if (ax == NULL)
		return -1;
	f->n_axes = (int)json_object_array_length(ax);
	if (f->n_axes < 1 || f->n_axes > FAMILY_MAX_AXES) {
		*r->cause = xasprintf("%s: field axes has %d entries, expected 1 to %d", r->path, f->n_axes, FAMILY_MAX_AXES);
		return -1;
	}
	f->n_members = 1;
	for (int a = 0; a < f->n_axes; a++) {
		if (read_axis(r, json_object_array_get_idx(ax, (size_t)a), a, &f->axis[a]))
			return -1;
		f->n_members *= f->axis[a].n;
	}
	f->wl_nm = xcalloc(BAKE_MAX_WL, sizeof(double));
	if (get_arr(r, o, "", "wavelengths_nm", f->wl_nm, -1, BAKE_MAX_WL, &f->n_wl))
		return -1;
	if (f->n_wl < 1) {
		*r->cause = xasprintf("%s: field wavelengths_nm is empty", r->path);
		return -1;
	}
	json_object *w = get(r, o, "", "rgb_from_wl", json_type_array);
	if (w == NULL)
		return -1;
	f->rgb_from_wl = xcalloc(3 * (size_t)f->n_wl, sizeof(double));
	for (int c = 0; c < 3; c++) {
		json_object *row = json_object_array_get_idx(w, (size_t)c);
		char label[32];
		snprintf(label, sizeof label, "rgb_from_wl[%d]", c);
		if (row == NULL || !json_object_is_type(row, json_type_array)) {
			*r->cause = xasprintf("%s: field %s is missing or not an array", r->path, label);
			return -1;
		}
		if (arr_nums(r, row, label, f->rgb_from_wl + c * f->n_wl, f->n_wl, f->n_wl, NULL))
			return -1;
	}
	json_object *al = get(r, o, "", "albedo", json_type_object);
	double th;
	if (al == NULL || get_num(r, al, "albedo", "theta_i_deg", &th))
		return -1;
	f->albedo_theta_i = th * M_PI / 180.0;
	return 0;
}

struct family *family_load(const char *dir, char **cause)
{
	char *path = xasprintf("%s/family.json", dir);
	struct rd r = { path, cause };
	struct family *f = xcalloc(1, sizeof *f);
	f->dir = xstrdup(dir);
	json_object *o = NULL;
	if (access(path, R_OK) != 0) {
		*cause = xasprintf("%s: not a family directory (%s: %s)", dir, path, strerror(errno));
		goto fail;
	}
	o = json_load(path);
	if (o == NULL || !json_object_is_type(o, json_type_object)) {
		*cause = xasprintf("%s: not a skinbake family index (corrupt JSON)", path);
		goto fail;
	}
	if (checksum_verify_dir(dir, "family.json", cause) != 0)
		goto fail;
	if (read_head(&r, o, f) || read_spec(&r, o, f))
		goto fail;
	json_object *mem = get(&r, o, "", "members", json_type_array), *v;
	if (mem == NULL)
		goto fail;
	if ((int)json_object_array_length(mem) != f->n_members) {
		*cause = xasprintf("%s: field members has %d entries, expected %d (the product of the axes' nodes)", path,
		    (int)json_object_array_length(mem), f->n_members);
		goto fail;
	}
	f->member = xcalloc((size_t)f->n_members, sizeof *f->member);
	for (int m = 0; m < f->n_members; m++)
		if (read_member(&r, json_object_array_get_idx(mem, (size_t)m), f, m))
			goto fail;
	if (json_object_object_get_ex(o, "preset_file", &v)) {
		char *ip = xasprintf("%s/%s", dir, json_object_get_string(v));
		FILE *fp = fopen(ip, "r");
		if (fp) {
			size_t cap = 4096, len = 0, k;
			f->preset_ini = xmalloc(cap);
			while ((k = fread(f->preset_ini + len, 1, cap - len - 1, fp)) > 0) {
				len += k;
				if (len + 1 >= cap)
					f->preset_ini = xreallocarray(f->preset_ini, cap *= 2, 1);
			}
			f->preset_ini[len] = '\0';
			fclose(fp);
		}
		free(ip);
	}
	json_object_put(o);
	free(path);
	return f;
fail:
	if (o)
		json_object_put(o);
	free(path);
	family_free(f);
	return NULL;
}

int family_load_tables(struct family *f, char **cause)
{
	if (f->bake)
		return 0;
	struct bake **b = xcalloc((size_t)f->n_members, sizeof *b);
	for (int m = 0; m < f->n_members; m++) {
		char *d = xasprintf("%s/m%04d", f->dir, m);
		b[m] = bake_load(d, cause);
		int bad = b[m] == NULL;
		if (!bad && (b[m]->n_wl != f->n_wl || b[m]->n_ti != f->spec->n_ti || b[m]->n_to != f->spec->n_to ||
		    b[m]->n_phi != f->spec->n_phi)) {
			*cause = xasprintf("%s: its table (%d wavelengths, %d x %d x %d) is not the family's (%d, %d x %d x %d)", d,
			    b[m]->n_wl, b[m]->n_ti, b[m]->n_to, b[m]->n_phi, f->n_wl, f->spec->n_ti, f->spec->n_to,
			    f->spec->n_phi);
			bad = 1;
		}
		free(d);
		if (bad) {
			for (int k = 0; k <= m; k++)
				bake_free(b[k]);
			free(b);
			return -1;
		}
	}
	f->bake = b;
	return 0;
}

