/* placement: where a scene's lights and objects are in POV-Ray's world
 * (left-handed, +y up, units of the scene). */
#ifndef SKINBAKE_PLACEMENT_H
#define SKINBAKE_PLACEMENT_H
#include "scene/scene.h"

/* Unit direction from a point toward the light (parallel: constant). */
void placement_light_dir(const struct scene_light *l, const double p[3], double out[3]);
/* Axis-aligned world bounds of object o (conservative for hand/head). */
void placement_bounds(const struct scene_object *o, double lo[3], double hi[3]);
/* Object o's scale, rotate and translate applied to point p (as POV-Ray
 * applies them), and its rotation alone to direction d. */
void placement_point(const struct scene_object *o, const double p[3], double out[3]);
void placement_dir(const struct scene_object *o, const double d[3], double out[3]);
/* Place a loaded mesh object's mesh (in its file's right-handed
 * coordinates) in the world: z mirrored, normals kept outward, tangent
 * frames flipped with it, then the object's scale, rotate, translate; sets
 * the object's bounds. */
void placement_mesh(struct scene_object *o);
/* Read a mesh object's model (file and mesh name), subdivide it as asked
 * and place it; -1 and *cause when the model cannot be read. */
int placement_load_mesh(struct scene_object *o, char **cause);
#endif
