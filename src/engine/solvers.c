/* solvers: the engine's methods in one table (solvers.h). */
#include "config.h"

#include "engine/solvers.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/util.h"
#include "engine/ad_solver.h"
#include "engine/mc.h"

const struct solver_ops *const solvers[] = {
	&mc_solver,
	&ad_solver,
	NULL,
};

/* `bake --solver auto`: this method, and its fallback where it refuses. */
const char *const solvers_auto = "ad";

int solvers_index(const char *name)
{
	if (name == NULL)
		return -1;
	for (int i = 0; solvers[i] != NULL; i++)
		if (strcmp(solvers[i]->name, name) == 0)
			return i;
	return -1;
}

const struct solver_ops *solvers_find(const char *name)
{
	int i = solvers_index(name);
	if (i < 0)
		return NULL;
	return solvers[i];
}

const char *solvers_choices(void)
{
	static char buf[128];
	if (buf[0] == '\0')
		for (int i = 0; solvers[i] != NULL; i++) {
			size_t n = strlen(buf);
			snprintf(buf + n, sizeof buf - n, "%s%s", i ? "|" : "", solvers[i]->name);
		}
	return buf;
}

/* The names of A and B ('+'-joined lists) as a bit mask over solvers[]. */
static unsigned mask_of(const char *joined, unsigned mask)
{
	char buf[SOLVERS_JOINED_MAX + 1];
	snprintf(buf, sizeof buf, "%s", joined);
	char *save = NULL;
	for (char *t = strtok_r(buf, "+", &save); t != NULL; t = strtok_r(NULL, "+", &save)) {
		int i = solvers_index(t);
		CHECK(i >= 0);
		mask |= 1u << i;
	}
	return mask;
}

static int by_name(const void *a, const void *b)
{
	return strcmp(*(const char *const *)a, *(const char *const *)b);
}

const char *solvers_union(const char *a, const char *b)
{
	/* One text per mask, made once: up to 2^SOLVERS_MAX combinations. */
	static char *text[1u << SOLVERS_MAX];
	unsigned mask = mask_of(b, mask_of(a, 0));
	CHECK(mask < (1u << SOLVERS_MAX));
	if (text[mask] == NULL) {
		const char *names[SOLVERS_MAX];
		int n = 0;
		for (int i = 0; solvers[i] != NULL; i++)
			if (mask & (1u << i))
				names[n++] = solvers[i]->name;
		qsort(names, (size_t)n, sizeof names[0], by_name);
		char buf[SOLVERS_JOINED_MAX + 1] = "";
		for (int i = 0; i < n; i++) {
			size_t len = strlen(buf);
			snprintf(buf + len, sizeof buf - len, "%s%s", i ? "+" : "", names[i]);
		}
		text[mask] = xstrdup(buf);
	}
	return text[mask];
}

const char *solvers_reading(const char *option)
{
	static char who[128];
	who[0] = '\0';
	for (int i = 0; solvers[i] != NULL; i++) {
		int ignores = 0;
		for (const char *const *o = solvers[i]->sim_ignores; o && *o; o++)
			ignores |= strcmp(*o, option) == 0;
		size_t n = strlen(who);
		const char *sep = n ? " or " : "";
		if (!ignores)
			snprintf(who + n, sizeof who - n, "%s%s", sep, solvers[i]->name);
	}
	return who;
}
