/* family: the family directory (layout in family.h): axes, family.json
 * written and read, the swatch preview, the member tables. */
#include "config.h"
#include "family/family.h"

#include <json-c/json.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/check.h"
#include "base/srgb.h"
#include "base/checksum.h"
#include "base/util.h"
#include "io/json.h"
#include "io/pngio.h"
#include "skin/preset.h"

/* ---- axes ---- */

const char *family_spacing_name(enum family_spacing s)
{
	static const char *names[] = { "lin", "log", "de", "list" };
	return names[s];
}

int family_axis_init(struct family_axis *a, const char *key, double lo, double hi, int n, enum family_spacing spacing,
    const double *list, char **cause)
{
	memset(a, 0, sizeof *a);
	const char *unit;
	if (strlen(key) >= sizeof a->key || preset_number_key(key, &a->key_lo, &a->key_hi, &unit, cause) != 0) {
		if (*cause == NULL)
			*cause = xasprintf("'%s' is not a numeric preset key", key);
		return -1;
	}
	snprintf(a->key, sizeof a->key, "%s", key);
	snprintf(a->unit, sizeof a->unit, "%s", unit);
	a->spacing = spacing;
	a->n = n;
	const char *u = *unit ? " " : "";
	if (n < 2 || n > FAMILY_MAX_NODES) {
		*cause = xasprintf("%s: %d nodes is out of range [2, %d]", key, n, FAMILY_MAX_NODES);
		return -1;
	}
	if (spacing == FAMILY_SPACING_LIST) {
		lo = list[0];
		hi = list[n - 1];
		for (int i = 1; i < n; i++)
			if (!(list[i] > list[i - 1])) {
				*cause = xasprintf("%s: the values must ascend strictly (%g after %g)", key, list[i], list[i - 1]);
				return -1;
			}
	}
	if (!(lo >= a->key_lo && hi <= a->key_hi)) {
		*cause = xasprintf("%s: %g:%g is outside the key's range [%g, %g]%s%s", key, lo, hi, a->key_lo, a->key_hi, u,
		    unit);
		return -1;
	}
	if (!(hi > lo)) {
		*cause = xasprintf("%s: the range %g:%g is empty (the end must exceed the start)", key, lo, hi);
		return -1;
	}
	if (spacing == FAMILY_SPACING_LOG && !(lo > 0)) {
		*cause = xasprintf("%s: log spacing needs a start > 0 (%g given)", key, lo);
		return -1;
	}
	a->lo = lo;
	a->hi = hi;
	for (int i = 0; i < n; i++) {
		double t = (double)i / (n - 1);
		if (spacing == FAMILY_SPACING_LIST)
			a->node[i] = list[i];
		else if (spacing == FAMILY_SPACING_LOG)
			a->node[i] = exp(log(lo) + t * (log(hi) - log(lo)));
		else
			a->node[i] = lo + t * (hi - lo);	/* lin; de until placed */
	}
	a->node[0] = lo;
	a->node[n - 1] = hi;
	a->log_coord = spacing != FAMILY_SPACING_LIN && lo > 0;
	return 0;
}

void family_member_index(const struct family *f, int m, int idx[FAMILY_MAX_AXES])
{
	for (int a = 0; a < FAMILY_MAX_AXES; a++) {
		if (a < f->n_axes) {
			idx[a] = m % f->axis[a].n;
			m /= f->axis[a].n;
		} else
			idx[a] = 0;
	}
}

void family_free(struct family *f)
{
	if (f == NULL)
		return;
	for (int m = 0; m < f->n_members && f->member; m++)
		free(f->member[m].albedo_wl);
	if (f->bake)
		for (int m = 0; m < f->n_members; m++)
			bake_free(f->bake[m]);
	free(f->bake);
	free(f->log_albedo);
	free(f->member);
	free(f->dir);
	free(f->preset);
	free(f->preset_ini);
	free(f->notes);
	free(f->wl_nm);
	free(f->rgb_from_wl);
	free(f->solver);
	free(f->spec);
	free(f);
}

/* ---- writer ---- */

static json_object *jarr(const double *v, int n)
{
	return json_num_array(v, n);
}

static void add(json_object *o, const char *key, json_object *v)
{
	json_object_object_add(o, key, v);
}

static json_object *axis_json(const struct family_axis *a)
{
	json_object *o = json_object_new_object();
	add(o, "key", json_object_new_string(a->key));
	add(o, "unit", json_object_new_string(a->unit));
	add(o, "spacing", json_object_new_string(family_spacing_name(a->spacing)));
	add(o, "log_coordinate", json_object_new_boolean(a->log_coord));
	add(o, "interpolation", json_object_new_string(a->log_coord ? "4-point Lagrange in log(value)"
	    : "4-point Lagrange in the value"));
	double r[2] = { a->lo, a->hi }, kr[2] = { a->key_lo, a->key_hi };
	add(o, "range", jarr(r, 2));
	add(o, "key_range", jarr(kr, 2));
	add(o, "nodes", jarr(a->node, a->n));
	if (a->spacing == FAMILY_SPACING_DE) {
		json_object *p = json_object_new_object();
		add(p, "values", jarr(a->pilot_value, a->n_pilot));
		add(p, "cumulative_de2000", jarr(a->pilot_de, a->n_pilot));
		add(p, "fallback_uniform", json_object_new_boolean(a->de_fallback));
		add(o, "pilot", p);
	}
	return o;
}

static json_object *spec_json(const struct family *f)
{
	const struct bake_spec *s = f->spec;
	json_object *o = json_object_new_object();
	double th[BAKE_MAX_TI];
	for (int i = 0; i < s->n_ti; i++)
		th[i] = s->theta_i[i] * 180.0 / M_PI;
	add(o, "solver", json_object_new_string(f->solver ? f->solver : ""));
	add(o, "theta_i_deg", jarr(th, s->n_ti));
	add(o, "n_theta_o", json_object_new_int(s->n_to));
	add(o, "n_delta_phi", json_object_new_int(s->n_phi));
	add(o, "n_r", json_object_new_int(s->n_r));
	add(o, "dr_cm", json_num(s->dr));
	add(o, "fresnel", json_object_new_string(s->opts.fresnel == OPTICS_FRESNEL_SCHLICK ? "schlick" : "exact"));
	add(o, "estimator", json_object_new_string(s->nee ? "nee" : "bins"));
	add(o, "seed", json_object_new_uint64(s->seed));
	add(o, "batch_photons", json_object_new_int64(s->batch_photons));
	add(o, "min_batches", json_object_new_int(s->min_batches));
	add(o, "target_error", json_num(s->target_error));
	add(o, "max_photons", json_object_new_int64(s->max_photons));
	add(o, "roulette_w", json_num(s->opts.roulette_w));
	add(o, "roulette_chance", json_num(s->opts.roulette_chance));
	add(o, "max_steps", json_object_new_int64(s->opts.max_steps));
	/* The solver asked for and its settings, so that a reader (an off-node
	 * bake, family_bake_at's users) bakes as the members were baked. */
	add(o, "requested", json_object_new_string(bake_method_name(s->method)));
	add(o, "ad_tol", json_num(s->ad_tol));
	add(o, "ad_quad", json_object_new_int(s->ad_quad));
	add(o, "radial_error", json_num(s->radial_error));
	add(o, "radial_photons", json_object_new_int64(s->radial_photons));
	return o;
}

static json_object *member_json(const struct family *f, int m)
{
	const struct family_member *fm = &f->member[m];
	int idx[FAMILY_MAX_AXES];
	family_member_index(f, m, idx);
	json_object *o = json_object_new_object();
	char name[16];
	snprintf(name, sizeof name, "m%04d", m);
	add(o, "index", json_object_new_int(m));
	add(o, "dir", json_object_new_string(name));
	json_object *ni = json_object_new_array();
	for (int a = 0; a < f->n_axes; a++)
		json_object_array_add(ni, json_object_new_int(idx[a]));
	add(o, "node", ni);
	add(o, "params", jarr(fm->param, f->n_axes));
	add(o, "albedo_wl", jarr(fm->albedo_wl, f->n_wl));
	add(o, "albedo_rgb", jarr(fm->albedo_rgb, 3));
	add(o, "albedo_lab", jarr(fm->albedo_lab, 3));
	add(o, "sss_radius_rgb_cm", jarr(fm->sss_radius_rgb_cm, 3));
	add(o, "rms_rel_err", json_num(fm->rms_rel_err));
	add(o, "seconds", json_num(fm->seconds));
	return o;
}

static char *index_text(const struct family *f, const char *command)
{
	json_object *o = json_object_new_object();
	add(o, "format", json_object_new_string("skinbake-family"));
	add(o, "format_version", json_object_new_int(FAMILY_FORMAT_VERSION));
	add(o, "skinbake_version", json_object_new_string(PACKAGE_VERSION));
	if (command)
		add(o, "command", json_object_new_string(command));
	add(o, "preset", json_object_new_string(f->preset ? f->preset : ""));
	add(o, "preset_file", json_object_new_string("preset.ini"));
	add(o, "member_order", json_object_new_string("m = i0 + n0 * (i1 + n1 * i2), i_a the node index on axis a; "
	    "member m is the bake directory mNNNN (4 digits)"));
	json_object *ax = json_object_new_array();
	for (int a = 0; a < f->n_axes; a++)
		json_object_array_add(ax, axis_json(&f->axis[a]));
	add(o, "axes", ax);
	add(o, "wavelengths_nm", jarr(f->wl_nm, f->n_wl));
	json_object *w = json_object_new_array();
	for (int c = 0; c < 3; c++)
		json_object_array_add(w, jarr(f->rgb_from_wl + c * f->n_wl, f->n_wl));
	add(o, "rgb_from_wl", w);
	json_object *al = json_object_new_object();
	add(al, "theta_i_deg", json_num(f->albedo_theta_i * 180.0 / M_PI));
	add(al, "definition", json_object_new_string("directional-hemispherical diffuse albedo (specular excluded) at "
	    "theta_i_deg; albedo_rgb in linear sRGB (Rec. 709, D65, CIE 1931 2-degree), albedo_lab CIELAB with the "
	    "sRGB white (D65); sss_radius_rgb_cm the mean exit radius per R, G, B (bake manifest radial section)"));
	add(o, "albedo", al);
	add(o, "bake", spec_json(f));
	add(o, "rms_rel_err", json_num(f->rms_rel_err));
	json_object *mem = json_object_new_array_ext(f->n_members);
	for (int m = 0; m < f->n_members; m++)
		json_object_array_add(mem, member_json(f, m));
	add(o, "members", mem);
	char *text = json_text(o, JSON_PRETTY);
	json_object_put(o);
	return text;
}

/* swatches.png: SW x SW pixels per member, axis 0 across, the rest down. */
static int write_swatches(const char *dir, const struct family *f, char **cause)
{
	enum { SW = 16 };
	int nx = f->axis[0].n, ny = f->n_members / nx, W = nx * SW, H = ny * SW;
	uint16_t *px = xmalloc(sizeof(uint16_t) * 3 * (size_t)W * (size_t)H);
	for (int y = 0; y < H; y++)
		for (int x = 0; x < W; x++) {
			const struct family_member *fm = &f->member[(y / SW) * nx + x / SW];
			for (int c = 0; c < 3; c++)
				px[((size_t)y * W + x) * 3 + c] = (uint16_t)lround(255.0 * srgb_encode(fm->albedo_rgb[c]));
		}
	char *path = xasprintf("%s/swatches.png", dir);
	struct png_text_kv tx[] = { { "Software", PACKAGE_STRING },
		{ "Comment", "family members' diffuse albedo at the first incidence node, sRGB; axis 0 across, axis 1 "
		  "down, axis 2 in blocks down" } };
	int rc = pngio_write(path, W, H, 3, 8, px, 1, 2, tx, cause);
	free(path);
	free(px);
	return rc;
}

int family_write_index(const char *dir, const struct family *f, const char *command, char **cause)
{
	if (write_swatches(dir, f, cause) != 0)
		return -1;
	char *text = index_text(f, command);
	int rc = checksum_write_manifest(dir, "family.json", text, cause);
	free(text);
	return rc;
}

static const char *const family_names[] = { "family.json", "preset.ini", "swatches.png", "m[0-9][0-9][0-9][0-9]*",
	NULL };
const struct outdir_kind family_outdir_kind = { "family directory", "family.json", "format", "skinbake-family",
	family_names };

int family_check_out(const char *dir, char **cause)
{
	return outdir_check(dir, &family_outdir_kind, NULL, cause);
}
