/* Fuzz target: the POV-Ray exporter's scene reader (src/export/pov/scene.c). */
#include "config.h"
#include "fuzz.h"

#include <stdlib.h>

#include "scene/placement.h"
#include "scene/scene.h"
#include "scene/scene_load.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *cause = NULL;
	struct scene *s = scene_load(fuzz_file(data, size), &cause);
	if (s == NULL) {
		if (cause == NULL || *cause == '\0')
			fuzz_fail("scene refused without a message");
		fuzz_refused(cause);
		return 0;
	}
	/* What the exporter does with a loaded scene, short of writing SDL. */
	double lo[3], hi[3], dir[3], at[3] = { 0, 0, 0 };
	for (int i = 0; i < s->n_objects; i++)
		placement_bounds(&s->objects[i], lo, hi);
	for (int i = 0; i < s->n_lights; i++)
		placement_light_dir(&s->lights[i], at, dir);
	scene_free(s);
	return 0;
}
