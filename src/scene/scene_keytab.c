/* scene_keytab: the table of a scene file's keys (scene_keytab.h). */
#include "config.h"

#include "scene/scene_keytab.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define T SCENE_KEY_TEXT
#define NM SCENE_KEY_NAME
#define PA SCENE_KEY_PATH
#define NU SCENE_KEY_NUMBER
#define IN SCENE_KEY_INTEGER
#define VE SCENE_KEY_VECTOR
#define CO SCENE_KEY_COLOUR
#define SW SCENE_KEY_SWITCH
#define CH SCENE_KEY_CHOICE

const struct scene_key scene_key_table[] = {
	{ "scene", "title", T, "", 0, 0, NULL, "the file name",
	  "one-line description, copied into the .pov" },
	{ "scene", "width", IN, "px", 16, 8192, NULL, "320", "image width" },
	{ "scene", "height", IN, "px", 16, 8192, NULL, "240", "image height" },
	{ "scene", "unit_mm", NU, "mm", 1e-3, 1e6, NULL, "10",
	  "one scene unit in millimetres (sets the bump-map tile size)" },
	{ "scene", "background", CO, "", 0, 1e6, NULL, "0 0 0", "background colour" },
	{ "scene", "antialias", NU, "", 0, 3, NULL, "0",
	  "POV-Ray antialiasing threshold written to the .ini, 0 = off" },
	{ "scene", "fill", CO, "", 0, 1e6, NULL, "0 0 0",
	  "POV-Ray, one light (key): a uniform sky light of this colour (a light of it facing a "
	  "white Lambert surface gives the same); skins get it as their hemispherical albedo "
	  "a(θo) × fill, other objects as `emission` (no shadows; no occlusion unless "
	  "`fill_occlusion`)" },
	{ "scene", "fill_occlusion", IN, "rays", 0, 4096, NULL, "0",
	  "rays per mesh vertex (rounded down to a square) for the fill's occlusion: skin and "
	  "`model` meshes with UVs get the fill times V, the cosine-weighted part of the sky each "
	  "vertex in view sees past every mesh of the scene, as a UV map `BASE_ao_NAME.png` "
	  "(docs/pov.md); 0: none" },
	{ "scene", "lights", CH, "", 0, 0, "auto|key|mixture|passes|separable", "auto",
	  "how the lights are rendered (light strategies, below)" },
	{ "camera", "type", CH, "", 0, 0, "orthographic|perspective", "",
	  "the projection (required)" },
	{ "camera", "location", VE, "units", 0, 0, NULL, "0 0 0", "camera position" },
	{ "camera", "look_at", VE, "units", 0, 0, NULL, "0 0 0", "camera target" },
	{ "camera", "angle", NU, "deg", 1, 170, NULL, "",
	  "perspective: horizontal field of view (required)" },
	{ "camera", "width", NU, "units", 1e-6, 1e9, NULL, "",
	  "orthographic: horizontal view size (required)" },
	{ "light", "type", CH, "", 0, 0, "parallel|point", "parallel", "the kind of light" },
	{ "light", "position", VE, "units", 0, 0, NULL, "0 0 0",
	  "point: the light's position; parallel: a point on the light side (put it far away: "
	  "POV-Ray tests shadows only up to it)" },
	{ "light", "point_at", VE, "units", 0, 0, NULL, "0 0 0",
	  "parallel: the light shines from `position` toward here" },
	{ "light", "color", CO, "", 0, 1e6, NULL, "1 1 1",
	  "POV-Ray light colour = irradiance at normal incidence (a white Lambertian shows this "
	  "value)" },
	{ "light", "area_size", NU, "units", 0, 1e9, NULL, "0",
	  "side of a square area light, 0 = none" },
	{ "light", "area_samples", IN, "", 2, 33, NULL, "5", "area-light samples per side" },
	{ "skin", "preset", T, "", 0, 0, NULL, "",
	  "the preset the bake was made from (required; a mismatch prints a note)" },
	{ "skin", "site", NM, "", 0, 0, NULL, "none",
	  "the micro-geometry site the textures were grown for (`skinbake texture "
	  "--list-sites`), or `none`" },
	{ "skin", "bake", PA, "", 0, 0, NULL, "none",
	  "bake directory, relative to this file (`--bake` overrides)" },
	{ "skin", "textures", PA, "", 0, 0, NULL, "none",
	  "`skinbake texture` directory, relative to this file (`--textures` overrides)" },
	{ "skin", "bumps", SW, "", 0, 0, NULL, "on",
	  "use the height map as a bump map when textures are given" },
	{ "skin", "reflection", SW, "", 0, 0, NULL, "off",
	  "add `reflection { 0, 1 fresnel on }` with the bake's index: mirrors other objects; "
	  "lights are already in the table" },
	{ "object", "shape", CH, "", 0, 0, "sphere|box|plane|patch|hand|head|mesh", "",
	  "`patch`: a flat square facing -z, for bump maps; `mesh`: a model file, below "
	  "(required)" },
	{ "object", "material", CH, "", 0, 0, "skin|lambert|phong|plain|model", "skin",
	  "`skin` (the baked table), `lambert` or `phong` (stand-ins with the skin's albedo), "
	  "`plain` (grey Lambertian `color`), `model` (meshes: the model file's own diffuse "
	  "texture or colour and specular, e.g. eyes)" },
	{ "object", "skin", NM, "", 0, 0, NULL, "the only skin",
	  "which `[skin]` (needed when there are several)" },
	{ "object", "color", CO, "", 0, 1e6, NULL, "0.8 0.8 0.8", "`plain`: diffuse albedo" },
	{ "object", "center", VE, "units", 0, 0, NULL, "0 0 0", "sphere, box and patch: centre" },
	{ "object", "radius", NU, "units", 1e-9, 1e9, NULL, "1", "sphere: radius" },
	{ "object", "size", VE, "units", 0, 0, NULL, "1 1 1", "box and patch edges (each > 0)" },
	{ "object", "normal", VE, "", 0, 0, NULL, "", "plane: normal (not of zero length)" },
	{ "object", "offset", NU, "units", -1e9, 1e9, NULL, "", "plane: distance from the origin" },
	{ "object", "scale", NU, "", 1e-6, 1e6, NULL, "1", "uniform scale (applied first)" },
	{ "object", "rotate", VE, "deg", 0, 0, NULL, "0 0 0",
	  "rotation about x then y then z (applied after `scale`)" },
	{ "object", "translate", VE, "units", 0, 0, NULL, "0 0 0", "translation (applied last)" },
	{ "object", "file", PA, "", 0, 0, NULL, "",
	  "mesh: the model file, relative to this file; any format libassimp reads (OBJ, PLY, "
	  "glTF, Collada `.dae`/`.zae`, FBX, STL, ...)" },
	{ "object", "mesh", T, "", 0, 0, NULL, "every mesh of the file",
	  "mesh: which mesh (or node) of the file; an unknown name is an error that lists the "
	  "file's names" },
	{ "object", "subdivide", IN, "", 0, 3, NULL, "0",
	  "mesh: levels of smooth subdivision: each splits every triangle into four, the new "
	  "vertices on the curve the edge's normals describe (PN triangles), so coarse meshes "
	  "get smoother silhouettes and terminators; 4x the triangles per level; for smooth "
	  "meshes (normals split along an edge would open it)" },
	{ NULL, NULL, T, NULL, 0, 0, NULL, NULL, NULL },
};

const struct scene_key *scene_key_find(const char *section, const char *name)
{
	for (const struct scene_key *k = scene_key_table; k->section != NULL; k++)
		if (strcmp(k->section, section) == 0 && strcmp(k->name, name) == 0)
			return k;
	return NULL;
}

const char *scene_key_list(const char *section)
{
	static char buf[512];
	buf[0] = '\0';
	for (const struct scene_key *k = scene_key_table; k->section != NULL; k++) {
		size_t n = strlen(buf);
		if (strcmp(k->section, section) == 0)
			snprintf(buf + n, sizeof buf - n, "%s%s", n ? ", " : "", k->name);
	}
	return buf;
}

const char *scene_key_type_name(enum scene_key_type t)
{
	static const char *const names[] = {
		"text", "name", "path", "number", "integer", "vector", "colour", "on/off", "choice",
	};
	return names[t];
}
