/* scenespec: parse the command-line forms of scene lights and cameras. */
#include "config.h"

#include "export/pov/scenespec.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

static int spec_vec(const char *opt, const char *key, const char *v, double out[3], char **cause)
{
	char *end;
	const char *s = v;
	for (int i = 0; i < 3; i++) {
		errno = 0;
		out[i] = strtod(s, &end);
		if (end == s || errno || !isfinite(out[i]) || (i < 2 && *end != ':') || (i == 2 && *end != '\0'))
			return *cause = xasprintf("%s %s = '%s' is not X:Y:Z", opt, key, v), -1;
		s = end + 1;
	}
	return 0;
}

static int spec_num(const char *opt, const char *v, double lo, double hi, double *out, char **cause)
{
	double x;
	if (util_parse_double(v, &x) != 0 || isnan(x))
		return *cause = xasprintf("%s: '%s' is not a number (allowed range [%g, %g])", opt, v, lo, hi), -1;
	if (x < lo || x > hi)
		return *cause = xasprintf("%s = %g is out of range [%g, %g]", opt, x, lo, hi), -1;
	*out = x;
	return 0;
}

static int light_spec_key(struct scene_light *l, const char *k, const char *v, int *have_pos, char **cause)
{
	if (!strcmp(k, "type")) {
		if (!strcmp(v, "parallel"))
			l->type = SCENE_LIGHT_PARALLEL;
		else if (!strcmp(v, "point"))
			l->type = SCENE_LIGHT_POINT;
		else
			return *cause = xasprintf("--light type = '%s' is not parallel or point", v), -1;
	} else if (!strcmp(k, "position")) {
		if (spec_vec("--light", k, v, l->position, cause) != 0)
			return -1;
		*have_pos = 1;
	} else if (!strcmp(k, "point_at")) {
		if (spec_vec("--light", k, v, l->point_at, cause) != 0)
			return -1;
	} else if (!strcmp(k, "color")) {
		if (spec_vec("--light", k, v, l->color, cause) != 0)
			return -1;
		for (int i = 0; i < 3; i++)
			if (l->color[i] < 0 || l->color[i] > 1e6)
				return *cause = xasprintf("--light color = '%s': components must be in [0, 1e6]", v), -1;
	} else if (!strcmp(k, "name")) {
		size_t n = strlen(v);
		if (!scene_valid_name(v))
			return *cause = xasprintf("--light name = '%s' is not a name (letters, digits, _)", v), -1;
		memcpy(l->name, v, n + 1);
	} else
		return *cause = xasprintf("--light: unknown key '%s' (keys type, position, point_at, color, name)", k), -1;
	return 0;
}

int scenespec_add_light(struct scene *s, const char *spec, char **cause)
{
	if (s->n_lights == SCENE_MAX_LIGHTS)
		return *cause = xasprintf("--light: at most %d lights", SCENE_MAX_LIGHTS), -1;
	struct scene_light *l = &s->lights[s->n_lights];
	*l = (struct scene_light){ .type = SCENE_LIGHT_PARALLEL, .color = { 1, 1, 1 }, .area_samples = 5 };
	snprintf(l->name, sizeof l->name, "L%d", s->n_lights + 1);
	char *buf = xstrdup(spec), *save = NULL;
	int have_pos = 0, rc = -1;
	for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		char *eq = strchr(t, '=');
		if (eq == NULL) {
			*cause = xasprintf("--light: '%s' is not key=value (keys type, position, point_at, color, name)", t);
			goto out;
		}
		*eq = '\0';
		if (light_spec_key(l, t, eq + 1, &have_pos, cause) != 0)
			goto out;
	}
	if (!have_pos) {
		*cause = xasprintf("--light '%s' lacks position=X:Y:Z", spec);
		goto out;
	}
	s->n_lights++;
	rc = 0;
out:
	free(buf);
	return rc;
}

static int camera_spec_key(struct scene_camera *c, const char *k, const char *v, int *have_type, int *have_loc,
    char **cause)
{
	double x;
	if (!strcmp(k, "type")) {
		if (strcmp(v, "orthographic") && strcmp(v, "perspective"))
			return *cause = xasprintf("--camera type = '%s' is not orthographic or perspective", v), -1;
		c->ortho = !strcmp(v, "orthographic");
		*have_type = 1;
	} else if (!strcmp(k, "location")) {
		if (spec_vec("--camera", k, v, c->location, cause) != 0)
			return -1;
		*have_loc = 1;
	} else if (!strcmp(k, "look_at")) {
		if (spec_vec("--camera", k, v, c->look_at, cause) != 0)
			return -1;
	} else if (!strcmp(k, "angle")) {
		if (spec_num("--camera angle", v, 1, 170, &x, cause) != 0)
			return -1;
		c->angle = x * M_PI / 180;
	} else if (!strcmp(k, "width")) {
		if (spec_num("--camera width", v, 1e-6, 1e9, &c->width, cause) != 0)
			return -1;
	} else
		return *cause = xasprintf("--camera: unknown key '%s' (keys type, location, look_at, angle, width)", k), -1;
	return 0;
}

int scenespec_set_camera(struct scene *s, const char *spec, char **cause)
{
	struct scene_camera *c = &s->camera;
	char *buf = xstrdup(spec), *save = NULL;
	int have_type = 0, have_loc = 0, rc = -1;
	*c = (struct scene_camera){ .angle = 40 * M_PI / 180, .width = 2.4 };
	for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		char *eq = strchr(t, '=');
		if (eq == NULL) {
			*cause = xasprintf("--camera: '%s' is not key=value (keys type, location, look_at, angle, width)", t);
			goto out;
		}
		*eq = '\0';
		if (camera_spec_key(c, t, eq + 1, &have_type, &have_loc, cause) != 0)
			goto out;
	}
	if (!have_type || !have_loc) {
		*cause = xasprintf("--camera '%s' lacks %s", spec, !have_type ? "type=orthographic|perspective" : "location=X:Y:Z");
		goto out;
	}
	rc = 0;
out:
	free(buf);
	return rc;
}
