/* bumpmap: the micro-relief height map of `skinbake texture` (DIR/height.png,
 * 16-bit, its physical range in tEXt chunks) as a POV-Ray bump_map.  POV-Ray
 * tilts the normal by tan = bump_size * (h[i+1] - h[i]) per image pixel (h in
 * [0, 1]; all 16 bits are used), so bump_size = H_range * n_px / tile in one
 * unit.  Relief far below an image pixel only adds aliasing noise to
 * POV-Ray's per-sample normals, so the map can be box-filtered to the
 * image's pixel footprint first (aligned blocks: it still tiles). */
#ifndef SKINBAKE_BUMPMAP_H
#define SKINBAKE_BUMPMAP_H
#include <stdint.h>

struct bumpmap {
	char *src;		/* DIR/height.png */
	int size_px;		/* tile edge [px] */
	double tile_mm;		/* tile edge [mm] */
	double h_min_um;	/* height of value 0 [um] */
	double h_range_um;	/* max - min height [um] */
	uint16_t *px;		/* size_px^2 samples */
	int filter;		/* box-filter factor applied (1 = none) */
};

/* The height map of texture directory DIR (read by geom/texdir); -1 and
 * *cause (naming the file) when it is missing, not a square 16-bit
 * grayscale tile, or lacks its physical range. */
int bumpmap_load(const char *dir, struct bumpmap *h, char **cause);
void bumpmap_free(struct bumpmap *h);
/* Box-filter the map by factor f (a divisor of size_px) and re-encode it
 * over its new range. */
void bumpmap_reduce(struct bumpmap *h, int f);
/* Write the (reduced) map as a 16-bit PNG with its tEXt keys. */
int bumpmap_write_png(const struct bumpmap *h, const char *path, char **cause);

/* bump_size for a height map spanning h_range_um over n_px pixels per tile
 * of tile_mm: B = H_range * n_px / tile (same units). */
double bumpmap_size(double h_range_um, int n_px, double tile_mm);

/* Box-filter a square 16-bit height tile (n x n, values 0..65535 spanning
 * [h_min, h_max] um) by factor f (a divisor of n): the result (n/f)^2,
 * re-encoded over its own range [*o_min, *o_max] um; caller frees. */
uint16_t *bumpmap_filter(const uint16_t *px, int n, double h_min, double h_max, int f, double *o_min,
    double *o_max);
/* The filter factor (a power of two dividing n, result >= 16 px) that
 * brings texels of texel_units to at most one pixel_units footprint (the
 * mip level a renderer would pick: POV-Ray traces one ray per pixel, so
 * texels under a pixel alias into glints; the relief they lose goes to the
 * specular's roughness, povexport.c). */
int bumpmap_filter_factor(int n, double texel_units, double pixel_units);
#endif
