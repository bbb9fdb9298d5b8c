/* cmd_bake_family: `skinbake bake --vary KEY=...`, the family bake (one
 * preset varied over up to three numeric keys; family/family.h).  cmd_bake.c
 * declares the option and hands over to bake_family_run after it has read
 * the preset. */
#ifndef SKINBAKE_CMD_BAKE_FAMILY_H
#define SKINBAKE_CMD_BAKE_FAMILY_H
#include "bake/bake.h"
#include "family/family.h"
#include "cli/opt.h"
#include "skin/tissue.h"

/* The --vary options given. */
struct bake_vary {
	int n;
	struct family_axis axis[FAMILY_MAX_AXES];
};

/* --vary KEY=LO:HI:N[:lin|log|de] or KEY=V1,V2,... (OPT_CUSTOM callback). */
int bake_vary_parse(struct opt_ctx *x, const struct opt *o, const char *v);
#define BAKE_VARY_HELP "vary a numeric preset key over the family's members: KEY=LO:HI:N[:SPACING] with SPACING " \
	"de (default: equal CIEDE2000 steps of the albedo, from a 17-point pilot), log or lin, or KEY=V1,V2,... " \
	"(ascending values); N in [2, 64]; up to 3 axes, at most 4096 members; writes a family directory " \
	"(docs/maps.md)"
/* The family bake of preset p (label names it) with the bake settings in
 * s; writes OUT.  Returns the exit status. */
int bake_family_run(const struct bake_spec *s, const struct skin_params *p, const char *label, const char *out,
    const struct bake_vary *vary, int quiet, const char *cmdline);
#endif
