/* family_interp: values between the members of a family (family.h):
 * per axis 4-point Lagrange weights in the axis' coordinate, their tensor
 * product, and blends of positive quantities as logarithms (a family's
 * tables and albedos vary roughly exponentially with an absorber, so the
 * logarithm is the smoother function to interpolate). */
#include "config.h"
#include "family/family.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/util.h"
#include "engine/macro.h"

/* Weights of axis a at x: nodes first .. first + *k - 1. */
static void axis_weights(const struct family_axis *a, double x, int *first, int *k, double w[4])
{
	int n = a->n;
	x = fmin(fmax(x, a->node[0]), a->node[n - 1]);
	int i = 0;
	while (i < n - 2 && a->node[i + 1] <= x)
		i++;
	*k = n < 4 ? n : 4;
	int s = i - 1;
	if (s > n - *k)
		s = n - *k;
	if (s < 0)
		s = 0;
	*first = s;
	double t = family_axis_coord(a, x), tj[4];
	for (int j = 0; j < *k; j++)
		tj[j] = family_axis_coord(a, a->node[s + j]);
	for (int j = 0; j < *k; j++) {
		double l = 1.0;
		for (int m = 0; m < *k; m++)
			if (m != j)
				l *= (t - tj[m]) / (tj[j] - tj[m]);
		w[j] = l;
	}
}

void family_stencil(const struct family *f, const double *x, struct family_stencil *st)
{
	int first[FAMILY_MAX_AXES] = { 0 }, k[FAMILY_MAX_AXES] = { 1, 1, 1 };
	double w[FAMILY_MAX_AXES][4] = { { 1 }, { 1 }, { 1 } };
	for (int a = 0; a < f->n_axes; a++)
		axis_weights(&f->axis[a], x[a], &first[a], &k[a], w[a]);
	int n1 = f->n_axes > 1 ? f->axis[1].n : 1, n0 = f->axis[0].n;
	st->n = 0;
	for (int c = 0; c < k[2]; c++)
		for (int b = 0; b < k[1]; b++)
			for (int a = 0; a < k[0]; a++) {
				double ww = w[0][a] * w[1][b] * w[2][c];
				if (ww == 0.0)
					continue;
				CHECK(st->n < FAMILY_STENCIL_MAX);
				st->member[st->n] = (first[0] + a) + n0 * ((first[1] + b) + n1 * (first[2] + c));
				st->w[st->n++] = ww;
			}
}

double family_blend(const struct family_stencil *st, const double *v, size_t stride)
{
	int pos = 1;
	for (int j = 0; j < st->n && pos; j++)
		pos = v[(size_t)st->member[j] * stride] > 0.0;
	double s = 0.0;
	for (int j = 0; j < st->n; j++) {
		double y = v[(size_t)st->member[j] * stride];
		s += st->w[j] * (pos ? log(y) : y);
	}
	return pos ? exp(s) : s;
}

void family_albedo_prepare(struct family *f)
{
	if (f->log_albedo)
		return;
	double *l = xmalloc(sizeof(double) * (size_t)f->n_members * (size_t)f->n_wl);
	for (int m = 0; m < f->n_members; m++)
		for (int w = 0; w < f->n_wl; w++) {
			double a = f->member[m].albedo_wl[w];
			if (!(a > 0.0)) {
				free(l);	/* a zero albedo: blend the values (family_blend's rule) */
				return;
			}
			l[(size_t)m * f->n_wl + w] = log(a);
		}
	f->log_albedo = l;
}

void family_albedo(const struct family *f, const double *x, double *albedo_wl, double rgb[3], double radius_rgb_cm[3])
{
	struct family_stencil st;
	family_stencil(f, x, &st);
	double a[BAKE_MAX_WL], v[FAMILY_STENCIL_MAX];
	CHECK(f->n_wl <= BAKE_MAX_WL);
	struct family_stencil loc = st;
	for (int j = 0; j < st.n; j++)
		loc.member[j] = j;
	if (f->log_albedo) {
		for (int w = 0; w < f->n_wl; w++)
			a[w] = 0.0;
		for (int j = 0; j < st.n; j++) {
			const double *l = f->log_albedo + (size_t)st.member[j] * f->n_wl;
			for (int w = 0; w < f->n_wl; w++)
				a[w] += st.w[j] * l[w];
		}
		for (int w = 0; w < f->n_wl; w++)
			a[w] = exp(a[w]);
	} else
		for (int w = 0; w < f->n_wl; w++) {
			for (int j = 0; j < st.n; j++)
				v[j] = f->member[st.member[j]].albedo_wl[w];
			a[w] = family_blend(&loc, v, 1);
		}
	for (int c = 0; c < 3; c++) {
		rgb[c] = 0.0;
		for (int w = 0; w < f->n_wl; w++)
			rgb[c] += f->rgb_from_wl[c * f->n_wl + w] * a[w];
	}
	if (albedo_wl)
		memcpy(albedo_wl, a, sizeof(double) * (size_t)f->n_wl);
	if (radius_rgb_cm)
		for (int c = 0; c < 3; c++) {
			for (int j = 0; j < st.n; j++)
				v[j] = f->member[st.member[j]].sss_radius_rgb_cm[c];
			radius_rgb_cm[c] = family_blend(&loc, v, 1);
		}
}

int family_contains(const struct family *f, const double *x, int *axis)
{
	for (int a = 0; a < f->n_axes; a++)
		if (!(x[a] >= f->axis[a].node[0] && x[a] <= f->axis[a].node[f->axis[a].n - 1])) {
			if (axis)
				*axis = a;
			return 0;
		}
	return 1;
}

/* out[i] = blend over the stencil of plane[member][i], i < n. */
static void blend_planes(const struct family *f, const struct family_stencil *st, size_t off, size_t n, int which,
    float *out)
{
	const float *p[FAMILY_STENCIL_MAX];
	for (int j = 0; j < st->n; j++) {
		const struct bake *b = f->bake[st->member[j]];
		p[j] = (which == 0 ? b->fr : which == 1 ? b->fr_err : b->fr_rgb) + off;
	}
	for (size_t i = 0; i < n; i++) {
		int pos = 1;
		for (int j = 0; j < st->n && pos; j++)
			pos = p[j][i] > 0.0f;
		double s = 0.0;
		for (int j = 0; j < st->n; j++) {
			double y = p[j][i];
			/* Errors are combined with |w|: an upper bound for the blend's error. */
			s += (which == 1 ? fabs(st->w[j]) : st->w[j]) * (pos && which != 1 ? log(y) : y);
		}
		out[i] = (float)(pos && which != 1 ? exp(s) : s);
	}
}

static double *dup(const double *v, int n)
{
	double *d = xmalloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
	memcpy(d, v, sizeof(double) * (size_t)n);
	return d;
}

struct bake *family_bake_at(const struct family *f, const double *x)
{
	CHECK(f->bake != NULL);
	const struct bake *b0 = f->bake[0];
	struct family_stencil st;
	family_stencil(f, x, &st);
	struct bake *b = xcalloc(1, sizeof *b);
	b->dir = xasprintf("%s (interpolated)", f->dir);
	b->preset = xstrdup(b0->preset ? b0->preset : "");
	b->n_wl = b0->n_wl;
	b->n_ti = b0->n_ti;
	b->n_to = b0->n_to;
	b->n_phi = b0->n_phi;
	b->wl_nm = dup(b0->wl_nm, b->n_wl);
	b->theta_i = dup(b0->theta_i, b->n_ti);
	b->theta_o = dup(b0->theta_o, b->n_to);
	b->phi = dup(b0->phi, b->n_phi);
	b->rgb_from_wl = dup(b0->rgb_from_wl, 3 * b->n_wl);
	size_t npx = (size_t)b->n_ti * b->n_to * b->n_phi;
	b->fr = xmalloc(sizeof(float) * npx * (size_t)b->n_wl);
	b->fr_err = xmalloc(sizeof(float) * npx * (size_t)b->n_wl);
	blend_planes(f, &st, 0, npx * (size_t)b->n_wl, 0, b->fr);
	blend_planes(f, &st, 0, npx * (size_t)b->n_wl, 1, b->fr_err);
	b->fr_rgb = xcalloc(npx * 3, sizeof(float));
	for (int c = 0; c < 3; c++)
		for (size_t i = 0; i < npx; i++) {
			double v = 0.0;
			for (int w = 0; w < b->n_wl; w++)
				v += b->rgb_from_wl[c * b->n_wl + w] * b->fr[(size_t)w * npx + i];
			b->fr_rgb[(size_t)c * npx + i] = (float)v;
		}
	/* Albedos, radii, index and roughness; the stacks of the heaviest member. */
	struct family_stencil loc = st;
	double v[FAMILY_STENCIL_MAX];
	for (int j = 0; j < st.n; j++)
		loc.member[j] = j;
	b->albedo = xcalloc((size_t)b->n_wl * b->n_ti, sizeof(double));
	b->albedo_rgb = xcalloc(3 * (size_t)b->n_ti, sizeof(double));
	b->sss_radius_cm = xcalloc((size_t)b->n_wl, sizeof(double));
	for (int i = 0; i < b->n_wl * b->n_ti; i++) {
		for (int j = 0; j < st.n; j++)
			v[j] = f->bake[st.member[j]]->albedo[i];
		b->albedo[i] = family_blend(&loc, v, 1);
	}
	for (int c = 0; c < 3; c++)
		for (int t = 0; t < b->n_ti; t++)
			for (int w = 0; w < b->n_wl; w++)
				b->albedo_rgb[c * b->n_ti + t] += b->rgb_from_wl[c * b->n_wl + w] * b->albedo[w * b->n_ti + t];
	for (int w = 0; w < b->n_wl; w++) {
		for (int j = 0; j < st.n; j++)
			v[j] = f->bake[st.member[j]]->sss_radius_cm[w];
		b->sss_radius_cm[w] = family_blend(&loc, v, 1);
	}
	for (int c = 0; c < 3; c++) {
		for (int j = 0; j < st.n; j++)
			v[j] = f->bake[st.member[j]]->sss_radius_rgb_cm[c];
		b->sss_radius_rgb_cm[c] = family_blend(&loc, v, 1);
	}
	int heavy = 0;
	for (int j = 0; j < st.n; j++) {
		b->ior += st.w[j] * f->bake[st.member[j]]->ior;
		b->roughness += st.w[j] * f->bake[st.member[j]]->roughness;
		b->macro_slope += st.w[j] * f->bake[st.member[j]]->macro_slope;
		if (st.w[j] > st.w[heavy])
			heavy = j;
	}
	if (b->macro_slope > 0.0) {	/* the members' mm-scale relief, blended as the roughness */
		b->macro = xmalloc(sizeof *b->macro);
		macro_rule_init(b->macro, b->macro_slope, MACRO_NQ);
	}
	b->stack = xmalloc(sizeof *b->stack * (size_t)b->n_wl);
	memcpy(b->stack, f->bake[st.member[heavy]]->stack, sizeof *b->stack * (size_t)b->n_wl);
	if (b0->points && b0->theta_o_nodes) {	/* point values: member 0's layout (the members' tables blend as values) */
		b->points = xmalloc(sizeof(int) * (size_t)b->n_wl);
		memcpy(b->points, b0->points, sizeof(int) * (size_t)b->n_wl);
		b->theta_o_nodes = dup(b0->theta_o_nodes, b->n_to);
		b->phi_nodes = dup(b0->phi_nodes, b->n_phi);
	}
	bake_prepare(b);
	return b;
}
