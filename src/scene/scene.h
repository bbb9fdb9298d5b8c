/* scene: the renderer-neutral scene model (camera, lights, skins,
 * objects), read from scene files by scene_load.h and written as
 * scene.json by scene_json.h; POV-Ray-only settings (antialias, the light
 * strategy) ride along.  The file format is documented in scenes/README.md.  Lengths are scene units
 * (one unit = unit_mm millimetres), angles radians once parsed (the file
 * says degrees), colours linear RGB. */
#ifndef SKINBAKE_SCENE_H
#define SKINBAKE_SCENE_H

#define SCENE_MAX_LIGHTS 16
#define SCENE_MAX_SKINS 8
#define SCENE_MAX_OBJECTS 64
#define SCENE_NAME_MAX 32

struct mesh;

enum scene_light_type { SCENE_LIGHT_PARALLEL, SCENE_LIGHT_POINT };
enum scene_strategy { SCENE_LIGHTS_AUTO, SCENE_LIGHTS_KEY, SCENE_LIGHTS_MIXTURE, SCENE_LIGHTS_PASSES,
	SCENE_LIGHTS_SEPARABLE };
enum scene_shape { SCENE_SPHERE, SCENE_BOX, SCENE_PLANE, SCENE_PATCH, SCENE_HAND, SCENE_HEAD, SCENE_MESH };
enum scene_material { SCENE_MAT_SKIN, SCENE_MAT_LAMBERT, SCENE_MAT_PHONG, SCENE_MAT_PLAIN, SCENE_MAT_MODEL };

struct scene_camera {
	int ortho;		/* 1 orthographic, 0 perspective */
	double location[3];	/* [units] */
	double look_at[3];	/* [units] */
	double angle;		/* perspective: horizontal field of view [rad] */
	double width;		/* orthographic: horizontal view size [units] */
};

struct scene_light {
	char name[SCENE_NAME_MAX];
	enum scene_light_type type;
	double position[3];	/* point: position; parallel: a point on the light side [units] */
	double point_at[3];	/* parallel: the light shines from position toward here [units] */
	double color[3];	/* POV light colour: irradiance at normal incidence, linear RGB [-] */
	double area_size;	/* side of a square area light, 0 = none [units] */
	int area_samples;	/* area light samples per side [-] */
};

struct scene_skin {
	char name[SCENE_NAME_MAX];
	char *preset;		/* preset name the bake must have been made from */
	char *site;		/* micro-geometry site (skinbake texture --list-sites) or NULL */
	char *bake;		/* bake directory (resolved against the scene file) or NULL */
	char *textures;		/* micro-geometry directory (resolved) or NULL */
	int bumps;		/* use the height map as bump map [0/1] */
	int reflection;		/* add reflection { fresnel } with the bake's index [0/1] */
};

struct scene_object {
	char name[SCENE_NAME_MAX];
	enum scene_shape shape;
	enum scene_material material;
	int skin;		/* index into scene.skins for skin-derived materials, else -1 */
	double color[3];	/* plain material: diffuse albedo, linear RGB [-] */
	double center[3];	/* sphere centre / patch centre [units] */
	double radius;		/* sphere radius [units] */
	double size[3];		/* box/patch edge lengths [units] */
	double normal[3];	/* plane normal (unit) */
	double offset;		/* plane: distance from origin along normal [units] */
	double scale;		/* uniform scale (hand, head, mesh) [-] */
	double rotate[3];	/* rotation about x, then y, then z [rad] */
	double translate[3];	/* [units] */
	char *file;		/* mesh: model file (resolved against the scene file) */
	char *mesh_name;	/* mesh: the mesh or node of the file, NULL = all of them */
	int subdivide;		/* mesh: levels of smooth subdivision (mesh_subdivide), 0 to 3 */
	struct mesh *mesh;	/* mesh: loaded and placed: POV-Ray world coordinates [units] */
	double mesh_lo[3], mesh_hi[3];	/* mesh: world bounds [units] */
};

struct scene {
	char *path;		/* the scene file */
	char *title;		/* one-line description */
	int width, height;	/* image size [px] */
	double unit_mm;		/* one scene unit [mm] */
	double background[3];	/* linear RGB */
	double antialias;	/* POV +A threshold, 0 = off */
	double fill[3];		/* uniform sky light, as a light's colour (POV-Ray, one light) */
	int fill_occlusion;	/* rays per mesh vertex, the fill's occlusion (povao.h); 0: none */
	enum scene_strategy lights_strategy;
	struct scene_camera camera;
	int n_lights;
	struct scene_light lights[SCENE_MAX_LIGHTS];
	int n_skins;
	struct scene_skin skins[SCENE_MAX_SKINS];
	int n_objects;
	struct scene_object objects[SCENE_MAX_OBJECTS];
};

void scene_free(struct scene *s);
/* A scene without a file: the lights and camera of PARTS (given on a
 * command line; PARTS owns no strings), 320x240 px, unit_mm UNIT_MM (10
 * when 0), one skin "skin" with bump maps, no objects (the exporter adds
 * its own).  Caller frees with scene_free. */
struct scene *scene_from_parts(const struct scene *parts, double unit_mm);
/* The skin index named NAME, or -1. */
int scene_find_skin(const struct scene *s, const char *name);
/* Whether n is a section name: 1 to 31 of [A-Za-z0-9_]. */
int scene_valid_name(const char *n);
/* Names of enum values, as written in scene files. */
const char *scene_shape_name(enum scene_shape sh);
const char *scene_strategy_name(enum scene_strategy st);
const char *scene_material_name(enum scene_material m);
#endif
