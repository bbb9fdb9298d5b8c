/* mtsexport: a scene (scene/scene.h) as a directory for Mitsuba 3, read by
 * exporters/mitsuba (python -m skinbake_mitsuba render DIR):
 *   manifest.json  format "skinbake-mitsuba", the mode, per object its PLY
 *                  file, skin, bake and (meshes) open-edge count, per skin
 *                  the bake directory
 *   scene.json     the renderer-neutral scene (docs/scene-json.md)
 *   OBJECT.ply     each mesh object placed, in Mitsuba's right-handed frame
 *                  (meshply.h)
 * The skin is the baked table (mode "table") or the preset's layers as
 * participating media in shells under the mesh surface (mode "volumetric":
 * every skin mesh must close a volume), or a fitted medium inside it (mode
 * "translucent", exporters/mitsuba/skinbake_mitsuba/transfit.py: closed too). */
#ifndef SKINBAKE_MTSEXPORT_H
#define SKINBAKE_MTSEXPORT_H
#include "base/outdir.h"
#include "scene/scene.h"

enum mts_mode { MTS_TABLE, MTS_VOLUMETRIC, MTS_BOTH, MTS_TRANSLUCENT };

struct mts_options {
	enum mts_mode mode;
	const char *bake;	/* bake directory for skins that name none, or NULL */
	const char *out;	/* output directory */
};

extern const struct outdir_kind mts_outdir_kind;

/* Whether Mitsuba (through this exporter) can show scene S in mode O->mode:
 * 0, or -1 and *cause naming the object or skin and the feature. */
int mts_check(const struct scene *s, const struct mts_options *o, char **cause);
/* Write the directory (outdir staging, all or nothing); -1 and *cause. */
int mts_export(const struct scene *s, const struct mts_options *o, char **cause);
#endif
