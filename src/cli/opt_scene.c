/* opt_scene: the --light and --camera options of exporters that take a
 * scene without a scene file (scene/scene.h; scene_from_parts): the keys
 * of the scene file's [light] and [camera] sections, as opt_keys tables. */
#include "config.h"

#include "cli/opt_scene.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>

/* --light and --camera: the keys of the scene file's [light] and [camera]. */
struct light_spec {
	int type;	/* 0 parallel, 1 point (staged: the field is an enum) */
	struct scene_light l;
};
const struct opt_key opt_scene_light_keys[] = {
	{ "type", OPT_ENUM, offsetof(struct light_spec, type), "parallel", .choices = "parallel|point", .help = "light type" },
	{ "position", OPT_VEC3, offsetof(struct light_spec, l.position), .lo = -1e9, .hi = 1e9, .flags = OPT_REQUIRED,
	  .help = "point: the light; parallel: a point on the light side" },
	{ "point_at", OPT_VEC3, offsetof(struct light_spec, l.point_at), "0:0:0", .lo = -1e9, .hi = 1e9,
	  .help = "parallel: shines from position toward here" },
	{ "color", OPT_VEC3, offsetof(struct light_spec, l.color), "1:1:1", .lo = 0, .hi = 1e6,
	  .help = "irradiance at normal incidence, linear RGB" },
	{ "name", OPT_STRING, offsetof(struct light_spec, l.name), .size = SCENE_NAME_MAX, .help = "default L1, L2, ..." },
	{ .name = NULL },
};
const struct opt_key opt_scene_camera_keys[] = {
	{ "type", OPT_ENUM, offsetof(struct scene_camera, ortho), .choices = "perspective|orthographic",
	  .flags = OPT_REQUIRED, .help = "projection" },
	{ "location", OPT_VEC3, offsetof(struct scene_camera, location), .lo = -1e9, .hi = 1e9, .flags = OPT_REQUIRED,
	  .help = "camera position" },
	{ "look_at", OPT_VEC3, offsetof(struct scene_camera, look_at), "0:0:0", .lo = -1e9, .hi = 1e9, .help = "target" },
	{ "angle", OPT_DOUBLE, offsetof(struct scene_camera, angle), "40", .lo = 1, .hi = 170, .unit = "deg",
	  .help = "perspective: horizontal field of view" },
	{ "width", OPT_DOUBLE, offsetof(struct scene_camera, width), "2.4", .lo = 0, .hi = 1e9, .flags = OPT_LO_OPEN,
	  .help = "orthographic: view width in units" },
	{ .name = NULL },
};

int opt_scene_light(struct opt_ctx *x, const struct opt *o, const char *v)
{
	struct scene *s = o->dest;
	struct light_spec k = { .l = { .area_samples = 5 } };
	snprintf(k.l.name, sizeof k.l.name, "L%d", s->n_lights + 1);
	if (opt_keys(x, "--light", v, opt_scene_light_keys, &k) != 0)
		return -1;
	if (!scene_valid_name(k.l.name)) {
		opt_error(x, "--light name = '%s' is not a name (letters, digits, _)", k.l.name);
		return -1;
	}
	k.l.type = k.type ? SCENE_LIGHT_POINT : SCENE_LIGHT_PARALLEL;
	s->lights[s->n_lights++] = k.l;
	return 0;
}

int opt_scene_camera(struct opt_ctx *x, const struct opt *o, const char *v)
{
	struct scene_camera *c = &((struct scene *)o->dest)->camera;
	*c = (struct scene_camera){ 0 };
	if (opt_keys(x, "--camera", v, opt_scene_camera_keys, c) != 0)
		return -1;
	c->angle *= M_PI / 180;
	return 0;
}
