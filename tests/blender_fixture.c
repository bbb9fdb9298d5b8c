/* blender_fixture DIR [TEXTURES]: write an image set from the analytic test
 * BRDF through the exporter code, for tests/blender_import.sh. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include "export/blender/blender.h"
#include "geom/texdir.h"
#include "blender_analytic.h"

int main(int argc, char **argv)
{
	if (argc < 2 || argc > 3) {
		fprintf(stderr, "usage: blender_fixture DIR [TEXTURES]\n");
		return 2;
	}
	struct brdf_source m;
	struct blender_options o;
	char *cause = NULL;
	analytic_model(&m);
	blender_options_default(&o);
	o.lut_cos = 32;
	o.lut_phi = 19;
	struct texdir *t = NULL;
	if (argc == 3 && (t = texdir_load(argv[2], 1, &cause)) == NULL) {
		fprintf(stderr, "blender_fixture: %s\n", cause);
		free(cause);
		return 1;
	}
	m.detail = t;
	int rc = blender_export(&m, &o, argv[1], &cause);
	if (rc != 0) {
		fprintf(stderr, "blender_fixture: %s\n", cause);
		free(cause);
	}
	texdir_free(t);
	return rc != 0;
}
