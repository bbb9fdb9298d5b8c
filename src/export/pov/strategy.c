/* strategy: choose the light strategy and convert the scene's lights and
 * camera for the table writers. */
#include "config.h"

#include "export/pov/strategy.h"

#include <math.h>
#include <string.h>

#include "export/pov/vec3.h"

enum scene_strategy strategy_resolve(const struct scene *s)
{
	if (s->lights_strategy != SCENE_LIGHTS_AUTO)
		return s->lights_strategy;
	return s->n_lights == 1 ? SCENE_LIGHTS_KEY : s->n_lights == 2 ? SCENE_LIGHTS_MIXTURE : SCENE_LIGHTS_PASSES;
}

void strategy_light(const struct scene_light *sl, struct pov_light *l)
{
	*l = (struct pov_light){ .parallel = sl->type == SCENE_LIGHT_PARALLEL };
	memcpy(l->pos, sl->position, sizeof l->pos);
	memcpy(l->rgb, sl->color, sizeof l->rgb);
	double o[3] = { 0, 0, 0 };
	scene_light_dir(sl, o, l->dir);
}

void strategy_view(const struct scene_camera *c, struct pov_view *v)
{
	*v = (struct pov_view){ .ortho = c->ortho };
	memcpy(v->pos, c->location, sizeof v->pos);
	vec3_unit_toward(c->look_at, c->location, v->dir);
}

int strategy_skin_bounds(const struct scene *s, int k, double lo[3], double hi[3])
{
	int any = 0;
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		double a[3], b[3];
		if (o->material != SCENE_MAT_SKIN || o->skin != k)
			continue;
		scene_object_bounds(o, a, b);
		for (int j = 0; j < 3; j++) {
			lo[j] = any ? fmin(lo[j], a[j]) : a[j];
			hi[j] = any ? fmax(hi[j], b[j]) : b[j];
		}
		any = 1;
	}
	if (!any) /* include-only export: around the look_at point */
		for (int j = 0; j < 3; j++)
			lo[j] = s->camera.look_at[j] - 1, hi[j] = s->camera.look_at[j] + 1;
	return any;
}
