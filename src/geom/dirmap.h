/* dirmap: a preferred-direction map in UV for `skinbake texture`, read from
 * a PNG of the map's own size (row 0 = top = +y end of the tile):
 *
 * - gray (1 or 2 channels): the angle of the furrows from +x toward +y,
 *   value / 65536 * 180 degrees (8-bit values count as value * 257), so
 *   0 is along +x and mid-gray about 90 degrees (along +y);
 * - RGB or RGBA: the doubled-angle vector, R = (cos 2a + 1) / 2 and
 *   G = (sin 2a + 1) / 2 (B and A are ignored), which blurs and resamples
 *   without the 180-degree wrap; where R = G = 1/2 the angle is 0.
 *
 * Directions are axial: a and a + 180 degrees are the same. */
#ifndef SKINBAKE_DIRMAP_H
#define SKINBAKE_DIRMAP_H

/* The n*n angles [rad] of PATH, which must be n x n pixels.  NULL and
 * *cause (caller frees; it names the file, its size or what is wrong, and
 * the allowed size) otherwise. */
float *dirmap_read(const char *path, int n, char **cause);

struct texture_config;
/* Read PATH at cfg->size and point cfg->relief.direction (and
 * cfg->direction_map) at it; the angles are returned for the caller to
 * free after use.  NULL and *cause as dirmap_read. */
float *dirmap_apply(struct texture_config *cfg, const char *path, char **cause);
#endif
