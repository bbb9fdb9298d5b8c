/* solvers: the table of the engine's methods (struct solver_ops of
 * engine/solver.h), the one place they are listed.  A new method is its
 * file (engine/NAME.c with a struct solver_ops) and one line in solvers[]
 * (solvers.c); its index there is its code in packed results (family
 * members, checkpoints), so lines are only ever added at the end. */
#ifndef SKINBAKE_SOLVERS_H
#define SKINBAKE_SOLVERS_H
#include "engine/solver.h"

/* Monte Carlo, adding-doubling, ...; NULL-terminated. */
extern const struct solver_ops *const solvers[];

/* The index in solvers[] of the method named NAME, or -1. */
int solvers_index(const char *name);
/* The method named NAME, or NULL. */
const struct solver_ops *solvers_find(const char *name);
#endif
