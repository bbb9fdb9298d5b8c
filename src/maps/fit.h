/* fit: per texel, the family parameters whose albedo matches a colour
 * (`skinbake maps fit`).
 *
 * Method.  The family's albedo (family_albedo: cubic in log between the
 * members) is tabulated on a dense grid uniform in each axis' coordinate
 * (2048 points for one axis, 160^2 for two, 48^3 for three), as CIELAB
 * (D65, the sRGB white).  Every distinct input colour (texels of equal
 * colour are solved once) starts at the point nearest in CIELAB among a
 * coarse subset of the grid (every 16th, 4th, 4th point per axis, in
 * buckets of 2 CIELAB units searched shell by shell), or, within a chunk
 * of 512 colours in order of first appearance, from the previous colour's
 * solution when that reaches an exact match (0.02), and is refined by
 * damped Gauss-Newton on the grid's multilinear
 * interpolant, minimising the CIELAB distance plus a tiny pull (0.01 per
 * unit of the normalised coordinate) toward the middle of each axis, which
 * only decides parameters the colour does not determine.  Parameters stay
 * inside the family's range.  The reported error is the CIEDE2000 between
 * the input colour and the family's albedo at the parameters (exact
 * interpolation, not the grid).  Texels whose error exceeds max_de are
 * unmatched (status 255, their parameters the closest in range, not
 * forced to a match); transparent texels (alpha < 0.5) and texels outside
 * the mask (< 0.5) are not fitted (status 128, parameters at the middle).
 * Chunks are fixed, so the result does not depend on the number of
 * threads. */
#ifndef SKINBAKE_FIT_H
#define SKINBAKE_FIT_H
#include "family/family.h"
#include "maps/image.h"
#include "maps/mapset.h"

struct maps_fit_opts {
	int input_linear;	/* 1: the albedo's values are linear sRGB; 0: sRGB-encoded */
	double max_de;		/* CIEDE2000 above which a texel is unmatched */
	int threads;		/* OpenMP threads, 0 = all */
	/* maps_fit_files: read the albedo again for the maps even when its
	 * colour ids fit in MAPS_FIT_IDS_MAX (tests; the same files) */
	int reread;
};

/* maps_fit_files keeps each texel's colour id (4 bytes) from its first
 * reading of the albedo when they take at most this many bytes (up to
 * 5792^2 texels); larger albedos are read twice. */
#define MAPS_FIT_IDS_MAX 128e6

struct maps_fit_summary {
	long texels;		/* in the image */
	long fitted;		/* not transparent, inside the mask */
	long matched, unmatched;	/* fitted texels within / beyond max_de */
	long unique;		/* distinct colours solved */
	double de_median, de_p95, de_max;	/* CIEDE2000 over the fitted texels (0.001 bins) */
	double seconds;		/* wall time of the fit [s] */
};

/* Estimated needs of maps fit per texel of the albedo (the budget check of
 * `maps fit`), for the worst case of every texel a distinct colour: the
 * streamed fit (maps_fit_files) holds per distinct colour its key (12
 * bytes), result (12 with two axes, 16 with three) and 8 to 16 bytes of
 * hash slots, and per texel its colour id (4); bands and the table are
 * the fixed part.  Measured: 49 MB peak at 1024^2 with noise (1.05 M
 * colours), 84 MB at 4096^2 with 77 k colours (the images are not held).
 * Files at most 2 bytes (16-bit PNG) or 4 (EXR) per map (the family's
 * axes and de2000) and 1 for the status map, uncompressed. */
#define MAPS_FIT_MEM_PER_TEXEL 40.0
#define MAPS_FIT_MEM_FIXED 32e6

/* Fit f (family_albedo_prepare'd or not) to the colours of albedo (RGB or
 * grey, optional alpha); mask (NULL: all) must have albedo's size.  *out
 * gets the maps with de2000 and status (caller frees).  -1 and *cause when
 * the sizes differ. */
int maps_fit(struct family *f, const struct image *albedo, const struct image *mask,
    const struct maps_fit_opts *o,
    struct mapset **out, struct maps_fit_summary *sum, char **cause);
/* The same fit from files to a maps directory without holding the images:
 * the albedo (and mask) read in bands of rows for the distinct colours
 * and each texel's colour id, then the maps written band by band
 * (mapset_writer) with the fit's summary and COMMAND as their history;
 * beyond MAPS_FIT_IDS_MAX (or with o->reread) the albedo is read a second
 * time instead of keeping the ids.  Memory is the distinct colours' (about
 * 40 bytes each), the ids and a few bands.
 * The files are byte for byte maps_fit's written by mapset_write (but for
 * the seconds in maps.json).  -1 and *cause on failure, with
 * *input_error set when an input (unreadable, corrupt, sizes that differ)
 * is the cause; OUT is then as it was. */
int maps_fit_files(struct family *f, const char *albedo, const char *mask,
    const struct maps_fit_opts *o,
    const char *out, int exr, const char *command, struct maps_fit_summary *sum, int *input_error,
    char **cause);
/* The summary as a JSON object (caller frees), for maps.json. */
char *maps_fit_summary_json(const struct maps_fit_summary *s, const struct maps_fit_opts *o,
    const char *albedo);
/* Linear sRGB of texel i of an image read as the fit reads it. */
void maps_texel_linear(const struct image *im, size_t i, int input_linear, double rgb[3]);
#endif
