/* family_pack: one member's bake result (bake.h) as a flat array of
 * doubles: what the MPI gather of a family bake sends (through the bake's
 * allreduce hook) and what the family checkpoint keeps per finished member.
 * v[0] is the status (1: baked); the methods are codes over engine/solvers.h
 * (the table's methods as a bit mask, each entry's method as 1 + index). */
#ifndef SKINBAKE_FAMILY_PACK_H
#define SKINBAKE_FAMILY_PACK_H
#include <stddef.h>

#include "bake/bake.h"

/* Room for the methods' joined name ("ad+mc") [characters]. */
#define FAMILY_SOLVER_NAME_MAX 8

/* Doubles of one member's record for spec s. */
size_t family_pack_len(const struct bake_spec *s);
/* r into v[family_pack_len(s)]. */
void family_pack(const struct bake_spec *s, const struct bake_result *r, double *v);
/* The result back from v (caller frees with bake_result_free), its
 * methods' name into solver[FAMILY_SOLVER_NAME_MAX + 1] (r->solver points
 * there); the specular stacks as bake_run makes them, from s's slabs. */
void family_unpack(const struct bake_spec *s, const double *v, char *solver, struct bake_result *r);
#endif
