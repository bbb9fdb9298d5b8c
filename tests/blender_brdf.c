/* blender_brdf BAKE [--ad]: the baked BRDF for many directions at once, for
 * tests/blender_lights.sh and tests/blender_silhouette.sh.  Reads "theta_i
 * theta_o delta_phi" in degrees, one triple per line, and prints the
 * linear-sRGB total BRDF [1/sr] per line: bake_eval_rgb, the value
 * `skinbake eval --json` prints as rgb_total; with --ad, adding-doubling
 * point values of the bake's own stacks instead (tests/ad_points.h: the
 * independent reference, not the table). */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ad_points.h"
#include "bake/bakefile.h"
#include "base/util.h"

/* --ad: every triple read first, then solved together. */
static int print_ad(const char *dir, const struct bake *b)
{
	long n = 0, cap = 0, solves = 0;
	double *ti = NULL, *to = NULL, *ph = NULL, x[3], d2r = M_PI / 180.0;
	while (scanf("%lf %lf %lf", &x[0], &x[1], &x[2]) == 3) {
		if (n == cap) {
			cap = cap ? 2 * cap : 1024;
			ti = xreallocarray(ti, (size_t)cap, sizeof(double));
			to = xreallocarray(to, (size_t)cap, sizeof(double));
			ph = xreallocarray(ph, (size_t)cap, sizeof(double));
		}
		ti[n] = x[0] * d2r;
		to[n] = x[1] * d2r;
		ph[n++] = x[2] * d2r;
	}
	double *rgb = xmalloc(sizeof(double) * 3 * (size_t)(n + 1));
	char *cause = NULL;
	int rc = ad_points_rgb(dir, b, n, ti, to, ph, rgb, &solves, &cause);
	if (rc != 0) {
		fprintf(stderr, "blender_brdf: --ad: %s\n", cause);
		free(cause);
	}
	for (long k = 0; k < n && rc == 0; k++)
		printf("%.9g %.9g %.9g\n", rgb[3 * k], rgb[3 * k + 1], rgb[3 * k + 2]);
	free(ti);
	free(to);
	free(ph);
	free(rgb);
	return rc == 0 ? 0 : 1;
}

int main(int argc, char **argv)
{
	int ad = argc == 3 && strcmp(argv[2], "--ad") == 0;
	if (argc != 2 && !ad) {
		fprintf(stderr, "usage: blender_brdf BAKE_DIR [--ad] < angles\n");
		return 2;
	}
	char *cause = NULL;
	struct bake *b = bake_load(argv[1], &cause);
	if (b == NULL) {
		fprintf(stderr, "blender_brdf: %s\n", cause);
		free(cause);
		return 1;
	}
	int rc = 0;
	if (ad) {
		rc = print_ad(argv[1], b);
	} else {
		double ti, to, ph, rgb[3], d2r = M_PI / 180.0;
		while (scanf("%lf %lf %lf", &ti, &to, &ph) == 3) {
			bake_eval_rgb(b, ti * d2r, to * d2r, ph * d2r, rgb);
			printf("%.9g %.9g %.9g\n", rgb[0], rgb[1], rgb[2]);
		}
	}
	bake_free(b);
	return rc;
}
