/* bumpmap: read, box-filter and write the height map of a texture
 * directory, and the POV-Ray bump_size that gives its physical slopes. */
#include "config.h"

#include "export/pov/bumpmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/util.h"
#include "io/pngio.h"

int bumpmap_load(const char *dir, struct bumpmap *h, char **cause)
{
	int w, hh, ch, bits;
	char *err = NULL;
	h->src = xasprintf("%s/height.png", dir);
	h->filter = 1;
	uint16_t *px = pngio_read(h->src, &w, &hh, &ch, &bits, &err);
	if (px == NULL) {
		*cause = xasprintf("--textures %s: %s", dir, err);
		free(err);
		return -1;
	}
	h->px = px;
	if (ch != 1 || bits != 16 || w != hh)
		return *cause = xasprintf("%s: expected a square 16-bit grayscale PNG, got %dx%d, %d channel(s), %d bit",
			   h->src, w, hh, ch, bits),
		       -1;
	static const char *keys[] = { "skinbake:tile_mm", "skinbake:height_min_um", "skinbake:height_max_um" };
	double v[3];
	for (int i = 0; i < 3; i++) {
		char *t = pngio_read_text(h->src, keys[i]);
		int bad = t == NULL || util_parse_double(t, &v[i]) != 0 || !isfinite(v[i]);
		if (bad) {
			*cause = xasprintf("%s: tEXt key %s is %s", h->src, keys[i], t ? "not a number" : "missing");
			free(t);
			return -1;
		}
		free(t);
	}
	if (v[0] <= 0 || v[2] < v[1])
		return *cause = xasprintf("%s: tile_mm = %g must be > 0 and height_max_um = %g >= height_min_um = %g",
			   h->src, v[0], v[2], v[1]),
		       -1;
	h->size_px = w;
	h->tile_mm = v[0];
	h->h_min_um = v[1];
	h->h_range_um = v[2] - v[1];
	return 0;
}

void bumpmap_free(struct bumpmap *h)
{
	free(h->src);
	free(h->px);
	h->src = NULL;
	h->px = NULL;
}

void bumpmap_reduce(struct bumpmap *h, int f)
{
	double lo, hi;
	uint16_t *px = bumpmap_filter(h->px, h->size_px, h->h_min_um, h->h_min_um + h->h_range_um, f, &lo, &hi);
	free(h->px);
	h->px = px;
	h->size_px /= f;
	h->filter *= f;
	h->h_min_um = lo;
	h->h_range_um = hi - lo;
}

int bumpmap_write_png(const struct bumpmap *h, const char *path, char **cause)
{
	char v[3][32];
	snprintf(v[0], sizeof v[0], "%.9g", h->tile_mm);
	snprintf(v[1], sizeof v[1], "%.9g", h->h_min_um);
	snprintf(v[2], sizeof v[2], "%.9g", h->h_min_um + h->h_range_um);
	struct png_text_kv kv[3] = { { "skinbake:tile_mm", v[0] }, { "skinbake:height_min_um", v[1] },
		{ "skinbake:height_max_um", v[2] } };
	return pngio_write(path, h->size_px, h->size_px, 1, 16, h->px, 0, 3, kv, cause);
}

double bumpmap_size(double h_range_um, int n_px, double tile_mm)
{
	return h_range_um * 1e-3 * n_px / tile_mm;
}

uint16_t *bumpmap_filter(const uint16_t *px, int n, double h_min, double h_max, int f, double *o_min,
    double *o_max)
{
	int m = n / f;
	double *h = xmalloc(sizeof(double) * (size_t)m * m), scale = (h_max - h_min) / 65535.0;
	*o_min = INFINITY, *o_max = -INFINITY;
	for (int y = 0; y < m; y++)
		for (int x = 0; x < m; x++) {
			double sum = 0;
			for (int j = 0; j < f; j++)
				for (int i = 0; i < f; i++)
					sum += px[(size_t)(y * f + j) * n + x * f + i];
			double v = h_min + scale * sum / (f * f);
			h[y * m + x] = v;
			*o_min = fmin(*o_min, v);
			*o_max = fmax(*o_max, v);
		}
	uint16_t *out = xmalloc(sizeof(uint16_t) * (size_t)m * m);
	double range = *o_max - *o_min;
	for (int i = 0; i < m * m; i++)
		out[i] = range > 0 ? (uint16_t)lround((h[i] - *o_min) / range * 65535.0) : 0;
	free(h);
	return out;
}

int bumpmap_filter_factor(int n, double texel_units, double pixel_units)
{
	int f = 1;
	while (texel_units * f * 4 <= pixel_units && n % (f * 2) == 0 && n / (f * 2) >= 16)
		f *= 2;
	return f;
}
