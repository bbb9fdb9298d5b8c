/* image: PNG and OpenEXR pictures in memory (see image.h). */
#include "config.h"
#include "maps/image.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/check.h"
#include "base/util.h"
#include "io/exrio.h"

enum image_kind image_kind(const char *path, char **cause)
{
	FILE *fp = fopen(path, "rb");
	if (fp == NULL) {
		*cause = xasprintf("%s: cannot read: %s", path, strerror(errno));
		return IMAGE_NONE;
	}
	unsigned char b[8] = { 0 };
	size_t n = fread(b, 1, sizeof b, fp);
	fclose(fp);
	static const unsigned char png[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
	static const unsigned char exr[4] = { 0x76, 0x2f, 0x31, 0x01 };
	if (n == 8 && memcmp(b, png, 8) == 0)
		return IMAGE_PNG;
	if (n >= 4 && memcmp(b, exr, 4) == 0)
		return IMAGE_EXR;
	*cause = xasprintf("%s: not a PNG or OpenEXR image (its first bytes are neither signature)",
	    path);
	return IMAGE_NONE;
}

struct image *image_new(int w, int h, int nch, int bits)
{
	struct image *im = xcalloc(1, sizeof *im);
	im->w = w;
	im->h = h;
	im->nch = nch;
	im->bits = bits;
	im->v = xcalloc((size_t)w * (size_t)h * (size_t)nch, sizeof(float));
	return im;
}

void image_free(struct image *im)
{
	if (im == NULL)
		return;
	free(im->v);
	free(im);
}

float image_get(const struct image *im, size_t i, int c)
{
	const float *p = im->v + i * (size_t)im->nch;
	if (c == 3)
		return im->nch == 4 ? p[3] : im->nch == 2 ? p[1] : 1.0f;
	return im->nch >= 3 ? p[c] : p[0];
}

int image_size(const char *path, int *w, int *h, char **cause)
{
	enum image_kind k = image_kind(path, cause);
	if (k == IMAGE_EXR)
		return exrio_size(path, w, h, cause);
	if (k == IMAGE_NONE)
		return -1;
	/* PNG: width and height are the first fields of IHDR (bytes 16-23). */
	FILE *fp = fopen(path, "rb");
	unsigned char b[24];
	size_t n = fp ? fread(b, 1, sizeof b, fp) : 0;
	if (fp)
		fclose(fp);
	if (n != sizeof b || memcmp(b + 12, "IHDR", 4) != 0) {
		*cause = xasprintf("%s: not a readable PNG file (no IHDR)", path);
		return -1;
	}
	*w = (int)((unsigned)b[16] << 24 | (unsigned)b[17] << 16 | (unsigned)b[18] << 8 | b[19]);
	*h = (int)((unsigned)b[20] << 24 | (unsigned)b[21] << 16 | (unsigned)b[22] << 8 | b[23]);
	return 0;
}

static struct image *read_png(const char *path, char **cause)
{
	int w, h, nch, bits;
	uint16_t *px = pngio_read(path, &w, &h, &nch, &bits, cause);
	if (px == NULL)
		return NULL;
	struct image *im = image_new(w, h, nch, bits);
	size_t n = (size_t)w * h * nch;
	for (size_t i = 0; i < n; i++)
		im->v[i] = (float)(px[i] / 65535.0);
	free(px);
	return im;
}

/* EXR: R, G, B (A optional) or a single Y channel. */
static struct image *read_exr(const char *path, char **cause)
{
	int w, h;
	if (exrio_size(path, &w, &h, cause) != 0)
		return NULL;
	size_t n = (size_t)w * h;
	float *plane = xmalloc(sizeof(float) * n);
	char *why = NULL;
	struct image *im = NULL;
	if (exrio_read_channel(path, "R", w, h, plane, &why) == 0) {
		free(why);
		why = NULL;
		int has_a = exrio_read_channel(path, "A", w, h, plane, &why) == 0;
		free(why);
		why = NULL;
		im = image_new(w, h, has_a ? 4 : 3, 32);
		static const char *names[] = { "R", "G", "B", "A" };
		for (int c = 0; c < im->nch; c++) {
			if (exrio_read_channel(path, names[c], w, h, plane, cause) != 0) {
				image_free(im);
				free(plane);
				return NULL;
			}
			for (size_t i = 0; i < n; i++)
				im->v[i * im->nch + c] = plane[i];
		}
	} else if (free(why), why = NULL, exrio_read_channel(path, "Y", w, h, plane, &why) == 0) {
		im = image_new(w, h, 1, 32);
		memcpy(im->v, plane, sizeof(float) * n);
	} else
		*cause = xasprintf("%s: an OpenEXR image without R, G, B or Y channels", path);
	free(why);
	free(plane);
	return im;
}

struct image *image_read(const char *path, char **cause)
{
	enum image_kind k = image_kind(path, cause);
	struct image *im = k == IMAGE_PNG ? read_png(path, cause) : k == IMAGE_EXR ? read_exr(path,
	    cause) : NULL;
	if (im && im->bits == 32)
		for (size_t i = 0; i < (size_t)im->w * im->h * im->nch; i++)
			if (!isfinite(im->v[i])) {
				*cause = xasprintf("%s: texel %zu holds a value that is not finite",
				    path, i / (size_t)im->nch);
				image_free(im);
				return NULL;
			}
	return im;
}

struct image_stream {
	char *path;
	int w, h, nch, bits, y;		/* size, channels, bits, rows read */
	struct pngio_reader *png;	/* or NULL: EXR */
	uint16_t *px;			/* PNG band samples */
	float *plane;			/* EXR band of one channel */
	int band;			/* rows px and plane hold */
};

void image_stream_close(struct image_stream *s)
{
	if (s == NULL)
		return;
	pngio_reader_close(s->png);
	free(s->px);
	free(s->plane);
	free(s->path);
	free(s);
}

struct image_stream *image_stream_open(const char *path, int *w, int *h, int *nch, int *bits,
    char **cause)
{
	enum image_kind k = image_kind(path, cause);
	if (k == IMAGE_NONE)
		return NULL;
	struct image_stream *s = xcalloc(1, sizeof *s);
	s->path = xstrdup(path);
	if (k == IMAGE_PNG) {
		s->png = pngio_reader_open(path, &s->w, &s->h, &s->nch, &s->bits, cause);
		if (s->png == NULL) {
			image_stream_close(s);
			return NULL;
		}
	} else {
		/* R, G, B (A optional) or Y, found as read_exr finds them */
		if (exrio_size(path, &s->w, &s->h, cause) != 0) {
			image_stream_close(s);
			return NULL;
		}
		float *row = xmalloc(sizeof(float) * (size_t)s->w);
		char *why = NULL;
		s->bits = 32;
		if (exrio_read_channel_rows(path, "R", s->w, s->h, 0, 1, row, &why) == 0) {
			free(why);
			why = NULL;
			s->nch = exrio_read_channel_rows(path, "A", s->w, s->h, 0, 1, row,
			    &why) == 0 ? 4 : 3;
		} else if (free(why), why = NULL, exrio_read_channel_rows(path, "Y", s->w, s->h, 0,
		    1, row, &why) == 0)
			s->nch = 1;
		else
			*cause = xasprintf("%s: an OpenEXR image without R, G, B or Y channels",
			    path);
		free(why);
		free(row);
		if (s->nch == 0) {
			image_stream_close(s);
			return NULL;
		}
	}
	*w = s->w;
	*h = s->h;
	*nch = s->nch;
	*bits = s->bits;
	return s;
}

int image_stream_rows(struct image_stream *s, struct image *band, int nrows, char **cause)
{
	CHECK(band->w == s->w && band->nch == s->nch && nrows <= band->h && s->y + nrows <= s->h);
	size_t n = (size_t)s->w * (size_t)nrows * (size_t)s->nch;
	if (nrows > s->band) {
		s->band = nrows;
		if (s->png)
			s->px = xreallocarray(s->px, (size_t)s->w * (size_t)nrows * (size_t)s->nch,
			    sizeof(uint16_t));
		else
			s->plane = xreallocarray(s->plane, (size_t)s->w * (size_t)nrows,
			    sizeof(float));
	}
	if (s->png) {
		if (pngio_reader_rows(s->png, s->px, nrows, cause) != 0)
			return -1;
		for (size_t i = 0; i < n; i++)
			band->v[i] = (float)(s->px[i] / 65535.0);
	} else {
		static const char *names[] = { "R", "G", "B", "A" };
		size_t np = (size_t)s->w * (size_t)nrows;
		for (int c = 0; c < s->nch; c++) {
			if (exrio_read_channel_rows(s->path, s->nch == 1 ? "Y" : names[c], s->w,
			    s->h, s->y, nrows, s->plane,
			    cause) != 0)
				return -1;
			for (size_t i = 0; i < np; i++)
				band->v[i * s->nch + c] = s->plane[i];
		}
		for (size_t i = 0; i < n; i++)
			if (!isfinite(band->v[i])) {
				*cause = xasprintf("%s: texel %zu holds a value that is not finite",
				    s->path,
				    (size_t)s->y * (size_t)s->w + i / (size_t)s->nch);
				return -1;
			}
	}
	s->y += nrows;
	return 0;
}

int image_write_png(const char *path, const struct image *im, int bits, int srgb, int ntext,
    const struct png_text_kv *text, char **cause)
{
	size_t n = (size_t)im->w * im->h * im->nch;
	uint16_t *px = xmalloc(sizeof(uint16_t) * n);
	double top = bits == 16 ? 65535.0 : 255.0;
	for (size_t i = 0; i < n; i++)
		px[i] = (uint16_t)lround(top * fmin(1.0, fmax(0.0, im->v[i])));
	int rc = pngio_write(path, im->w, im->h, im->nch, bits, px, srgb, ntext, text, cause);
	free(px);
	return rc;
}

int image_write_exr(const char *path, const struct image *im, const char *const *names, int nattr,
    const char *const *attr_kv, char **cause)
{
	size_t n = (size_t)im->w * im->h;
	float **planes = xcalloc((size_t)im->nch, sizeof(float *));
	for (int c = 0; c < im->nch; c++) {
		planes[c] = xmalloc(sizeof(float) * n);
		for (size_t i = 0; i < n; i++)
			planes[c][i] = im->v[i * im->nch + c];
	}
	struct exr_attr_kv *a = xcalloc((size_t)(nattr > 0 ? nattr : 1), sizeof *a);
	for (int k = 0; k < nattr; k++) {
		a[k].key = attr_kv[2 * k];
		a[k].value = attr_kv[2 * k + 1];
	}
	int rc = exrio_write(path, im->w, im->h, im->nch, names, (const float *const *)planes,
	    nattr, a, cause);
	for (int c = 0; c < im->nch; c++)
		free(planes[c]);
	free(planes);
	free(a);
	return rc;
}

int image_check_out(const char *path, int *exr, char **cause)
{
	size_t n = strlen(path);
	struct stat st;
	*exr = n > 4 && strcmp(path + n - 4, ".exr") == 0;
	if (!(*exr || (n > 4 && strcmp(path + n - 4, ".png") == 0))) {
		*cause = xasprintf("'%s' does not end with .png or .exr", path);
		return -1;
	}
	if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
		*cause = xasprintf("'%s' is a directory, expected a file name", path);
		return -1;
	}
	char *dir = xstrdup(path), *sl = strrchr(dir, '/');
	if (sl)
		*(sl == dir ? sl + 1 : sl) = '\0';
	int ok = access(sl ? dir : ".", W_OK) == 0;
	if (!ok)
		*cause = xasprintf("'%s': its directory '%s' is missing or not writable", path, sl
		    ? dir : ".");
	free(dir);
	return ok ? 0 : -1;
}
