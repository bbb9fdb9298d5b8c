/* pngio: PNG files with tEXt metadata through libpng (see pngio.h). */
#include "config.h"
#include "io/pngio.h"

#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/util.h"

int pngio_write(const char *path, int w, int h, int channels, int bits, const uint16_t *px,
    int srgb, int ntext, const struct png_text_kv *text, char **cause)
{
	static const int types[] = { 0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
		PNG_COLOR_TYPE_RGB_ALPHA };
	if (channels < 1 || channels > 4 || (bits != 8 && bits != 16) || w < 1 || h < 1) {
		*cause = xasprintf("%s: unsupported PNG layout (%d channels, %d bits)", path, channels, bits);
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
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	if (!info || setjmp(png_jmpbuf(png))) {
		png_destroy_write_struct(&png, &info);
		fclose(fp);
		unlink(tmp);
		free(tmp);
		free(row);
		*cause = xasprintf("%s: writing the PNG failed", path);
		return -1;
	}
	png_init_io(png, fp);
	/* Data maps are large and noisy: fast zlib and one fixed filter cost a
	 * little size and save most of the write time. */
	png_set_compression_level(png, 2);
	png_set_filter(png, 0, PNG_FILTER_UP);
	png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, bits, types[channels], PNG_INTERLACE_NONE,
	    PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
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
				row[2 * i] = (unsigned char)(src[i] >> 8);	/* PNG is big-endian */
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

uint16_t *pngio_read(const char *path, int *w, int *h, int *channels, int *bits, char **cause)
{
	FILE *fp = fopen(path, "rb");
	if (!fp) {
		*cause = xasprintf("%s: cannot read: %s", path, strerror(errno));
		return NULL;
	}
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	uint16_t *volatile px = NULL;
	unsigned char *volatile row = NULL;
	if (!info || setjmp(png_jmpbuf(png))) {
		png_destroy_read_struct(&png, &info, NULL);
		fclose(fp);
		free(px);
		free(row);
		*cause = xasprintf("%s: not a readable PNG file", path);
		return NULL;
	}
	png_init_io(png, fp);
	png_read_info(png, info);
	int bd = png_get_bit_depth(png, info), ct = png_get_color_type(png, info);
	if (ct == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (bd < 8)
		png_set_expand(png);
	png_read_update_info(png, info);
	*w = (int)png_get_image_width(png, info);
	*h = (int)png_get_image_height(png, info);
	*channels = png_get_channels(png, info);
	*bits = bd < 8 ? 8 : bd;
	int b = png_get_bit_depth(png, info);
	size_t n = (size_t)*w * (size_t)*channels;
	px = xmalloc(n * (size_t)*h * sizeof(uint16_t));
	row = xmalloc(png_get_rowbytes(png, info));
	for (int y = 0; y < *h; y++) {
		png_read_row(png, row, NULL);
		uint16_t *dst = px + (size_t)y * n;
		for (size_t i = 0; i < n; i++)
			dst[i] = b == 16 ? (uint16_t)((row[2 * i] << 8) | row[2 * i + 1]) : (uint16_t)(row[i] * 257);
	}
	png_read_end(png, NULL);
	png_destroy_read_struct(&png, &info, NULL);
	fclose(fp);
	free(row);
	return px;
}

char *pngio_read_text(const char *path, const char *key)
{
	FILE *fp = fopen(path, "rb");
	if (!fp)
		return NULL;
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
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
