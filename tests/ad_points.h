/* ad_points: the independent reference of the renderer tests at
 * silhouettes (issue 26).  A bake's BRDF, not from its table (eval, which
 * every exporter follows by construction) but from adding-doubling point
 * values of the bake's own layer stacks (the manifest's), solved at the
 * asked incidence angles, plus the bake's analytic specular, summed to
 * linear sRGB with the bake's weights.  Used by tests/pov_compare (expect
 * --ad) and tests/blender_brdf (--ad). */
#ifndef SKINBAKE_TESTS_AD_POINTS_H
#define SKINBAKE_TESTS_AD_POINTS_H
#include "bake/bakedir.h"

/* rgb[3 k + c] = the total BRDF [1/sr] at (ti[k], to[k], dphi[k]) [rad] of
 * the bake b read from dir, for k < n; 0 where ti[k] >= pi/2.  The angles
 * are solved AD_MAX_BEAMS at a time per wavelength, in the given order, at
 * adding-doubling's default tolerance; *n_solves (may be NULL) counts the
 * solves.  0, or -1 with *cause (caller frees). */
int ad_points_rgb(const char *dir, const struct bake *b, long n, const double *ti, const double *to,
    const double *dphi, double *rgb, long *n_solves, char **cause);
#endif
