/* image: the pictures the maps commands read and write: a user's albedo
 * texture and masks, and single-channel data maps.  PNG (8 or 16 bit, grey,
 * grey + alpha, RGB, RGBA) and OpenEXR (channels R, G, B, A or Y) are told
 * apart by their first bytes, not by the file name, so that anything else
 * gets a clear message.  Values are floats: PNG samples scaled to [0, 1]
 * (still encoded as the file was), EXR values as stored. */
#ifndef SKINBAKE_IMAGE_H
#define SKINBAKE_IMAGE_H
#include <stddef.h>
#include <stdint.h>
#include "io/pngio.h"

struct image {
	int w, h;		/* pixels */
	int nch;		/* channels: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA */
	int bits;		/* 8 or 16 (PNG), 32 (EXR float) */
	float *v;		/* [h][w][nch], row 0 at the top */
};

enum image_kind { IMAGE_NONE, IMAGE_PNG, IMAGE_EXR };

/* What PATH holds by its first bytes: IMAGE_PNG, IMAGE_EXR, or IMAGE_NONE
 * with *cause ("PATH: not a PNG or OpenEXR image (...)" or why it cannot
 * be opened). */
enum image_kind image_kind(const char *path, char **cause);
/* Size of a PNG or EXR image without reading its pixels; -1 and *cause. */
int image_size(const char *path, int *w, int *h, char **cause);
/* Read PATH; NULL and *cause.  Caller frees with image_free. */
struct image *image_read(const char *path, char **cause);
/* PATH a band of rows at a time (maps fit on images too large to hold
 * whole): the same values image_read gives, rows in order.  The band is
 * an image of the stream's width and channels and at least nrows rows;
 * -1 (NULL) and *cause as image_read's, a non-finite EXR value naming
 * its texel in the whole image. */
struct image_stream;
struct image_stream *image_stream_open(const char *path, int *w, int *h, int *nch, int *bits,
    char **cause);
int image_stream_rows(struct image_stream *s, struct image *band, int nrows, char **cause);
void image_stream_close(struct image_stream *s);	/* NULL is a no-op */
struct image *image_new(int w, int h, int nch, int bits);
void image_free(struct image *im);	/* NULL is a no-op */
/* The value of channel c at texel i, with grey standing for every colour
 * channel and a missing alpha for 1. */
float image_get(const struct image *im, size_t i, int c);

/* An output image path: ends with .png or .exr (*exr set accordingly), is
 * not a directory, its directory exists and is writable; -1 and *cause
 * ("'PATH' does not end with .png or .exr", ...). */
int image_check_out(const char *path, int *exr, char **cause);

/* Write a PNG of bits 8 or 16 from values in [0, 1] (clamped, rounded);
 * srgb marks an 8-bit colour picture as sRGB-encoded (io/pngio.h). */
int image_write_png(const char *path, const struct image *im, int bits, int srgb, int ntext,
    const struct png_text_kv *text, char **cause);
/* Write an OpenEXR of float channels named names[c] with string attributes. */
int image_write_exr(const char *path, const struct image *im, const char *const *names, int nattr,
    const char *const *attr_kv, char **cause);
#endif
