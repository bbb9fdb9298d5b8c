/* solvers: the engine's methods in one table (solvers.h). */
#include "config.h"

#include "engine/solvers.h"

#include <stddef.h>
#include <string.h>

#include "engine/ad_solver.h"
#include "engine/mc.h"

const struct solver_ops *const solvers[] = {
	&mc_solver,
	&ad_solver,
	NULL,
};

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
