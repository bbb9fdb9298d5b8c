/* exrio: OpenEXR files with named float channels through OpenEXRCore
 * (see exrio.h). */
#include "config.h"
#include "io/exrio.h"

#include <openexr.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/util.h"

/* OpenEXR 3.1.5's C core decodes a chunk whose compressed size equals its
 * packed size as if uncompressed, so a chunk that does not shrink must be
 * stored raw (as the C++ library does).  The default routine is kept per
 * pipeline in encoding_user_data. */
static exr_result_t guarded_compress(exr_encode_pipeline_t *e)
{
	typedef exr_result_t (*compress_fn)(exr_encode_pipeline_t *);
	compress_fn fn = (compress_fn)e->encoding_user_data;
	exr_result_t r = fn(e);
	if (r == EXR_ERR_SUCCESS && e->compressed_bytes >= e->packed_bytes) {
		memcpy(e->compressed_buffer, e->packed_buffer, e->packed_bytes);
		e->compressed_bytes = e->packed_bytes;
	}
	return r;
}

/* The library's first message of a write (e.g. "... No space left on
 * device"), kept for *cause instead of printed. */
struct exr_msg {
	char text[256];
};

/* The handler runs with the context locked (no exr_get_user_data there),
 * and writers run in parallel threads: a thread's own message buffer. */
static _Thread_local struct exr_msg *write_msg;

static void keep_first(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
	(void)ctx;
	(void)code;
	if (write_msg != NULL && write_msg->text[0] == '\0')
		snprintf(write_msg->text, sizeof write_msg->text, "%s", msg);
}

struct exrio_writer {
	char *path, *tmp;
	exr_context_t f;
	struct exr_msg msg;
	exr_encode_pipeline_t enc;
	int enc_init, started;
	int w, h, nch, spc, y;	/* size, channels, scanlines per chunk, rows written */
	char **names;
	float **buf;		/* [nch][spc * w]: the chunk being filled */
	int nbuf;		/* rows in buf */
};

static void writer_free(struct exrio_writer *wr)
{
	for (int c = 0; c < wr->nch; c++) {
		free(wr->names[c]);
		free(wr->buf ? wr->buf[c] : NULL);
	}
	free(wr->names);
	free(wr->buf);
	free(wr->tmp);
	free(wr->path);
	free(wr);
}

void exrio_writer_abort(struct exrio_writer *wr)
{
	if (wr == NULL)
		return;
	write_msg = &wr->msg;
	if (wr->enc_init)
		exr_encoding_destroy(wr->f, &wr->enc);
	if (wr->started)
		exr_finish(&wr->f);
	write_msg = NULL;
	unlink(wr->tmp);
	writer_free(wr);
}

static int writer_fail(struct exrio_writer *wr, char **cause)
{
	*cause = xasprintf("%s: writing the EXR failed%s%s", wr->path, wr->msg.text[0] ? ": " : "",
	    wr->msg.text);
	exrio_writer_abort(wr);
	return -1;
}

struct exrio_writer *exrio_writer_open(const char *path, int w, int h, int nch,
    const char *const *names,
    int nattr, const struct exr_attr_kv *attrs, char **cause)
{
	struct exrio_writer *wr = xcalloc(1, sizeof *wr);
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	init.error_handler_fn = keep_first;
	write_msg = &wr->msg;
	wr->path = xstrdup(path);
	wr->tmp = util_tmp_name(path);
	wr->w = w;
	wr->h = h;
	wr->nch = nch;
	wr->names = xcalloc((size_t)nch, sizeof *wr->names);
	for (int c = 0; c < nch; c++)
		wr->names[c] = xstrdup(names[c]);
	exr_encode_pipeline_t enc0 = EXR_ENCODE_PIPELINE_INITIALIZER;
	wr->enc = enc0;
	int part;
	if (exr_start_write(&wr->f, wr->tmp, EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS) {
		*cause = xasprintf("%s: cannot write EXR%s%s", path, wr->msg.text[0] ? ": " : "",
		    wr->msg.text);
		write_msg = NULL;
		writer_free(wr);
		return NULL;
	}
	wr->started = 1;
	if (exr_add_part(wr->f, NULL, EXR_STORAGE_SCANLINE, &part) ||
	    exr_initialize_required_attr_simple(wr->f, part, w, h, EXR_COMPRESSION_ZIP))
		goto fail;
	for (int c = 0; c < nch; c++)
		if (exr_add_channel(wr->f, part, names[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR,
		    1,
		    1))
			goto fail;
	for (int a = 0; a < nattr; a++)
		if (exr_attr_set_string(wr->f, part, attrs[a].key, attrs[a].value))
			goto fail;
	if (exr_write_header(wr->f))
		goto fail;
	int32_t spc;
	exr_get_scanlines_per_chunk(wr->f, part, &spc);
	wr->spc = spc;
	wr->buf = xcalloc((size_t)nch, sizeof *wr->buf);
	for (int c = 0; c < nch; c++)
		wr->buf[c] = xmalloc(sizeof(float) * (size_t)spc * (size_t)w);
	write_msg = NULL;
	return wr;
fail:
	writer_fail(wr, cause);
	write_msg = NULL;
	return NULL;
}

/* Encode the rows of planes[c] + row0 * w (rows wr->y .. wr->y + n - 1, n
 * at most a chunk, a whole chunk unless the image's last). */
static int write_chunk(struct exrio_writer *wr, const float *const *planes, size_t row0)
{
	exr_chunk_info_t ci;
	if (exr_write_scanline_chunk_info(wr->f, 0, wr->y, &ci))
		return -1;
	exr_result_t er = wr->enc_init ? exr_encoding_update(wr->f, 0, &ci, &wr->enc)
	    : exr_encoding_initialize(wr->f, 0, &ci, &wr->enc);
	if (er)
		return -1;
	for (int k = 0; k < wr->enc.channel_count; k++) {
		exr_coding_channel_info_t *ch = &wr->enc.channels[k];
		int c = 0;
		while (c < wr->nch && strcmp(wr->names[c], ch->channel_name) != 0)
			c++;	/* the file keeps channels sorted by name */
		ch->user_pixel_stride = sizeof(float);
		ch->user_line_stride = wr->w * (int)sizeof(float);
		ch->user_bytes_per_element = sizeof(float);
		ch->user_data_type = EXR_PIXEL_FLOAT;
		ch->encode_from_ptr = (const uint8_t *)(planes[c] + row0 * (size_t)wr->w);
	}
	if (!wr->enc_init) {
		wr->enc_init = 1;
		if (exr_encoding_choose_default_routines(wr->f, 0, &wr->enc))
			return -1;
		if (wr->enc.compress_fn) {
			wr->enc.encoding_user_data = (void *)wr->enc.compress_fn;
			wr->enc.compress_fn = guarded_compress;
		}
	}
	if (exr_encoding_run(wr->f, 0, &wr->enc))
		return -1;
	wr->y += ci.height;
	return 0;
}

int exrio_writer_rows(struct exrio_writer *wr, const float *const *planes, int nrows, char **cause)
{
	write_msg = &wr->msg;
	int r = 0;
	while (r < nrows) {
		int full = wr->h - wr->y < wr->spc ? wr->h - wr->y : wr->spc;
		if (wr->nbuf == 0 && nrows - r >= full) {
			/* a whole chunk straight from the caller's rows */
			if (write_chunk(wr, planes, (size_t)r) != 0)
				goto fail;
			r += full;
			continue;
		}
		int take = full - wr->nbuf < nrows - r ? full - wr->nbuf : nrows - r;
		for (int c = 0; c < wr->nch; c++)
			memcpy(wr->buf[c] + (size_t)wr->nbuf * (size_t)wr->w,
			    planes[c] + (size_t)r * (size_t)wr->w,
			    sizeof(float) * (size_t)take * (size_t)wr->w);
		wr->nbuf += take;
		r += take;
		if (wr->nbuf == full) {
			if (write_chunk(wr, (const float *const *)wr->buf, 0) != 0)
				goto fail;
			wr->nbuf = 0;
		}
	}
	write_msg = NULL;
	return 0;
fail:
	writer_fail(wr, cause);
	write_msg = NULL;
	return -1;
}

int exrio_writer_close(struct exrio_writer *wr, char **cause)
{
	write_msg = &wr->msg;
	int rc = 0;
	if (wr->enc_init)
		exr_encoding_destroy(wr->f, &wr->enc);
	wr->enc_init = 0;
	wr->started = 0;
	if (wr->y != wr->h || exr_finish(&wr->f) != EXR_ERR_SUCCESS)
		rc = -1;
	if (rc != 0) {
		*cause = xasprintf("%s: writing the EXR failed%s%s", wr->path, wr->msg.text[0]
		    ? ": " : "",
		    wr->msg.text[0] ? wr->msg.text : wr->y != wr->h ? "rows missing" : "");
		unlink(wr->tmp);
	} else
		rc = util_commit_tmp(wr->tmp, wr->path, cause);
	write_msg = NULL;
	writer_free(wr);
	return rc;
}

int exrio_write(const char *path, int w, int h, int nch, const char *const *names,
    const float *const *planes, int nattr, const struct exr_attr_kv *attrs, char **cause)
{
	struct exrio_writer *wr = exrio_writer_open(path, w, h, nch, names, nattr, attrs, cause);
	if (wr == NULL || exrio_writer_rows(wr, planes, h, cause) != 0)
		return -1;
	return exrio_writer_close(wr, cause);
}

/* Library messages are turned into our own *cause text instead. */
static void quiet(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
	(void)ctx;
	(void)code;
	(void)msg;
}

static int open_read(const char *path, exr_context_t *f, char **cause)
{
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	init.error_handler_fn = quiet;
	if (access(path, R_OK) != 0) {
		*cause = xasprintf("%s: missing or unreadable", path);
		return -1;
	}
	if (exr_start_read(f, path, &init) != EXR_ERR_SUCCESS) {
		*cause = xasprintf("%s: not a readable OpenEXR file", path);
		return -1;
	}
	return 0;
}

int exrio_size(const char *path, int *w, int *h, char **cause)
{
	exr_context_t f;
	if (open_read(path, &f, cause))
		return -1;
	exr_attr_box2i_t dw;
	if (exr_get_data_window(f, 0, &dw)) {
		exr_finish(&f);
		*cause = xasprintf("%s: no data window", path);
		return -1;
	}
	*w = dw.max.x - dw.min.x + 1;
	*h = dw.max.y - dw.min.y + 1;
	exr_finish(&f);
	return 0;
}

int exrio_read_channel_rows(const char *path, const char *name, int w, int h, int y0, int ny,
    float *out,
    char **cause)
{
	exr_context_t f;
	if (open_read(path, &f, cause))
		return -1;
	int rc = -1, found = 0, dec_init = 0, routines = 0;
	exr_attr_box2i_t dw;
	int32_t spc;
	float *tmp = NULL;	/* a chunk reaching outside the rows asked for */
	exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
	if (exr_get_data_window(f, 0, &dw) || dw.max.x - dw.min.x + 1 != w
	    || dw.max.y - dw.min.y + 1 != h || exr_get_scanlines_per_chunk(f, 0, &spc)) {
		*cause = xasprintf("%s: size is not %d x %d", path, w, h);
		goto out;
	}
	if (y0 < 0 || ny < 1 || y0 + ny > h) {
		*cause = xasprintf("%s: rows %d to %d asked of %d", path, y0, y0 + ny - 1, h);
		goto out;
	}
	/* from the first row of the chunk holding row y0 */
	for (int y = dw.min.y + y0 / spc * spc; y < dw.min.y + y0 + ny; y += spc) {
		exr_chunk_info_t ci;
		if (exr_read_scanline_chunk_info(f, 0, y, &ci))
			goto corrupt;
		/* dec owns memory from a successful initialize on: every exit below frees it. */
		if (!dec_init) {
			if (exr_decoding_initialize(f, 0, &ci, &dec))
				goto corrupt;
			dec_init = 1;
		} else if (exr_decoding_update(f, 0, &ci, &dec))
			goto corrupt;
		int r0 = ci.start_y - dw.min.y, inside = r0 >= y0 && r0 + ci.height <= y0 + ny;
		if (!inside && tmp == NULL)
			tmp = xmalloc(sizeof(float) * (size_t)spc * (size_t)w);
		for (int k = 0; k < dec.channel_count; k++) {
			exr_coding_channel_info_t *ch = &dec.channels[k];
			if (strcmp(ch->channel_name, name) != 0) {
				ch->decode_to_ptr = NULL;
				continue;
			}
			found = 1;
			ch->user_pixel_stride = sizeof(float);
			ch->user_line_stride = w * (int)sizeof(float);
			ch->user_bytes_per_element = sizeof(float);
			ch->user_data_type = EXR_PIXEL_FLOAT;
			ch->decode_to_ptr = (uint8_t *)(inside ? out + (size_t)(r0 - y0) * (size_t)w
			    : tmp);
		}
		if (!found) {
			*cause = xasprintf("%s: no channel '%s'", path, name);
			goto out;
		}
		if (!routines) {
			routines = 1;
			if (exr_decoding_choose_default_routines(f, 0, &dec))
				goto corrupt;
		}
		if (exr_decoding_run(f, 0, &dec))
			goto corrupt;
		if (!inside)
			for (int r = 0; r < ci.height; r++)
				if (r0 + r >= y0 && r0 + r < y0 + ny)
					memcpy(out + (size_t)(r0 + r - y0) * (size_t)w,
					    tmp + (size_t)r * (size_t)w,
					    sizeof(float) * (size_t)w);
	}
	rc = 0;
	goto out;
corrupt:
	*cause = xasprintf("%s: corrupt OpenEXR data", path);
out:
	if (dec_init)
		exr_decoding_destroy(f, &dec);
	exr_finish(&f);
	free(tmp);
	return rc;
}

int exrio_read_channel(const char *path, const char *name, int w, int h, float *out, char **cause)
{
	return exrio_read_channel_rows(path, name, w, h, 0, h, out, cause);
}

char *exrio_read_string_attr(const char *path, const char *key, char **cause)
{
	exr_context_t f;
	if (open_read(path, &f, cause))
		return NULL;
	const char *s = NULL;
	int32_t len = 0;
	char *res = NULL;
	if (exr_attr_get_string(f, 0, key, &len, &s) == EXR_ERR_SUCCESS && s != NULL) {
		res = xmalloc((size_t)len + 1);
		memcpy(res, s, (size_t)len);
		res[len] = '\0';
	} else
		*cause = xasprintf("%s: no string attribute '%s'", path, key);
	exr_finish(&f);
	return res;
}
