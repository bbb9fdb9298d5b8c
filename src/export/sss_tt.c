/* sss_tt: Tt of a bake's stack cut to a thickness (see sss_tt.h). */
#include "config.h"
#include "export/sss_tt.h"

#include <math.h>
#include <string.h>

#include "bake/manifest.h"
#include "engine/ad.h"

/* Stack S cut to D_CM (the deeper layers shortened, the last extended to
 * fill) and turned over, so that light enters the deepest layer. */
static int cut_stack(const struct slab *s, double d_cm, struct slab *out, char **cause)
{
	struct layer l[SLAB_MAX_LAYERS];
	int n = 0;
	double left = d_cm;
	for (int i = 1; i <= s->n_layers && left > 0; i++) {
		l[n] = s->layer[i];
		l[n].d = fmin(l[n].d, left);
		l[n].rough = 0.0;
		left -= l[n].d;
		n++;
	}
	l[n - 1].d += fmax(left, 0.0);
	slab_init(out, 1.0, 1.0);
	for (int i = n - 1; i >= 0; i--)
		if (slab_add(out, &l[i], cause) != 0)
			return -1;
	if (slab_check(out, cause) != 0)
		return -1;
	slab_prepare(out);
	return 0;
}

int sss_stack_tt(const struct bake *b, const double *d_mm, int n, double (*tt)[3], char **cause)
{
	struct bake_provenance p;
	if (b->dir == NULL || bake_provenance_read(b->dir, &p, cause) != 0)
		return -1;
	struct ad_opts o;
	ad_opts_default(&o);
	o.tol = 1e-3;
	o.n_to = 1;
	o.n_phi = 1;
	o.max_orders = 1;
	o.threads = 1;
	o.error_estimate = 0;	/* the totals only: 1e-3 of Tt */
	double ti = 0.0;
	int rc = 0;
	memset(tt, 0, sizeof(double) * (size_t)n * 3);
	for (int k = 0; k < n && rc == 0; k++)
		for (int w = 0; w < p.n_wl && rc == 0; w++) {
			struct slab s;
			struct ad_result r;
			if (cut_stack(&p.slab[w], d_mm[k] / 10, &s, cause) != 0
			    || ad_solve(&s, p.fresnel, &ti, 1, &o, &r, cause) != 0) {
				rc = -1;
				break;
			}
			for (int c = 0; c < 3; c++)
				tt[k][c] += b->rgb_from_wl[c * b->n_wl + w] * r.beam[0].tt.v;
			ad_result_free(&r);
		}
	bake_provenance_free(&p);
	return rc;
}
