/* preset: named skin parameter sets in an INI format read through libinih,
 * both from files and from the built-in presets (held as INI text, so one
 * parser serves both).  Every key, its unit, default and range: see
 * docs/presets.md or `skinbake preset keys`.  Errors name file:line, the key,
 * the value and the allowed range. */
#ifndef SKINBAKE_PRESET_H
#define SKINBAKE_PRESET_H
#include <stdio.h>
#include "skin/tissue.h"

/* struct skin_params is defined in tissue.h. */

/* A built-in preset by name; NULL + *cause (listing the names) if unknown.
 * Caller frees with preset_free. */
struct skin_params *preset_load_builtin(const char *name, char **cause);
/* A preset file; NULL + *cause ("FILE:LINE: key = value: problem (range)",
 * "cannot open FILE: ...", "FILE:LINE: line N is longer than 199 characters").
 * Caller frees with preset_free. */
struct skin_params *preset_load_file(const char *path, char **cause);
/* Parse INI text; origin names it in messages (e.g. a file name). */
struct skin_params *preset_load_string(const char *text, const char *origin, char **cause);
void preset_free(struct skin_params *p);	/* NULL is a no-op */

/* The built-in presets, in listing order. */
int preset_count(void);
const char *preset_name(int i);
const char *preset_summary(int i);
/* The built-in preset's INI text (a starting point for own presets). */
const char *preset_builtin_text(int i);
/* Index of a built-in preset or -1. */
int preset_find(const char *name);

/* Default wavelengths of this preset [nm], ascending (paper: 470, 550, 656;
 * physiological: 400..700 step 20): copies at most max of them into wl_nm and
 * returns the number copied.  p->n_wl is the full count (up to SKIN_MAX_WL),
 * so a caller with max < SKIN_MAX_WL should reject p->n_wl > max. */
int preset_default_wavelengths(const struct skin_params *p, double *wl_nm, int max);
/* Index of the top surface for the analytic specular: the sebum's n if there
 * is sebum, else the epidermis n at 550 nm. */
double preset_surface_ior(const struct skin_params *p);
/* GGX alpha of the top surface: roughness_sebum with sebum, else roughness_skin. */
double preset_surface_roughness(const struct skin_params *p);
const char *preset_get_name(const struct skin_params *p);

/* The fully resolved parameters as preset INI text that loads back to the
 * same values (for metadata and `preset show --ini`).  Caller frees. */
char *preset_to_ini(const struct skin_params *p);
/* Parse a wavelength list in the preset syntax ("400:700:10, 720"; ascending,
 * each in [380, 780] nm) into wl[SKIN_MAX_WL]; returns the count, or -1 with
 * *cause (the problem only; the caller names the option). */
int preset_parse_wavelengths(const char *s, double *wl, char **cause);
/* Numeric keys ("epidermis.melanin", "dermis.blood", ...): those whose value
 * is a number in a range (thicknesses, indices and anisotropies given as
 * numbers included), which a family bake may vary.  preset_number_key gives
 * the key's range and unit (unit "" for pure numbers); -1 and *cause naming
 * the key and listing the numeric keys when KEY is not one. */
int preset_number_key(const char *key, double *lo, double *hi, const char **unit, char **cause);
/* Set numeric key KEY of p to v, range-checked; -1 and *cause ("KEY = V:
 * out of range [LO, HI] UNIT") otherwise. */
int preset_set_number(struct skin_params *p, const char *key, double v, char **cause);
/* The value of numeric key KEY in p (NAN when it is ding2006 or
 * vangemert1989, INFINITY for a semi-infinite layer); -1 if KEY is not one. */
int preset_get_number(const struct skin_params *p, const char *key, double *v);
/* Print every key: section, name, unit, default, range, meaning. */
void preset_print_keys(FILE *fp);
#endif
