/* solvers: the table of the engine's methods (struct solver_ops of
 * engine/solver.h), the one place they are listed.  A new method is its
 * file (engine/NAME.c with a struct solver_ops: its name, what it gives,
 * its settings from the knobs, its manifest block, its `simulate`) and one
 * line in solvers[] (solvers.c); its index there is its code in packed
 * results (family members, checkpoints), so lines are only ever added at
 * the end.  Nothing outside the methods' own files and this table names a
 * method (tests/check_solvers.sh). */
#ifndef SKINBAKE_SOLVERS_H
#define SKINBAKE_SOLVERS_H
#include "engine/solver.h"

#define SOLVERS_MAX 8		/* lines of solvers[] at most */
#define SOLVERS_JOINED_MAX 63	/* characters of a '+'-joined list of names */

/* Monte Carlo, adding-doubling, ...; NULL-terminated.  solvers[0] is the
 * method of results written before there was a choice (Monte Carlo). */
extern const struct solver_ops *const solvers[];
/* The method `bake --solver auto` runs first (its fallback where it refuses). */
extern const char *const solvers_auto;

/* The index in solvers[] of the method named NAME, or -1. */
int solvers_index(const char *name);
/* The method named NAME, or NULL. */
const struct solver_ops *solvers_find(const char *name);
/* The names joined by '|' in table order, as OPT_ENUM choices ("mc|ad"). */
const char *solvers_choices(void);
/* The methods of two '+'-joined lists of names (a bake's result.solver,
 * e.g. "ad" and "mc") as one such list in alphabetical order ("ad+mc");
 * the text is static. */
const char *solvers_union(const char *a, const char *b);
/* The methods whose `simulate` reads option NAME (not in their sim_ignores),
 * as "mc" or "mc or ad" (static text). */
const char *solvers_reading(const char *option);
#endif
