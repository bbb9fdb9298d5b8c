/* preset_keys: the keys of the preset format, for preset.c (the two files
 * are one module; skin/preset.h is its public face).  The table of every
 * key with its unit, default and range; setting one key's or one
 * [override.WL] key's value; the defaults; the wavelength list syntax (the
 * resolved INI text and the key listing are in preset_ini.c).  The
 * parse state is shared: preset.c drives libinih, these setters report into
 * it. */
#ifndef SKINBAKE_PRESET_KEYS_H
#define SKINBAKE_PRESET_KEYS_H
#include "io/inifile.h"
#include "skin/tissue.h"

#define PRESET_MAX_KEYS 64	/* room in struct preset_ctx; the table has fewer */
#define PRESET_MAX_BASE_DEPTH 4

/* The state of one parse. */
struct preset_ctx {
	const char *origin;	/* for messages: a path or "built-in preset NAME" */
	struct inifile in;	/* the reader: current line and its number */
	char *err;		/* first error, with origin:line */
	int err_line;
	struct skin_params *p;
	int depth;		/* base nesting */
	/* Built-in preset NAME as the base of this one, DEPTH levels down (the
	 * loader, preset.c, passes itself: the keys never call up into it). */
	struct skin_params *(*load_base)(const char *name, int depth, char **cause);
	int n_calls;		/* handler calls so far */
	int name_set, desc_set, wl_set;
	unsigned char seen[PRESET_MAX_KEYS];
	unsigned char *ov_seen;	/* [n_override][SKIN_N_LAYERS][number of override props] */
	char last_section[80], last_name[80];
	int last_line;
};

/* Record the first error as "origin:line: message". */
void preset_ctx_err(struct preset_ctx *c, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* What preset.c needs of key i (0 <= i < preset_key_count()). */
struct preset_key_info {
	const char *section, *name, *unit;
	double lo, hi;		/* range of a numeric key */
	int layer;		/* enum skin_layer_id, or -1 for a struct skin_params field */
	size_t off;		/* offset of the double in the layer or the params */
	int numeric;		/* a number (or thickness, index, anisotropy given as a
				 * number) */
};
void preset_key_info(int i, struct preset_key_info *out);
int preset_key_count(void);

/* The key table (preset_keys.c); its order is the order of the INI text
 * and of the listing (preset_ini.c). */
enum preset_key_kind {
	K_NUM,		/* a number in [lo, hi] */
	K_LEN,		/* a thickness in [lo, hi] or "inf" */
	K_IOR,		/* a number or "ding2006" */
	K_ANISO,	/* a number or "vangemert1989" */
	K_TEXT,		/* name or description */
	K_MODEL,	/* chromophores | tables */
	K_WL,		/* wavelength list */
	K_BASE,		/* start from a built-in preset */
	K_ROUGH		/* a rough-surface number in [lo, hi], left out of the
			 * resolved text when 0 */
};
struct preset_key {
	const char *section;
	const char *name;
	enum preset_key_kind kind;
	int layer;		/* enum skin_layer_id, or -1 for a struct skin_params field */
	size_t off;		/* field offset in the layer or the params */
	double lo, hi;		/* inclusive range */
	const char *unit;
	const char *dflt;	/* default, in the file syntax ("" = none) */
	const char *doc;
};
extern const struct preset_key preset_key_table[];
/* Keys of [override.WL] sections: LAYER.PROP. */
enum { OV_MUA, OV_MUS, OV_G, OV_N, OV_N_PROPS };
struct preset_ov_prop {
	const char *name;
	double lo, hi;
	const char *unit;
	const char *doc;
};
extern const struct preset_ov_prop preset_ov_props[OV_N_PROPS];

/* Index of key section.name in the table; -1 when the section has no such
 * key, -2 when there is no such section. */
int preset_key_find(const char *section, const char *name);
/* The keys of a section as "a, b, c" (caller frees). */
char *preset_key_names(const char *section);
/* Set key ki from its file text v; 0 or -1 (message in c). */
int preset_key_set(struct preset_ctx *c, int ki, const char *v);
/* Section header SECTION: a known section or override.WL with WL in range;
 * 0 or -1 (message in c). */
int preset_section_check(struct preset_ctx *c, const char *section);
/* [override.WL] LAYER.PROP = v; 0 or -1 (message in c). */
int preset_override_set(struct preset_ctx *c, const char *section, const char *name, const char *v);
/* Every key's default, through the setters. */
void preset_apply_defaults(struct skin_params *p);
/* Free what p owns and zero it (p itself stays). */
void preset_free_contents(struct skin_params *p);
/* "400:700:10, 720" -> ascending list in [380, 780] nm; -1 and *why. */
int preset_wavelengths_parse(const char *v, double *wl, int *n, char **why);
#endif
