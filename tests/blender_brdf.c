/* blender_brdf BAKE: the baked BRDF for many directions at once, for
 * tests/blender_lights.sh.  Reads "theta_i theta_o delta_phi" in degrees, one
 * triple per line, and prints the linear-sRGB total BRDF [1/sr] per line:
 * bake_eval_rgb, the value `skinbake eval --json` prints as rgb_total. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bake/bakefile.h"

int main(int argc, char **argv)
{
	if (argc != 2) {
		fprintf(stderr, "usage: blender_brdf BAKE_DIR < angles\n");
		return 2;
	}
	char *cause = NULL;
	struct bake *b = bake_load(argv[1], &cause);
	if (b == NULL) {
		fprintf(stderr, "blender_brdf: %s\n", cause);
		free(cause);
		return 1;
	}
	double ti, to, ph, rgb[3], d2r = M_PI / 180.0;
	while (scanf("%lf %lf %lf", &ti, &to, &ph) == 3) {
		bake_eval_rgb(b, ti * d2r, to * d2r, ph * d2r, rgb);
		printf("%.9g %.9g %.9g\n", rgb[0], rgb[1], rgb[2]);
	}
	bake_free(b);
	return 0;
}
