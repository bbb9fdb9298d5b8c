/* povfar: the relief's far roughness in POV-Ray (docs/relief.md section 6).
 * Where a primary furrow cell of the relief is smaller than an image pixel,
 * the bump map's normals vary inside every pixel and POV-Ray, sampling them
 * a few times, shows noise, or after box-filtering, nothing.  Instead the
 * lit table is blended with a rough copy of itself by roughness_far.png of
 * `skinbake texture` (alpha_relief per block of the tile):
 *
 *   pigment { image_pattern { png "far.png" map_type 0 interpolate 2 }
 *             pigment_map { [0 TABLE] [alpha_max TABLE_Rough] } }
 *
 * projected along z at the tile's size (the entries are scaled back, so the
 * tables keep their world-space patterns).  TABLE_Rough is the BRDF averaged
 * over a ring of POVFAR_RING normals tilted by tan t = alpha_max in evenly
 * spaced azimuths, each weighted by its cosine to the light, which is what
 * the bump map would give averaged over a pixel: (1/N) sum_k f(m_k) (L.m_k)
 * / (L.n), facets facing away from the camera left out.  The ring has mean
 * tan^2 = alpha_max^2, Toksvig's alpha_relief^2 for small slopes. */
#ifndef SKINBAKE_POVFAR_H
#define SKINBAKE_POVFAR_H
#include <stdint.h>
#include <stdio.h>

#include "export/pov/littable.h"

#define POVFAR_RING 8

struct pov_far {
	int on;			/* 1: the tables of this skin are blended as above */
	const char *png;	/* roughness_far.png's name in the output directory */
	double alpha_max;	/* largest alpha_relief of the map [1] */
	double tile_units;	/* tile edge [scene units] */
	const struct pov_brdf *base;	/* the skin's BRDF */
};

/* Read DIR/roughness_far.png: 1 and *px (n x n values alpha * 65535, caller
 * frees), *n when it is a square 16-bit gray map, 0 when DIR has none (older
 * texture directories), -1 and *cause when it cannot be read. */
int povfar_read(const char *dir, uint16_t **px, int *n, char **cause);

/* The map seen through pixels of m blocks per tile (m <= n): alpha is the
 * RMS of the blocks each pixel covers (area weighted; their mean normals
 * are close to the plane, so the spread adds up as alpha^2), so no block
 * pattern aliases below a pixel.  Returns m x m values; *alpha_max their
 * largest [1].  Caller frees. */
uint16_t *povfar_filter(const uint16_t *px, int n, int m, double *alpha_max);

/* The BRDF of f's base averaged over the tilted ring (for littable). */
void povfar_brdf(void *far, double theta_i, double theta_o, double dphi, double rgb[3]);

/* littable_write_key for NAME, then with far->on also NAME_Rough and NAME
 * redeclared as the blend above.  Returns littable_write_key's gamma nodes. */
int povfar_write_key(FILE *fp, const char *name, const struct pov_far *far,
    const struct pov_brdf *f, const struct pov_light *l, const struct pov_view *v,
    const double lo[3], const double hi[3], int n_theta, int n_gamma);
#endif
