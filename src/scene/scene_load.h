/* scene_load: a scene file (scenes/README.md) read into the scene model
 * of scene.h, every value checked, mesh objects' models read and placed
 * (placement.h). */
#ifndef SKINBAKE_SCENE_LOAD_H
#define SKINBAKE_SCENE_LOAD_H
#include "scene/scene.h"

/* Parse and validate PATH; NULL with *cause ("FILE:LINE: ..." for syntax,
 * unknown sections/keys and bad values) on failure.  Caller frees. */
struct scene *scene_load(const char *path, char **cause);
#endif
