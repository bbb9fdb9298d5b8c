/* ad_points: adding-doubling point values of a bake's stacks (see the
 * header). */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "ad_points.h"
#include "bake/bakefile.h"
#include "bake/manifest.h"
#include "base/util.h"
#include "engine/ad.h"

/* One chunk of at most AD_MAX_BEAMS angles, every wavelength. */
static int chunk(const struct bake_provenance *pv, const struct bake *b, long n, const double *ti,
    const double *to, const double *dphi, double *rgb, char **cause)
{
	double t[AD_MAX_BEAMS];
	int idx[AD_MAX_BEAMS], m = 0;
	for (long k = 0; k < n; k++) {
		rgb[3 * k] = rgb[3 * k + 1] = rgb[3 * k + 2] = 0.0;
		if (ti[k] < 0.5 * M_PI) {
			idx[m] = (int)k;
			t[m++] = ti[k];
		}
	}
	if (m == 0)
		return 0;
	for (int w = 0; w < b->n_wl; w++) {
		struct ad_opts o;
		struct ad_result r;
		ad_opts_default(&o);
		o.n_to = o.n_phi = 1;
		if (ad_solve(&pv->slab[w], pv->fresnel, t, m, &o, &r, cause) != 0)
			return -1;
		for (int j = 0; j < m; j++) {
			int k = idx[j];
			double sp[BAKE_MAX_WL];
			bake_eval_specular(b, ti[k], to[k], dphi[k], sp);
			double f = ad_brdf(&r, j, to[k], dphi[k], NULL) + sp[w];
			for (int c = 0; c < 3; c++)
				rgb[3 * k + c] += b->rgb_from_wl[c * b->n_wl + w] * f;
		}
		ad_result_free(&r);
	}
	return 0;
}

int ad_points_rgb(const char *dir, const struct bake *b, long n, const double *ti, const double *to,
    const double *dphi, double *rgb, long *n_solves, char **cause)
{
	struct bake_provenance pv;
	if (bake_provenance_read(dir, &pv, cause) != 0)
		return -1;
	int rc = 0;
	long solves = 0;
	for (long k0 = 0; k0 < n && rc == 0; k0 += AD_MAX_BEAMS) {
		long m = n - k0 < AD_MAX_BEAMS ? n - k0 : AD_MAX_BEAMS;
		rc = chunk(&pv, b, m, ti + k0, to + k0, dphi + k0, rgb + 3 * k0, cause);
		solves += b->n_wl;
	}
	bake_provenance_free(&pv);
	if (n_solves)
		*n_solves = solves;
	return rc;
}
