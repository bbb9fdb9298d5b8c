/* edit: masked scale, add and set of parameter maps, clamped to the
 * family's range (see edit.h). */
#include "config.h"
#include "maps/edit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

int maps_edit(struct mapset *m, const struct maps_op *ops, int n_ops, const struct image *mask, int invert,
    long clamped[FAMILY_MAX_AXES], char **cause)
{
	if (mask && (mask->w != m->w || mask->h != m->h)) {
		*cause = xasprintf("the mask is %d x %d texels, the maps %d x %d", mask->w, mask->h, m->w, m->h);
		return -1;
	}
	memset(clamped, 0, sizeof(long) * FAMILY_MAX_AXES);
	size_t n = (size_t)m->w * m->h;
	unsigned char *hit = xcalloc(n * FAMILY_MAX_AXES, 1);
	for (int k = 0; k < n_ops; k++) {
		struct maps_param *p = &m->p[ops[k].param];
		for (size_t i = 0; i < n; i++) {
			double w = mask ? fmin(1.0, fmax(0.0, image_get(mask, i, 0))) : 1.0;
			if (invert)
				w = 1.0 - w;
			double v = p->v[i], e = ops[k].kind == MAPS_SCALE ? v * ops[k].value
			    : ops[k].kind == MAPS_ADD ? v + ops[k].value : ops[k].value;
			/* A convex mix, exact at w = 0 and 1: `--set` to the range's end
			 * under a full mask gives the end itself, not one rounding beyond. */
			double nv = (1.0 - w) * v + w * e;
			/* Only a texel beyond the range by more than rounding counts as
			 * clamped (the message tells of a real edit limit). */
			double slack = 1e-9 * (p->fam_hi - p->fam_lo);
			if (nv < p->fam_lo - slack || nv > p->fam_hi + slack)
				hit[i * FAMILY_MAX_AXES + (size_t)ops[k].param] = 1;
			nv = fmin(fmax(nv, p->fam_lo), p->fam_hi);
			p->v[i] = (float)nv;
		}
	}
	for (size_t i = 0; i < n; i++)
		for (int a = 0; a < FAMILY_MAX_AXES; a++)
			clamped[a] += hit[i * FAMILY_MAX_AXES + (size_t)a];
	free(hit);
	/* The fit's error map describes the maps before the edit; its status
	 * (which texels are skin) still holds. */
	free(m->de2000);
	m->de2000 = NULL;
	return 0;
}

int maps_ops_resolve(const struct mapset *m, const struct maps_edit_arg *args, int n, struct maps_op *ops,
    char **cause)
{
	for (int k = 0; k < n; k++) {
		int a = mapset_find(m, args[k].key);
		if (a < 0) {
			char names[256] = "";
			for (int b = 0; b < m->n; b++)
				snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", b ? ", " : "", m->p[b].key);
			*cause = xasprintf("%s: not one of the maps (%s)", args[k].key, names);
			return -1;
		}
		if (args[k].kind == MAPS_SET && !(args[k].value >= m->p[a].fam_lo && args[k].value <= m->p[a].fam_hi))
			return *cause = xasprintf("--set %s = %g is outside the family's range [%g, %g]", args[k].key,
			    args[k].value, m->p[a].fam_lo, m->p[a].fam_hi), -1;
		ops[k] = (struct maps_op){ args[k].kind, a, args[k].value };
	}
	return 0;
}
