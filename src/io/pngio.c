/* pngio: PNG files with tEXt metadata through libpng (see pngio.h). */
#include "config.h"
#include "io/pngio.h"

#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/util.h"

/* libpng's messages become the *cause text instead of going to stderr. */
struct png_msg {
	char text[128];	/* libpng's error message, or ours */
	int ours;	/* text is ours: keep it */
};

static void on_error(png_structp png, png_const_charp msg)
{
	struct png_msg *m = png_get_error_ptr(png);
	if (m != NULL && !m->ours)
		snprintf(m->text, sizeof m->text, "%s", msg);
	png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

/* libpng 1.6.39 allocates whatever a chunk's length field says before it
 * reads the chunk (1.6 GB for a 1 kB file, found by fuzzing), and
 * png_set_chunk_malloc_max only limits decompressed text.  Its own
 * allocations for a real image are rows (at most 8 MB for libpng's widest,
 * 1e6 pixels of 64 bits) and zlib state, so anything over 64 MB is refused. */
#define PNG_MAX_ALLOC ((png_alloc_size_t)64 << 20)

static png_voidp limited_malloc(png_structp png, png_alloc_size_t size)
{
	if (size <= PNG_MAX_ALLOC)
		return malloc(size);
	struct png_msg *m = png_get_error_ptr(png);
	if (m != NULL && !m->ours) {
		snprintf(m->text, sizeof m->text, "a chunk asks for %.0f bytes", (double)size);
		m->ours = 1;
	}
	return NULL;
}

static void plain_free(png_structp png, png_voidp p)
{
	(void)png;
	free(p);
}

static png_structp create_reader(struct png_msg *m)
{
	png_structp png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, m, on_error, on_warning,
	    NULL, limited_malloc, plain_free);
	if (png == NULL)
		return NULL;
	png_set_chunk_malloc_max(png, 1 << 20);	/* decompressed text */
	png_set_chunk_cache_max(png, 256);
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
	/* Fuzzers cannot forge checksums; let their mutations reach the decoder. */
	png_set_crc_action(png, PNG_CRC_QUIET_USE, PNG_CRC_QUIET_USE);
#endif
	return png;
}

int pngio_write(const char *path, int w, int h, int channels, int bits, const uint16_t *px,
    int srgb, int ntext, const struct png_text_kv *text, char **cause)
{
	static const int types[] = { 0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
		PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA };
	if (channels < 1 || channels > 4 || (bits != 8 && bits != 16) || w < 1 || h < 1) {
		*cause = xasprintf("%s: unsupported PNG layout (%d channels, %d bits)", path,
		    channels, bits);
		return -1;
	}
	char *tmp = util_tmp_name(path);
	FILE *fp = fopen(tmp, "wb");
	if (!fp) {
		*cause = xasprintf("%s: cannot write: %s", path, strerror(errno));
		free(tmp);
		return -1;
	}
	size_t rowlen = (size_t)w * (size_t)channels * (size_t)(bits / 8);
	unsigned char *volatile row = xmalloc(rowlen);
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, on_error,
	    on_warning);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	errno = 0;
	if (!info || setjmp(png_jmpbuf(png))) {
		int e = errno;	/* libpng's write stops at the failed fwrite: its cause */
		png_destroy_write_struct(&png, &info);
		fclose(fp);
		unlink(tmp);
		free(tmp);
		free(row);
		*cause = xasprintf("%s: writing the PNG failed%s%s", path, e ? ": " : "",
		    e ? strerror(e) : "");
		return -1;
	}
	png_init_io(png, fp);
	/* Data maps are large and noisy: fast zlib and one fixed filter cost a
	 * little size and save most of the write time. */
	png_set_compression_level(png, 2);
	png_set_filter(png, 0, PNG_FILTER_UP);
	png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, bits, types[channels],
	    PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	if (srgb)
		png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
	if (ntext > 0) {
		png_text *t = xcalloc((size_t)ntext, sizeof *t);
		for (int i = 0; i < ntext; i++) {
			t[i].compression = PNG_TEXT_COMPRESSION_NONE;
			t[i].key = (char *)text[i].key;
			t[i].text = (char *)text[i].value;
		}
		png_set_text(png, info, t, ntext);
		free(t);
	}
	png_write_info(png, info);
	size_t n = (size_t)w * (size_t)channels;
	for (int y = 0; y < h; y++) {
		const uint16_t *src = px + (size_t)y * n;
		if (bits == 16)
			for (size_t i = 0; i < n; i++) {
				/* PNG is big-endian */
				row[2 * i] = (unsigned char)(src[i] >> 8);
				row[2 * i + 1] = (unsigned char)(src[i] & 0xff);
			}
		else
			for (size_t i = 0; i < n; i++)
				row[i] = (unsigned char)(src[i] > 255 ? 255 : src[i]);
		png_write_row(png, row);
	}
	png_write_end(png, NULL);
	png_destroy_write_struct(&png, &info);
	free(row);
	if (fclose(fp) != 0) {
		*cause = xasprintf("%s: write failed: %s", path, strerror(errno));
		unlink(tmp);
		free(tmp);
		return -1;
	}
	int rc = util_commit_tmp(tmp, path, cause);
	free(tmp);
	return rc;
}

/* Deflate expands at most 1032-fold (258-byte matches in 2 bits), so a file
 * of S bytes holds at most about 1032 S bytes of image: a header promising
 * more is corrupt, and is refused before anything is allocated. */
#define PNG_MAX_INFLATE 1032.0

uint16_t *pngio_read(const char *path, int *w, int *h, int *channels, int *bits, char **cause)
{
	FILE *fp = fopen(path, "rb");
	if (!fp) {
		*cause = xasprintf("%s: cannot read: %s", path, strerror(errno));
		return NULL;
	}
	struct stat st;
	double file_bytes = fstat(fileno(fp), &st) == 0 ? (double)st.st_size : 0.0;
	struct png_msg msg = { "", 0 };
	png_structp png = create_reader(&msg);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	uint16_t *volatile px = NULL;
	png_bytep *volatile rows = NULL;
	if (!info || setjmp(png_jmpbuf(png))) {
		png_destroy_read_struct(&png, &info, NULL);
		fclose(fp);
		free(px);
		free(rows);
		*cause = msg.text[0] ? xasprintf("%s: not a readable PNG file (%s)", path, msg.text)
				     : xasprintf("%s: not a readable PNG file", path);
		return NULL;
	}
	png_init_io(png, fp);
	png_read_info(png, info);
	png_uint_32 pw = png_get_image_width(png, info), ph = png_get_image_height(png, info);
	double need = (double)png_get_rowbytes(png, info) * (double)ph;
	if (need > PNG_MAX_INFLATE * file_bytes + 65536.0) {
		snprintf(msg.text, sizeof msg.text, "%lu x %lu pixels cannot be held in %.0f bytes",
		    (unsigned long)pw, (unsigned long)ph, file_bytes);
		png_longjmp(png, 1);
	}
	int bd = png_get_bit_depth(png, info), ct = png_get_color_type(png, info);
	if (ct == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (bd < 8)
		png_set_expand(png);
	png_set_interlace_handling(png);	/* Adam7 files are read whole */
	png_read_update_info(png, info);
	*w = (int)pw;
	*h = (int)ph;
	*channels = png_get_channels(png, info);
	*bits = bd < 8 ? 8 : bd;
	int b = png_get_bit_depth(png, info);
	size_t n = (size_t)*w * (size_t)*channels, rowbytes = png_get_rowbytes(png, info);
	if (rowbytes != n * (size_t)(b / 8)) {
		snprintf(msg.text, sizeof msg.text, "unexpected row layout");
		png_longjmp(png, 1);
	}
	/* Decode the bytes packed at the start of px, then widen them in place
	 * from the end (sample i moves from byte i or 2i to bytes 2i, 2i+1). */
	px = xmalloc(n * (size_t)*h * sizeof(uint16_t));
	rows = xmalloc(sizeof(png_bytep) * (size_t)*h);
	for (int y = 0; y < *h; y++)
		rows[y] = (png_bytep)px + (size_t)y * rowbytes;
	png_read_image(png, rows);
	png_read_end(png, NULL);
	png_destroy_read_struct(&png, &info, NULL);
	fclose(fp);
	free(rows);
	unsigned char *raw = (unsigned char *)px;
	size_t total = n * (size_t)*h;
	if (b == 16)	/* PNG is big-endian */
		for (size_t i = 0; i < total; i++)
			px[i] = (uint16_t)((raw[2 * i] << 8) | raw[2 * i + 1]);
	else
		for (size_t i = total; i-- > 0;)
			px[i] = (uint16_t)(raw[i] * 257);
	return px;
}

char *pngio_read_text(const char *path, const char *key)
{
	FILE *fp = fopen(path, "rb");
	if (!fp)
		return NULL;
	struct png_msg msg = { "", 0 };
	png_structp png = create_reader(&msg);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	char *volatile res = NULL;
	if (!info || setjmp(png_jmpbuf(png))) {
		png_destroy_read_struct(&png, &info, NULL);
		fclose(fp);
		return res;
	}
	png_init_io(png, fp);
	png_read_info(png, info);
	png_textp t;
	int nt = 0;
	png_get_text(png, info, &t, &nt);
	for (int i = 0; i < nt; i++)
		if (strcmp(t[i].key, key) == 0) {
			res = xstrdup(t[i].text);
			break;
		}
	png_destroy_read_struct(&png, &info, NULL);
	fclose(fp);
	return res;
}
