/* blender_family: the image set of a family with parameter maps (`skinbake
 * export blender --family DIR --maps DIR`): the usual files (blender.h) of
 * the family at the middle of the maps' ranges, and per texel
 *
 *   albedo_map.exr      RGB: bihemispherical diffuse albedo (the members'
 *                       blended as family_albedo blends, cubic in log)
 *   sss_radius_map.exr  RGB: mean exit radius per R, G, B [m]
 *   family_coord.exr    RGB: the texel's position in the sub-grid below,
 *                       per axis in [0, K_a - 1] (0 for absent axes)
 *   family_lut.exr      the exact-mode atlas (brdf_lut.exr's layout) of
 *                       each sub-grid point, stacked: slice s holds rows
 *                       s * cos_nodes .. (s + 1) * cos_nodes - 1 from the
 *                       bottom (Blender v), s = i0 + K0 (i1 + K1 i2)
 *
 * The sub-grid spans each map's value range with K_a points uniform in the
 * axis' interpolation coordinate (one point when a map is constant); each
 * point's table is the family interpolated there (brdf_family_at).  The
 * importer blends the atlases of the texel's 2^k neighbouring points
 * multilinearly, so the exact mode follows the maps per texel; the
 * general mode takes albedo and radius from the maps.  manifest.json gets
 * a "family" section naming these files and the sub-grid. */
#ifndef SKINBAKE_BLENDER_FAMILY_H
#define SKINBAKE_BLENDER_FAMILY_H
#include "export/blender/blender.h"
#include "export/source_family.h"
#include "maps/mapset.h"

#define BLENDER_FAMILY_SUB_MIN 2
#define BLENDER_FAMILY_SUB_MAX 8

/* Export family f (tables loaded here) with maps m into DIR, sub points
 * per varying axis; detail_dir (NULL: flat) is a texture directory.
 * Translucent (blender_sss.h): Cycles' subsurface node of every calibrated
 * Blender fitted to each member the maps reach, per texel the fits
 * interpolated between them (export/sss_family.h) into
 * sss_colour_M.N.exr and sss_radius_M.N.exr, each sub-grid table the
 * remainder at its point's fits, and sss_extra_M.N.exr that version's
 * lambert_extra per sub-grid point (manifest translucent.versions[].maps).
 * -1 and *cause on bad input (before anything is written), -2 on an I/O
 * failure. */
int blender_family_export(struct brdf_family *f, const struct mapset *m,
    const struct blender_options *o, int sub, const char *detail_dir, int translucent,
    const char *dir, char **cause);
#endif
