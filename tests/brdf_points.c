/* brdf_points: evaluate a bake at many geometries in one process, for the
 * validation report and the CUReT fit (scripts/validate-brdf.sh,
 * scripts/fit-curet.py), where one `skinbake eval` per point would cost more
 * than the bake.  Same interpolation as `skinbake eval` (bake_eval_diffuse,
 * bake_eval_specular); --alpha replaces the bake's GGX roughness, which enters
 * only the analytic specular, so a fit can vary it without baking again.
 *
 *   brdf_points BAKE_DIR [--alpha A] < points
 *
 * Input lines: theta_i theta_o delta_phi [deg] (delta_phi 0 = back toward the
 * light, 180 = mirror side); anything after the third field is ignored, '#'
 * lines are skipped.  Output, one line per input line: total, diffuse,
 * specular [1/sr], each the mean over the bake's wavelengths (470/550/656 nm
 * stand for a camera's B, G, R), and the standard error of the diffuse mean. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"

int main(int argc, char **argv)
{
	if (argc != 2 && !(argc == 4 && strcmp(argv[2], "--alpha") == 0)) {
		fprintf(stderr, "usage: brdf_points BAKE_DIR [--alpha A] < points (theta_i theta_o delta_phi in deg)\n");
		return 2;
	}
	char *cause = NULL;
	struct bake *b = bake_load(argv[1], &cause);
	if (b == NULL) {
		fprintf(stderr, "brdf_points: %s\n", cause);
		free(cause);
		return 2;
	}
	if (argc == 4) {
		char *end;
		double a = strtod(argv[3], &end);
		if (*end != '\0' || !(a >= 0.01 && a <= 1.0)) {
			fprintf(stderr, "brdf_points: --alpha %s: not a number in [0.01, 1]\n", argv[3]);
			bake_free(b);
			return 2;
		}
		b->roughness = a;
	}
	double *f = malloc(sizeof *f * 3 * (size_t)b->n_wl), *e = f + b->n_wl, *s = e + b->n_wl;
	char line[512];
	int ln = 0, rc = 0;
	const double rad = M_PI / 180.0;
	while (fgets(line, sizeof line, stdin)) {
		ln++;
		if (line[0] == '#' || line[0] == '\n')
			continue;
		double ti, to, ph;
		if (sscanf(line, "%lf %lf %lf", &ti, &to, &ph) != 3 || !(ti >= 0 && ti <= 90) || !(to >= 0 && to <= 90)
		    || !(ph >= 0 && ph <= 360)) {
			fprintf(stderr, "brdf_points: line %d: expected theta_i theta_o delta_phi in degrees "
			    "(theta in [0, 90], delta_phi in [0, 360])\n", ln);
			rc = 2;
			break;
		}
		bake_eval_diffuse(b, ti * rad, to * rad, ph * rad, f, e);
		bake_eval_specular(b, ti * rad, to * rad, ph * rad, s);
		double fd = 0, fs = 0, ve = 0;
		for (int k = 0; k < b->n_wl; k++) {
			fd += f[k];
			fs += s[k];
			ve += e[k] * e[k];
		}
		fd /= b->n_wl;
		fs /= b->n_wl;
		printf("%.6g\t%.6g\t%.6g\t%.3g\n", fd + fs, fd, fs, sqrt(ve) / b->n_wl);
	}
	free(f);
	bake_free(b);
	return rc;
}
