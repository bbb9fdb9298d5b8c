/* scene_json: the renderer-neutral scene (scene.h) as scene.json, for
 * renderers that do not read skinbake's scene files themselves (the Blender
 * importer, a Mitsuba exporter).  The schema is docs/scene-json.md. */
#ifndef SKINBAKE_SCENE_JSON_H
#define SKINBAKE_SCENE_JSON_H
#include <json-c/json.h>

#include "scene/scene.h"

#define SCENE_JSON_VERSION 1

/* The scene as a JSON object (caller puts it). */
struct json_object *scene_json(const struct scene *s);
/* Write scene S to PATH (all or nothing); -1 and *cause on failure. */
int scene_json_write(const struct scene *s, const char *path, char **cause);
/* The 4x4 row-major matrix taking object O's local coordinates to the
 * scene's world: for primitives the shape's own frame (scale, then rotate
 * about x, y, z, then translate); for a mesh the model file's right-handed
 * coordinates (z mirrored first, as placement.h says). */
void scene_object_to_world(const struct scene_object *o, double m[4][4]);
#endif
