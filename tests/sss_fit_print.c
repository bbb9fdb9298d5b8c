/* sss_fit_print RENDERER BAKE_DIR [SCALE]: the calibrated closure of
 * RENDERER (pov, cycles: Debian's Blender, cycles-M.N: that Blender's, from
 * export/blender/blender_sss.h) fitted to the bake's Rd(r) (export/sss_fit.h),
 * printed as one JSON object for tests/sss_profile.sh; exit 2 with a message
 * for a bake without a radial profile or an unknown renderer.  A test tool,
 * not a test. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export/sss_fit.h"
#include "export/blender/blender_sss.h"

static void arr(const char *key, const double *v, int last)
{
	printf("\"%s\": [%.8g, %.8g, %.8g]%s", key, v[0], v[1], v[2], last ? "" : ", ");
}

int main(int argc, char **argv)
{
	char *cause = NULL;
	if (argc < 3) {
		fprintf(stderr, "usage: sss_fit_print pov|cycles BAKE_DIR [SCALE]\n");
		return 2;
	}
	const struct sss_table *t = !strcmp(argv[1], "pov") ? &sss_pov_table :
	    !strcmp(argv[1], "cycles") ? &sss_cycles_table : NULL;
	int bl = !strncmp(argv[1], "cycles-", 7);
	for (int v = 0; t == NULL && bl && blender_sss_tables[v]; v++) {
		char ser[32];
		blender_sss_series(blender_sss_tables[v], ser, sizeof ser);
		if (!strcmp(argv[1] + 7, ser))
			t = blender_sss_tables[v];
	}
	if (t == NULL) {
		fprintf(stderr, "sss_fit_print: renderer '%s' has no calibration (pov, cycles, "
		    "cycles-M.N)\n", argv[1]);
		return 2;
	}
	struct bake *b = bake_load(argv[2], &cause);
	struct sss_fit f;
	if (b == NULL || sss_fit_bake(t, b, argc > 3 ? atof(argv[3]) : 1.0, &f, &cause) != 0) {
		fprintf(stderr, "sss_fit_print: %s\n", cause);
		free(cause);
		bake_free(b);
		return 2;
	}
	printf("{\"renderer\": \"%s\", \"version\": \"%s\", \"r_max_mm\": %.8g, ", t->renderer, t->version, f.r_max_mm);
	arr("colour", f.colour, 0);
	arr("length_mm", f.length_mm, 0);
	arr("local", f.local, 0);
	arr("integral_bake", f.integral_bake, 0);
	arr("integral_fit", f.integral_fit, 0);
	arr("mean_bake_mm", f.mean_bake_mm, 0);
	arr("mean_fit_mm", f.mean_fit_mm, 0);
	arr("rms_log", f.rms_log, 0);
	/* The closure's reflected power beyond d (times scale, no local part): what POV-Ray's
	 * dipole transmits through a slab d thick, about (docs/translucency.md, back light). */
	printf("\"closure_beyond\": [");
	for (int k = 0; k < 3; k++) {
		double d = k == 0 ? 1.0 : k == 1 ? 2.0 : 4.0, g[3];
		for (int c = 0; c < 3; c++)
			g[c] = sss_fit_ring(&f, c, d, 1e4);
		printf("%s[%g, %.8g, %.8g, %.8g]", k ? ", " : "", d, g[0], g[1], g[2]);
	}
	printf("], ");
	printf("\"bake_rings\": [");
	for (int k = 0; sss_ring_edges_mm[k + 1] > 0 && sss_ring_edges_mm[k] < f.r_max_mm; k++) {
		double r2 = sss_ring_edges_mm[k + 1] < f.r_max_mm ? sss_ring_edges_mm[k + 1] : f.r_max_mm;
		printf("%s[%.8g, %.8g, %.8g, %.8g, %.8g]", k ? ", " : "", sss_ring_edges_mm[k], r2,
		    sss_bake_ring(b, 0, sss_ring_edges_mm[k], r2), sss_bake_ring(b, 1, sss_ring_edges_mm[k], r2),
		    sss_bake_ring(b, 2, sss_ring_edges_mm[k], r2));
	}
	printf("]}\n");
	bake_free(b);
	return 0;
}
