/* preset_keys: the keys of the preset format, for preset.c (the two files
 * are one module; skin/preset.h is its public face).  The table of every
 * key with its unit, default and range; setting one key's or one
 * [override.WL] key's value; the defaults; the wavelength list syntax.  The
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
	int n_calls;		/* handler calls so far */
	int name_set, desc_set, wl_set;
	unsigned char seen[PRESET_MAX_KEYS];
	unsigned char *ov_seen;	/* [n_override][SKIN_N_LAYERS][number of override props] */
	char last_section[80], last_name[80];
	int last_line;
};

/* Record the first error as "origin:line: message". */
void preset_ctx_err(struct preset_ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Index of key section.name in the table; -1 when the section has no such
 * key, -2 when there is no such section. */
int preset_key_find(const char *section, const char *name);
/* The keys of a section as "a, b, c" (caller frees). */
char *preset_key_names(const char *section);
/* Set key ki from its file text v; 0 or -1 (message in c). */
int preset_key_set(struct preset_ctx *c, int ki, const char *v);
/* [override.WL] LAYER.PROP = v; 0 or -1 (message in c). */
int preset_override_set(struct preset_ctx *c, const char *section, const char *name, const char *v);
/* Every key's default, through the setters. */
void preset_apply_defaults(struct skin_params *p);
/* Free what p owns and zero it (p itself stays). */
void preset_free_contents(struct skin_params *p);
/* "400:700:10, 720" -> ascending list in [380, 780] nm; -1 and *why. */
int preset_wavelengths_parse(const char *v, double *wl, int *n, char **why);

/* In preset.c: built-in preset NAME as the base of another, depth levels down. */
struct skin_params *preset_load_base(const char *name, int depth, char **cause);
#endif
