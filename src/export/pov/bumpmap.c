/* bumpmap: read, box-filter and write the height map of a texture
 * directory, and the POV-Ray bump_size that gives its physical slopes. */
#include "config.h"

#include "export/pov/bumpmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/util.h"
#include "geom/texdir.h"
#include "io/pngio.h"

int bumpmap_load(const char *dir, struct bumpmap *h, char **cause)
{
	char *err = NULL;
	struct texdir *t = texdir_load(dir, 0, &err);
	*h = (struct bumpmap){ .filter = 1 };
	if (t == NULL) {
		*cause = xasprintf("--textures %s: %s", dir, err);
		free(err);
		return -1;
	}
	h->src = xasprintf("%s/height.png", dir);
	if (t->w != t->h || !t->have_range || !isfinite(t->tile_mm) || t->h_max_um < t->h_min_um) {
		*cause = xasprintf("%s: the POV-Ray bump map needs a square tile with its height range, got %dx%d, "
				   "tile_mm = %g, heights [%g, %g] um",
		    h->src, t->w, t->h, t->tile_mm, t->h_min_um, t->h_max_um);
		texdir_free(t);
		return -1;
	}
	h->size_px = t->w;
	h->tile_mm = t->tile_mm;
	h->h_min_um = t->h_min_um;
	h->h_range_um = t->h_max_um - t->h_min_um;
	h->px = t->height;	/* taken over */
	t->height = NULL;
	texdir_free(t);
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
	*o_min = INFINITY;
	*o_max = -INFINITY;
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
	while (texel_units * f * 2 <= pixel_units && n % (f * 2) == 0 && n / (f * 2) >= 16)
		f *= 2;
	return f;
}
