/* povsplit_ms: the POV-Ray split's specular part with a widened alpha keeps
 * the facets' later reflections (issue 21, round 6; tests/povsplit_ms.sh).
 *
 *   povsplit_ms BAKE_DIR
 *
 * For a bake with multiple scattering on a rough top, povsplit_specular at an
 * alpha 1e-9 above the bake's (the branch a relief's Toksvig widening takes)
 * must equal the bake's own specular (bake_eval_specular_rgb: the GGX lobe
 * plus engine/microfacet_ms.h's lobe) to 1e-6 relative: the branches agree
 * where they meet.  Prints one TAP line per geometry and 'ms 1' or 'ms 0'. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bake/bakefile.h"
#include "export/pov/povsplit.h"

int main(int argc, char **argv)
{
	if (argc != 2) {
		fprintf(stderr, "usage: povsplit_ms BAKE_DIR\n");
		return 2;
	}
	char *cause = NULL;
	struct bake *b = bake_load(argv[1], &cause);
	if (b == NULL) {
		fprintf(stderr, "povsplit_ms: %s\n", cause);
		free(cause);
		return 2;
	}
	static const double g[][3] = { { 10, 20, 180 }, { 60, 70, 150 }, { 78.75, 80, 140 }, { 30, 85, 0 } };
	struct povsplit_spec sp = { b, b->roughness + 1e-9 };
	int bad = 0, n = (int)(sizeof g / sizeof g[0]);
	printf("# ms %d\n", b->ms != NULL);
	for (int i = 0; i < n; i++) {
		double ti = g[i][0] * M_PI / 180, to = g[i][1] * M_PI / 180, ph = g[i][2] * M_PI / 180;
		double a[3], e[3], d = 0;
		povsplit_specular(&sp, ti, to, ph, a);
		bake_eval_specular_rgb(b, ti, to, ph, e);
		for (int c = 0; c < 3; c++)
			d = fmax(d, fabs(a[c] - e[c]) / fmax(fabs(e[c]), 1e-300));
		int ok = d <= 1e-6;
		bad |= !ok;
		printf("%s %d - %g/%g/%g deg: widened-alpha branch %.6g, bake's lobe %.6g (relative %.2g)\n",
		    ok ? "ok" : "not ok", i + 1, g[i][0], g[i][1], g[i][2], a[1], e[1], d);
	}
	printf("1..%d\n", n);
	bake_free(b);
	return bad;
}
