/* strategy: how a scene's lights become lit tables.  A lit table depends on
 * one light's direction, so it is exact for one light; `key` writes one per
 * object for the first light, `mixture` one table for two lights (exact
 * where both reach the surface), `passes` one render per light summed,
 * `separable` one approximate pass for any lights.  Also the lights, camera
 * and regions of the scene as the table writers see them. */
#ifndef SKINBAKE_STRATEGY_H
#define SKINBAKE_STRATEGY_H
#include "export/pov/littable.h"
#include "scene/scene.h"

/* The scene's choice, or for AUTO one whose error for the scene's lights and
 * camera is below 1 %: key for one light (exact with the light-view angle
 * axis); for two the mixture table when its estimated error
 * (strategy_mixture_error) is below STRATEGY_MIX_MAX, which leaves room for
 * the tables' interpolation (0.1-0.5 % measured); else passes, which are
 * exact.  brdf[k] is skin k's BRDF (NULL: the analytic stand-in);
 * *mix_error gets the estimate when one was made, else -1. */
#define STRATEGY_MIX_MAX 0.005
enum scene_strategy strategy_resolve(const struct scene *s, const struct pov_brdf *const *brdf, double *mix_error);

/* The mixture table's error from taking each light-view angle at the
 * objects' centre: over points of the skin objects that face the camera,
 * sum |mixture - exact| / sum exact of the rendered radiance, both lights
 * assumed visible (where one is shadowed the mixture's weights are off too,
 * which this does not count).  Points: mesh vertices, points spread over
 * spheres, the faces of boxes and patches, a sphere around hand and head. */
double strategy_mixture_error(const struct scene *s, const struct pov_brdf *const *brdf);

void strategy_light(const struct scene_light *sl, struct pov_light *l);
void strategy_view(const struct scene_camera *c, struct pov_view *v);
/* Whether point p is in the camera's view, the field grown by `margin`
 * (a fraction). */
int strategy_in_view(const struct scene *s, const double p[3], double margin);
/* Bounds of the objects that use skin k (of meshes, of what is in view) (the region the tables' light-view
 * angle axis must cover); without any, +-1 unit around the camera's look_at.
 * Returns whether any object uses skin k. */
int strategy_skin_bounds(const struct scene *s, int k, double lo[3], double hi[3]);
#endif
