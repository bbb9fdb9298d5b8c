/* opt_scene: --light SPEC and --camera SPEC for exporters (opt_scene.c). */
#ifndef SKINBAKE_OPT_SCENE_H
#define SKINBAKE_OPT_SCENE_H
#include "cli/opt.h"
#include "scene/scene.h"

/* The KEY=VALUE keys of --light and --camera (for --help). */
extern const struct opt_key opt_scene_light_keys[];
extern const struct opt_key opt_scene_camera_keys[];
/* OPT_CUSTOM callbacks, dest a struct scene: --light adds a light (named
 * L1, L2, ... unless given), --camera sets the camera (angle in degrees on
 * the command line, radians in the scene). */
int opt_scene_light(struct opt_ctx *x, const struct opt *o, const char *v);
int opt_scene_camera(struct opt_ctx *x, const struct opt *o, const char *v);
#endif
