/* povinc: BASE.inc, the include file of an export (part of the files
 * povfiles.h writes): lights (and, for per-light layers, each light with its
 * colour times the number of lights), finishes, lit-table pigments per
 * strategy, bump maps and the Lambert and Phong stand-ins. */
#ifndef SKINBAKE_POVINC_H
#define SKINBAKE_POVINC_H
#include <stdio.h>

#include "export/pov/povtypes.h"

void povinc_write(FILE *fp, const struct scene *s, const struct pov_skin *skins, const struct pov_options *o,
    enum scene_strategy st, int layered, struct pov_report *r);
#endif
