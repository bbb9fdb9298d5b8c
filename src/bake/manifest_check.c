/* manifest_check: the checks of a bake's manifest.json before use
 * (manifest_check.h). */
#include "config.h"
#include "bake/manifest_check.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bake.h"
#include "bake/bakedir.h"
#include "base/checksum.h"
#include "base/util.h"
#include "engine/specular.h"
#include "io/exrio.h"

struct ctx {
	const char *path;	/* manifest.json, for messages */
	char **cause;
};

/* A JSON number (not text, not a boolean), finite and in [lo, hi]. */
static int number(struct ctx *c, json_object *v, const char *what, double lo, double hi, double *out)
{
	if (v == NULL || !(json_object_is_type(v, json_type_double) || json_object_is_type(v, json_type_int))) {
		*c->cause = xasprintf("%s: %s = %s is not a number", c->path, what,
		    v ? json_object_to_json_string(v) : "(missing)");
		return -1;
	}
	double x = json_object_get_double(v);
	if (!isfinite(x) || x < lo || x > hi) {
		*c->cause = xasprintf("%s: %s = %g is out of range [%g, %g]", c->path, what, x, lo, hi);
		return -1;
	}
	*out = x;
	return 0;
}

/* The array A (LABEL in messages): n in [nmin, nmax] numbers in [lo, hi],
 * strictly ascending if asked; its length into *n (values into out when
 * not NULL). */
static int numbers_of(struct ctx *c, json_object *a, const char *label, int nmin, int nmax, double lo, double hi,
    int ascending, double *out, int *n)
{
	if (a == NULL || !json_object_is_type(a, json_type_array)) {
		*c->cause = xasprintf("%s: %s is missing or not an array", c->path, label);
		return -1;
	}
	*n = (int)json_object_array_length(a);
	if (*n < nmin || *n > nmax) {
		*c->cause = xasprintf("%s: %s has %d entries; allowed %d to %d", c->path, label, *n, nmin, nmax);
		return -1;
	}
	double prev = -INFINITY;
	for (int i = 0; i < *n; i++) {
		char what[96];
		double x;
		snprintf(what, sizeof what, "%s[%d]", label, i);
		if (number(c, json_object_array_get_idx(a, (size_t)i), what, lo, hi, &x) != 0)
			return -1;
		if (ascending && !(x > prev)) {
			*c->cause = xasprintf("%s: %s = %g is not above %s[%d] = %g (the axis must ascend)", c->path, what, x,
			    label, i - 1, prev);
			return -1;
		}
		prev = x;
		if (out)
			out[i] = x;
	}
	return 0;
}

/* Member KEY of o (PREFIX.KEY in messages) as numbers_of. */
static int numbers(struct ctx *c, json_object *o, const char *prefix, const char *key, int nmin, int nmax, double lo,
    double hi, int ascending, double *out, int *n)
{
	json_object *a = NULL;
	char label[96];
	snprintf(label, sizeof label, "%s%s%s", prefix, *prefix ? "." : "", key);
	json_object_object_get_ex(o, key, &a);
	return numbers_of(c, a, label, nmin, nmax, lo, hi, ascending, out, n);
}

/* The wavelengths: whole nanometres after rounding, each once. */
static int wavelengths(struct ctx *c, json_object *o, int *n_wl)
{
	double wl[BAKE_MAX_WL];
	if (numbers(c, o, "", "wavelengths_nm", 1, BAKE_MAX_WL, 300, 1000, 0, wl, n_wl) != 0)
		return -1;
	for (int i = 0; i < *n_wl; i++)
		for (int j = 0; j < i; j++)
			if (lround(wl[i]) == lround(wl[j])) {
				*c->cause = xasprintf("%s: wavelengths_nm[%d] = %g repeats wavelengths_nm[%d] = %g (each wavelength "
				    "names its own table channels)", c->path, i, wl[i], j, wl[j]);
				return -1;
			}
	return 0;
}

static int rgb(struct ctx *c, json_object *o, int n_wl)
{
	json_object *r, *m;
	if (!json_object_object_get_ex(o, "rgb", &r) || !json_object_object_get_ex(r, "rgb_from_wl", &m) ||
	    !json_object_is_type(m, json_type_array) || json_object_array_length(m) != 3) {
		*c->cause = xasprintf("%s: rgb.rgb_from_wl is missing or not 3 rows", c->path);
		return -1;
	}
	for (int k = 0; k < 3; k++) {
		char key[40];
		int n;
		snprintf(key, sizeof key, "rgb.rgb_from_wl[%d]", k);
		if (numbers_of(c, json_object_array_get_idx(m, (size_t)k), key, n_wl, n_wl, -100, 100, 0, NULL, &n) != 0)
			return -1;
	}
	return 0;
}

static int specular(struct ctx *c, json_object *o, int n_wl)
{
	json_object *sp, *v, *st;
	double x;
	if (!json_object_object_get_ex(o, "specular", &sp) || !json_object_is_type(sp, json_type_object)) {
		*c->cause = xasprintf("%s: specular is missing", c->path);
		return -1;
	}
	if (number(c, json_object_object_get_ex(sp, "ior", &v) ? v : NULL, "specular.ior", 1, 3, &x) != 0 ||
	    number(c, json_object_object_get_ex(sp, "alpha", &v) ? v : NULL, "specular.alpha", 0.01, 1, &x) != 0)
		return -1;
	if (!json_object_object_get_ex(sp, "stack_n", &st) || !json_object_is_type(st, json_type_array) ||
	    (int)json_object_array_length(st) != n_wl) {
		*c->cause = xasprintf("%s: specular.stack_n is missing or has not one row per wavelength (%d)", c->path, n_wl);
		return -1;
	}
	for (int w = 0; w < n_wl; w++) {
		char key[48];
		int n;
		snprintf(key, sizeof key, "specular.stack_n[%d]", w);
		if (numbers_of(c, json_object_array_get_idx(st, (size_t)w), key, 2, SPECULAR_MAX_IFACES, 1, 3, 0, NULL,
		    &n) != 0)
			return -1;
	}
	return 0;
}

/* The radial section is optional; when there, its sizes and values. */
static int radial(struct ctx *c, json_object *o, int n_wl)
{
	json_object *r, *v;
	int n;
	if (!json_object_object_get_ex(o, "radial", &r))
		return 0;
	if (json_object_object_get_ex(r, "mean_radius_cm", &v) &&
	    numbers(c, r, "radial", "mean_radius_cm", n_wl, n_wl, 0, 1e3, 0, NULL, &n) != 0)
		return -1;
	if (json_object_object_get_ex(r, "mean_radius_rgb_cm", &v) &&
	    numbers(c, r, "radial", "mean_radius_rgb_cm", 3, 3, 0, 1e3, 0, NULL, &n) != 0)
		return -1;
	return 0;
}

/* FILE in dir is W x H, as the manifest's axes say. */
static int table_size(struct ctx *c, const char *dir, const char *file, int w, int h)
{
	char *p = xasprintf("%s/%s", dir, file);
	int ew, eh, rc = exrio_size(p, &ew, &eh, c->cause);
	if (rc == 0 && (ew != w || eh != h)) {
		*c->cause = xasprintf("%s: %d x %d, but manifest.json's axes make it %d x %d", p, ew, eh, w, h);
		rc = -1;
	}
	free(p);
	return rc;
}

int manifest_check_bake(const char *dir, char **cause)
{
	char *mp = xasprintf("%s/manifest.json", dir);
	struct ctx c = { mp, cause };
	json_object *o = json_object_from_file(mp), *v;
	int rc = -1, n_wl, n_ti, n_to, n_phi;
	double ver;
	if (o == NULL || !json_object_is_type(o, json_type_object)) {
		rc = 0;	/* missing or not JSON: bake_manifest_read says so */
		goto out;
	}
	if (number(&c, json_object_object_get_ex(o, "format_version", &v) ? v : NULL, "format_version", 1, 1e6,
	    &ver) != 0 || wavelengths(&c, o, &n_wl) != 0 ||
	    numbers(&c, o, "", "theta_i_deg", 1, BAKE_MAX_TI, 0, 89.999999, 1, NULL, &n_ti) != 0 ||
	    numbers(&c, o, "", "theta_o_centres_deg", 1, 360, 0, 90, 1, NULL, &n_to) != 0 ||
	    numbers(&c, o, "", "delta_phi_centres_deg", 1, 360, 0, 180, 1, NULL, &n_phi) != 0 ||
	    rgb(&c, o, n_wl) != 0 || specular(&c, o, n_wl) != 0 || radial(&c, o, n_wl) != 0)
		goto out;
	if (checksum_verify_dir(dir, "manifest.json", cause) != 0 ||
	    table_size(&c, dir, "brdf.exr", n_phi, n_ti * n_to) != 0 ||
	    table_size(&c, dir, "brdf_rgb.exr", n_phi, n_ti * n_to) != 0 || table_size(&c, dir, "albedo.exr", n_ti, 1) != 0)
		goto out;
	rc = 0;
out:
	if (o)
		json_object_put(o);
	free(mp);
	return rc;
}

static int finite_all(const char *dir, const char *file, const float *v, size_t n, char **cause)
{
	for (size_t i = 0; i < n; i++)
		if (!isfinite(v[i])) {
			*cause = xasprintf("%s/%s: value %zu is %g, not a finite number", dir, file, i, (double)v[i]);
			return -1;
		}
	return 0;
}

int manifest_check_values(const struct bake *b, char **cause)
{
	size_t npx = (size_t)b->n_ti * (size_t)b->n_to * (size_t)b->n_phi;
	if (finite_all(b->dir, "brdf.exr", b->fr, npx * (size_t)b->n_wl, cause) != 0 ||
	    finite_all(b->dir, "brdf.exr", b->fr_err, npx * (size_t)b->n_wl, cause) != 0 ||
	    finite_all(b->dir, "brdf_rgb.exr", b->fr_rgb, 3 * npx, cause) != 0)
		return -1;
	for (size_t i = 0; i < (size_t)b->n_wl * (size_t)b->n_ti; i++)
		if (!isfinite(b->albedo[i])) {
			*cause = xasprintf("%s/albedo.exr: value %zu is %g, not a finite number", b->dir, i, b->albedo[i]);
			return -1;
		}
	return 0;
}
