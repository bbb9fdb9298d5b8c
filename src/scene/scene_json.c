/* scene_json: write the scene model as scene.json (docs/scene-json.md):
 * camera, lights, skins and objects in the scene's world (left-handed, +y
 * up, scene units), angles in degrees, each object with its matrix to the
 * world. */
#include "config.h"

#include "scene/scene_json.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/util.h"
#include "io/json.h"
#include "scene/placement.h"

static double deg(double rad)
{
	return rad * 180.0 / M_PI;
}

static struct json_object *vec3(const double v[3])
{
	return json_num_array(v, 3);
}

static struct json_object *str_or_null(const char *s)
{
	if (s == NULL)
		return NULL;
	return json_object_new_string(s);
}

/* A path of the scene as an absolute path, so that scene.json can be read
 * from anywhere: the file's real path when it exists, else the path joined
 * to the working directory. */
static struct json_object *abs_path(const char *p)
{
	if (p == NULL)
		return NULL;
	char *r = realpath(p, NULL);
	if (r == NULL && p[0] != '/') {
		char *cwd = getcwd(NULL, 0);
		if (cwd != NULL)
			r = xasprintf("%s/%s", cwd, p);
		free(cwd);
	}
	struct json_object *j = json_object_new_string(r != NULL ? r : p);
	free(r);
	return j;
}

void scene_object_to_world(const struct scene_object *o, double m[4][4])
{
	double zero[3] = { 0, 0, 0 };
	double t[3];
	placement_point(o, zero, t);
	for (int j = 0; j < 3; j++) {
		double e[3] = { 0, 0, 0 };
		double c[3];
		e[j] = 1;
		if (o->shape == SCENE_MESH && j == 2)
			e[j] = -1;	/* the file is right-handed: z mirrored */
		placement_point(o, e, c);
		for (int i = 0; i < 3; i++)
			m[i][j] = c[i] - t[i];
	}
	for (int i = 0; i < 3; i++) {
		m[i][3] = t[i];
		m[3][i] = 0;
	}
	m[3][3] = 1;
}

static struct json_object *camera(const struct scene *s)
{
	const struct scene_camera *c = &s->camera;
	struct json_object *j = json_object_new_object();
	json_put(j, "type", json_object_new_string(c->ortho ? "orthographic" : "perspective"));
	json_put(j, "location", vec3(c->location));
	json_put(j, "look_at", vec3(c->look_at));
	double sky[3] = { 0, 1, 0 };
	json_put(j, "sky", vec3(sky));
	if (c->ortho)
		json_put(j, "width", json_num(c->width));
	else
		json_put(j, "horizontal_fov_deg", json_num(deg(c->angle)));
	return j;
}

static struct json_object *light(const struct scene_light *l)
{
	struct json_object *j = json_object_new_object();
	json_put(j, "name", json_object_new_string(l->name));
	int par = l->type == SCENE_LIGHT_PARALLEL;
	json_put(j, "type", json_object_new_string(par ? "parallel" : "point"));
	json_put(j, "position", vec3(l->position));
	if (par) {
		double d[3];
		json_put(j, "point_at", vec3(l->point_at));
		placement_light_dir(l, l->point_at, d);
		for (int i = 0; i < 3; i++)
			d[i] = -d[i];
		json_put(j, "direction", vec3(d));
	}
	json_put(j, "irradiance_rgb", vec3(l->color));
	json_put(j, "area_size", json_num(l->area_size));
	json_put(j, "area_samples", json_object_new_int(l->area_size > 0 ? l->area_samples : 0));
	return j;
}

static struct json_object *skin(const struct scene_skin *k)
{
	struct json_object *j = json_object_new_object();
	json_put(j, "name", json_object_new_string(k->name));
	json_put(j, "preset", str_or_null(k->preset));
	json_put(j, "site", str_or_null(k->site));
	json_put(j, "bake", abs_path(k->bake));
	json_put(j, "textures", abs_path(k->textures));
	json_put(j, "bumps", json_object_new_boolean(k->bumps));
	json_put(j, "reflection", json_object_new_boolean(k->reflection));
	return j;
}

/* The shape's own parameters, in its local frame. */
static void shape_fields(struct json_object *j, const struct scene_object *o)
{
	switch (o->shape) {
	case SCENE_SPHERE:
		json_put(j, "center", vec3(o->center));
		json_put(j, "radius", json_num(o->radius));
		break;
	case SCENE_BOX:
	case SCENE_PATCH:
		json_put(j, "center", vec3(o->center));
		json_put(j, "size", vec3(o->size));
		break;
	case SCENE_PLANE:
		json_put(j, "normal", vec3(o->normal));
		json_put(j, "offset", json_num(o->offset));
		break;
	case SCENE_MESH:
		json_put(j, "file", abs_path(o->file));
		json_put(j, "mesh", str_or_null(o->mesh_name));
		json_put(j, "subdivide", json_object_new_int(o->subdivide));
		json_put(j, "world_lo", vec3(o->mesh_lo));
		json_put(j, "world_hi", vec3(o->mesh_hi));
		break;
	case SCENE_HAND:
	case SCENE_HEAD:
		break;
	}
}

static struct json_object *object(const struct scene *s, const struct scene_object *o)
{
	struct json_object *j = json_object_new_object();
	json_put(j, "name", json_object_new_string(o->name));
	json_put(j, "shape", json_object_new_string(scene_shape_name(o->shape)));
	json_put(j, "material", json_object_new_string(scene_material_name(o->material)));
	json_put(j, "skin", o->skin >= 0 ? json_object_new_string(s->skins[o->skin].name) : NULL);
	if (o->material == SCENE_MAT_PLAIN)
		json_put(j, "color", vec3(o->color));
	shape_fields(j, o);
	json_put(j, "scale", json_num(o->scale));
	double r[3] = { deg(o->rotate[0]), deg(o->rotate[1]), deg(o->rotate[2]) };
	json_put(j, "rotate_deg", vec3(r));
	json_put(j, "translate", vec3(o->translate));
	double m[4][4];
	scene_object_to_world(o, m);
	struct json_object *rows = json_object_new_array();
	for (int i = 0; i < 4; i++)
		json_object_array_add(rows, json_num_array(m[i], 4));
	json_put(j, "to_world", rows);
	return j;
}

struct json_object *scene_json(const struct scene *s)
{
	struct json_object *j = json_object_new_object();
	json_put(j, "format", json_object_new_string("skinbake-scene"));
	json_put(j, "version", json_object_new_int(SCENE_JSON_VERSION));
	json_put(j, "source", abs_path(s->path));
	json_put(j, "title", str_or_null(s->title));
	json_put(j, "world", json_object_new_string("left-handed, +y up, +z into the screen (POV-Ray's)"));
	json_put(j, "unit_mm", json_num(s->unit_mm));
	json_put(j, "width_px", json_object_new_int(s->width));
	json_put(j, "height_px", json_object_new_int(s->height));
	json_put(j, "background_rgb", vec3(s->background));
	json_put(j, "camera", camera(s));
	struct json_object *a = json_object_new_array();
	for (int i = 0; i < s->n_lights; i++)
		json_object_array_add(a, light(&s->lights[i]));
	json_put(j, "lights", a);
	a = json_object_new_array();
	for (int i = 0; i < s->n_skins; i++)
		json_object_array_add(a, skin(&s->skins[i]));
	json_put(j, "skins", a);
	a = json_object_new_array();
	for (int i = 0; i < s->n_objects; i++)
		json_object_array_add(a, object(s, &s->objects[i]));
	json_put(j, "objects", a);
	return j;
}

int scene_json_write(const struct scene *s, const char *path, char **cause)
{
	struct json_object *j = scene_json(s);
	int rc = json_save(path, j, JSON_PRETTY, cause);
	json_object_put(j);
	return rc;
}
