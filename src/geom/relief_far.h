/* relief_far: the relief as roughness for views in which it is smaller than
 * a rendered pixel.  A renderer that filters (or undersamples) the normal
 * map sees the mean normal of a footprint and loses the spread of the
 * normals inside it; Toksvig (J Graphics Tools 2005;10(3):65-71) measures
 * that spread by the length |N| < 1 of the averaged unit normals, and with
 * the Blinn-Phong/Beckmann correspondence alpha^2 = 2 / (s + 2) his
 * shortened exponent becomes the roughness to add,
 *
 *     alpha_relief^2 = 2 (1 - |N|) / |N|,  alpha_total^2 = alpha_skin^2 + alpha_relief^2,
 *
 * per block of texels.  The map roughness_far.png holds alpha_relief on
 * blocks about one primary furrow cell wide (docs/relief.md says how the
 * exporters use it). */
#ifndef SKINBAKE_RELIEF_FAR_H
#define SKINBAKE_RELIEF_FAR_H

/* Blocks per edge of the far map of an n-pixel tile of pitch [cm] whose
 * primary cell is cell [cm]: about tile / cell, at least 1, at most n. */
int relief_far_size(int n, double pitch, double cell);

/* alpha_relief of m x m blocks of the n x n unit normals (block i spans
 * texels floor(i n / m) .. floor((i + 1) n / m) - 1 on each axis; row 0 on
 * top).  alpha receives m*m values [1]. */
void relief_far_alpha(int n, const float *nx, const float *ny, const float *nz, int m,
    float *alpha);

/* Write alpha (m x m) as a 16-bit gray PNG, value = min(alpha, 1) * 65535,
 * with tEXt keys for the block size [um], the site and the software. */
int relief_far_write(const char *path, int m, const float *alpha, double block_um, const char *site,
    const char *software, char **cause);
#endif
