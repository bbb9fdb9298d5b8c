/* scene_parse: the state of one scene file's parse, shared by scene.c
 * (loading, whole-file checks) and scene_keys.c (each section's keys). */
#ifndef SKINBAKE_SCENE_PARSE_H
#define SKINBAKE_SCENE_PARSE_H
#include "io/inifile.h"
#include "scene/scene.h"

struct scene_parse {
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
	char **seen;			/* [n_seen] "SECTION\nKEY" of every key read, for repeats */
	int *seen_line;
	int n_seen;
};

enum { OBJ_CENTER = 1, OBJ_RADIUS = 2, OBJ_SIZE = 4, OBJ_NORMAL = 8, OBJ_SHAPE = 16, OBJ_COLOR = 32, OBJ_FILE = 64,
	OBJ_MESH = 128 };
enum { CAM_ANGLE = 1, CAM_WIDTH = 2, CAM_TYPE = 4 };

/* Record the first error as "path:line: message"; returns 0 (stop libinih). */
int scene_fail(struct scene_parse *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* libinih callbacks: one key = value of a section; a section header. */
int scene_key(void *user, const char *section, const char *k, const char *v);
int scene_section(void *user, const char *section);
#endif
