/* scenespec: the command-line forms of a scene's lights and camera
 * (`export pov --light SPEC --camera SPEC`): "key=value,..." with vectors
 * X:Y:Z; the keys are those of the scene file's [light] and [camera]. */
#ifndef SKINBAKE_SCENESPEC_H
#define SKINBAKE_SCENESPEC_H
#include "export/pov/scene.h"

/* Add a light (named L1, L2, ... unless name= is given) or set the camera;
 * -1 and *cause on a bad spec. */
int scenespec_add_light(struct scene *s, const char *spec, char **cause);
int scenespec_set_camera(struct scene *s, const char *spec, char **cause);
#endif
