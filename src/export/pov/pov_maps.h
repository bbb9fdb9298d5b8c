/* pov_maps: a skin whose parameters vary per texel, a family of bakes
 * (export/source_family.h) plus a maps directory (maps/mapset.h), as one POV-Ray
 * pigment.  Each member the maps reach gets its own lit table
 * (littable.h); the pigment blends them by the maps:
 *
 *   pigment { [uv_mapping] image_pattern { png "BASE_map0.png" gamma 1.0 }
 *     pigment_map { [t_0 <inner over axis 1, or member (0)>] ... }
 *     [scale/translate: planar projection of the map over the skin's x-y box] }
 *
 * The map images hold the axis coordinate t in [0, 1] over the family's
 * range (log of the value for log axes, as the family interpolates), 16
 * bits; a pigment_map entry sits at each node's t.  POV-Ray blends the
 * member tables linearly in t between neighbouring nodes (the family's own
 * interpolation is a 4-point Lagrange stencil of log albedo: the two agree
 * at the nodes and differ between them by the curvature, see docs/maps.md).
 * Measured (/tmp experiments, docs/maps.md): image_pattern with `gamma 1.0`
 * reads 16-bit values linearly; the outer pigment's transform reaches the
 * nested pigments, so only the outer one carries it. */
#ifndef SKINBAKE_POV_MAPS_H
#define SKINBAKE_POV_MAPS_H
#include <stdio.h>

#include "export/pov/littable.h"
#include "export/pov/povsss.h"
#include "export/source_family.h"
#include "maps/mapset.h"

struct pov_maps {
	struct brdf_family *fam;	/* with its member tables */
	struct mapset *maps;
	struct brdf_source **src;	/* [n_members], NULL for members the maps do not reach */
	int lo_idx[FAMILY_MAX_AXES];	/* per axis the first and last node the maps reach */
	int hi_idx[FAMILY_MAX_AXES];
	int ref;			/* the member at the maps' median node: stand-ins,
					 * strategy */
	char *png[FAMILY_MAX_AXES];	/* coordinate map file names inside the output directory */
	struct pov_sss *sss;		/* [n_members] translucent: each member reached fitted
					 * (povsss.h), else NULL */
	char *sss_exr;			/* translucent: the per-texel parameters' file name */
};

/* Read family FAMILY_DIR and maps MAPS_DIR and check that they fit each
 * other (mapset_check_family); the map files will be BASE_SKIN_KEY.png.
 * NULL and *cause (caller frees) on bad input. */
struct pov_maps *pov_maps_open(const char *family_dir, const char *maps_dir, const char *base,
    const char *skin, char **cause);
void pov_maps_free(struct pov_maps *pm);	/* NULL is a no-op */
/* Translucent (docs/maps.md, docs/translucency.md): POV-Ray's closure
 * fitted to each member's Rd(r) the maps reach; from then on
 * pov_maps_brdf gives each member's remainder.  *ior becomes the
 * calibration's.  -1 and *cause (a member without a radial profile). */
int pov_maps_sss_setup(struct pov_maps *pm, double *ior, char **cause);
/* The per-texel closure parameters, interpolated between the members the
 * way POV-Ray blends them (multilinear in the axis coordinates t between
 * the neighbouring nodes; the colour linearly, the length as its log):
 * colour[3] [-] and length_mm[3] at the axis values v[n_axes]. */
void pov_maps_sss_at(const struct pov_maps *pm, const double *v, double colour[3],
    double length_mm[3]);
/* The BRDF of member m for the table writers (m reached by the maps). */
struct pov_brdf pov_maps_brdf(const struct pov_maps *pm, int m);
/* Write the coordinate maps into OUTDIR, and when translucent the per-texel
 * parameters (pov_maps_sss_at) as float OpenEXR BASE_SKIN_sss.exr, channels
 * colour.R/G/B [-] and length_mm.R/G/B [mm]; -1 and *cause. */
int pov_maps_write_images(const struct pov_maps *pm, const char *outdir, char **cause);
/* Translucent, after the members' remainder tables (pov_maps_write_key
 * named SKIN_<skin>_Remainder) and SKIN_<skin>_Finish: per member reached
 * `SKIN_<skin>_M<m>_Subsurface` (povsss_write) and `..._Layered` (it under
 * its remainder, as povsss.h layers one bake), and `SKIN_<skin>_Translucent`,
 * a texture_map blending the layered members by the maps as the lit tables
 * are (POV-Ray cannot layer over a patterned texture; a texture_map of
 * layered textures renders their blend: measured 0.3-1 % from the mean of
 * the single renders). */
void pov_maps_write_sss(FILE *fp, const char *skin, const struct pov_maps *pm, int reflection,
    const double lo[3], const double hi[3], int uv);
/* `#declare NAME_M<m> = pigment {...}` per member reached (littable_write_key
 * with light l and view v over [lo, hi]) and `#declare NAME = pigment {...}`
 * blending them.  uv: map by the mesh's UVs; else planar along z over the
 * box's x-y extent (row 0 of the map at hi[1]).  Returns the gamma nodes
 * used (as littable_write_key). */
int pov_maps_write_key(FILE *fp, const char *name, const struct pov_maps *pm,
    const struct pov_light *l, const struct pov_view *v, const double lo[3], const double hi[3],
    int n_theta, int n_gamma, int uv);
/* The same for a part of each member's bake (povsplit.h): part 1 the
 * diffuse table, 2 the surface specular with GGX alpha spec_alpha (one
 * table when every member's specular is the same, as a family varying
 * only absorbers has). */
int pov_maps_write_part(FILE *fp, const char *name, const struct pov_maps *pm, int part,
    double spec_alpha, const struct pov_light *l, const struct pov_view *v, const double lo[3],
    const double hi[3], int n_theta, int n_gamma, int uv);
/* `#declare NAME_M<m> = pigment { aoi ... }` per member reached, its
 * directional-hemispherical albedo a(theta_o) (the fill, povinc.c), and
 * NAME blending them by the maps; with bounce, a(theta_o) times the
 * member's white-sky albedo instead (povsplit_bounce_curve). */
void pov_maps_write_fill(FILE *fp, const char *name, const struct pov_maps *pm, int bounce,
    const double lo[3], const double hi[3], int uv);
#endif
