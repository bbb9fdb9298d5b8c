/* edit: tanning, flushing, pallor and the like as edits of the physical
 * maps (`skinbake maps edit`): per map scale, add or set, blended by a mask
 * (new = old + w (edited - old), w the mask's grey in [0, 1]), and clamped
 * to the family's range, counting the texels clamped. */
#ifndef SKINBAKE_EDIT_H
#define SKINBAKE_EDIT_H
#include "maps/image.h"
#include "maps/mapset.h"

enum maps_op_kind { MAPS_SCALE, MAPS_ADD, MAPS_SET };

/* An edit as given (--scale, --add, --set KEY=VALUE), its key not yet looked up. */
struct maps_edit_arg {
	enum maps_op_kind kind;
	char key[64];		/* a map's preset key */
	double value;		/* factor, addend or value (key's unit) */
};

struct maps_op {
	enum maps_op_kind kind;
	int param;		/* map index in the mapset */
	double value;		/* factor, addend or value (key's unit) */
};

/* Apply ops in order; mask (NULL: weight 1 everywhere) must have m's size;
 * invert uses 1 - w.  clamped[a] counts the texels of map a held at the
 * family's range.  -1 and *cause when the mask's size differs. */
int maps_edit(struct mapset *m, const struct maps_op *ops, int n_ops, const struct image *mask, int invert,
    long clamped[FAMILY_MAX_AXES], char **cause);
/* The edits args[n] as operations on m: each key one of m's maps, each set
 * value within the family's range; -1 and *cause ("KEY: not one of the maps
 * (...)", "--set KEY = V is outside the family's range [LO, HI]"). */
int maps_ops_resolve(const struct mapset *m, const struct maps_edit_arg *args, int n, struct maps_op *ops,
    char **cause);
#endif
