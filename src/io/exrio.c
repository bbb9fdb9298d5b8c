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

int exrio_write(const char *path, int w, int h, int nch, const char *const *names,
    const float *const *planes, int nattr, const struct exr_attr_kv *attrs, char **cause)
{
	exr_context_t f;
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	struct exr_msg msg = { "" };
	init.error_handler_fn = keep_first;
	write_msg = &msg;
	int part, rc = -1;
	char *tmp = util_tmp_name(path);
	if (exr_start_write(&f, tmp, EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS) {
		*cause = xasprintf("%s: cannot write EXR%s%s", path, msg.text[0] ? ": " : "",
		    msg.text);
		write_msg = NULL;
		free(tmp);
		return -1;
	}
	exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
	int enc_init = 0;
	if (exr_add_part(f, NULL, EXR_STORAGE_SCANLINE, &part) ||
	    exr_initialize_required_attr_simple(f, part, w, h, EXR_COMPRESSION_ZIP))
		goto done;
	for (int c = 0; c < nch; c++)
		if (exr_add_channel(f, part, names[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1,
		    1))
			goto done;
	for (int a = 0; a < nattr; a++)
		if (exr_attr_set_string(f, part, attrs[a].key, attrs[a].value))
			goto done;
	if (exr_write_header(f))
		goto done;
	int32_t spc;
	exr_get_scanlines_per_chunk(f, part, &spc);
	for (int y = 0; y < h; y += spc) {
		exr_chunk_info_t ci;
		if (exr_write_scanline_chunk_info(f, part, y, &ci))
			goto done;
		exr_result_t er = enc_init ? exr_encoding_update(f, part, &ci, &enc)
		    : exr_encoding_initialize(f, part, &ci, &enc);
		if (er)
			goto done;
		for (int k = 0; k < enc.channel_count; k++) {
			exr_coding_channel_info_t *ch = &enc.channels[k];
			int c = 0;
			while (c < nch && strcmp(names[c], ch->channel_name) != 0)
				c++;	/* the file keeps channels sorted by name */
			ch->user_pixel_stride = sizeof(float);
			ch->user_line_stride = w * (int)sizeof(float);
			ch->user_bytes_per_element = sizeof(float);
			ch->user_data_type = EXR_PIXEL_FLOAT;
			ch->encode_from_ptr = (const uint8_t *)(planes[c] + (size_t)y * (size_t)w);
		}
		if (!enc_init) {
			enc_init = 1;
			if (exr_encoding_choose_default_routines(f, part, &enc))
				goto done;
			if (enc.compress_fn) {
				enc.encoding_user_data = (void *)enc.compress_fn;
				enc.compress_fn = guarded_compress;
			}
		}
		if (exr_encoding_run(f, part, &enc))
			goto done;
	}
	rc = 0;
done:
	if (enc_init)
		exr_encoding_destroy(f, &enc);
	if (exr_finish(&f) != EXR_ERR_SUCCESS)
		rc = -1;
	if (rc != 0) {
		*cause = xasprintf("%s: writing the EXR failed%s%s", path, msg.text[0] ? ": " : "",
		    msg.text);
		unlink(tmp);
	} else
		rc = util_commit_tmp(tmp, path, cause);
	free(tmp);
	write_msg = NULL;
	return rc;
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

int exrio_read_channel(const char *path, const char *name, int w, int h, float *out, char **cause)
{
	exr_context_t f;
	if (open_read(path, &f, cause))
		return -1;
	int rc = -1, found = 0, dec_init = 0, routines = 0;
	exr_attr_box2i_t dw;
	int32_t spc;
	exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
	if (exr_get_data_window(f, 0, &dw) || dw.max.x - dw.min.x + 1 != w
	    || dw.max.y - dw.min.y + 1 != h || exr_get_scanlines_per_chunk(f, 0, &spc)) {
		*cause = xasprintf("%s: size is not %d x %d", path, w, h);
		goto out;
	}
	for (int y = dw.min.y; y <= dw.max.y; y += spc) {
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
			size_t row = (size_t)(ci.start_y - dw.min.y);
			ch->decode_to_ptr = (uint8_t *)(out + row * (size_t)w);
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
	}
	rc = 0;
	goto out;
corrupt:
	*cause = xasprintf("%s: corrupt OpenEXR data", path);
out:
	if (dec_init)
		exr_decoding_destroy(f, &dec);
	exr_finish(&f);
	return rc;
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
