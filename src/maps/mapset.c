/* mapset: the maps directory (layout in mapset.h): maps.json and one
 * image per parameter, the fit's error map and status, written through a
 * staging directory and read back with messages that name the file. */
#include "config.h"
#include "maps/mapset.h"

#include <errno.h>
#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <stdio.h>
#include <unistd.h>

#include "base/outdir.h"
#include "base/checksum.h"
#include "base/check.h"
#include "base/util.h"
#include "io/exrio.h"
#include "io/json.h"
#include "io/pngio.h"
#include "maps/image.h"

struct mapset *mapset_new(const struct family *f, int w, int h, const double *x)
{
	struct mapset *m = xcalloc(1, sizeof *m);
	m->w = w;
	m->h = h;
	m->n = f->n_axes;
	size_t n = (size_t)w * h;
	for (int a = 0; a < f->n_axes; a++) {
		const struct family_axis *ax = &f->axis[a];
		struct maps_param *p = &m->p[a];
		snprintf(p->key, sizeof p->key, "%s", ax->key);
		snprintf(p->unit, sizeof p->unit, "%s", ax->unit);
		p->key_lo = ax->key_lo;
		p->key_hi = ax->key_hi;
		p->fam_lo = ax->node[0];
		p->fam_hi = ax->node[ax->n - 1];
		double v = x ? x[a] : ax->log_coord ? sqrt(p->fam_lo * p->fam_hi) : 0.5 * (p->fam_lo + p->fam_hi);
		p->v = xmalloc(sizeof(float) * n);
		for (size_t i = 0; i < n; i++)
			p->v[i] = (float)v;
	}
	m->family_dir = xstrdup(f->dir ? f->dir : "");
	m->family_preset = xstrdup(f->preset ? f->preset : "");
	return m;
}

void mapset_free(struct mapset *m)
{
	if (m == NULL)
		return;
	for (int a = 0; a < m->n; a++)
		free(m->p[a].v);
	for (int i = 0; i < m->n_history; i++)
		free(m->history[i]);
	free(m->history);
	free(m->de2000);
	free(m->status);
	free(m->family_dir);
	free(m->family_preset);
	free(m->fit);
	free(m);
}

void mapset_add_history(struct mapset *m, const char *command)
{
	m->history = xreallocarray(m->history, (size_t)m->n_history + 1, sizeof *m->history);
	m->history[m->n_history++] = xstrdup(command);
}

int mapset_find(const struct mapset *m, const char *key)
{
	for (int a = 0; a < m->n; a++)
		if (strcmp(m->p[a].key, key) == 0)
			return a;
	return -1;
}

static const char *const mapset_names[] = { "maps.json", "*.png", "*.exr", NULL };
const struct outdir_kind mapset_outdir_kind = { "maps directory", "maps.json", "format", "skinbake-maps", mapset_names };

int mapset_check_out(const char *dir, char **cause)
{
	return outdir_check(dir, &mapset_outdir_kind, NULL, cause);
}

/* ---- reader ---- */

static const char *jstr(json_object *o, const char *k)
{
	json_object *v;
	return json_object_object_get_ex(o, k, &v) && json_object_is_type(v, json_type_string) ? json_object_get_string(v)
	    : NULL;
}

static int jnum(json_object *o, const char *k, double *out)
{
	return json_get_num(o, k, out) == 0 ? 0 : -1;
}

/* A map file of the directory: its size must be maps.json's. */
static float *read_map(const char *dir, const char *file, const struct mapset *m, int png, double lo, double hi,
    char **cause)
{
	char *path = xasprintf("%s/%s", dir, file);
	struct image *im = image_read(path, cause);
	float *v = NULL;
	if (im && (im->w != m->w || im->h != m->h))
		*cause = xasprintf("%s: %d x %d texels, expected %d x %d (maps.json)", path, im->w, im->h, m->w, m->h);
	else if (im && ((png && im->bits == 32) || (!png && im->bits != 32)))
		*cause = xasprintf("%s: a %s image, expected %s (maps.json image_format)", path, im->bits == 32 ? "EXR"
		    : "PNG", png ? "PNG" : "EXR");
	else if (im) {
		size_t n = (size_t)m->w * m->h;
		v = xmalloc(sizeof(float) * n);
		for (size_t i = 0; i < n; i++) {
			double x = image_get(im, i, 0);
			v[i] = (float)(png ? lo + (hi - lo) * x : x);
		}
	}
	image_free(im);
	free(path);
	return v;
}

static int read_params(const char *dir, const char *path, json_object *o, struct mapset *m, int png, char **cause)
{
	json_object *maps;
	if (!json_object_object_get_ex(o, "maps", &maps) || !json_object_is_type(maps, json_type_array) ||
	    json_object_array_length(maps) < 1 || json_object_array_length(maps) > FAMILY_MAX_AXES) {
		*cause = xasprintf("%s: field maps is missing or not an array of 1 to %d maps", path, FAMILY_MAX_AXES);
		return -1;
	}
	m->n = (int)json_object_array_length(maps);
	for (int a = 0; a < m->n; a++) {
		json_object *e = json_object_array_get_idx(maps, (size_t)a), *fr;
		struct maps_param *p = &m->p[a];
		const char *key = jstr(e, "key"), *file = jstr(e, "file"), *unit = jstr(e, "unit");
		if (!key || !file || jnum(e, "lo", &p->key_lo) || jnum(e, "hi", &p->key_hi) ||
		    !json_object_object_get_ex(e, "family_range", &fr) || json_object_array_length(fr) != 2) {
			*cause = xasprintf("%s: field maps[%d] lacks key, file, lo, hi or family_range", path, a);
			return -1;
		}
		if (strlen(key) >= sizeof p->key || strchr(file, '/')) {
			*cause = xasprintf("%s: field maps[%d] has a bad key or file name", path, a);
			return -1;
		}
		snprintf(p->key, sizeof p->key, "%s", key);
		snprintf(p->unit, sizeof p->unit, "%s", unit ? unit : "");
		p->fam_lo = json_object_get_double(json_object_array_get_idx(fr, 0));
		p->fam_hi = json_object_get_double(json_object_array_get_idx(fr, 1));
		if ((p->v = read_map(dir, file, m, png, p->key_lo, p->key_hi, cause)) == NULL)
			return -1;
	}
	return 0;
}

static int read_extras(const char *dir, json_object *o, struct mapset *m, int png, char **cause)
{
	json_object *e, *h;
	const char *f;
	if (json_object_object_get_ex(o, "de2000", &e) && (f = jstr(e, "file")) != NULL &&
	    (m->de2000 = read_map(dir, f, m, png, 0.0, 65.535, cause)) == NULL)
		return -1;
	if (json_object_object_get_ex(o, "status", &e) && (f = jstr(e, "file")) != NULL) {
		float *s = read_map(dir, f, m, 1, 0.0, 255.0, cause);
		if (s == NULL)
			return -1;
		m->status = xmalloc((size_t)m->w * m->h);
		for (size_t i = 0; i < (size_t)m->w * m->h; i++)
			m->status[i] = (unsigned char)lround(s[i]);
		free(s);
	}
	if (json_object_object_get_ex(o, "fit", &e))
		m->fit = json_text(e, JSON_PLAIN);
	if (json_object_object_get_ex(o, "history", &h) && json_object_is_type(h, json_type_array))
		for (size_t i = 0; i < json_object_array_length(h); i++)
			mapset_add_history(m, json_object_get_string(json_object_array_get_idx(h, i)));
	return 0;
}

/* DIR/maps.json (path) read and its head checked into m: format, version,
 * size, image format; checksums of the files when verify.  The JSON
 * object, or NULL and *cause. */
static json_object *read_index(const char *dir, const char *path, struct mapset *m, int verify,
    char **cause)
{
	json_object *o = NULL, *fam;
	double ver, w, h;
	const char *s, *fmt;
	if (access(path, R_OK) != 0) {
		*cause = xasprintf("%s: not a maps directory (%s: %s)", dir, path, strerror(errno));
		goto fail;
	}
	if ((o = json_load(path)) == NULL || !json_object_is_type(o, json_type_object)) {
		*cause = xasprintf("%s: not a skinbake maps index (corrupt JSON)", path);
		goto fail;
	}
	if (verify && checksum_verify_dir(dir, "maps.json", cause) != 0)
		goto fail;
	if ((s = jstr(o, "format")) == NULL || strcmp(s, "skinbake-maps") != 0) {
		*cause = xasprintf("%s: field format = '%s', expected 'skinbake-maps'", path, s ? s : "(missing)");
		goto fail;
	}
	if (jnum(o, "format_version", &ver) || ver != MAPS_FORMAT_VERSION) {
		*cause = xasprintf("%s: field format_version = %g, expected %d", path, ver, MAPS_FORMAT_VERSION);
		goto fail;
	}
	if (jnum(o, "width", &w) || jnum(o, "height", &h) || !(w >= 1 && h >= 1 && w <= 65536 && h <= 65536)) {
		*cause = xasprintf("%s: fields width and height must be sizes in [1, 65536]", path);
		goto fail;
	}
	m->w = (int)w;
	m->h = (int)h;
	if ((fmt = jstr(o, "image_format")) == NULL || (strcmp(fmt, "png") != 0 && strcmp(fmt, "exr") != 0)) {
		*cause = xasprintf("%s: field image_format = '%s', expected png or exr", path, fmt ? fmt : "(missing)");
		goto fail;
	}
	m->exr = strcmp(fmt, "exr") == 0;
	if (json_object_object_get_ex(o, "family", &fam)) {
		m->family_dir = xstrdup(jstr(fam, "dir") ? jstr(fam, "dir") : "");
		m->family_preset = xstrdup(jstr(fam, "preset") ? jstr(fam, "preset") : "");
	}
	return o;
fail:
	if (o)
		json_object_put(o);
	return NULL;
}

struct mapset *mapset_read(const char *dir, char **cause)
{
	char *path = xasprintf("%s/maps.json", dir);
	struct mapset *m = xcalloc(1, sizeof *m);
	json_object *o = read_index(dir, path, m, 1, cause);
	if (o == NULL || read_params(dir, path, o, m, !m->exr, cause)
	    || read_extras(dir, o, m, !m->exr, cause)) {
		if (o)
			json_object_put(o);
		free(path);
		mapset_free(m);
		return NULL;
	}
	json_object_put(o);
	free(path);
	return m;
}

int mapset_read_size(const char *dir, int *w, int *h, int *n, char **cause)
{
	char *path = xasprintf("%s/maps.json", dir);
	struct mapset *m = xcalloc(1, sizeof *m);
	json_object *o = read_index(dir, path, m, 0, cause), *maps;
	int rc = -1;
	int ok = o && json_object_object_get_ex(o, "maps", &maps);
	ok = ok && json_object_is_type(maps, json_type_array);
	if (o && !ok)
		*cause = xasprintf("%s: field maps is missing or not an array", path);
	else if (o) {
		*w = m->w;
		*h = m->h;
		*n = (int)json_object_array_length(maps);
		rc = 0;
	}
	if (o)
		json_object_put(o);
	free(path);
	mapset_free(m);
	return rc;
}

int mapset_check_family(const struct mapset *m, const char *dir, const struct family *f, char **cause)
{
	if (m->n != f->n_axes) {
		*cause = xasprintf("%s: %d maps, but the family %s has %d axes", dir, m->n, f->dir, f->n_axes);
		return -1;
	}
	size_t n = (size_t)m->w * m->h;
	const char *ext = m->exr ? "exr" : "png";
	for (int a = 0; a < m->n; a++) {
		const struct family_axis *ax = &f->axis[a];
		if (strcmp(m->p[a].key, ax->key) != 0) {
			*cause = xasprintf("%s: map %d is %s, but axis %d of the family %s is %s", dir, a, m->p[a].key, a, f->dir,
			    ax->key);
			return -1;
		}
		/* Allow the 16-bit quantisation of the PNG encoding at the ends. */
		double lo = ax->node[0], hi = ax->node[ax->n - 1], tol = m->exr ? 0 : (m->p[a].key_hi - m->p[a].key_lo) / 65535.0;
		for (size_t i = 0; i < n; i++)
			if (!(m->p[a].v[i] >= lo - tol && m->p[a].v[i] <= hi + tol)) {
				*cause = xasprintf("%s/%s.%s: texel (%zu, %zu) has %s = %g, outside the family's range [%g, %g]", dir,
				    m->p[a].key, ext, i % (size_t)m->w, i / (size_t)m->w, m->p[a].key, m->p[a].v[i], lo, hi);
				return -1;
			}
	}
	return 0;
}

char *mapset_command_line(const char *action, int argc, char **argv)
{
	char *s = xasprintf("skinbake maps %s", action);
	for (int i = 1; i < argc; i++) {
		char *t = xasprintf("%s %s", s, argv[i]);
		free(s);
		s = t;
	}
	return s;
}
