/* fit: parameters per texel from an albedo colour (method in fit.h): the
 * dense CIELAB table of the family, its bucket grid, the nearest node and
 * the Gauss-Newton refinement, distinct colours, the summary. */
#include "config.h"
#include "maps/fit.h"

#include <json-c/json.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/check.h"
#include "base/srgb.h"
#include "base/util.h"
#include "io/json.h"
#include "maps/fitlut.h"
#include "skin/colour.h"

static int n_threads(int t)
{
#ifdef _OPENMP
	return t > 0 ? t : omp_get_max_threads();
#else
	(void)t;
	return 1;
#endif
}

void maps_texel_linear(const struct image *im, size_t i, int input_linear, double rgb[3])
{
	for (int c = 0; c < 3; c++) {
		double v = image_get(im, i, c);
		rgb[c] = input_linear ? v : srgb_decode(v);
	}
}

/* Distinct colours: a hash of the bits of the three values, ids in the
 * order of first appearance (raster order, so neighbouring ids are mostly
 * neighbouring texels of similar colour).  The table grows with the
 * colours found, so a texture streamed in bands needs memory for its
 * distinct colours only: per colour its key (12 bytes), 8 to 16 bytes of
 * 4-byte hash slots and its result (4 bytes per axis and the error). */
struct colours {
	long n;			/* distinct colours */
	uint32_t (*key)[3];	/* [n] the bits of the texel's three float values */
	size_t kcap;		/* keys allocated */
	int32_t *slot;		/* [cap] colour id or -1 */
	size_t cap;		/* 2^bits, at least 2 n */
	int bits;
};

static void texel_bits(const struct image *im, size_t i, uint32_t k[3])
{
	for (int c = 0; c < 3; c++) {
		float v = image_get(im, i, c);
		memcpy(&k[c], &v, sizeof v);
	}
}

/* Multiplicative hashing: the top bits of a product mix every key bit
 * (the low bits of a product see only the key's low bits). */
static size_t key_hash(const uint32_t k[3], int bits)
{
	uint64_t h = (((uint64_t)k[0] * 0x9E3779B97F4A7C15ULL) ^ k[1]) * 0xC2B2AE3D27D4EB4FULL;
	h = (h ^ k[2]) * 0x165667B19E3779F9ULL;
	return (size_t)(h >> (64 - bits));
}

static void colours_init(struct colours *cl)
{
	memset(cl, 0, sizeof *cl);
	cl->cap = 1024;
	cl->bits = 10;
	cl->slot = xmalloc(sizeof(int32_t) * cl->cap);
	for (size_t i = 0; i < cl->cap; i++)
		cl->slot[i] = -1;
}

/* The slot of key k: its colour's, or the empty one where it goes. */
static size_t colours_slot(const struct colours *cl, const uint32_t k[3])
{
	size_t j = key_hash(k, cl->bits);
	for (;;) {
		int32_t id = cl->slot[j];
		if (id < 0)
			return j;
		const uint32_t *q = cl->key[id];
		if (q[0] == k[0] && q[1] == k[1] && q[2] == k[2])
			return j;
		j = (j + 1) & (cl->cap - 1);
	}
}

/* The id of colour k, added if new. */
static int32_t colours_add(struct colours *cl, const uint32_t k[3])
{
	size_t j = colours_slot(cl, k);
	if (cl->slot[j] >= 0)
		return cl->slot[j];
	CHECK(cl->n < INT32_MAX);
	if ((size_t)cl->n == cl->kcap) {
		cl->kcap = cl->kcap ? 2 * cl->kcap : 1024;
		cl->key = xreallocarray(cl->key, cl->kcap, sizeof *cl->key);
	}
	memcpy(cl->key[cl->n], k, sizeof(uint32_t) * 3);
	cl->slot[j] = (int32_t)cl->n++;
	if (2 * (size_t)cl->n > cl->cap) {
		/* grow: the ids stay, only their slots move */
		free(cl->slot);
		cl->cap *= 2;
		cl->bits++;
		cl->slot = xmalloc(sizeof(int32_t) * cl->cap);
		for (size_t i = 0; i < cl->cap; i++)
			cl->slot[i] = -1;
		for (long u = 0; u < cl->n; u++)
			cl->slot[colours_slot(cl, cl->key[u])] = (int32_t)u;
	}
	return (int32_t)cl->n - 1;
}

/* The id of colour k, or -1 if it was not added. */
static int32_t colours_id(const struct colours *cl, const uint32_t k[3])
{
	return cl->slot[colours_slot(cl, k)];
}

/* The texel values a colour's key holds (as image_get returned them). */
static void key_values(const uint32_t k[3], float v[3])
{
	for (int c = 0; c < 3; c++)
		memcpy(&v[c], &k[c], sizeof v[c]);
}

/* After the last colour: the keys' spare room returned (realloc to a
 * smaller size does not move) and, when no colour will be looked up
 * again, the hash slots freed. */
static void colours_drop_hash(struct colours *cl)
{
	free(cl->slot);
	cl->slot = NULL;
	cl->kcap = (size_t)(cl->n > 0 ? cl->n : 1);
	cl->key = xreallocarray(cl->key, cl->kcap, sizeof *cl->key);
}

static void colours_free(struct colours *cl)
{
	free(cl->key);
	free(cl->slot);
}

/* The errors over fitted texels, in 0.001 bins up to 100, for the median
 * and 95th percentile; their maximum. */
struct de_hist {
	long *h;
	double max;
};
enum { DE_BINS = 100000 };

static void hist_add(struct de_hist *dh, double d)
{
	dh->max = fmax(dh->max, d);
	long b = lround(d * 1000.0);
	dh->h[b > DE_BINS ? DE_BINS : b]++;
}

static void hist_stats(const struct de_hist *dh, struct maps_fit_summary *s)
{
	long cum = 0;
	s->de_max = dh->max;
	s->de_median = s->de_p95 = -1.0;
	for (long b = 0; b <= DE_BINS && s->fitted > 0; b++) {
		cum += dh->h[b];
		if (s->de_median < 0 && 2 * cum >= s->fitted)
			s->de_median = b / 1000.0;
		if (s->de_p95 < 0 && 100 * cum >= 95 * s->fitted)
			s->de_p95 = b / 1000.0;
	}
	if (s->fitted == 0)
		s->de_median = s->de_p95 = 0.0;
}

/* The fit's state between its passes: the table, the colours and their
 * results (nr floats each: the parameters and the error). */
struct fitter {
	struct family *f;
	const struct maps_fit_opts *o;
	int threads;
	struct fit_lut t;
	struct colours cl;
	int nr;
	float *res;
	struct de_hist dh;
};

static void fitter_init(struct fitter *F, struct family *f, const struct maps_fit_opts *o)
{
	memset(F, 0, sizeof *F);
	F->f = f;
	F->o = o;
	F->threads = n_threads(o->threads);
	family_albedo_prepare(f);
	colours_init(&F->cl);
	F->dh.h = xcalloc(DE_BINS + 1, sizeof(long));
}

static void fitter_free(struct fitter *F)
{
	if (F->res)
		fit_lut_free(&F->t);
	if ((void *)F->res != (void *)F->cl.key)
		free(F->res);
	colours_free(&F->cl);
	free(F->dh.h);
}

/* Whether texel i of a band is fitted (opaque, inside the mask). */
static int texel_in(const struct image *albedo, const struct image *mask, size_t i)
{
	return image_get(albedo, i, 3) >= 0.5f && (mask == NULL || image_get(mask, i, 0) >= 0.5f);
}

/* Pass 1 over a band: its fitted texels' colours, in raster order; ids
 * (NULL or one per texel of the band) gets each texel's colour, -1 when
 * it is not fitted. */
static void fitter_scan(struct fitter *F, const struct image *albedo, const struct image *mask,
    int nrows,
    int32_t *ids, struct maps_fit_summary *sum)
{
	size_t n = (size_t)albedo->w * (size_t)nrows;
	uint32_t prev[3] = { 0 };
	int32_t prev_id = -1;	/* the id of colour prev, -1 none yet */
	for (size_t i = 0; i < n; i++) {
		int32_t id = -1;
		if (texel_in(albedo, mask, i)) {
			sum->fitted++;
			uint32_t k[3];
			texel_bits(albedo, i, k);
			/* runs of one colour: no hash */
			id = prev_id >= 0 && memcmp(k, prev, sizeof k) == 0 ? prev_id
			    : colours_add(&F->cl, k);
			memcpy(prev, k, sizeof k);
			prev_id = id;
		}
		if (ids)
			ids[i] = id;
	}
	sum->texels += (long)n;
}

/* Solve every colour: fixed chunks, each solved in order with warm starts,
 * so the result does not depend on the threads.  in_place: the colours
 * are not looked up again (pass 2 has their ids), so a result of the
 * size of a key (two axes: 3 floats) overwrites its key once read. */
static void fitter_solve(struct fitter *F, int in_place)
{
	const struct colours *cl = &F->cl;
	fit_lut_build(&F->t, F->f, F->threads);
	const struct fit_lut *t = &F->t;
	enum { CHUNK = 512 };
	const int nr = F->nr = t->k + 1;
	if (in_place && cl->n > 0 && sizeof(float) * (size_t)nr == sizeof *cl->key)
		F->res = (float *)cl->key;
	else
		F->res = xmalloc(sizeof(float) * (size_t)(cl->n > 0 ? cl->n : 1) * (size_t)nr);
	float *res = F->res;
	const struct maps_fit_opts *o = F->o;
	struct family *f = F->f;
	long n_chunks = (cl->n + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(dynamic, 1) num_threads(F->threads)
	for (long ch = 0; ch < n_chunks; ch++) {
		double g[FAMILY_MAX_AXES] = { 0 };
		for (long u = ch * CHUNK; u < cl->n && u < (ch + 1) * CHUNK; u++) {
			double rgb[3], target[3], x[FAMILY_MAX_AXES], lab[3];
			float v[3];
			key_values(cl->key[u], v);
			for (int c = 0; c < 3; c++)
				rgb[c] = o->input_linear ? v[c] : srgb_decode(v[c]);
			colour_linear_srgb_to_lab(rgb, target);
			fit_lut_solve(t, target, g, u > ch * CHUNK);
			fit_lut_params(t, g, x);
			fit_lut_lab(f, x, lab);
			float *r = res + (size_t)u * (size_t)nr;
			for (int a = 0; a < t->k; a++)
				r[a] = (float)x[a];
			r[t->k] = (float)colour_de2000(target, lab);
		}
	}
}

/* Pass 2 over a band: each texel's maps from its colour's result, the
 * colour from ids (pass 1's) or else from the albedo and mask; not fitted
 * texels keep the values v[a] and de2000 hold, and status 128.  -1 when a
 * colour was not seen by pass 1 (the file changed). */
static int fitter_apply(struct fitter *F, const int32_t *ids, const struct image *albedo,
    const struct image *mask,
    long n, float *const *v, float *de2000, unsigned char *status, struct maps_fit_summary *sum)
{
	long unmatched = 0, unseen = 0;
	const int k = F->t.k, nr = F->nr;
	const double max_de = F->o->max_de;
#pragma omp parallel num_threads(F->threads) reduction(+ : unmatched, unseen)
	{
	uint32_t prev[3] = { 0 };
	int32_t prev_id = -1;	/* the id of colour prev, -1 none yet */
#pragma omp for schedule(static)
	for (long i = 0; i < n; i++) {
		int32_t id;
		if (ids)
			id = ids[i];
		else if (!texel_in(albedo, mask, (size_t)i))
			id = -1;
		else {
			uint32_t key[3];
			texel_bits(albedo, (size_t)i, key);
			id = prev_id >= 0 && memcmp(key, prev, sizeof key) == 0 ? prev_id
			    : colours_id(&F->cl, key);
			memcpy(prev, key, sizeof key);
			prev_id = id;
			unseen += id < 0;
		}
		if (id < 0) {
			status[i] = MAPS_NOT_FITTED;
			continue;
		}
		const float *r = F->res + (size_t)id * (size_t)nr;
		for (int a = 0; a < k; a++)
			v[a][i] = r[a];
		de2000[i] = r[k];
		status[i] = r[k] <= max_de ? MAPS_MATCHED : MAPS_UNMATCHED;
		unmatched += status[i] == MAPS_UNMATCHED;
	}
	}
	for (long i = 0; i < n; i++)
		if (status[i] != MAPS_NOT_FITTED)
			hist_add(&F->dh, de2000[i]);
	sum->unmatched += unmatched;
	return unseen ? -1 : 0;
}

int maps_fit(struct family *f, const struct image *albedo, const struct image *mask,
    const struct maps_fit_opts *o,
    struct mapset **out, struct maps_fit_summary *sum, char **cause)
{
	if (mask && (mask->w != albedo->w || mask->h != albedo->h)) {
		*cause = xasprintf("the mask is %d x %d texels, the albedo %d x %d", mask->w,
		    mask->h, albedo->w, albedo->h);
		return -1;
	}
	double t0 = util_now();
	struct fitter F;
	fitter_init(&F, f, o);
	memset(sum, 0, sizeof *sum);
	fitter_scan(&F, albedo, mask, albedo->h, NULL, sum);
	sum->unique = F.cl.n;
	fitter_solve(&F, 0);
	struct mapset *m = mapset_new(f, albedo->w, albedo->h, NULL);
	size_t n = (size_t)albedo->w * albedo->h;
	m->de2000 = xcalloc(n, sizeof(float));
	m->status = xmalloc(n);
	float *v[FAMILY_MAX_AXES];
	for (int a = 0; a < m->n; a++)
		v[a] = m->p[a].v;
	CHECK(fitter_apply(&F, NULL, albedo, mask, (long)n, v, m->de2000, m->status, sum) == 0);
	sum->matched = sum->fitted - sum->unmatched;
	hist_stats(&F.dh, sum);
	fitter_free(&F);
	sum->seconds = util_now() - t0;
	*out = m;
	return 0;
}

/* Open the albedo (and mask) streams; -1 and *cause. */
static int open_inputs(const char *albedo, const char *mask, struct image_stream **sa,
    struct image_stream **sm,
    struct image **ba, struct image **bm, int band, int *w, int *h, char **cause)
{
	int nch, bits, mw, mh, mch, mbits;
	*sa = image_stream_open(albedo, w, h, &nch, &bits, cause);
	if (*sa == NULL)
		return -1;
	*ba = image_new(*w, band, nch, bits);
	if (mask) {
		*sm = image_stream_open(mask, &mw, &mh, &mch, &mbits, cause);
		if (*sm == NULL)
			return -1;
		if (mw != *w || mh != *h) {
			*cause = xasprintf("the mask is %d x %d texels, the albedo %d x %d", mw, mh,
			    *w, *h);
			return -1;
		}
		*bm = image_new(*w, band, mch, mbits);
	}
	return 0;
}

static void close_inputs(struct image_stream **sa, struct image_stream **sm, struct image **ba,
    struct image **bm)
{
	image_stream_close(*sa);
	image_stream_close(*sm);
	image_free(*ba);
	image_free(*bm);
	*sa = *sm = NULL;
	*ba = *bm = NULL;
}

int maps_fit_files(struct family *f, const char *albedo, const char *mask,
    const struct maps_fit_opts *o,
    const char *out, int exr, const char *command, struct maps_fit_summary *sum, int *input_error,
    char **cause)
{
	enum { BAND = 64 };
	double t0 = util_now();
	struct image_stream *sa = NULL, *sm = NULL;
	struct image *ba = NULL, *bm = NULL;
	struct mapset_writer *wr = NULL;
	struct mapset *m = NULL;
	float *v[FAMILY_MAX_AXES] = { NULL }, *de = NULL;
	unsigned char *st = NULL;
	int32_t *ids = NULL;	/* pass 1's colour per texel, or NULL: read again */
	int w, h, rc = -1;
	struct fitter F;
	fitter_init(&F, f, o);
	memset(sum, 0, sizeof *sum);
	*input_error = 1;
	/* Pass 1: the distinct colours, and each texel's when they fit in
	 * MAPS_FIT_IDS_MAX (pass 2 then needs no second reading). */
	if (open_inputs(albedo, mask, &sa, &sm, &ba, &bm, BAND, &w, &h, cause) != 0)
		goto out;
	if (!o->reread && (double)w * h * sizeof(int32_t) <= MAPS_FIT_IDS_MAX)
		ids = xmalloc(sizeof(int32_t) * (size_t)w * (size_t)h);
	for (int y = 0; y < h; y += BAND) {
		int nr = h - y < BAND ? h - y : BAND;
		if (image_stream_rows(sa, ba, nr, cause) != 0 || (sm && image_stream_rows(sm, bm,
		    nr, cause) != 0))
			goto out;
		fitter_scan(&F, ba, bm, nr, ids ? ids + (size_t)y * (size_t)w : NULL, sum);
	}
	close_inputs(&sa, &sm, &ba, &bm);
	sum->unique = F.cl.n;
	if (ids)
		colours_drop_hash(&F.cl);
	fitter_solve(&F, ids != NULL);
	/* Pass 2: the maps, band by band, straight to the files. */
	m = mapset_new(f, 1, 1, NULL);
	m->w = w;
	m->h = h;
	m->exr = exr;
	size_t nb = (size_t)w * BAND;
	for (int a = 0; a < m->n; a++) {
		v[a] = xmalloc(sizeof(float) * nb);
		for (size_t i = 0; i < nb; i++)
			v[a][i] = m->p[a].v[0];	/* the not fitted texels' value */
	}
	de = xcalloc(nb, sizeof(float));
	st = xmalloc(nb);
	if (ids == NULL && open_inputs(albedo, mask, &sa, &sm, &ba, &bm, BAND, &w, &h, cause) != 0)
		goto out;
	if (w != m->w || h != m->h) {
		*cause = xasprintf("%s: changed while it was read", albedo);
		goto out;
	}
	*input_error = 0;
	if ((wr = mapset_writer_begin(out, m, 1, F.threads, cause)) == NULL)
		goto out;
	for (int y = 0; y < h; y += BAND) {
		int nr = h - y < BAND ? h - y : BAND;
		*input_error = 1;
		if (ids == NULL && (image_stream_rows(sa, ba, nr, cause) != 0 ||
		    (sm && image_stream_rows(sm, bm, nr, cause) != 0)))
			goto out;
		if (fitter_apply(&F, ids ? ids + (size_t)y * (size_t)w : NULL, ba, bm, (long)w * nr,
		    v, de, st, sum) != 0) {
			*cause = xasprintf("%s: changed while it was read (a colour the first "
			    "reading did not have)", albedo);
			goto out;
		}
		*input_error = 0;
		for (size_t i = 0; i < (size_t)w * nr; i++)
			if (st[i] == MAPS_NOT_FITTED) {
				for (int a = 0; a < m->n; a++)
					v[a][i] = m->p[a].v[0];
				de[i] = 0.0f;
			}
		int fail = mapset_writer_rows(wr, nr, (const float *const *)v, de, st, cause) != 0;
		if (fail) {
			wr = NULL;	/* freed by its failure */
			goto out;
		}
	}
	sum->matched = sum->fitted - sum->unmatched;
	hist_stats(&F.dh, sum);
	sum->seconds = util_now() - t0;
	m->fit = maps_fit_summary_json(sum, o, albedo);
	mapset_add_history(m, command);
	rc = mapset_writer_end(wr, m, cause);
	wr = NULL;
out:
	mapset_writer_abort(wr);
	close_inputs(&sa, &sm, &ba, &bm);
	for (int a = 0; a < FAMILY_MAX_AXES; a++)
		free(v[a]);
	free(de);
	free(st);
	free(ids);
	mapset_free(m);
	fitter_free(&F);
	return rc;
}

char *maps_fit_summary_json(const struct maps_fit_summary *s, const struct maps_fit_opts *o,
    const char *albedo)
{
	json_object *j = json_object_new_object();
	json_object_object_add(j, "albedo", json_object_new_string(albedo));
	json_object_object_add(j, "input", json_object_new_string(o->input_linear ? "linear sRGB"
	    : "sRGB-encoded"));
	json_object_object_add(j, "max_de2000", json_num(o->max_de));
	json_object_object_add(j, "texels", json_object_new_int64(s->texels));
	json_object_object_add(j, "fitted", json_object_new_int64(s->fitted));
	json_object_object_add(j, "matched", json_object_new_int64(s->matched));
	json_object_object_add(j, "unmatched", json_object_new_int64(s->unmatched));
	json_object_object_add(j, "not_fitted", json_object_new_int64(s->texels - s->fitted));
	json_object_object_add(j, "distinct_colours", json_object_new_int64(s->unique));
	json_object_object_add(j, "de2000_median", json_num(s->de_median));
	json_object_object_add(j, "de2000_p95", json_num(s->de_p95));
	json_object_object_add(j, "de2000_max", json_num(s->de_max));
	json_object_object_add(j, "seconds", json_num(s->seconds));
	char *text = json_text(j, JSON_PLAIN);
	json_object_put(j);
	return text;
}
