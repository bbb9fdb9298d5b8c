/* relief_ranges: the measured ranges of relief statistics per body site
 * (data/relief_sites.tsv, installed in the package data directory; every
 * row cites its source) and the comparison of a generated map's statistics
 * with them, for `skinbake texture --stats`.  A value outside its range is
 * reported, not refused: the ranges describe populations, a tile is one
 * sample. */
#ifndef SKINBAKE_RELIEF_RANGES_H
#define SKINBAKE_RELIEF_RANGES_H

#include "geom/relief_stats.h"

struct relief_range {
	char site[32];	/* body site as in sites.c */
	char stat[32];	/* statistic key, e.g. "furrow_depth_um" */
	double lo, hi;	/* measured range in the key's unit */
	char source[160];	/* short citation */
};

struct relief_ranges {
	int n;
	struct relief_range *row;
};

/* The range table: $SKINBAKE_DATADIR/relief_sites.tsv, else the installed
 * one; NULL and *cause (caller frees) when neither is readable or a row is
 * malformed (file, line, what is wrong). */
struct relief_ranges *relief_ranges_load(char **cause);
void relief_ranges_free(struct relief_ranges *rr);	/* NULL is a no-op */
/* The row of SITE and STAT, or NULL. */
const struct relief_range *relief_ranges_find(const struct relief_ranges *rr, const char *site,
    const char *stat);

/* The table (relief_ranges_load), then one line per statistic: key,
 * value, and "in [lo, hi] (source)", "OUT OF [lo, hi] (source)" or "no
 * sourced range"; a first line "# no range table: CAUSE" when the table
 * cannot be read.  *outside receives the number of values outside their
 * range, or -1 without a table (nothing was compared).  Caller frees. */
char *relief_ranges_report(const struct relief_stats *st, const char *site, int *outside);
#endif
