/* render: the forward direction, a family's quantities per texel from
 * parameter maps (`skinbake maps render-albedo`): the diffuse albedo in
 * linear sRGB and the subsurface radius per R, G, B, interpolated between
 * the members exactly as the fit models them (family_albedo). */
#ifndef SKINBAKE_RENDER_H
#define SKINBAKE_RENDER_H
#include "bake/family.h"
#include "maps/image.h"
#include "maps/mapset.h"

/* An RGB image (float, linear sRGB albedo) of m's size; radius (NULL: not
 * wanted) gets the mean exit radius per R, G, B [cm] the same way.  The
 * maps must suit the family (mapset_check_family). */
struct image *maps_render_albedo(struct family *f, const struct mapset *m, struct image **radius, int threads);
#endif
