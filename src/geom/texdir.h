/* texdir: the texture directory of `skinbake texture`, written and read.
 * One tile of skin micro-relief as seamless maps, row 0 at the top = +y end
 * of the tile:
 *
 *   height.png          16-bit gray, 0 = lowest point, 65535 = highest; tEXt
 *                       skinbake:tile_mm, skinbake:height_min_um and
 *                       skinbake:height_max_um give the physical range
 *   pores_height.png    the same for the pores alone
 *   furrows_height.png  the same for the furrows alone
 *   normal.png          16-bit RGB tangent-space normal, OpenGL +Y:
 *                       value = (n + 1) / 2 * 65535
 *   normal.exr          float R, G, B = unit normal x, y, z
 *   height.exr          float Y = height [um] over the undisturbed surface
 *   preview.png         8-bit sRGB Lambert shading, for people
 *   manifest.json       parameters, ranges, furrow levels, files
 *
 * Exporters read it through texdir_load (height and normal maps with their
 * tEXt numbers); nothing else parses these files. */
#ifndef SKINBAKE_TEXDIR_H
#define SKINBAKE_TEXDIR_H
#include <stdint.h>

#include "base/outdir.h"
#include "geom/relief.h"
#include "geom/relief_stats.h"
#include "geom/sites.h"

/* ---- writer ---- */

/* The maps of one tile, n x n pixels, row 0 at the top. */
struct texdir_maps {
	int n;			/* tile edge [px] */
	float *pores;		/* [n * n] pore heights [cm], 0 = undisturbed surface */
	float *furrows;		/* [n * n] furrow heights [cm] */
	float *height;		/* [n * n] pores + furrows [cm] */
	float *nx, *ny, *nz;	/* [n * n] unit normal, x right, y up, z out */
};

/* Render relief r (placed for cfg) at cfg->size pixels: heights and normals.
 * Free with texdir_maps_free. */
void texdir_maps_render(struct texdir_maps *m, const struct relief *r, const struct texture_config *cfg);
void texdir_maps_free(struct texdir_maps *m);
/* Lowest and highest point of m->height [cm]. */
void texdir_height_range(const struct texdir_maps *m, double *lo, double *hi);

/* Notes on features too small for the pixel pitch (furrows under 2 px wide,
 * pores under 1.5 px), one line each without a newline at the end, or
 * NULL when there are none.  Caller frees. */
char *texdir_resolution_notes(const struct texture_config *cfg, const struct relief *r);

/* A texture directory, for base/outdir.h: manifest.json of kind
 * "skinbake texture" and the maps above. */
extern const struct outdir_kind texdir_outdir_kind;

/* Estimated needs per pixel of a tile (budget check of texdir_make):
 * measured 37-49 bytes of memory and 26-27 bytes of files at 1024 and 2048 px. */
#define TEXDIR_MEM_PER_PX 48.0
#define TEXDIR_DISK_PER_PX 28.0

/* What texdir_make did, for the command's summary. */
struct texdir_made {
	int n_pores;		/* pores placed */
	double h_min, h_max;	/* lowest and highest point of the height map [cm] */
	double t_place, t_render, t_write;	/* wall time of each step [s] */
	char *notes;		/* texdir_resolution_notes, or NULL; caller frees */
	int refused;		/* 1: DIR or the size was refused before any work (exit status 2) */
	int have_stats;		/* 1 when cfg->with_stats: stats below are set */
	struct relief_stats stats;	/* of the written maps (relief_stats_for) */
};

/* All of `skinbake texture` after its options: place the relief of cfg,
 * render the maps at cfg->size and write DIR through base/outdir.h (all or
 * nothing, one swap; refused when DIR is not a texture directory, is being
 * written, or the size does not fit the memory or disk: made->refused).  Nothing is
 * written when placing fails.  -1 and *cause (caller frees) on failure;
 * made->notes may be set either way. */
int texdir_make(const char *dir, const struct texture_config *cfg, struct texdir_made *made, char **cause);

/* ---- reader ---- */

struct texdir {
	char *dir;		/* the directory as given */
	int w, h;		/* map size [px] (a tile need not be square here) */
	uint16_t *height;	/* [h][w] height.png, 0 = height_min_um .. 65535 = height_max_um */
	uint16_t *normal;	/* [h][w][3] normal.png, or NULL when not asked for */
	double tile_mm;		/* tile edge [mm], in tile-mm's range [0.5, 500] */
	int have_range;		/* 1 when both heights below are finite numbers */
	double h_min_um, h_max_um;	/* height of value 0 and 65535 [um] */
	/* The tEXt values as written, for copies that keep them to the letter
	 * (NULL when absent). */
	char *tile_mm_text, *h_min_text, *h_max_text;
};

/* Read DIR/height.png (16-bit gray, each side in [2, 16384] px, tEXt
 * skinbake:tile_mm in the range of the texture parameter tile-mm, the
 * height range both absent or finite with min <= max) and, with with_normal,
 * DIR/normal.png (16-bit RGB of the same size); DIR/manifest.json, when
 * there is one, must be a skinbake texture whose size_px, tile_mm and
 * height range agree with height.png.  NULL and *cause (caller frees)
 * naming the file, the key, the value and what was expected otherwise. */
struct texdir *texdir_load(const char *dir, int with_normal, char **cause);
void texdir_free(struct texdir *t);	/* NULL is a no-op */
#endif
