/* scene_load: parse and validate skinbake scene files (INI through libinih).
 * Errors name the file and line; unknown sections and keys are errors, so a
 * typo never silently falls back to a default.  The keys of each section
 * are read in scene_keys.c; this file loads and makes the whole-file checks. */
#include "config.h"

#include "scene/scene_load.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "geom/mesh.h"
#include "io/inifile.h"
#include "scene/placement.h"
#include "scene/scene_parse.h"

int scene_fail(struct scene_parse *p, const char *fmt, ...)
{
	if (p->err == NULL) {
		va_list ap;
		va_start(ap, fmt);
		p->err = inifile_vmsg(p->s->path, p->in.line, fmt, ap);
		va_end(ap);
	}
	return 0;
}

static double dist3(const double a[3], const double b[3])
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Read a mesh object's model and place it in POV-Ray's world. */
static int load_mesh(struct scene_parse *p, struct scene_object *o)
{
	char *cause = NULL;
	if (placement_load_mesh(o, &cause) == 0)
		return 0;
	scene_fail(p, "[object %s]: %s", o->name, cause);
	free(cause);
	return -1;
}

/* Checks that need the whole file; errors point at the section's first line. */
static int validate(struct scene_parse *p)
{
	struct scene *s = p->s;
	if (!p->have_camera)
		return p->err = xasprintf("%s: no [camera] section", s->path), -1;
	p->in.line = p->cam_line;
	if (!(p->cam_has & CAM_TYPE))
		return scene_fail(p, "[camera]: type is required (orthographic or perspective)"), -1;
	if (s->camera.ortho && !(p->cam_has & CAM_WIDTH))
		return scene_fail(p, "[camera]: an orthographic camera needs width"), -1;
	if (!s->camera.ortho && !(p->cam_has & CAM_ANGLE))
		return scene_fail(p, "[camera]: a perspective camera needs angle"), -1;
	if (dist3(s->camera.location, s->camera.look_at) < 1e-9)
		return scene_fail(p, "[camera]: location and look_at coincide"), -1;
	if (s->n_lights == 0)
		return p->err = xasprintf("%s: no [light NAME] section", s->path), -1;
	for (int i = 0; i < s->n_lights; i++) {
		struct scene_light *l = &s->lights[i];
		p->in.line = p->light_line[i];
		if (l->type == SCENE_LIGHT_PARALLEL && dist3(l->position, l->point_at) < 1e-9)
			return scene_fail(p, "[light %s]: position and point_at coincide", l->name), -1;
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
			return scene_fail(p, "[object %s]: shape is required", o->name), -1;
		if (o->shape == SCENE_SPHERE && !(p->obj_has[i] & OBJ_RADIUS))
			return scene_fail(p, "[object %s]: a sphere needs radius", o->name), -1;
		if (o->shape == SCENE_PLANE && !(p->obj_has[i] & OBJ_NORMAL))
			return scene_fail(p, "[object %s]: a plane needs normal", o->name), -1;
		if (o->shape == SCENE_MESH && !(p->obj_has[i] & OBJ_FILE))
			return scene_fail(p, "[object %s]: a mesh needs file = PATH (a model libassimp reads)", o->name), -1;
		if (o->shape != SCENE_MESH && (p->obj_has[i] & (OBJ_FILE | OBJ_MESH)))
			return scene_fail(p, "[object %s]: file, mesh and subdivide are only for shape = mesh", o->name), -1;
		if (o->shape == SCENE_MESH && load_mesh(p, o) != 0)
			return -1;
		if (o->material == SCENE_MAT_MODEL && o->shape != SCENE_MESH)
			return scene_fail(p, "[object %s]: material = model (the model file's own) is only for shape = mesh", o->name),
			       -1;
		if (o->material == SCENE_MAT_PLAIN || o->material == SCENE_MAT_MODEL) {
			if (p->obj_skin[i][0])
				return scene_fail(p, "[object %s]: skin is only for skin, lambert and phong materials",
				    o->name), -1;
			continue;
		}
		if (p->obj_skin[i][0]) {
			o->skin = scene_find_skin(s, p->obj_skin[i]);
			if (o->skin < 0)
				return scene_fail(p, "[object %s]: skin = '%s' names no [skin] section", o->name,
				    p->obj_skin[i]), -1;
		} else if (s->n_skins == 1)
			o->skin = 0;
		else if (s->n_skins == 0)
			return scene_fail(p, "[object %s]: material %s needs a [skin NAME] section", o->name,
			    o->material == SCENE_MAT_SKIN ? "skin" : o->material == SCENE_MAT_LAMBERT ? "lambert" : "phong"),
			    -1;
		else
			return scene_fail(p, "[object %s]: several skins: say which with skin = NAME", o->name), -1;
	}
	return 0;
}

struct scene *scene_load(const char *path, char **cause)
{
	struct scene_parse p = { 0 };
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
	int rc = inifile_parse(&p.in, path, text, scene_key, scene_section, &p);
	free(text);
	if (p.in.error && p.err == NULL) {
		p.err = p.in.error;
		p.in.error = NULL;
	}
	free(p.in.error);
	for (int i = 0; i < p.n_seen; i++)
		free(p.seen[i]);
	free(p.seen);
	free(p.seen_line);
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
