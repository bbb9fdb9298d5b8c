/* blender_kind: the Blender image set as an output kind (base/outdir.h): the
 * manifest that marks it and every file it may hold, so that a rewrite owns
 * exactly these and refuses a directory holding anything else. */
#include "config.h"

#include <stddef.h>

#include "base/outdir.h"
#include "export/blender/blender.h"

static const char *const blender_names[] = {
	"albedo*.exr", "brdf_lut.exr", "roughness*.png", "height.png", "normal.png",
	"family_lut.exr", "family_coord.exr", "sss_*.exr", NULL
};

const struct outdir_kind blender_outdir_kind = {
	"Blender image set", "manifest.json", "format", "skinbake-blender-image-set",
	blender_names
};
