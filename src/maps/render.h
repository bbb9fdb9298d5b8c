/* render: the forward direction, a family's quantities per texel from
 * parameter maps (`skinbake maps render-albedo`): the diffuse albedo in
 * linear sRGB and the subsurface radius per R, G, B, interpolated between
 * the members exactly as the fit models them (family_albedo). */
#ifndef SKINBAKE_RENDER_H
#define SKINBAKE_RENDER_H
#include "family/family.h"
#include "maps/image.h"
#include "maps/mapset.h"

/* An RGB image (float, linear sRGB albedo) of m's size; radius (NULL: not
 * wanted) gets the mean exit radius per R, G, B [cm] the same way.  The
 * maps must suit the family (mapset_check_family). */
struct image *maps_render_albedo(struct family *f, const struct mapset *m, struct image **radius, int threads);
/* Write the albedo im to out: a float EXR (exr), else a PNG of bits 8 or
 * 16, sRGB-encoded (srgb: im's values are encoded in place) or linear
 * values; then the radius rad, if not NULL, to the EXR radius_path.  -1 and
 * *cause. */
int maps_render_write(const char *out, int exr, int bits, int srgb, struct image *im, const char *radius_path,
    const struct image *rad, char **cause);
#endif
