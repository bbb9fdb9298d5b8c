/* povback: the back light through thin parts of translucent meshes
 * (issue 27; docs/translucency.md, Back light).  POV-Ray's subsurface
 * closure, fitted to the bake's reflection profile Rd(r), lights a slab from
 * its lit back face with the half-space dipole, so it lets through about
 * POVBACK_KAPPA times its own reflected power beyond the thickness d
 * (measured with scripts/sss_profile.py --back), well under the layered
 * stack's transmittance Tt(d) (`paper`: 0.39/0.25/0.08 of Tt, R/G/B).  The
 * exporter adds the difference where the mesh is thin:
 *
 *   - per vertex the local thickness d: a ray from the vertex along the
 *     inward normal to the mesh's other side (its first hit);
 *   - the irradiance E of the scene's lights on that other side (the hit
 *     triangle's interpolated normal; shadowed by the mesh itself, other
 *     objects are no occluders);
 *   - the transmitted exitance T(d) E, T = max(0, Tt(d) - KAPPA G(d)) per
 *     channel, Tt the bake's stack cut to d (the deeper layers shortened, the
 *     last extended, light entering the deepest layer; adding-doubling per
 *     wavelength into linear sRGB as the bake's colours), G the closure's
 *     power beyond d (export/sss_fit.h), leaving Lambertian: a POV-Ray pixel
 *     (pi x radiance) of T E.
 *
 * It is the emission of a copy of the mesh POVBACK_LIFT_PX pixels outside
 * it (at least 2e-4 units), only its triangles with a lit vertex, clear but
 * for that: a mesh2 texture per triangle (its vertices' mean: write_copy),
 * pigment rgbt <1000 T E, 0.999>, finish emission 1, so that the skin
 * under it shows at 0.999 and the copy adds T E; it casts no shadow. */
#ifndef SKINBAKE_POVBACK_H
#define SKINBAKE_POVBACK_H
#include <stdio.h>

#include "bake/bakedir.h"
#include "export/sss_fit.h"
#include "scene/scene.h"

#define POVBACK_N 12			/* thickness nodes */
#define POVBACK_KAPPA 1.35		/* the closure's transmission / its power beyond d */
#define POVBACK_CLEAR 0.999		/* the copy's transmit */

/* The thickness nodes [mm], ascending; beyond the last nothing is added. */
extern const double povback_d_mm[POVBACK_N];

struct pov_back {
	int on;				/* 0: no back-light term (*why says why) */
	char why[160];			/* the reason when off */
	double tt[POVBACK_N][3];	/* the stack's Tt per node and R, G, B [-] */
	double closure[POVBACK_N][3];	/* KAPPA x the closure's power beyond d [-] */
};

/* The table of bake B and closure fit F; pb->on is 0 (with pb->why) when
 * B's manifest has no layers or the solver fails. */
void povback_setup(struct pov_back *pb, const struct bake *b, const struct sss_fit *f);

/* T = max(0, Tt - closure) of channel C at D_MM (ln T linear in d between
 * the nodes, the first node's below it, 0 beyond the last) [-]. */
double povback_extra(const struct pov_back *pb, int c, double d_mm);

struct povback_stats {
	int n_vertices;			/* vertices with a thickness (their ray hit the mesh) */
	int n_lit;			/* of them lit through (T E > 0) */
	int n_triangles;		/* triangles of the copy */
	double d_min_mm, d_median_mm;	/* thickness over the hit vertices [mm] */
};

/* The copy of mesh object O (scene S, lights of S) with back table PB:
 * `mesh2 { ... no_shadow }` or nothing when no vertex is lit through.
 * LIFT is how far outside the mesh it sits [units]. */
void povback_write(FILE *fp, const struct scene *s, const struct scene_object *o,
    const struct pov_back *pb, double lift, struct povback_stats *st);
#endif
