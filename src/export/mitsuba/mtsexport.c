/* mtsexport: the Mitsuba 3 export directory (see mtsexport.h). */
#include "config.h"
#include "export/mitsuba/mtsexport.h"

#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#include "base/checksum.h"
#include "base/util.h"
#include "export/mitsuba/meshply.h"
#include "geom/mesh.h"
#include "io/json.h"
#include "scene/scene_json.h"

static const char *const mts_names[] = { "manifest.json", "scene.json", "*.ply", NULL };
const struct outdir_kind mts_outdir_kind = { "Mitsuba export directory", "manifest.json", "format",
	"skinbake-mitsuba", mts_names };

static const char *mode_name(enum mts_mode m)
{
	return m == MTS_TABLE ? "table" : m == MTS_VOLUMETRIC ? "volumetric" :
	       m == MTS_TRANSLUCENT ? "translucent" : "both";
}

/* The bake directory of skin K: the scene's, else the option's, else NULL. */
static const char *skin_bake(const struct scene *s, int k, const struct mts_options *o)
{
	if (k < 0)
		return NULL;
	return s->skins[k].bake ? s->skins[k].bake : o->bake;
}

static int check_object(const struct scene *s, const struct scene_object *ob, const struct mts_options *o,
    char **cause)
{
	if (ob->shape == SCENE_HAND || ob->shape == SCENE_HEAD) {
		*cause = xasprintf("object '%s': shape = %s is a POV-Ray macro (exporters/pov/skinbake_shapes.inc) that "
		    "Mitsuba cannot show; use shape = mesh", ob->name, scene_shape_name(ob->shape));
		return -1;
	}
	if (ob->shape == SCENE_BOX || ob->shape == SCENE_PLANE) {
		*cause = xasprintf("object '%s': shape = %s is not written for Mitsuba (sphere, patch and mesh are)",
		    ob->name, scene_shape_name(ob->shape));
		return -1;
	}
	if (ob->material == SCENE_MAT_PHONG) {
		*cause = xasprintf("object '%s': material = phong is POV-Ray's highlight model, which Mitsuba cannot show; "
		    "use skin, lambert or plain", ob->name);
		return -1;
	}
	if (ob->skin >= 0 && skin_bake(s, ob->skin, o) == NULL) {
		*cause = xasprintf("object '%s': skin '%s' names no bake and --bake is not given", ob->name,
		    s->skins[ob->skin].name);
		return -1;
	}
	if (o->mode != MTS_TABLE && ob->material == SCENE_MAT_SKIN && ob->shape == SCENE_PATCH) {
		*cause = xasprintf("object '%s': a patch has no interior to hold the skin's layers "
		    "(volumetric and translucent modes need a sphere or a closed mesh)", ob->name);
		return -1;
	}
	if (o->mode != MTS_TABLE && ob->material == SCENE_MAT_SKIN && ob->shape == SCENE_MESH) {
		long open = meshply_open_edges(ob->mesh);
		if (open > 0) {
			*cause = xasprintf("object '%s': the mesh %s has %ld open edges, so it has no interior to hold "
			    "the skin's layers (volumetric and translucent modes need a closed "
			    "mesh)", ob->name, ob->mesh->source, open);
			return -1;
		}
	}
	return 0;
}

int mts_check(const struct scene *s, const struct mts_options *o, char **cause)
{
	for (int i = 0; i < s->n_objects; i++)
		if (check_object(s, &s->objects[i], o, cause) != 0)
			return -1;
	return 0;
}

static struct json_object *manifest(const struct scene *s, const struct mts_options *o)
{
	struct json_object *j = json_object_new_object(), *objs = json_object_new_array();
	struct json_object *files = json_object_new_array(), *skins = json_object_new_array();
	json_put(j, "format", json_object_new_string("skinbake-mitsuba"));
	json_put(j, "version", json_object_new_int(1));
	json_put(j, "skinbake_version", json_object_new_string(PACKAGE_VERSION));
	json_put(j, "mode", json_object_new_string(mode_name(o->mode)));
	json_put(j, "frame", json_object_new_string("Mitsuba: right-handed, +y up; a scene.json point (x, y, z) is "
	    "(x, y, -z) here; PLY files are already in this frame"));
	json_object_array_add(files, json_object_new_string("scene.json"));
	for (int k = 0; k < s->n_skins; k++) {
		struct json_object *sk = json_object_new_object();
		json_put(sk, "name", json_object_new_string(s->skins[k].name));
		const char *b = skin_bake(s, k, o);
		json_put(sk, "bake", b ? json_object_new_string(b) : NULL);
		json_put(sk, "bumps_exported", json_object_new_boolean(0));
		json_object_array_add(skins, sk);
	}
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *ob = &s->objects[i];
		struct json_object *e = json_object_new_object();
		json_put(e, "name", json_object_new_string(ob->name));
		if (ob->shape == SCENE_MESH) {
			char *ply = xasprintf("%s.ply", ob->name);
			json_put(e, "ply", json_object_new_string(ply));
			json_object_array_add(files, json_object_new_string(ply));
			free(ply);
			json_put(e, "open_edges", json_object_new_int64(meshply_open_edges(ob->mesh)));
			json_put(e, "model_diffuse_rgb", json_num_array(ob->mesh->diffuse_rgb, 3));
		}
		json_put(e, "skin", ob->skin >= 0 ? json_object_new_string(s->skins[ob->skin].name) : NULL);
		json_object_array_add(objs, e);
	}
	json_put(j, "skins", skins);
	json_put(j, "objects", objs);
	json_put(j, "files", files);
	return j;
}

static int write_all(const struct scene *s, const struct mts_options *o, const char *dir, char **cause)
{
	char *path = xasprintf("%s/scene.json", dir);
	int rc = scene_json_write(s, path, cause);
	free(path);
	for (int i = 0; rc == 0 && i < s->n_objects; i++) {
		if (s->objects[i].shape != SCENE_MESH)
			continue;
		path = xasprintf("%s/%s.ply", dir, s->objects[i].name);
		rc = meshply_write(s->objects[i].mesh, path, cause);
		free(path);
	}
	if (rc != 0)
		return -1;
	struct json_object *j = manifest(s, o);
	char *text = json_text(j, JSON_PRETTY);
	rc = checksum_write_manifest(dir, "manifest.json", text, cause);	/* SHA-256 of each file (issue 23) */
	free(text);
	json_object_put(j);
	return rc;
}

int mts_export(const struct scene *s, const struct mts_options *o, char **cause)
{
	if (mts_check(s, o, cause) != 0)
		return -1;
	struct outdir od;
	if (outdir_begin(&od, o->out, &mts_outdir_kind, cause) != 0)
		return -1;
	if (write_all(s, o, outdir_path(&od), cause) != 0) {
		outdir_fail(&od, cause);
		return -1;
	}
	return outdir_commit(&od, cause);
}
