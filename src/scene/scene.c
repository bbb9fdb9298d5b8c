/* scene: the renderer-neutral scene model (scene.h): names, lookups, the
 * scene of command-line lights and camera, and freeing.  Reading scene
 * files is scene_load.c. */
#include "config.h"

#include "scene/scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "geom/mesh.h"

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

int scene_find_skin(const struct scene *s, const char *name)
{
	for (int i = 0; i < s->n_skins; i++)
		if (!strcmp(s->skins[i].name, name))
			return i;
	return -1;
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

struct scene *scene_from_parts(const struct scene *parts, double unit_mm)
{
	struct scene *s = xcalloc(1, sizeof *s);
	*s = *parts;
	s->path = xstrdup("the command line");
	s->width = 320;
	s->height = 240;
	s->unit_mm = 10;
	if (unit_mm > 0)
		s->unit_mm = unit_mm;
	s->n_skins = 1;
	snprintf(s->skins[0].name, sizeof s->skins[0].name, "skin");
	s->skins[0].preset = xstrdup("(from the bake)");
	s->skins[0].bumps = 1;
	return s;
}
