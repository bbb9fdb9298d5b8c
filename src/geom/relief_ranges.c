/* relief_ranges: read data/relief_sites.tsv and compare statistics with
 * its rows (format in the file's header and docs/texture.md). */
#include "config.h"

#include "geom/relief_ranges.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

/* One data row "site<TAB>stat<TAB>lo<TAB>hi<TAB>source"; -1 if malformed. */
static int parse_row(char *line, struct relief_range *r)
{
	char *f[5];
	int k = 0;
	for (char *s = line, *tab; k < 5 && s; s = tab ? tab + 1 : NULL) {
		tab = k < 4 ? strchr(s, '\t') : NULL;
		if (tab)
			*tab = '\0';
		f[k++] = s;
	}
	if (k != 5)
		return -1;
	f[4][strcspn(f[4], "\r\n")] = '\0';
	char *e1, *e2;
	r->lo = strtod(f[2], &e1);
	r->hi = strtod(f[3], &e2);
	if (*e1 || *e2 || !(r->lo <= r->hi) || strlen(f[0]) >= sizeof r->site ||
	    strlen(f[1]) >= sizeof r->stat)
		return -1;
	int known = 0;
	for (int i = 0; i < RELIEF_STATS_KEYS; i++)
		known |= strcmp(f[1], relief_stats_key(i)) == 0;
	if (!known)
		return -1;
	snprintf(r->site, sizeof r->site, "%s", f[0]);
	snprintf(r->stat, sizeof r->stat, "%s", f[1]);
	snprintf(r->source, sizeof r->source, "%.159s", f[4]);
	return 0;
}

struct relief_ranges *relief_ranges_load(char **cause)
{
	const char *env = getenv("SKINBAKE_DATADIR");
	char *path = env && *env ? xasprintf("%s/relief_sites.tsv", env)
	    : xasprintf("%s/relief_sites.tsv", PKGDATADIR);
	FILE *fp = fopen(path, "r");
	if (fp == NULL) {
		*cause = xasprintf("%s: %s", path, strerror(errno));
		free(path);
		return NULL;
	}
	struct relief_ranges *rr = xcalloc(1, sizeof *rr);
	char line[512];
	int lineno = 0, cap = 0;
	while (fgets(line, sizeof line, fp)) {
		lineno++;
		if (line[0] == '#' || line[strspn(line, " \t\r\n")] == '\0')
			continue;
		if (rr->n == cap) {
			cap = cap ? 2 * cap : 16;
			struct relief_range *grown = xcalloc((size_t)cap, sizeof *grown);
			if (rr->n)
				memcpy(grown, rr->row, sizeof *grown * (size_t)rr->n);
			free(rr->row);
			rr->row = grown;
		}
		if (parse_row(line, &rr->row[rr->n]) != 0) {
			*cause = xasprintf("%s:%d: expected site, a statistic key, lo <= hi and a "
			    "source, tab-separated", path, lineno);
			fclose(fp);
			free(path);
			relief_ranges_free(rr);
			return NULL;
		}
		rr->n++;
	}
	fclose(fp);
	free(path);
	return rr;
}

void relief_ranges_free(struct relief_ranges *rr)
{
	if (rr == NULL)
		return;
	free(rr->row);
	free(rr);
}

const struct relief_range *relief_ranges_find(const struct relief_ranges *rr, const char *site,
    const char *stat)
{
	for (int i = 0; rr && i < rr->n; i++) {
		if (strcmp(rr->row[i].site, site) == 0 && strcmp(rr->row[i].stat, stat) == 0)
			return &rr->row[i];
	}
	return NULL;
}

char *relief_ranges_report(const struct relief_stats *st, const char *site, int *outside)
{
	char *cause = NULL;
	struct relief_ranges *rr = relief_ranges_load(&cause);
	char *s = rr ? xasprintf("# %s: statistic, value, measured range\n", site)
		     : xasprintf("# no range table: %s (SKINBAKE_DATADIR names its directory, "
			 "e.g. the source tree's data/)\n", cause);
	free(cause);
	*outside = rr ? 0 : -1;
	for (int i = 0; i < RELIEF_STATS_KEYS; i++) {
		double v = relief_stats_value(st, i);
		const struct relief_range *r = relief_ranges_find(rr, site, relief_stats_key(i));
		char *t;
		if (r == NULL) {
			t = xasprintf("%s%-22s %10.4g  no sourced range\n", s, relief_stats_key(i),
			    v);
		} else {
			int in = v >= r->lo && v <= r->hi;
			*outside += !in;	/* r != NULL only with a table */
			t = xasprintf("%s%-22s %10.4g  %s [%g, %g] (%s)\n", s, relief_stats_key(i),
			    v, in ? "in" : "OUT OF", r->lo, r->hi, r->source);
		}
		free(s);
		s = t;
	}
	relief_ranges_free(rr);
	return s;
}
