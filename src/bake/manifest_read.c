/* manifest_read: read manifest.json of a bake directory (manifest.h): the
 * axes, RGB weights, specular model and subsurface radii into struct bake,
 * and the provenance (layer stacks, methods, batches) behind verify. */
#include "config.h"
#include "bake/manifest.h"

#include <errno.h>
#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/util.h"
#include "engine/macro.h"
#include "engine/microfacet_ms.h"
#include "io/json.h"

static int jnum_array(json_object *o, const char *key, double **out, int *n, char **cause,
    const char *path)
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
		*cause = xasprintf("%s: %d wavelengths, more than a bake holds (%d)", mpath,
		    b->n_wl, BAKE_MAX_WL);
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
	if (!json_object_object_get_ex(o, "rgb", &rgb) ||
	    !json_object_object_get_ex(rgb, "rgb_from_wl", &v) ||
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
			*cause = xasprintf(
			    "%s: rgb_from_wl row %d holds a value that is not a number", mpath, c);
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
	b->macro_slope = jnum(sp, "macro_slope", 0.0);
	if (!(b->macro_slope >= 0.0 && b->macro_slope <= MACRO_SLOPE_MAX)) {
		*cause = xasprintf("%s: specular.macro_slope %g is out of range [0, %g]", mpath,
		    b->macro_slope, MACRO_SLOPE_MAX);
		return -1;
	}
	if (b->macro_slope > 0.0) {
		b->macro = xmalloc(sizeof *b->macro);
		macro_rule_init(b->macro, b->macro_slope, MACRO_NQ);
	}
	b->stack = xcalloc((size_t)b->n_wl, sizeof *b->stack);
	enum optics_fresnel model = OPTICS_FRESNEL_EXACT;
	if (json_object_object_get_ex(sp, "fresnel", &fr) &&
	    json_object_is_type(fr, json_type_string) &&
	    strcmp(json_object_get_string(fr), "schlick") == 0)
		model = OPTICS_FRESNEL_SCHLICK;
	if (!json_object_object_get_ex(sp, "stack_n", &v) ||
	    (int)json_object_array_length(v) != b->n_wl) {
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
			*cause =
			    xasprintf("%s: specular.stack_n[%d] holds a value that is not a number",
			    mpath, w);
			return -1;
		}
	}
	/* Multiple scattering on the facets: the walk's reflection the lobe lacks
	 * (engine/microfacet_ms.h), at the first interface of the clear stack;
	 * tabulated once per distinct pair of indices. */
	if (jnum(sp, "multiple_scattering", 0.0) == 1.0 && b->roughness > 0.0) {
		b->ms = xcalloc((size_t)b->n_wl, sizeof *b->ms);
		for (int w = 0; w < b->n_wl; w++) {
			const double *nl = b->stack[w].n_list;
			int k = 0;
			while (k < w && !(b->ms[k].n_i == nl[0] && b->ms[k].n_t == nl[1]))
				k++;
			if (k < w)
				b->ms[w] = b->ms[k];
			else
				microfacet_ms_init(&b->ms[w], b->roughness, nl[0], nl[1], model, 0);
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
	if (!json_object_object_get_ex(rad, "rd_r", &prof) ||
	    !json_object_is_type(prof, json_type_array) ||
	    (int)json_object_array_length(prof) != b->n_wl || n_r < 1 || n_r > 100000 ||
	    !(dr > 0 && dr < 100))
		return;
	double *rgb = xcalloc((size_t)(3 * n_r), sizeof(double));
	for (int w = 0; w < b->n_wl; w++) {
		json_object *row = json_object_array_get_idx(prof, (size_t)w);
		if (!json_object_is_type(row, json_type_array) ||
		    (int)json_object_array_length(row) != n_r) {
			free(rgb);
			return;
		}
		for (int i = 0; i < n_r; i++) {
			double v =
			    json_object_get_double(json_object_array_get_idx(row, (size_t)i));
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
	if (!json_object_object_get_ex(o, "table", &t) ||
	    !json_object_object_get_ex(t, "values", &vals))
		return 0;
	b->points = xcalloc((size_t)b->n_wl, sizeof(int));
	for (int w = 0; w < b->n_wl && bad < 0; w++) {
		const char *v = json_object_get_string(json_object_array_get_idx(vals, (size_t)w));
		b->points[w] = v && strcmp(v, "points") == 0;
		bad = b->points[w] || (v && strcmp(v, "bins") == 0) ? -1 : w;
		any |= b->points[w];
	}
	if (bad >= 0 || (int)json_object_array_length(vals) != b->n_wl) {
		*cause = xasprintf(
		    "%s: table.values must list 'points' or 'bins' for each of the %d wavelengths",
		    mpath, b->n_wl);
		return -1;
	}
	if (any && (jnum_array(o, "theta_o_nodes_deg", &b->theta_o_nodes, &nt, cause, mpath) ||
	    jnum_array(o, "delta_phi_nodes_deg", &b->phi_nodes, &np, cause, mpath)))
		return -1;
	if (any && (nt != b->n_to || np != b->n_phi)) {
		*cause = xasprintf("%s: %d x %d nodes for a %d x %d table", mpath, nt, np, b->n_to,
		    b->n_phi);
		return -1;
	}
	for (int i = 0; i < nt + np; i++)
		*(i < nt ? &b->theta_o_nodes[i] : &b->phi_nodes[i - nt]) *= M_PI / 180.0;
	return 0;
}

/* Whether some wavelength's stack has a rough top boundary (b->rough_top). */
static void read_rough_top(json_object *o, struct bake *b)
{
	json_object *layers, *ls;
	if (!json_object_object_get_ex(o, "layers", &layers) ||
	    !json_object_is_type(layers, json_type_array))
		return;
	for (size_t w = 0; w < json_object_array_length(layers); w++) {
		json_object *lw = json_object_array_get_idx(layers, w);
		if (json_object_object_get_ex(lw, "layers", &ls) &&
		    json_object_is_type(ls, json_type_array) && json_object_array_length(ls) > 0 &&
		    jnum(json_object_array_get_idx(ls, 0), "rough_top", 0.0) > 0.0)
			b->rough_top = 1;
	}
}

int bake_manifest_read(const char *dir, struct bake *b, char **cause)
{
	char *mpath = xasprintf("%s/manifest.json", dir);
	json_object *o = NULL, *v;
	int rc = -1;
	if (access(mpath, R_OK) != 0) {
		*cause = xasprintf("%s: not a bake directory (%s: %s)", dir, mpath,
		    strerror(errno));
		goto out;
	}
	o = json_load(mpath);
	if (o == NULL || !json_object_object_get_ex(o, "format", &v) ||
	    !json_object_is_type(v, json_type_string) ||
	    strcmp(json_object_get_string(v), "skinbake-bake") != 0) {
		*cause = xasprintf(
		    "%s: not a skinbake bake manifest (corrupt JSON or wrong format)", mpath);
		goto out;
	}
	/* a double: (int)1e999 is undefined */
	if (jnum(o, "format_version", 0) != BAKE_FORMAT_VERSION) {
		*cause = xasprintf("%s: format_version %g is not %d", mpath,
		    jnum(o, "format_version", 0), BAKE_FORMAT_VERSION);
		goto out;
	}
	if (json_object_object_get_ex(o, "preset", &v) && json_object_is_type(v, json_type_string))
		b->preset = xstrdup(json_object_get_string(v));
	if (read_axes(o, b, mpath, cause) || read_rgb(o, b, mpath, cause) ||
	    read_specular(o, b, mpath, cause) || read_points(o, b, mpath, cause))
		goto out;
	read_radial(o, b, mpath);
	read_rough_top(o, b);
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
	if (!json_object_object_get_ex(lw, "layers", &ls) ||
	    !json_object_is_type(ls, json_type_array)) {
		*cause = xasprintf("%s: layers[%d] has no layer list", mpath, w);
		return -1;
	}
	for (size_t i = 0; i < json_object_array_length(ls); i++) {
		json_object *lo = json_object_array_get_idx(ls, i), *d;
		struct layer l = { INFINITY, jnum(lo, "n", 1.0), jnum(lo, "mua_per_cm", 0.0),
		    jnum(lo, "mus_per_cm", 0.0),
			jnum(lo, "g", 0.0), jnum(lo, "rough_top", 0.0) };
		if (jnum(lo, "rough_multiple", 0.0) == 1.0)
			s->rough_ms = 1;
		if (json_object_object_get_ex(lo, "d_cm", &d) &&
		    !json_object_is_type(d, json_type_string))
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
		const struct solver_ops *ops = json_object_object_get_ex(jo, "solver", &v) ?
		    solvers_find(json_object_get_string(v)) : solvers[0];
		int mc = ops != NULL && (ops->traits & SOLVER_SAMPLED);
		long photons = (long)jnum(jo, "photons", 0.0);
		p->entry_mc[j] = mc;
		p->entry_batches[j] = !mc ? 0 : json_object_object_get_ex(jo, "batches", &v)
		    ? json_object_get_int64(v)
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
	snprintf(p->solver, sizeof p->solver, "%s", solvers[0]->name);
	if (json_object_object_get_ex(o, "solver", &so) &&
	    json_object_object_get_ex(so, "name", &v))
		snprintf(p->solver, sizeof p->solver, "%s", json_object_get_string(v));
	p->fresnel = OPTICS_FRESNEL_EXACT;
	if (json_object_object_get_ex(o, "specular", &sp) &&
	    json_object_object_get_ex(sp, "fresnel", &v) &&
	    strcmp(json_object_get_string(v), "schlick") == 0)
		p->fresnel = OPTICS_FRESNEL_SCHLICK;
	if (json_object_object_get_ex(o, "settings", &v))
		p->seed = json_object_object_get_ex(v, "seed", &so) ? json_object_get_uint64(so)
		    : 1;	/* exact */
	if (!json_object_object_get_ex(o, "layers", &layers) ||
	    (int)json_object_array_length(layers) != p->n_wl) {
		*cause = xasprintf("%s: layers do not match the wavelengths", mpath);
		goto out;
	}
	p->slab = xcalloc((size_t)p->n_wl, sizeof *p->slab);
	p->entry_mc = xcalloc((size_t)(p->n_wl * p->n_ti), sizeof *p->entry_mc);
	p->entry_batches = xcalloc((size_t)(p->n_wl * p->n_ti), sizeof *p->entry_batches);
	for (int w = 0; w < p->n_wl; w++)
		if (read_stack(json_object_array_get_idx(layers, (size_t)w), &p->slab[w], w, mpath,
		    cause) != 0)
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
