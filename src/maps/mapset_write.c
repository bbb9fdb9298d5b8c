/* mapset_write: a maps directory written (layout in mapset.h): maps.json
 * and one image per parameter, the fit's error map and status, a band of
 * rows at a time through PNG and EXR row streams into a staging directory
 * renamed into place. */
#include "config.h"
#include "maps/mapset.h"

#include <json-c/json.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/checksum.h"
#include "base/outdir.h"
#include "base/util.h"
#include "io/exrio.h"
#include "io/json.h"
#include "io/pngio.h"

static void add(json_object *o, const char *k, json_object *v)
{
	json_object_object_add(o, k, v);
}

static json_object *num(double v)
{
	return json_num(v);
}

/* min, max and sum of a map's values, accumulated in texel order. */
struct map_stats {
	double lo, hi, s;
};

static void stats_add(struct map_stats *st, const float *v, size_t n)
{
	for (size_t i = 0; i < n; i++) {
		st->lo = fmin(st->lo, v[i]);
		st->hi = fmax(st->hi, v[i]);
		st->s += v[i];
	}
}

static json_object *summary_stats(const struct map_stats *st, size_t n)
{
	json_object *o = json_object_new_object();
	add(o, "min", num(st->lo));
	add(o, "max", num(st->hi));
	add(o, "mean", num(st->s / (double)n));
	return o;
}

static char *index_text(const struct mapset *m, int fit, const struct map_stats *st)
{
	const char *ext = m->exr ? "exr" : "png";
	json_object *o = json_object_new_object(), *fam = json_object_new_object(),
	    *maps = json_object_new_array();
	add(o, "format", json_object_new_string("skinbake-maps"));
	add(o, "format_version", json_object_new_int(MAPS_FORMAT_VERSION));
	add(o, "skinbake_version", json_object_new_string(PACKAGE_VERSION));
	add(o, "width", json_object_new_int(m->w));
	add(o, "height", json_object_new_int(m->h));
	add(o, "image_format", json_object_new_string(ext));
	add(fam, "dir", json_object_new_string(m->family_dir ? m->family_dir : ""));
	add(fam, "preset", json_object_new_string(m->family_preset ? m->family_preset : ""));
	add(o, "family", fam);
	size_t n = (size_t)m->w * m->h;
	for (int a = 0; a < m->n; a++) {
		const struct maps_param *p = &m->p[a];
		json_object *e = json_object_new_object();
		char *file = xasprintf("%s.%s", p->key, ext);
		add(e, "key", json_object_new_string(p->key));
		add(e, "unit", json_object_new_string(p->unit));
		add(e, "file", json_object_new_string(file));
		add(e, "encoding", json_object_new_string(m->exr
		    ? "float32 channel Y: the value in the key's unit"
		    : "16-bit grey q: value = lo + (hi - lo) * q / 65535"));
		add(e, "lo", num(p->key_lo));
		add(e, "hi", num(p->key_hi));
		json_object *fr = json_object_new_array();
		json_object_array_add(fr, num(p->fam_lo));
		json_object_array_add(fr, num(p->fam_hi));
		add(e, "family_range", fr);
		add(e, "values", summary_stats(&st[a], n));
		json_object_array_add(maps, e);
		free(file);
	}
	add(o, "maps", maps);
	if (fit) {
		json_object *e = json_object_new_object();
		char *file = xasprintf("de2000.%s", ext);
		add(e, "file", json_object_new_string(file));
		add(e, "encoding", json_object_new_string(m->exr ? "float32 channel Y: CIEDE2000"
		    : "16-bit grey q: CIEDE2000 = q / 1000 (up to 65.535)"));
		add(e, "meaning",
		    json_object_new_string("CIEDE2000 between the texel's colour and the family's "
		    "albedo at the fitted parameters"));
		add(o, "de2000", e);
		free(file);
	}
	if (fit) {
		json_object *e = json_object_new_object();
		add(e, "file", json_object_new_string("status.png"));
		add(e, "encoding",
		    json_object_new_string("8-bit grey: 0 matched, 255 unmatched (closest family "
		    "colour further than max_de), 128 not fitted (transparent or outside the "
		    "mask)"));
		add(o, "status", e);
	}
	if (m->fit) {
		json_object *f = json_parse(m->fit);
		if (f)
			add(o, "fit", f);
	}
	json_object *h = json_object_new_array();
	for (int i = 0; i < m->n_history; i++)
		json_object_array_add(h, json_object_new_string(m->history[i]));
	add(o, "history", h);
	char *text = json_text(o, JSON_PRETTY);
	json_object_put(o);
	return text;
}

/* One file of a maps directory being written: a PNG or EXR row stream
 * and its conversion (16-bit PNG of (v - lo) / (hi - lo), the value in a
 * float EXR, or the 8-bit status). */
struct map_file {
	char *path;
	struct pngio_writer *png;
	struct exrio_writer *exr;
	double lo, hi;
	int status;		/* the 8-bit status map */
	uint16_t *px;		/* a band's PNG samples */
	char *cause;		/* a failure's, reported after the band */
};

struct mapset_writer {
	struct outdir od;
	int w, h, y, n, fit, exr, threads;
	int nf;				/* files: the maps, then de2000 and status */
	struct map_file f[FAMILY_MAX_AXES + 2];
	struct map_stats st[FAMILY_MAX_AXES];
	int band;			/* rows the px buffers hold */
};

static int file_open(struct map_file *mf, const char *stage, const char *name,
    const struct mapset *m,
    const char *key, double lo, double hi, int status, char **cause)
{
	char los[40], his[40];
	mf->path = xasprintf("%s/%s", stage, name);
	mf->lo = lo;
	mf->hi = hi;
	mf->status = status;
	snprintf(los, sizeof los, "%.17g", lo);
	snprintf(his, sizeof his, "%.17g", hi);
	if (status) {
		struct png_text_kv tx[] = { { "Comment",
		    "0 matched, 255 unmatched, 128 not fitted (see maps.json)" } };
		mf->png = pngio_writer_open(mf->path, m->w, m->h, 1, 8, 0, 1, tx, cause);
		return mf->png ? 0 : -1;
	}
	if (m->exr) {
		const char *names[] = { "Y" };
		struct exr_attr_kv kv[] = { { "skinbake:key", key } };
		mf->exr = exrio_writer_open(mf->path, m->w, m->h, 1, names, 1, kv, cause);
		return mf->exr ? 0 : -1;
	}
	struct png_text_kv tx[] = { { "Software", PACKAGE_STRING }, { "skinbake:key", key },
		{ "skinbake:lo", los }, { "skinbake:hi", his },
		{ "Comment", "16-bit map: value = lo + (hi - lo) * q / 65535 (see maps.json)" } };
	mf->png = pngio_writer_open(mf->path, m->w, m->h, 1, 16, 0, 5, tx, cause);
	return mf->png ? 0 : -1;
}

/* lround(top * fmin(1, fmax(0, x))) as image_write_png computes it
 * (a NaN gives 0), without the library calls: y - trunc(y) is exact for
 * y in [0, 65535], so rounding half up from it is lround's. */
static inline uint16_t quantise(double top, float x)
{
	double c = x > 0.0f ? (x < 1.0f ? (double)x : 1.0) : 0.0, y = top * c;
	long r = (long)y;
	return (uint16_t)(r + (y - (double)r >= 0.5));
}

/* nrows rows of the file from v (floats) or st (status); the values
 * image_write_png and image_write_exr would write for the whole map. */
static int file_rows(struct map_file *mf, int w, int nrows, const float *v, const unsigned char *st)
{
	size_t n = (size_t)w * (size_t)nrows;
	if (mf->exr)
		return exrio_writer_rows(mf->exr, &v, nrows, &mf->cause) == 0 ? 0 : (mf->exr = NULL,
		    -1);
	if (mf->status)
		for (size_t i = 0; i < n; i++) {
			float x = (float)(st[i] / 255.0);
			mf->px[i] = quantise(255.0, x);
		}
	else
		for (size_t i = 0; i < n; i++) {
			float x = (float)((v[i] - mf->lo) / (mf->hi - mf->lo));
			mf->px[i] = quantise(65535.0, x);
		}
	return pngio_writer_rows(mf->png, mf->px, nrows, &mf->cause) == 0 ? 0 : (mf->png = NULL,
	    -1);
}

static void file_free(struct map_file *mf)
{
	pngio_writer_abort(mf->png);
	exrio_writer_abort(mf->exr);
	free(mf->path);
	free(mf->px);
	free(mf->cause);
	memset(mf, 0, sizeof *mf);
}

void mapset_writer_abort(struct mapset_writer *wr)
{
	if (wr == NULL)
		return;
	for (int k = 0; k < wr->nf; k++)
		file_free(&wr->f[k]);
	outdir_abort(&wr->od);
	free(wr);
}

/* The writer's failure: *cause (named by the target), everything removed. */
static int writer_fail(struct mapset_writer *wr, char **cause)
{
	for (int k = 0; k < wr->nf; k++)
		file_free(&wr->f[k]);
	wr->nf = 0;
	outdir_fail(&wr->od, cause);
	free(wr);
	return -1;
}

struct mapset_writer *mapset_writer_begin(const char *dir, const struct mapset *m, int fit,
    int threads,
    char **cause)
{
	struct mapset_writer *wr = xcalloc(1, sizeof *wr);
	if (outdir_begin(&wr->od, dir, &mapset_outdir_kind, cause) != 0) {
		free(wr);
		return NULL;
	}
	wr->w = m->w;
	wr->h = m->h;
	wr->n = m->n;
	wr->fit = fit;
	wr->exr = m->exr;
	wr->threads = threads;
	const char *stage = outdir_path(&wr->od), *ext = m->exr ? "exr" : "png";
	for (int a = 0; a < m->n; a++) {
		wr->st[a].lo = INFINITY;
		wr->st[a].hi = -INFINITY;
		char *name = xasprintf("%s.%s", m->p[a].key, ext);
		int rc = file_open(&wr->f[wr->nf++], stage, name, m, m->p[a].key, m->p[a].key_lo,
		    m->p[a].key_hi, 0, cause);
		free(name);
		if (rc != 0) {
			writer_fail(wr, cause);
			return NULL;
		}
	}
	if (fit) {
		char *name = xasprintf("de2000.%s", ext);
		int rc = file_open(&wr->f[wr->nf++], stage, name, m, "de2000", 0.0, 65.535, 0,
		    cause);
		free(name);
		if (rc != 0 || file_open(&wr->f[wr->nf++], stage, "status.png", m, NULL, 0.0, 255.0,
		    1, cause) != 0) {
			writer_fail(wr, cause);
			return NULL;
		}
	}
	return wr;
}

int mapset_writer_rows(struct mapset_writer *wr, int nrows, const float *const *v,
    const float *de2000,
    const unsigned char *status, char **cause)
{
	CHECK(wr->y + nrows <= wr->h);
	size_t n = (size_t)wr->w * (size_t)nrows;
	if (nrows > wr->band) {
		wr->band = nrows;
		for (int k = 0; k < wr->nf; k++)
			if (wr->f[k].png)
				wr->f[k].px = xreallocarray(wr->f[k].px, n, sizeof(uint16_t));
	}
	for (int a = 0; a < wr->n; a++)
		stats_add(&wr->st[a], v[a], n);
	int failed = 0;
	(void)wr->threads; /* only OpenMP's pragma reads it */
#pragma omp parallel for schedule(dynamic, 1) num_threads(wr->threads) reduction(+ : failed)
	for (int k = 0; k < wr->nf; k++)
		failed += file_rows(&wr->f[k], wr->w, nrows, k < wr->n ? v[k] : de2000,
		    status) != 0;
	if (failed) {
		for (int k = 0; k < wr->nf; k++)
			if (wr->f[k].cause) {
				*cause = wr->f[k].cause;
				wr->f[k].cause = NULL;
				break;
			}
		return writer_fail(wr, cause);
	}
	wr->y += nrows;
	return 0;
}

int mapset_writer_end(struct mapset_writer *wr, const struct mapset *m, char **cause)
{
	CHECK(wr->y == wr->h);
	for (int k = 0; k < wr->nf; k++) {
		struct map_file *mf = &wr->f[k];
		int rc = mf->png ? pngio_writer_close(mf->png, cause) : exrio_writer_close(mf->exr,
		    cause);
		mf->png = NULL;
		mf->exr = NULL;
		if (rc != 0)
			return writer_fail(wr, cause);
	}
	char *text = index_text(m, wr->fit, wr->st);
	int rc = checksum_write_manifest(outdir_path(&wr->od), "maps.json", text, cause);
	free(text);
	if (rc != 0)
		return writer_fail(wr, cause);
	for (int k = 0; k < wr->nf; k++)
		file_free(&wr->f[k]);
	rc = outdir_commit(&wr->od, cause);
	free(wr);
	return rc;
}

int mapset_write(const char *dir, const struct mapset *m, char **cause)
{
	struct mapset_writer *wr = mapset_writer_begin(dir, m, m->de2000 != NULL, 1, cause);
	if (wr == NULL)
		return -1;
	const float *v[FAMILY_MAX_AXES];
	unsigned char *st = NULL;
	/* (never made so; taken as the status 0 of every texel) */
	if (m->de2000 && m->status == NULL)
		st = xcalloc((size_t)m->w * m->h, 1);
	enum { BAND = 64 };
	for (int y = 0; y < m->h; y += BAND) {
		int nr = m->h - y < BAND ? m->h - y : BAND;
		size_t off = (size_t)y * (size_t)m->w;
		for (int a = 0; a < m->n; a++)
			v[a] = m->p[a].v + off;
		if (mapset_writer_rows(wr, nr, v, m->de2000 ? m->de2000 + off : NULL,
		    m->de2000 ? (st ? st : m->status) + off : NULL, cause) != 0) {
			free(st);
			return -1;
		}
	}
	free(st);
	return mapset_writer_end(wr, m, cause);
}

