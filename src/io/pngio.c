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

struct pngio_writer {
	char *path, *tmp;
	FILE *fp;
	png_structp png;
	png_infop info;
	int w, channels, bits;
	unsigned char *row;	/* one row in the file's byte layout */
};

/* The writer's failure: remove the temporary file, free everything, *cause
 * from errno (libpng's write stops at the failed fwrite: its cause). */
static int writer_fail(struct pngio_writer *wr, int e, char **cause)
{
	*cause = xasprintf("%s: writing the PNG failed%s%s", wr->path, e ? ": " : "", e
	    ? strerror(e) : "");
	pngio_writer_abort(wr);
	return -1;
}

void pngio_writer_abort(struct pngio_writer *wr)
{
	if (wr == NULL)
		return;
	png_destroy_write_struct(&wr->png, &wr->info);
	if (wr->fp)
		fclose(wr->fp);
	unlink(wr->tmp);
	free(wr->tmp);
	free(wr->path);
	free(wr->row);
	free(wr);
}

struct pngio_writer *pngio_writer_open(const char *path, int w, int h, int channels, int bits,
    int srgb,
    int ntext, const struct png_text_kv *text, char **cause)
{
	static const int types[] = { 0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
		PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA };
	if (channels < 1 || channels > 4 || (bits != 8 && bits != 16) || w < 1 || h < 1) {
		*cause = xasprintf("%s: unsupported PNG layout (%d channels, %d bits)", path,
		    channels, bits);
		return NULL;
	}
	struct pngio_writer *wr = xcalloc(1, sizeof *wr);
	wr->path = xstrdup(path);
	wr->tmp = util_tmp_name(path);
	wr->w = w;
	wr->channels = channels;
	wr->bits = bits;
	wr->fp = fopen(wr->tmp, "wb");
	if (!wr->fp) {
		*cause = xasprintf("%s: cannot write: %s", path, strerror(errno));
		pngio_writer_abort(wr);
		return NULL;
	}
	wr->row = xmalloc((size_t)w * (size_t)channels * (size_t)(bits / 8));
	wr->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, on_error,
	    on_warning);
	wr->info = wr->png ? png_create_info_struct(wr->png) : NULL;
	errno = 0;
	if (!wr->info || setjmp(png_jmpbuf(wr->png))) {
		writer_fail(wr, errno, cause);
		return NULL;
	}
	png_init_io(wr->png, wr->fp);
	/* Data maps are large and noisy: fast zlib and one fixed filter cost a
	 * little size and save most of the write time. */
	png_set_compression_level(wr->png, 2);
	png_set_filter(wr->png, 0, PNG_FILTER_UP);
	png_set_IHDR(wr->png, wr->info, (png_uint_32)w, (png_uint_32)h, bits, types[channels],
	    PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	if (srgb)
		png_set_sRGB_gAMA_and_cHRM(wr->png, wr->info, PNG_sRGB_INTENT_PERCEPTUAL);
	if (ntext > 0) {
		png_text *t = xcalloc((size_t)ntext, sizeof *t);
		for (int i = 0; i < ntext; i++) {
			t[i].compression = PNG_TEXT_COMPRESSION_NONE;
			t[i].key = (char *)text[i].key;
			t[i].text = (char *)text[i].value;
		}
		png_set_text(wr->png, wr->info, t, ntext);
		free(t);
	}
	png_write_info(wr->png, wr->info);
	return wr;
}

int pngio_writer_rows(struct pngio_writer *wr, const uint16_t *px, int nrows, char **cause)
{
	errno = 0;
	if (setjmp(png_jmpbuf(wr->png)))
		return writer_fail(wr, errno, cause);
	size_t n = (size_t)wr->w * (size_t)wr->channels;
	unsigned char *row = wr->row;
	for (int y = 0; y < nrows; y++) {
		const uint16_t *src = px + (size_t)y * n;
		if (wr->bits == 16)
			for (size_t i = 0; i < n; i++) {
				/* PNG is big-endian */
				row[2 * i] = (unsigned char)(src[i] >> 8);
				row[2 * i + 1] = (unsigned char)(src[i] & 0xff);
			}
		else
			for (size_t i = 0; i < n; i++)
				row[i] = (unsigned char)(src[i] > 255 ? 255 : src[i]);
		png_write_row(wr->png, row);
	}
	return 0;
}

int pngio_writer_close(struct pngio_writer *wr, char **cause)
{
	errno = 0;
	if (setjmp(png_jmpbuf(wr->png)))
		return writer_fail(wr, errno, cause);
	png_write_end(wr->png, NULL);
	png_destroy_write_struct(&wr->png, &wr->info);
	FILE *fp = wr->fp;
	wr->fp = NULL;
	if (fclose(fp) != 0) {
		*cause = xasprintf("%s: write failed: %s", wr->path, strerror(errno));
		pngio_writer_abort(wr);
		return -1;
	}
	int rc = util_commit_tmp(wr->tmp, wr->path, cause);
	free(wr->tmp);
	free(wr->path);
	free(wr->row);
	free(wr);
	return rc;
}

int pngio_write(const char *path, int w, int h, int channels, int bits, const uint16_t *px,
    int srgb, int ntext, const struct png_text_kv *text, char **cause)
{
	struct pngio_writer *wr = pngio_writer_open(path, w, h, channels, bits, srgb, ntext, text,
	    cause);
	if (wr == NULL || pngio_writer_rows(wr, px, h, cause) != 0)
		return -1;
	return pngio_writer_close(wr, cause);
}

/* Deflate expands at most 1032-fold (258-byte matches in 2 bits), so a file
 * of S bytes holds at most about 1032 S bytes of image: a header promising
 * more is corrupt, and is refused before anything is allocated. */
#define PNG_MAX_INFLATE 1032.0

/* The cause for a file libpng refused, with libpng's words when it gave any. */
static char *unreadable(const char *path, const struct png_msg *m)
{
	if (m->text[0])
		return xasprintf("%s: not a readable PNG file (%s)", path, m->text);
	return xasprintf("%s: not a readable PNG file", path);
}

/* The header of the file FP (FILE_BYTES long) read, its size checked against
 * PNG_MAX_INFLATE, palettes and low bit depths expanded to 8 or 16 bits per
 * sample (*b); *rowbytes the bytes of one row.  Returns the interlace
 * passes.  Errors long-jump to the caller's setjmp, with M's text set. */
static int read_header(png_structp png, png_infop info, FILE *fp, double file_bytes,
    struct png_msg *m, int *w, int *h, int *channels, int *bits, int *b, size_t *rowbytes)
{
	png_init_io(png, fp);
	png_read_info(png, info);
	png_uint_32 pw = png_get_image_width(png, info), ph = png_get_image_height(png, info);
	double need = (double)png_get_rowbytes(png, info) * (double)ph;
	if (need > PNG_MAX_INFLATE * file_bytes + 65536.0) {
		snprintf(m->text, sizeof m->text, "%lu x %lu pixels cannot be held in %.0f bytes",
		    (unsigned long)pw, (unsigned long)ph, file_bytes);
		png_longjmp(png, 1);
	}
	int bd = png_get_bit_depth(png, info), ct = png_get_color_type(png, info);
	if (ct == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (bd < 8)
		png_set_expand(png);
	int passes = png_set_interlace_handling(png);
	png_read_update_info(png, info);
	*w = (int)pw;
	*h = (int)ph;
	*channels = png_get_channels(png, info);
	*bits = bd < 8 ? 8 : bd;
	*b = png_get_bit_depth(png, info);
	*rowbytes = png_get_rowbytes(png, info);
	if (*rowbytes != (size_t)*w * (size_t)*channels * (size_t)(*b / 8)) {
		snprintf(m->text, sizeof m->text, "unexpected row layout");
		png_longjmp(png, 1);
	}
	return passes;
}

/* N samples of B bits (8 or 16) in the file's bytes RAW to 16 bits in DST,
 * which may be RAW itself: 16-bit samples move down (sample i from bytes 2i,
 * 2i+1), 8-bit ones up from the end (byte i to sample i). */
static void widen(uint16_t *dst, const unsigned char *raw, size_t n, int b)
{
	if (b == 16)	/* PNG is big-endian */
		for (size_t i = 0; i < n; i++)
			dst[i] = (uint16_t)((raw[2 * i] << 8) | raw[2 * i + 1]);
	else
		for (size_t i = n; i-- > 0;)
			dst[i] = (uint16_t)(raw[i] * 257);
}

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
		*cause = unreadable(path, &msg);
		return NULL;
	}
	int b;
	size_t rowbytes;
	/* (Adam7 files are read whole: the passes do not matter here) */
	read_header(png, info, fp, file_bytes, &msg, w, h, channels, bits, &b, &rowbytes);
	size_t n = (size_t)*w * (size_t)*channels;
	/* Decode the bytes packed at the start of px, then widen them in place. */
	px = xmalloc(n * (size_t)*h * sizeof(uint16_t));
	rows = xmalloc(sizeof(png_bytep) * (size_t)*h);
	for (int y = 0; y < *h; y++)
		rows[y] = (png_bytep)px + (size_t)y * rowbytes;
	png_read_image(png, rows);
	png_read_end(png, NULL);
	png_destroy_read_struct(&png, &info, NULL);
	fclose(fp);
	free(rows);
	widen(px, (unsigned char *)px, n * (size_t)*h, b);
	return px;
}

struct pngio_reader {
	char *path;
	FILE *fp;
	png_structp png;
	png_infop info;
	struct png_msg msg;
	int h, y;		/* rows, rows read */
	size_t n;		/* samples per row */
	int b;			/* bits per sample after the transforms: 8 or 16 */
	unsigned char *row;	/* one row of the file's bytes */
	uint16_t *whole;	/* an interlaced image, read at open */
};

void pngio_reader_close(struct pngio_reader *rd)
{
	if (rd == NULL)
		return;
	png_destroy_read_struct(&rd->png, &rd->info, NULL);
	if (rd->fp)
		fclose(rd->fp);
	free(rd->path);
	free(rd->row);
	free(rd->whole);
	free(rd);
}

static void *reader_fail(struct pngio_reader *rd, char **cause)
{
	*cause = unreadable(rd->path, &rd->msg);
	pngio_reader_close(rd);
	return NULL;
}

struct pngio_reader *pngio_reader_open(const char *path, int *w, int *h, int *channels, int *bits,
    char **cause)
{
	FILE *fp = fopen(path, "rb");
	if (!fp) {
		*cause = xasprintf("%s: cannot read: %s", path, strerror(errno));
		return NULL;
	}
	struct pngio_reader *rd = xcalloc(1, sizeof *rd);
	rd->fp = fp;
	rd->path = xstrdup(path);
	struct stat st;
	double file_bytes = fstat(fileno(fp), &st) == 0 ? (double)st.st_size : 0.0;
	rd->png = create_reader(&rd->msg);
	rd->info = rd->png ? png_create_info_struct(rd->png) : NULL;
	if (!rd->info || setjmp(png_jmpbuf(rd->png)))
		return reader_fail(rd, cause);
	png_structp png = rd->png;
	png_infop info = rd->info;
	size_t rowbytes;
	int passes = read_header(png, info, fp, file_bytes, &rd->msg, w, h, channels, bits, &rd->b,
	    &rowbytes);
	rd->h = *h;
	rd->n = (size_t)*w * (size_t)*channels;
	if (passes > 1) {
		/* Adam7: the image is read whole here, as pngio_read does. */
		uint16_t *px;
		int w2, h2, c2, b2;
		png_destroy_read_struct(&rd->png, &rd->info, NULL);
		fclose(rd->fp);
		rd->fp = NULL;
		free(rd->path);
		free(rd);
		px = pngio_read(path, &w2, &h2, &c2, &b2, cause);
		if (px == NULL)
			return NULL;
		rd = xcalloc(1, sizeof *rd);
		rd->path = xstrdup(path);
		rd->h = h2;
		rd->n = (size_t)w2 * (size_t)c2;
		rd->whole = px;
		return rd;
	}
	rd->row = xmalloc(rowbytes);
	return rd;
}

int pngio_reader_rows(struct pngio_reader *rd, uint16_t *px, int nrows, char **cause)
{
	if (nrows > rd->h - rd->y) {
		*cause = xasprintf("%s: rows %d to %d asked of %d", rd->path, rd->y,
		    rd->y + nrows - 1, rd->h);
		return -1;
	}
	if (rd->whole) {
		memcpy(px, rd->whole + (size_t)rd->y * rd->n,
		    sizeof(uint16_t) * rd->n * (size_t)nrows);
		rd->y += nrows;
		return 0;
	}
	if (setjmp(png_jmpbuf(rd->png))) {
		*cause = unreadable(rd->path, &rd->msg);
		return -1;
	}
	for (int y = 0; y < nrows; y++) {
		png_read_row(rd->png, rd->row, NULL);
		widen(px + (size_t)y * rd->n, rd->row, rd->n, rd->b);
	}
	rd->y += nrows;
	if (rd->y == rd->h) {
		if (setjmp(png_jmpbuf(rd->png))) {
			*cause = unreadable(rd->path, &rd->msg);
			return -1;
		}
		png_read_end(rd->png, NULL);
	}
	return 0;
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
