/* sss_family: a renderer's fitted subsurface closure (sss_fit.h) at any
 * point of a family of bakes, from the fits of its members (each fitted to
 * its own Rd(r)): per axis linear in the axis' interpolation coordinate t
 * between the two neighbouring nodes (multilinear over the axes, as
 * POV-Ray's blend maps and the Blender importer's sub-grid blend), the
 * colour and the powers linearly, the lengths and mean radii as their log.
 * What a texel between members gets (docs/maps.md, "Translucent"). */
#ifndef SKINBAKE_SSS_FAMILY_H
#define SKINBAKE_SSS_FAMILY_H
#include "export/source_family.h"
#include "export/sss_fit.h"

/* The fit at parameters x[n_axes] (each clamped to its axis) into *out:
 * fits[m] is member m's fit; only the members with a weight above 0 are
 * read (the others may be NULL).  out->table is the members' table. */
void sss_fit_family_at(const struct brdf_family *f, const struct sss_fit *const *fits,
    const double *x, struct sss_fit *out);

/* The node interval [*i0, *i1] of axis a that the values v[n] reach (the
 * members sss_fit_family_at reads for them, per axis). */
void sss_family_reach(const struct brdf_family *f, int a, const float *v, size_t n, int *i0,
    int *i1);
#endif
