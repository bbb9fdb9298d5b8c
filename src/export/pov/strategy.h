/* strategy: how a scene's lights become lit tables.  A lit table depends on
 * one light's direction, so it is exact for one light; `key` writes one per
 * object for the first light, `mixture` one table for two lights (exact
 * where both reach the surface), `passes` one render per light summed,
 * `separable` one approximate pass for any lights.  Also the lights, camera
 * and regions of the scene as the table writers see them. */
#ifndef SKINBAKE_STRATEGY_H
#define SKINBAKE_STRATEGY_H
#include "export/pov/littable.h"
#include "export/pov/scene.h"

/* The scene's choice, or for AUTO: key for one light, mixture for two,
 * passes for more. */
enum scene_strategy strategy_resolve(const struct scene *s);

void strategy_light(const struct scene_light *sl, struct pov_light *l);
void strategy_view(const struct scene_camera *c, struct pov_view *v);
/* Bounds of the objects that use skin k (the region the tables' light-view
 * angle axis must cover); without any, +-1 unit around the camera's look_at.
 * Returns whether any object uses skin k. */
int strategy_skin_bounds(const struct scene *s, int k, double lo[3], double hi[3]);
#endif
