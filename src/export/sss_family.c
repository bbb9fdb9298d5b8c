/* sss_family: fitted closures between family members (sss_family.h). */
#include "config.h"
#include "export/sss_family.h"

#include <math.h>

#include "base/check.h"

/* Axis a's bracket at v: node j and the weight w of node j + 1, in t. */
static int bracket(const struct family_axis *ax, double v, double *w)
{
	int j = 0;
	*w = 0.0;
	if (ax->n < 2)
		return 0;
	double t = family_axis_t(ax, v);
	while (j + 2 < ax->n && t > family_axis_t(ax, ax->node[j + 1]))
		j++;
	double t0 = family_axis_t(ax, ax->node[j]), t1 = family_axis_t(ax, ax->node[j + 1]);
	*w = fmin(fmax((t - t0) / (t1 - t0), 0.0), 1.0);
	return j;
}

void sss_fit_family_at(const struct brdf_family *f, const struct sss_fit *const *fits,
    const double *x, struct sss_fit *out)
{
	int j[FAMILY_MAX_AXES];
	double w[FAMILY_MAX_AXES];
	for (int a = 0; a < f->n_axes; a++)
		j[a] = bracket(&f->axis[a], x[a], &w[a]);
	*out = (struct sss_fit){ 0 };
	for (int corner = 0; corner < (1 << f->n_axes); corner++) {
		int idx[FAMILY_MAX_AXES];
		double wt = 1.0;
		for (int a = 0; a < f->n_axes; a++) {
			int up = (corner >> a) & 1;
			idx[a] = j[a] + up;
			wt *= up ? w[a] : 1.0 - w[a];
		}
		if (wt <= 0)
			continue;
		const struct sss_fit *g = fits[brdf_family_member(f, idx)];
		CHECK(g != NULL);
		out->table = g->table;
		out->scale += wt * g->scale;
		out->r_max_mm += wt * g->r_max_mm;
		for (int c = 0; c < 3; c++) {
			out->colour[c] += wt * g->colour[c];
			out->length_mm[c] += wt * log(g->length_mm[c]);
			out->integral_bake[c] += wt * g->integral_bake[c];
			out->local[c] += wt * g->local[c];
			out->integral_fit[c] += wt * g->integral_fit[c];
			out->mean_bake_mm[c] += wt * log(g->mean_bake_mm[c]);
			out->mean_fit_mm[c] += wt * log(g->mean_fit_mm[c]);
			out->rms_log[c] += wt * g->rms_log[c];
			out->clamped[c] |= g->clamped[c];
		}
	}
	for (int c = 0; c < 3; c++) {
		out->length_mm[c] = exp(out->length_mm[c]);
		out->mean_bake_mm[c] = exp(out->mean_bake_mm[c]);
		out->mean_fit_mm[c] = exp(out->mean_fit_mm[c]);
	}
}

void sss_family_reach(const struct brdf_family *f, int a, const float *v, size_t n, int *i0,
    int *i1)
{
	const struct family_axis *ax = &f->axis[a];
	*i0 = ax->n - 1;
	*i1 = 0;
	for (size_t i = 0; i < n; i++) {
		double w;
		int j = bracket(ax, v[i], &w);
		int lo = w < 1 ? j : j + 1, hi = w > 0 ? j + 1 : j;
		*i0 = lo < *i0 ? lo : *i0;
		*i1 = hi > *i1 ? hi : *i1;
	}
	if (*i1 < *i0)
		*i1 = *i0;
}
