/* mapset: a maps directory, the parameters of a family per texel (written
 * and read here).
 *
 * Directory (format "skinbake-maps", MAPS_FORMAT_VERSION):
 *   maps.json        size, the family (directory, preset, axes and their
 *                    ranges), per map its key, file and encoding, the fit's
 *                    summary, and the commands that made the maps
 *   KEY.png          one map per axis of the family (e.g.
 *                    epidermis.melanin.png): 16-bit grey, value =
 *                    lo + (hi - lo) q / 65535 with [lo, hi] the preset key's
 *                    whole range (so maps are independent of one family's
 *                    range and 16 bits resolve 1/65535 of it); or KEY.exr
 *                    (float channel Y, the value itself) with --format exr
 *   de2000.png       after a fit: the CIEDE2000 between the texel's colour
 *                    and the family's albedo at its parameters, q / 1000
 *                    (16-bit; de2000.exr with exr)
 *   status.png       after a fit: 8-bit, 0 matched, 255 unmatched (the
 *                    family's closest colour is further than the fit's
 *                    max_de), 128 not fitted (transparent or masked out)
 * Written in DIR.staging and renamed into place. */
#ifndef SKINBAKE_MAPSET_H
#define SKINBAKE_MAPSET_H
#include "family/family.h"

#define MAPS_FORMAT_VERSION 1

enum { MAPS_MATCHED = 0, MAPS_UNMATCHED = 255, MAPS_NOT_FITTED = 128 };

struct maps_param {
	char key[64];		/* the family axis' preset key */
	char unit[16];
	double key_lo, key_hi;	/* the key's whole range: the PNG encoding */
	double fam_lo, fam_hi;	/* the family's range of the key */
	float *v;		/* [w * h] values in the key's unit */
};

struct mapset {
	int w, h;		/* texels */
	int n;			/* parameter maps, one per family axis, in axis order */
	struct maps_param p[FAMILY_MAX_AXES];
	float *de2000;		/* [w * h] or NULL */
	unsigned char *status;	/* [w * h] MAPS_* or NULL */
	char *family_dir;	/* the family, as given */
	char *family_preset;
	char *fit;		/* the fit's summary, a JSON object as text, or NULL */
	int n_history;
	char **history;		/* commands that made and edited the maps */
	int exr;		/* write float EXR maps instead of 16-bit PNG */
};

/* Maps of size w x h for the axes of f, every texel at value x[a] (NULL:
 * the middle of each axis in its interpolation coordinate). */
struct mapset *mapset_new(const struct family *f, int w, int h, const double *x);
void mapset_free(struct mapset *m);	/* NULL is a no-op */
void mapset_add_history(struct mapset *m, const char *command);
/* "skinbake maps ACTION ARGS..." (argv[1] on), for the history.  Caller frees. */
char *mapset_command_line(const char *action, int argc, char **argv);
/* The index of the map of KEY, or -1. */
int mapset_find(const struct mapset *m, const char *key);

/* Write DIR (absent, empty, or earlier maps, which are replaced); -1 and
 * *cause. */
int mapset_write(const char *dir, const struct mapset *m, char **cause);
/* The same directory written a band of rows at a time (maps fit on
 * textures too large to hold whole): begin takes m's head (size, maps'
 * keys and ranges, exr; no values), fit whether de2000 and status follow,
 * threads the files encoded at once; rows in order, v[a] the rows of map
 * a; end writes maps.json (m's fit and history) and renames the directory
 * into place.  Byte for byte what mapset_write writes for the whole maps.
 * A failing call returns -1 (NULL) and *cause, leaves no output and frees
 * the writer; mapset_writer_abort drops a writer that has not failed. */
struct mapset_writer;
struct mapset_writer *mapset_writer_begin(const char *dir, const struct mapset *m, int fit,
    int threads,
    char **cause);
int mapset_writer_rows(struct mapset_writer *wr, int nrows, const float *const *v,
    const float *de2000,
    const unsigned char *status, char **cause);
int mapset_writer_end(struct mapset_writer *wr, const struct mapset *m, char **cause);
void mapset_writer_abort(struct mapset_writer *wr);	/* NULL is a no-op */
/* A maps directory, for base/outdir.h: maps.json of format "skinbake-maps"
 * and its images. */
extern const struct outdir_kind mapset_outdir_kind;
/* Check DIR can take maps (as family_check_out); -1 and *cause. */
int mapset_check_out(const char *dir, char **cause);
/* Read DIR; NULL and *cause naming the file, field, value and what was
 * expected when it is missing, corrupt, of another format version, or a
 * map's size differs from maps.json. */
struct mapset *mapset_read(const char *dir, char **cause);
/* The size and number of maps that maps.json of DIR states (its head
 * checked as by mapset_read, no image read), for a budget check before
 * reading; -1 and *cause. */
int mapset_read_size(const char *dir, int *w, int *h, int *n, char **cause);

/* Estimated needs of maps new, edit and render-albedo (their budget checks,
 * as MAPS_FIT_MEM_* for fit): peak memory measured with a 2-map family at
 * 1024^2 and 2048^2 texels: new 14 (PNG) / 16 (EXR) bytes per texel, edit
 * with an 8-bit mask 18 / 22, render-albedo 26 (PNG) / 46 (EXR with
 * --radius), each over about 16 MB.  Estimates: per map 8 bytes (its values
 * and write buffer); new 4 more, edit 8 (its marks, the fit's extra maps)
 * and 16 with a mask (up to 4 float channels), render-albedo 24 (the albedo
 * and its write buffer) and 24 with --radius; over 32 MB. */
#define MAPS_MEM_PER_TEXEL_MAP 8.0
#define MAPS_NEW_MEM_PER_TEXEL 4.0
#define MAPS_EDIT_MEM_PER_TEXEL 8.0
#define MAPS_MASK_MEM_PER_TEXEL 16.0
#define MAPS_RENDER_MEM_PER_TEXEL 24.0
#define MAPS_MEM_FIXED 32e6
/* Whether the maps fit family f: the same keys in the same order and
 * every value within the family's range; -1 and *cause naming the map
 * file, the texel, the value and the range otherwise. */
int mapset_check_family(const struct mapset *m, const char *dir, const struct family *f,
    char **cause);
#endif
