/* budget: memory and disk needs checked before work (budget.h). */
#include "config.h"
#include "base/budget.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/statvfs.h>

#include "base/util.h"

double budget_memory_available(void)
{
	FILE *f = fopen("/proc/meminfo", "r");
	if (f == NULL)
		return -1;
	char line[256];
	double kb = -1;
	while (fgets(line, sizeof line, f) != NULL)
		if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1)
			break;
	fclose(f);
	return kb < 0 ? -1 : kb * 1024.0;
}

double budget_disk_available(const char *path)
{
	char *p = xstrdup(path);
	struct statvfs st;
	double r = -1;
	for (;;) {
		if (statvfs(p, &st) == 0) {
			r = (double)st.f_bavail * (double)st.f_frsize;
			break;
		}
		char *slash = strrchr(p, '/');
		if (slash == NULL) {
			if (strcmp(p, ".") != 0 && statvfs(".", &st) == 0)
				r = (double)st.f_bavail * (double)st.f_frsize;
			break;
		}
		if (slash == p) {
			if (statvfs("/", &st) == 0)
				r = (double)st.f_bavail * (double)st.f_frsize;
			break;
		}
		*slash = '\0';
	}
	free(p);
	return r;
}

static const char *gb(char *b, size_t n, double bytes)
{
	if (bytes >= 1e9)
		snprintf(b, n, "%.1f GB", bytes / 1e9);
	else
		snprintf(b, n, "%.0f MB", bytes / 1e6);
	return b;
}

int budget_check(const char *what, double mem, double disk, const char *out, const char *lower,
    char **cause)
{
	char a[32], b[32];
	double m = mem > 0 ? budget_memory_available() : -1;
	double d = disk > 0 && out ? budget_disk_available(out) : -1;
	if (m >= 0 && mem > m) {
		*cause = xasprintf("%s needs about %s of memory (estimated), %s are available; %s",
		    what, gb(a, sizeof a, mem), gb(b, sizeof b, m), lower);
		return -1;
	}
	if (d >= 0 && disk > d) {
		*cause = xasprintf("%s writes about %s (estimated), %s are free on the disk of %s; "
		    "%s", what, gb(a, sizeof a, disk), gb(b, sizeof b, d), out, lower);
		return -1;
	}
	return 0;
}
