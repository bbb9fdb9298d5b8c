/* scene: parse and validate skinbake scene files (INI through libinih).
 * Errors name the file and line; unknown sections and keys are errors, so a
 * typo never silently falls back to a default. */
#include "config.h"

#include "export/pov/scene.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/util.h"
#include "geom/mesh.h"
#include "io/inifile.h"
#include "export/pov/placement.h"

struct parse {
	struct scene *s;
	struct inifile in;	/* the reader: line being parsed and its number */
	char *err;		/* first error message */
	int have_camera;
	int obj_line[SCENE_MAX_OBJECTS];	/* first line of each object section */
	int light_line[SCENE_MAX_LIGHTS];
	char obj_skin[SCENE_MAX_OBJECTS][SCENE_NAME_MAX];
	int obj_has[SCENE_MAX_OBJECTS];	/* bit mask of keys seen (OBJ_*) */
	int cam_has;			/* CAM_* bits */
	int cam_line;
};

enum { OBJ_CENTER = 1, OBJ_RADIUS = 2, OBJ_SIZE = 4, OBJ_NORMAL = 8, OBJ_SHAPE = 16, OBJ_COLOR = 32, OBJ_FILE = 64,
	OBJ_MESH = 128 };
enum { CAM_ANGLE = 1, CAM_WIDTH = 2, CAM_TYPE = 4 };

static int fail(struct parse *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(struct parse *p, const char *fmt, ...)
{
	if (p->err == NULL) {
		va_list ap;
		va_start(ap, fmt);
		p->err = inifile_vmsg(p->s->path, p->in.line, fmt, ap);
		va_end(ap);
	}
	return 0;
}

static int parse_vec(const char *v, int n, double *out)
{
	char *buf = xstrdup(v), *save = NULL;
	int k = 0, rc = 0;
	for (char *t = strtok_r(buf, " \t,<>", &save); t; t = strtok_r(NULL, " \t,<>", &save)) {
		if (k >= n || util_parse_double(t, &out[k]) != 0 || !isfinite(out[k])) {
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
	if (!strcasecmp(v, "on") || !strcasecmp(v, "yes") || !strcasecmp(v, "true") || !strcmp(v, "1"))
		return *out = 1, 0;
	if (!strcasecmp(v, "off") || !strcasecmp(v, "no") || !strcasecmp(v, "false") || !strcmp(v, "0"))
		return *out = 0, 0;
	return -1;
}

/* A number in [lo, hi]; on failure an error naming key, value and range. */
static int num(struct parse *p, const char *key, const char *v, double lo, double hi, double *out)
{
	double x;
	if (util_parse_double(v, &x) != 0 || !isfinite(x))
		return fail(p, "%s = '%s' is not a number", key, v), -1;
	if (x < lo || x > hi)
		return fail(p, "%s = %s is out of range [%g, %g]", key, v, lo, hi), -1;
	*out = x;
	return 0;
}

static int vec(struct parse *p, const char *key, const char *v, double *out)
{
	if (parse_vec(v, 3, out) != 0)
		return fail(p, "%s = '%s' is not three numbers 'x y z'", key, v), -1;
	return 0;
}

static int color(struct parse *p, const char *key, const char *v, double *out)
{
	if (vec(p, key, v, out) != 0)
		return -1;
	for (int i = 0; i < 3; i++)
		if (out[i] < 0 || out[i] > 1e6)
			return fail(p, "%s = '%s': components must be in [0, 1e6]", key, v), -1;
	return 0;
}

static int boolean(struct parse *p, const char *key, const char *v, int *out)
{
	if (parse_bool(v, out) != 0)
		return fail(p, "%s = '%s' is not on/off", key, v), -1;
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

int scene_valid_name(const char *n)
{
	size_t len = strlen(n);
	if (len == 0 || len >= SCENE_NAME_MAX)
		return 0;
	for (const char *c = n; *c; c++)
		if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_'))
			return 0;
	return 1;
}

static const char *shape_names[] = { "sphere", "box", "plane", "patch", "hand", "head", "mesh" };
static const char *strategy_names[] = { "auto", "key", "mixture", "passes", "separable" };

const char *scene_shape_name(enum scene_shape sh)
{
	return shape_names[sh];
}

const char *scene_strategy_name(enum scene_strategy st)
{
	return strategy_names[st];
}

static int key_scene(struct parse *p, const char *k, const char *v)
{
	struct scene *s = p->s;
	double x;
	if (!strcmp(k, "title")) {
		free(s->title);
		s->title = xstrdup(v);
	} else if (!strcmp(k, "width") || !strcmp(k, "height")) {
		if (num(p, k, v, 16, 8192, &x) != 0)
			return 0;
		if (x != floor(x))
			return fail(p, "%s = %s is not a whole number of pixels", k, v);
		*(k[0] == 'w' ? &s->width : &s->height) = (int)x;
	} else if (!strcmp(k, "unit_mm")) {
		if (num(p, k, v, 1e-3, 1e6, &s->unit_mm) != 0)
			return 0;
	} else if (!strcmp(k, "background")) {
		if (color(p, k, v, s->background) != 0)
			return 0;
	} else if (!strcmp(k, "antialias")) {
		if (num(p, k, v, 0, 3, &s->antialias) != 0)
			return 0;
	} else if (!strcmp(k, "lights")) {
		size_t i;
		for (i = 0; i < sizeof strategy_names / sizeof strategy_names[0]; i++)
			if (!strcmp(v, strategy_names[i]))
				break;
		if (i == sizeof strategy_names / sizeof strategy_names[0])
			return fail(p, "lights = '%s' is not one of auto, key, mixture, passes, separable", v);
		s->lights_strategy = (enum scene_strategy)i;
	} else
		return fail(p, "[scene]: unknown key '%s' (keys title, width, height, unit_mm, background, "
		    "antialias, lights)", k);
	return 1;
}

static int key_camera(struct parse *p, const char *k, const char *v)
{
	struct scene_camera *c = &p->s->camera;
	double x;
	if (!strcmp(k, "type")) {
		if (!strcmp(v, "orthographic"))
			c->ortho = 1;
		else if (!strcmp(v, "perspective"))
			c->ortho = 0;
		else
			return fail(p, "type = '%s' is not orthographic or perspective", v);
		p->cam_has |= CAM_TYPE;
	} else if (!strcmp(k, "location")) {
		if (vec(p, k, v, c->location) != 0)
			return 0;
	} else if (!strcmp(k, "look_at")) {
		if (vec(p, k, v, c->look_at) != 0)
			return 0;
	} else if (!strcmp(k, "angle")) {
		if (num(p, k, v, 1, 170, &x) != 0)
			return 0;
		c->angle = x * M_PI / 180;
		p->cam_has |= CAM_ANGLE;
	} else if (!strcmp(k, "width")) {
		if (num(p, k, v, 1e-6, 1e9, &c->width) != 0)
			return 0;
		p->cam_has |= CAM_WIDTH;
	} else
		return fail(p, "[camera]: unknown key '%s' (keys type, location, look_at, angle, width)", k);
	return 1;
}

static int key_light(struct parse *p, struct scene_light *l, const char *k, const char *v)
{
	double x;
	if (!strcmp(k, "type")) {
		if (!strcmp(v, "parallel"))
			l->type = SCENE_LIGHT_PARALLEL;
		else if (!strcmp(v, "point"))
			l->type = SCENE_LIGHT_POINT;
		else
			return fail(p, "type = '%s' is not parallel or point", v);
	} else if (!strcmp(k, "position")) {
		if (vec(p, k, v, l->position) != 0)
			return 0;
	} else if (!strcmp(k, "point_at")) {
		if (vec(p, k, v, l->point_at) != 0)
			return 0;
	} else if (!strcmp(k, "color")) {
		if (color(p, k, v, l->color) != 0)
			return 0;
	} else if (!strcmp(k, "area_size")) {
		if (num(p, k, v, 0, 1e9, &l->area_size) != 0)
			return 0;
	} else if (!strcmp(k, "area_samples")) {
		if (num(p, k, v, 2, 33, &x) != 0)
			return 0;
		l->area_samples = (int)x;
	} else
		return fail(p, "[light %s]: unknown key '%s' (keys type, position, point_at, color, area_size, "
		    "area_samples)", l->name, k);
	return 1;
}

static int key_skin(struct parse *p, struct scene_skin *sk, const char *k, const char *v)
{
	if (!strcmp(k, "preset")) {
		free(sk->preset);
		sk->preset = xstrdup(v);
	} else if (!strcmp(k, "site")) {
		if (!scene_valid_name(v))
			return fail(p, "site = '%s' is not a site name (skinbake texture --list-sites) or none", v);
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
		return fail(p, "[skin %s]: unknown key '%s' (keys preset, site, bake, textures, bumps, reflection)",
		    sk->name, k);
	return 1;
}

static int key_object(struct parse *p, int idx, const char *k, const char *v)
{
	struct scene_object *o = &p->s->objects[idx];
	double r[3];
	if (!strcmp(k, "shape")) {
		size_t i;
		for (i = 0; i < sizeof shape_names / sizeof shape_names[0]; i++)
			if (!strcmp(v, shape_names[i]))
				break;
		if (i == sizeof shape_names / sizeof shape_names[0])
			return fail(p, "shape = '%s' is not one of sphere, box, plane, patch, hand, head, mesh", v);
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
			return fail(p, "material = '%s' is not skin, lambert, phong, plain or model", v);
	} else if (!strcmp(k, "skin")) {
		if (!scene_valid_name(v))
			return fail(p, "skin = '%s' is not a name", v);
		snprintf(p->obj_skin[idx], SCENE_NAME_MAX, "%s", v);
	} else if (!strcmp(k, "color")) {
		if (color(p, k, v, o->color) != 0)
			return 0;
		p->obj_has[idx] |= OBJ_COLOR;
	} else if (!strcmp(k, "center")) {
		if (vec(p, k, v, o->center) != 0)
			return 0;
		p->obj_has[idx] |= OBJ_CENTER;
	} else if (!strcmp(k, "radius")) {
		if (num(p, k, v, 1e-9, 1e9, &o->radius) != 0)
			return 0;
		p->obj_has[idx] |= OBJ_RADIUS;
	} else if (!strcmp(k, "size")) {
		if (vec(p, k, v, o->size) != 0)
			return 0;
		for (int i = 0; i < 3; i++)
			if (o->size[i] <= 0)
				return fail(p, "size = '%s': edges must be > 0", v);
		p->obj_has[idx] |= OBJ_SIZE;
	} else if (!strcmp(k, "normal")) {
		if (vec(p, k, v, o->normal) != 0)
			return 0;
		double n = sqrt(o->normal[0] * o->normal[0] + o->normal[1] * o->normal[1] + o->normal[2] * o->normal[2]);
		if (n < 1e-12)
			return fail(p, "normal = '%s' has zero length", v);
		for (int i = 0; i < 3; i++)
			o->normal[i] /= n;
		p->obj_has[idx] |= OBJ_NORMAL;
	} else if (!strcmp(k, "offset")) {
		if (num(p, k, v, -1e9, 1e9, &o->offset) != 0)
			return 0;
	} else if (!strcmp(k, "scale")) {
		if (num(p, k, v, 1e-6, 1e6, &o->scale) != 0)
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
		if (num(p, k, v, 0, 3, &x) != 0)
			return 0;
		if (x != floor(x))
			return fail(p, "subdivide = %s is not a whole number of levels", v);
		o->subdivide = (int)x;
		p->obj_has[idx] |= OBJ_MESH;
	} else
		return fail(p, "[object %s]: unknown key '%s' (keys shape, material, skin, color, center, radius, "
		    "size, normal, offset, scale, rotate, translate, file, mesh, subdivide)", o->name, k);
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

static int handler(void *user, const char *section, const char *k, const char *v)
{
	struct parse *p = user;
	struct scene *s = p->s;
	char name[64];
	if (p->err != NULL)
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
				return fail(p, "[%s]: '%s' is not a name (letters, digits, _; at most %d)", section,
				    name, SCENE_NAME_MAX - 1);
			if (s->n_lights == SCENE_MAX_LIGHTS)
				return fail(p, "[%s]: more than %d lights", section, SCENE_MAX_LIGHTS);
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
				return fail(p, "[%s]: '%s' is not a name (letters, digits, _; at most %d)", section,
				    name, SCENE_NAME_MAX - 1);
			if (s->n_skins == SCENE_MAX_SKINS)
				return fail(p, "[%s]: more than %d skins", section, SCENE_MAX_SKINS);
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
				return fail(p, "[%s]: '%s' is not a name (letters, digits, _; at most %d)", section,
				    name, SCENE_NAME_MAX - 1);
			if (s->n_objects == SCENE_MAX_OBJECTS)
				return fail(p, "[%s]: more than %d objects", section, SCENE_MAX_OBJECTS);
			struct scene_object *o = &s->objects[s->n_objects++];
			*o = (struct scene_object){ .material = SCENE_MAT_SKIN, .skin = -1, .color = { 0.8, 0.8, 0.8 },
				.radius = 1, .size = { 1, 1, 1 }, .normal = { 0, 1, 0 }, .scale = 1 };
			memcpy(o->name, name, strlen(name) + 1);
			p->obj_line[i] = p->in.line;
		}
		return key_object(p, i, k, v);
	}
	return fail(p, "unknown section [%s] (sections [scene], [camera], [light NAME], [skin NAME], "
	    "[object NAME])", section);
}

static double dist3(const double a[3], const double b[3])
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Read a mesh object's model and place it in POV-Ray's world. */
static int load_mesh(struct parse *p, struct scene_object *o)
{
	char *cause = NULL;
	if (placement_load_mesh(o, &cause) == 0)
		return 0;
	fail(p, "[object %s]: %s", o->name, cause);
	free(cause);
	return -1;
}

/* Checks that need the whole file; errors point at the section's first line. */
static int validate(struct parse *p)
{
	struct scene *s = p->s;
	if (!p->have_camera)
		return p->err = xasprintf("%s: no [camera] section", s->path), -1;
	p->in.line = p->cam_line;
	if (!(p->cam_has & CAM_TYPE))
		return fail(p, "[camera]: type is required (orthographic or perspective)"), -1;
	if (s->camera.ortho && !(p->cam_has & CAM_WIDTH))
		return fail(p, "[camera]: an orthographic camera needs width"), -1;
	if (!s->camera.ortho && !(p->cam_has & CAM_ANGLE))
		return fail(p, "[camera]: a perspective camera needs angle"), -1;
	if (dist3(s->camera.location, s->camera.look_at) < 1e-9)
		return fail(p, "[camera]: location and look_at coincide"), -1;
	if (s->n_lights == 0)
		return p->err = xasprintf("%s: no [light NAME] section", s->path), -1;
	for (int i = 0; i < s->n_lights; i++) {
		struct scene_light *l = &s->lights[i];
		p->in.line = p->light_line[i];
		if (l->type == SCENE_LIGHT_PARALLEL && dist3(l->position, l->point_at) < 1e-9)
			return fail(p, "[light %s]: position and point_at coincide", l->name), -1;
	}
	if (s->n_objects == 0)
		return p->err = xasprintf("%s: no [object NAME] section", s->path), -1;
	for (int i = 0; i < s->n_skins; i++)
		if (s->skins[i].preset == NULL)
			return p->err = xasprintf("%s: [skin %s]: preset is required", s->path, s->skins[i].name), -1;
	for (int i = 0; i < s->n_objects; i++) {
		struct scene_object *o = &s->objects[i];
		p->in.line = p->obj_line[i];
		if (!(p->obj_has[i] & OBJ_SHAPE))
			return fail(p, "[object %s]: shape is required", o->name), -1;
		if (o->shape == SCENE_SPHERE && !(p->obj_has[i] & OBJ_RADIUS))
			return fail(p, "[object %s]: a sphere needs radius", o->name), -1;
		if (o->shape == SCENE_PLANE && !(p->obj_has[i] & OBJ_NORMAL))
			return fail(p, "[object %s]: a plane needs normal", o->name), -1;
		if (o->shape == SCENE_MESH && !(p->obj_has[i] & OBJ_FILE))
			return fail(p, "[object %s]: a mesh needs file = PATH (a model libassimp reads)", o->name), -1;
		if (o->shape != SCENE_MESH && (p->obj_has[i] & (OBJ_FILE | OBJ_MESH)))
			return fail(p, "[object %s]: file, mesh and subdivide are only for shape = mesh", o->name), -1;
		if (o->shape == SCENE_MESH && load_mesh(p, o) != 0)
			return -1;
		if (o->material == SCENE_MAT_MODEL && o->shape != SCENE_MESH)
			return fail(p, "[object %s]: material = model (the model file's own) is only for shape = mesh", o->name),
			       -1;
		if (o->material == SCENE_MAT_PLAIN || o->material == SCENE_MAT_MODEL) {
			if (p->obj_skin[i][0])
				return fail(p, "[object %s]: skin is only for skin, lambert and phong materials",
				    o->name), -1;
			continue;
		}
		if (p->obj_skin[i][0]) {
			o->skin = scene_find_skin(s, p->obj_skin[i]);
			if (o->skin < 0)
				return fail(p, "[object %s]: skin = '%s' names no [skin] section", o->name,
				    p->obj_skin[i]), -1;
		} else if (s->n_skins == 1)
			o->skin = 0;
		else if (s->n_skins == 0)
			return fail(p, "[object %s]: material %s needs a [skin NAME] section", o->name,
			    o->material == SCENE_MAT_SKIN ? "skin" : o->material == SCENE_MAT_LAMBERT ? "lambert" : "phong"),
			    -1;
		else
			return fail(p, "[object %s]: several skins: say which with skin = NAME", o->name), -1;
	}
	return 0;
}

struct scene *scene_load(const char *path, char **cause)
{
	struct parse p = { 0 };
	struct scene *s = xcalloc(1, sizeof *s);
	s->path = xstrdup(path);
	s->width = 320;
	s->height = 240;
	s->unit_mm = 10;
	s->lights_strategy = SCENE_LIGHTS_AUTO;
	p.s = s;
	char *text = inifile_read(path, cause);
	if (text == NULL) {
		scene_free(s);
		return NULL;
	}
	int rc = inifile_parse(&p.in, path, text, handler, &p);
	free(text);
	if (p.in.too_long && p.err == NULL)
		p.err = xasprintf("%s:%d: line %d is longer than %d characters", path, p.in.too_long, p.in.too_long, p.in.max_line);
	if (rc != 0 && p.err == NULL) {
		if (rc > 0)
			p.err = xasprintf("%s:%d: syntax error (expected [section], key = value or ; comment)", path, rc);
		else
			p.err = xasprintf("%s: cannot read", path);
	}
	if (p.err == NULL)
		validate(&p);
	if (p.err != NULL) {
		*cause = p.err;
		scene_free(s);
		return NULL;
	}
	return s;
}

void scene_free(struct scene *s)
{
	if (s == NULL)
		return;
	for (int i = 0; i < s->n_skins; i++) {
		free(s->skins[i].preset);
		free(s->skins[i].site);
		free(s->skins[i].bake);
		free(s->skins[i].textures);
	}
	for (int i = 0; i < s->n_objects; i++) {
		free(s->objects[i].file);
		free(s->objects[i].mesh_name);
		mesh_free(s->objects[i].mesh);
	}
	free(s->title);
	free(s->path);
	free(s);
}

int scene_find_skin(const struct scene *s, const char *name)
{
	for (int i = 0; i < s->n_skins; i++)
		if (!strcmp(s->skins[i].name, name))
			return i;
	return -1;
}
