/* sss_tt: the total transmittance Tt of a bake's layer stack cut to a
 * thickness, for the exporters' back light through thin parts (export/pov
 * povback, export/blender blender_sss_thick). */
#ifndef SKINBAKE_SSS_TT_H
#define SKINBAKE_SSS_TT_H

#include "bake/bakefile.h"

/* Tt into TT[k] (linear RGB through B's rgb_from_wl) of B's stack cut to
 * D_MM[k] [mm], k < N: the deeper layers shortened, the last extended to
 * fill, turned over so that light enters the deepest layer, smooth
 * boundaries, normal incidence, adding-doubling to 1e-3 without its error
 * estimate (the totals only).  -1 and *CAUSE when B has no stack. */
int sss_stack_tt(const struct bake *b, const double *d_mm, int n, double (*tt)[3], char **cause);

#endif
