/* scene_keys: each section's keys of a scene file ([scene], [camera],
 * [light NAME], [skin NAME], [object NAME]): values parsed, ranges checked,
 * repeats and unknown keys and sections refused, naming file and line. */
#include "config.h"

#include "scene/scene_parse.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/util.h"
#include "geom/sites.h"
#include "scene/scene_keytab.h"

/* A key given twice in one section (also when the section is opened again)
 * would silently take the last value: an error naming both lines. */
static int repeated(struct scene_parse *p, const char *section, const char *k)
{
	char *sk = xasprintf("%s\n%s", section, k);
	for (int i = 0; i < p->n_seen; i++)
		if (!strcmp(p->seen[i], sk)) {
			free(sk);
			scene_fail(p, "[%s]: %s is given twice (first on line %d)", section, k, p->seen_line[i]);
			return 1;
		}
	p->seen = xreallocarray(p->seen, (size_t)p->n_seen + 1, sizeof *p->seen);
	p->seen_line = xreallocarray(p->seen_line, (size_t)p->n_seen + 1, sizeof *p->seen_line);
	p->seen_line[p->n_seen] = p->in.line;
	p->seen[p->n_seen++] = sk;
	return 0;
}

static int parse_vec(const char *v, int n, double *out)
{
	char *buf = xstrdup(v), *save = NULL;
	int k = 0, rc = 0;
	for (char *t = strtok_r(buf, " \t,<>", &save); t; t = strtok_r(NULL, " \t,<>", &save)) {
		if (k >= n || util_parse_decimal(t, &out[k]) != 0) {
			rc = -1;
			break;
		}
		k++;
	}
	free(buf);
	return rc == 0 && k == n ? 0 : -1;
}

static int parse_bool(const char *v, int *out)
{
	if (!strcasecmp(v, "on") || !strcasecmp(v, "yes") || !strcasecmp(v, "true") || !strcmp(v, "1")) {
		*out = 1;
		return 0;
	}
	if (!strcasecmp(v, "off") || !strcasecmp(v, "no") || !strcasecmp(v, "false") || !strcmp(v, "0")) {
		*out = 0;
		return 0;
	}
	return -1;
}

/* A number in the key's range [d->lo, d->hi]; on failure an error naming
 * key, value and range. */
static int num(struct scene_parse *p, const struct scene_key *d, const char *v, double *out)
{
	const char *key = d->name;
	double lo = d->lo, hi = d->hi;
	double x;
	if (util_parse_decimal(v, &x) != 0) {
		scene_fail(p, "%s = '%s' is not a decimal number in [%g, %g]", key, v, lo, hi);
		return -1;
	}
	if (x < lo || x > hi) {
		scene_fail(p, "%s = %s is out of range [%g, %g]", key, v, lo, hi);
		return -1;
	}
	*out = x;
	return 0;
}

static int vec(struct scene_parse *p, const char *key, const char *v, double *out)
{
	if (parse_vec(v, 3, out) != 0) {
		scene_fail(p, "%s = '%s' is not three numbers 'x y z'", key, v);
		return -1;
	}
	return 0;
}

static int color(struct scene_parse *p, const struct scene_key *d, const char *v, double *out)
{
	if (vec(p, d->name, v, out) != 0)
		return -1;
	for (int i = 0; i < 3; i++)
		if (out[i] < d->lo || out[i] > d->hi) {
			scene_fail(p, "%s = '%s': components must be in [0, 1e6]", d->name, v);
			return -1;
		}
	return 0;
}

static int boolean(struct scene_parse *p, const char *key, const char *v, int *out)
{
	if (parse_bool(v, out) != 0) {
		scene_fail(p, "%s = '%s' is not on/off", key, v);
		return -1;
	}
	return 0;
}

/* A path relative to the scene file's directory. */
static char *resolve(const struct scene *s, const char *v)
{
	if (v[0] == '/')
		return xstrdup(v);
	const char *slash = strrchr(s->path, '/');
	if (slash == NULL)
		return xstrdup(v);
	return xasprintf("%.*s/%s", (int)(slash - s->path), s->path, v);
}

static const char *shape_names[] = { "sphere", "box", "plane", "patch", "hand", "head", "mesh" };
static const char *strategy_names[] = { "auto", "key", "mixture", "passes", "separable" };
static const char *material_names[] = { "skin", "lambert", "phong", "plain", "model" };

const char *scene_material_name(enum scene_material m)
{
	return material_names[m];
}

const char *scene_shape_name(enum scene_shape sh)
{
	return shape_names[sh];
}

const char *scene_strategy_name(enum scene_strategy st)
{
	return strategy_names[st];
}

/* A key not in the table: an error listing the section's keys. */
static int unknown(struct scene_parse *p, const char *label, const char *section, const char *k)
{
	return scene_fail(p, "%s: unknown key '%s' (keys %s)", label, k, scene_key_list(section));
}

static int unknown_named(struct scene_parse *p, const char *section, const char *name, const char *k)
{
	char *label = xasprintf("[%s %s]", section, name);
	int rc = unknown(p, label, section, k);
	free(label);
	return rc;
}

static int key_scene(struct scene_parse *p, const char *k, const char *v)
{
	const struct scene_key *d = scene_key_find("scene", k);
	if (d == NULL)
		return unknown(p, "[scene]", "scene", k);
	struct scene *s = p->s;
	double x;
	if (!strcmp(k, "title")) {
		free(s->title);
		s->title = xstrdup(v);
	} else if (!strcmp(k, "width") || !strcmp(k, "height")) {
		if (num(p, d, v, &x) != 0)
			return 0;
		if (x != floor(x))
			return scene_fail(p, "%s = %s is not a whole number of pixels", k, v);
		*(k[0] == 'w' ? &s->width : &s->height) = (int)x;
	} else if (!strcmp(k, "unit_mm")) {
		if (num(p, d, v, &s->unit_mm) != 0)
			return 0;
	} else if (!strcmp(k, "background")) {
		if (color(p, d, v, s->background) != 0)
			return 0;
	} else if (!strcmp(k, "antialias")) {
		if (num(p, d, v, &s->antialias) != 0)
			return 0;
	} else if (!strcmp(k, "fill")) {
		if (color(p, d, v, s->fill) != 0)
			return 0;
	} else if (!strcmp(k, "fill_occlusion")) {
		if (num(p, d, v, &x) != 0)
			return 0;
		if (x != floor(x))
			return scene_fail(p, "%s = %s is not a whole number of rays", k, v);
		s->fill_occlusion = (int)x;
	} else if (!strcmp(k, "lights")) {
		size_t i;
		for (i = 0; i < sizeof strategy_names / sizeof strategy_names[0]; i++)
			if (!strcmp(v, strategy_names[i]))
				break;
		if (i == sizeof strategy_names / sizeof strategy_names[0])
			return scene_fail(p, "lights = '%s' is not one of auto, key, mixture, passes, separable", v);
		s->lights_strategy = (enum scene_strategy)i;
	} else
		return unknown(p, "[scene]", "scene", k);
	return 1;
}

static int key_camera(struct scene_parse *p, const char *k, const char *v)
{
	const struct scene_key *d = scene_key_find("camera", k);
	if (d == NULL)
		return unknown(p, "[camera]", "camera", k);
	struct scene_camera *c = &p->s->camera;
	double x;
	if (!strcmp(k, "type")) {
		if (!strcmp(v, "orthographic"))
			c->ortho = 1;
		else if (!strcmp(v, "perspective"))
			c->ortho = 0;
		else
			return scene_fail(p, "type = '%s' is not orthographic or perspective", v);
		p->cam_has |= CAM_TYPE;
	} else if (!strcmp(k, "location")) {
		if (vec(p, k, v, c->location) != 0)
			return 0;
	} else if (!strcmp(k, "look_at")) {
		if (vec(p, k, v, c->look_at) != 0)
			return 0;
	} else if (!strcmp(k, "angle")) {
		if (num(p, d, v, &x) != 0)
			return 0;
		c->angle = x * M_PI / 180;
		p->cam_has |= CAM_ANGLE;
	} else if (!strcmp(k, "width")) {
		if (num(p, d, v, &c->width) != 0)
			return 0;
		p->cam_has |= CAM_WIDTH;
	} else
		return unknown(p, "[camera]", "camera", k);
	return 1;
}

static int key_light(struct scene_parse *p, struct scene_light *l, const char *k, const char *v)
{
	const struct scene_key *d = scene_key_find("light", k);
	if (d == NULL)
		return unknown_named(p, "light", l->name, k);
	double x;
	if (!strcmp(k, "type")) {
		if (!strcmp(v, "parallel"))
			l->type = SCENE_LIGHT_PARALLEL;
		else if (!strcmp(v, "point"))
			l->type = SCENE_LIGHT_POINT;
		else
			return scene_fail(p, "type = '%s' is not parallel or point", v);
	} else if (!strcmp(k, "position")) {
		if (vec(p, k, v, l->position) != 0)
			return 0;
	} else if (!strcmp(k, "point_at")) {
		if (vec(p, k, v, l->point_at) != 0)
			return 0;
	} else if (!strcmp(k, "color")) {
		if (color(p, d, v, l->color) != 0)
			return 0;
	} else if (!strcmp(k, "area_size")) {
		if (num(p, d, v, &l->area_size) != 0)
			return 0;
	} else if (!strcmp(k, "area_samples")) {
		if (num(p, d, v, &x) != 0)
			return 0;
		l->area_samples = (int)x;
	} else
		return unknown_named(p, "light", l->name, k);
	return 1;
}

static int key_skin(struct scene_parse *p, struct scene_skin *sk, const char *k, const char *v)
{
	const struct scene_key *d = scene_key_find("skin", k);
	if (d == NULL)
		return unknown_named(p, "skin", sk->name, k);
	if (!strcmp(k, "preset")) {
		free(sk->preset);
		sk->preset = xstrdup(v);
	} else if (!strcmp(k, "site")) {
		struct texture_config tc;
		char *why = NULL;
		if (!scene_valid_name(v) || (strcmp(v, "none") && sites_load(v, &tc, &why) != 0)) {
			free(why);
			return scene_fail(p, "site = '%s' is not a site name (skinbake texture --list-sites) or none", v);
		}
		free(sk->site);
		sk->site = strcmp(v, "none") ? xstrdup(v) : NULL;
	} else if (!strcmp(k, "bake")) {
		free(sk->bake);
		sk->bake = resolve(p->s, v);
	} else if (!strcmp(k, "textures")) {
		free(sk->textures);
		sk->textures = resolve(p->s, v);
	} else if (!strcmp(k, "bumps")) {
		if (boolean(p, k, v, &sk->bumps) != 0)
			return 0;
	} else if (!strcmp(k, "reflection")) {
		if (boolean(p, k, v, &sk->reflection) != 0)
			return 0;
	} else
		return unknown_named(p, "skin", sk->name, k);
	return 1;
}

static int key_object(struct scene_parse *p, int idx, const char *k, const char *v)
{
	const struct scene_key *d = scene_key_find("object", k);
	if (d == NULL)
		return unknown_named(p, "object", p->s->objects[idx].name, k);
	struct scene_object *o = &p->s->objects[idx];
	double r[3];
	if (!strcmp(k, "shape")) {
		size_t i;
		for (i = 0; i < sizeof shape_names / sizeof shape_names[0]; i++)
			if (!strcmp(v, shape_names[i]))
				break;
		if (i == sizeof shape_names / sizeof shape_names[0])
			return scene_fail(p, "shape = '%s' is not one of sphere, box, plane, patch, hand, head, mesh", v);
		o->shape = (enum scene_shape)i;
		p->obj_has[idx] |= OBJ_SHAPE;
	} else if (!strcmp(k, "material")) {
		if (!strcmp(v, "skin"))
			o->material = SCENE_MAT_SKIN;
		else if (!strcmp(v, "lambert"))
			o->material = SCENE_MAT_LAMBERT;
		else if (!strcmp(v, "phong"))
			o->material = SCENE_MAT_PHONG;
		else if (!strcmp(v, "plain"))
			o->material = SCENE_MAT_PLAIN;
		else if (!strcmp(v, "model"))
			o->material = SCENE_MAT_MODEL;
		else
			return scene_fail(p, "material = '%s' is not skin, lambert, phong, plain or model", v);
	} else if (!strcmp(k, "skin")) {
		if (!scene_valid_name(v))
			return scene_fail(p, "skin = '%s' is not a name", v);
		snprintf(p->obj_skin[idx], SCENE_NAME_MAX, "%s", v);
	} else if (!strcmp(k, "color")) {
		if (color(p, d, v, o->color) != 0)
			return 0;
		p->obj_has[idx] |= OBJ_COLOR;
	} else if (!strcmp(k, "center")) {
		if (vec(p, k, v, o->center) != 0)
			return 0;
		p->obj_has[idx] |= OBJ_CENTER;
	} else if (!strcmp(k, "radius")) {
		if (num(p, d, v, &o->radius) != 0)
			return 0;
		p->obj_has[idx] |= OBJ_RADIUS;
	} else if (!strcmp(k, "size")) {
		if (vec(p, k, v, o->size) != 0)
			return 0;
		for (int i = 0; i < 3; i++)
			if (o->size[i] <= 0)
				return scene_fail(p, "size = '%s': edges must be > 0", v);
		p->obj_has[idx] |= OBJ_SIZE;
	} else if (!strcmp(k, "normal")) {
		if (vec(p, k, v, o->normal) != 0)
			return 0;
		double n = sqrt(o->normal[0] * o->normal[0] + o->normal[1] * o->normal[1] + o->normal[2] * o->normal[2]);
		if (n < 1e-12)
			return scene_fail(p, "normal = '%s' has zero length", v);
		for (int i = 0; i < 3; i++)
			o->normal[i] /= n;
		p->obj_has[idx] |= OBJ_NORMAL;
	} else if (!strcmp(k, "offset")) {
		if (num(p, d, v, &o->offset) != 0)
			return 0;
	} else if (!strcmp(k, "scale")) {
		if (num(p, d, v, &o->scale) != 0)
			return 0;
	} else if (!strcmp(k, "rotate")) {
		if (vec(p, k, v, r) != 0)
			return 0;
		for (int i = 0; i < 3; i++)
			o->rotate[i] = r[i] * M_PI / 180;
	} else if (!strcmp(k, "translate")) {
		if (vec(p, k, v, o->translate) != 0)
			return 0;
	} else if (!strcmp(k, "file")) {
		free(o->file);
		o->file = resolve(p->s, v);
		p->obj_has[idx] |= OBJ_FILE;
	} else if (!strcmp(k, "mesh")) {
		free(o->mesh_name);
		o->mesh_name = xstrdup(v);
		p->obj_has[idx] |= OBJ_MESH;
	} else if (!strcmp(k, "subdivide")) {
		double x;
		if (num(p, d, v, &x) != 0)
			return 0;
		if (x != floor(x))
			return scene_fail(p, "subdivide = %s is not a whole number of levels", v);
		o->subdivide = (int)x;
		p->obj_has[idx] |= OBJ_MESH;
	} else
		return unknown_named(p, "object", o->name, k);
	return 1;
}

/* Split "light key" / "light.key" into kind and name. */
static int split_section(const char *sec, const char *kind, char *name)
{
	size_t n = strlen(kind);
	if (strncmp(sec, kind, n) != 0 || (sec[n] != ' ' && sec[n] != '.'))
		return 0;
	const char *nm = sec + n + 1;
	while (*nm == ' ')
		nm++;
	snprintf(name, 64, "%s", nm);
	return 1;
}

int scene_key(void *user, const char *section, const char *k, const char *v)
{
	struct scene_parse *p = user;
	struct scene *s = p->s;
	char name[64];
	if (p->err != NULL || repeated(p, section, k))
		return 0;
	if (!strcmp(section, "scene"))
		return key_scene(p, k, v);
	if (!strcmp(section, "camera")) {
		if (!p->have_camera)
			p->cam_line = p->in.line;
		p->have_camera = 1;
		return key_camera(p, k, v);
	}
	if (split_section(section, "light", name)) {
		int i;
		for (i = 0; i < s->n_lights; i++)
			if (!strcmp(s->lights[i].name, name))
				break;
		if (i == s->n_lights) {
			if (!scene_valid_name(name))
				return scene_fail(p, "[%s]: '%s' is not a name (letters, digits, _; at most %d)", section,
				    name, SCENE_NAME_MAX - 1);
			if (s->n_lights == SCENE_MAX_LIGHTS)
				return scene_fail(p, "[%s]: more than %d lights", section, SCENE_MAX_LIGHTS);
			struct scene_light *l = &s->lights[s->n_lights++];
			*l = (struct scene_light){ .type = SCENE_LIGHT_PARALLEL, .color = { 1, 1, 1 }, .area_samples = 5 };
			memcpy(l->name, name, strlen(name) + 1);
			p->light_line[i] = p->in.line;
		}
		return key_light(p, &s->lights[i], k, v);
	}
	if (split_section(section, "skin", name)) {
		int i = scene_find_skin(s, name);
		if (i < 0) {
			if (!scene_valid_name(name))
				return scene_fail(p, "[%s]: '%s' is not a name (letters, digits, _; at most %d)", section,
				    name, SCENE_NAME_MAX - 1);
			if (s->n_skins == SCENE_MAX_SKINS)
				return scene_fail(p, "[%s]: more than %d skins", section, SCENE_MAX_SKINS);
			i = s->n_skins++;
			s->skins[i] = (struct scene_skin){ .bumps = 1, .reflection = 0 };
			memcpy(s->skins[i].name, name, strlen(name) + 1);
		}
		return key_skin(p, &s->skins[i], k, v);
	}
	if (split_section(section, "object", name)) {
		int i;
		for (i = 0; i < s->n_objects; i++)
			if (!strcmp(s->objects[i].name, name))
				break;
		if (i == s->n_objects) {
			if (!scene_valid_name(name))
				return scene_fail(p, "[%s]: '%s' is not a name (letters, digits, _; at most %d)", section,
				    name, SCENE_NAME_MAX - 1);
			if (s->n_objects == SCENE_MAX_OBJECTS)
				return scene_fail(p, "[%s]: more than %d objects", section, SCENE_MAX_OBJECTS);
			struct scene_object *o = &s->objects[s->n_objects++];
			*o = (struct scene_object){ .material = SCENE_MAT_SKIN, .skin = -1, .color = { 0.8, 0.8, 0.8 },
				.radius = 1, .size = { 1, 1, 1 }, .normal = { 0, 1, 0 }, .scale = 1 };
			memcpy(o->name, name, strlen(name) + 1);
			p->obj_line[i] = p->in.line;
		}
		return key_object(p, i, k, v);
	}
	return scene_fail(p, "unknown section [%s] (sections [scene], [camera], [light NAME], [skin NAME], "
	    "[object NAME])", section);
}

/* Every section header, also of a section without keys. */
int scene_section(void *user, const char *section)
{
	struct scene_parse *p = user;
	static const char *const kinds[] = { "light", "skin", "object" };
	char name[64];
	if (p->err != NULL)
		return 0;
	if (!strcmp(section, "scene") || !strcmp(section, "camera"))
		return 1;
	for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
		if (split_section(section, kinds[i], name)) {
			if (!scene_valid_name(name))
				return scene_fail(p, "[%s]: '%s' is not a name (letters, digits, _; at most %d)", section, name,
				    SCENE_NAME_MAX - 1);
			return 1;
		}
	return scene_fail(p, "unknown section [%s] (sections [scene], [camera], [light NAME], [skin NAME], "
	    "[object NAME])", section);
}
