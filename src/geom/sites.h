/* sites: named parameter sets for skin micro-relief at body sites (face,
 * cheek, forehead, nose, hand, forearm, back), the table of every texture
 * parameter with its user unit, range and help, and the [texture] section
 * of INI preset files (libinih).  Values with their dermatology sources are
 * in sites.c and docs/texture.md. */
#ifndef SKINBAKE_SITES_H
#define SKINBAKE_SITES_H
#include <stddef.h>
#include <stdint.h>

#include "geom/relief.h"

#define SITES_NAME_MAX 32

struct texture_config {
	char site[SITES_NAME_MAX];	/* site the values started from, or "custom" */
	long size;	/* output edge [px] */
	uint64_t seed;	/* random seed [1] */
	struct relief_params relief;	/* geometry [cm, rad] */
	int with_stats;	/* 1: measure the map (relief_stats) into manifest.json "stats" */
	const char *direction_map;	/* path of the direction map in relief.direction, or NULL */
};

enum sites_type { SITES_REAL, SITES_LONG, SITES_SEED, SITES_INT };

/* One user-settable parameter.  The same key is the CLI option (--key) and,
 * with '-' written as '_', the INI key. */
struct texture_param {
	const char *key;	/* e.g. "pore-depth" */
	const char *unit;	/* unit shown to users, e.g. "um"; "1" for pure numbers */
	double scale;	/* internal value = user value * scale */
	double lo, hi;	/* allowed range in user units, inclusive */
	enum sites_type type;
	size_t offset;	/* of the field in struct texture_config */
	const char *help;	/* one line */
};

/* The parameter table; *n receives its length. */
const struct texture_param *sites_params(int *n);
const struct texture_param *sites_param_find(const char *key);

int sites_count(void);
const char *sites_name(int i);
const char *sites_summary(int i);
/* Fill cfg with the values of site NAME (also size 1024 and seed 1); -1 and
 * *cause listing the known sites if there is none of that name. */
int sites_load(const char *name, struct texture_config *cfg, char **cause);
/* Parse VALUE for parameter P and store it; -1 and *cause of the form
 * "LABEL = VALUE is out of range [lo, hi] unit" when it is not a number or
 * outside the range.  LABEL names the option or key in the message. */
int sites_set(struct texture_config *cfg, const struct texture_param *p, const char *label,
    const char *value, char **cause);
/* The value of P in user units. */
double sites_get(const struct texture_config *cfg, const struct texture_param *p);
/* Apply the [texture] section of the INI file PATH: an optional
 * `site = NAME` first resets cfg to that site (wherever it appears in the
 * section), then every other key overrides one parameter.  Other sections
 * are ignored; unknown keys in [texture] are errors.  -1 and *cause as
 * "PATH:LINE: message" on failure; cfg is then unspecified. */
int sites_read_ini(const char *path, struct texture_config *cfg, char **cause);
/* cfg as a [texture] section that sites_read_ini reads back to the same
 * values: the site, then every parameter (%.17g, in user units).  Caller
 * frees. */
char *sites_ini_text(const struct texture_config *cfg);
#endif
