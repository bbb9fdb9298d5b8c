/* blender_manifest: the image set's manifest.json (blender.h has the
 * layout), built from what blender.c prepared: the detail maps and the
 * exact-mode reference.  Numbers with nine significant digits, non-finite
 * ones as null (io/json.h). */
#ifndef SKINBAKE_BLENDER_MANIFEST_H
#define SKINBAKE_BLENDER_MANIFEST_H
#include <stdint.h>
#include "export/blender/blender_options.h"
#include "export/source.h"

struct json_object;

/* Detail maps: the source's (borrowed) or flat (owned). */
struct blender_maps {
	int w, h;		/* size [px] */
	const uint16_t *height;	/* [h][w] gray */
	const uint16_t *normal;	/* [h][w][3] RGB */
	int flat;		/* 1 when no textures were given */
	const char *tile_mm;	/* tEXt values as read, or NULL */
	const char *hmin_um, *hmax_um;
	uint16_t *own_height, *own_normal;	/* flat maps */
	/* The relief as roughness for distant views (DIR/roughness_far.png of
	 * `skinbake texture`, docs/relief.md), or NULL when the textures have none. */
	uint16_t *far;		/* [far_n][far_n] alpha_relief * 65535 */
	int far_n;		/* its edge [px] */
	/* The relief's cavity (DIR/cavity.png of the texture directory, or
	 * NULL when it has none): multiplied into the shading. */
	uint16_t *cavity;	/* [cavity_n][cavity_n] cavity * 65535 */
	int cavity_n;		/* its edge [px] */
};

/* Everything the exact-mode check needs: the reference plane (+Z normal)
 * under the sun, seen from the reference camera. */
struct blender_reference {
	double sun[3], view[3];		/* unit vectors toward sun and camera */
	double cos_l, cos_v, dphi;	/* on the +Z plane [-], [-], [rad] */
	double pi_fr[3];		/* pi f_r straight from the model */
	double pi_fr_lut[3];		/* what the node tree reads from the atlas */
	double radiance[3];		/* E cos_l f_r [W/(m^2 sr)] */
};

/* The manifest (caller puts it) of the set for M under O. */
struct json_object *blender_manifest_build(const struct brdf_source *m,
    const struct blender_options *o, const struct blender_maps *d, const double albedo[3],
    const struct blender_reference *r);
#endif
