/* bake_opts: the options of `skinbake bake` that choose and tune the
 * transport solution (cmd_bake.c holds the rest): the method (--solver),
 * adding-doubling's accuracy (ad:), Monte Carlo's error target, budget,
 * estimator and seed (mc:), the Rd(r) grid and its error, the boundary
 * model. */
#ifndef SKINBAKE_BAKE_OPTS_H
#define SKINBAKE_BAKE_OPTS_H
#include <stdint.h>

#include "bake/bake.h"
#include "cli/opt.h"

/* Where the options put their values: the spec's fields, and the choices
 * that cmd_bake maps onto it after parsing. */
struct bake_opts {
	struct bake_spec *s;
	int solver;	/* row of bake_method_at() */
	int fresnel;	/* 0 exact, 1 schlick */
	int estimator;	/* 0 next-event estimation, 1 bins */
	uint64_t seed;
};

/* Write the transport options into o[0 ..] (14 of them, in the order
 * --help lists them), with destinations in b; returns their count. */
int bake_opts_transport(struct opt *o, struct bake_opts *b);
#endif
