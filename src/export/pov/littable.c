/* littable: write the lit-table pigments (2-D, or 3-D with the light-view
 * angle; the two-light mixture) for a BRDF given as a function.  The pattern
 * facts used (slope/aoi values linear in angle, blend maps <= 256 entries)
 * were measured in /work/shared/notes/pov.md. */
#include "config.h"

#include "export/pov/littable.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine/specular.h"
#include "export/pov/sdl.h"
#include "export/pov/vec3.h"

void littable_light_dir(const struct pov_light *l, const double p[3], double out[3])
{
	if (l->parallel)
		memcpy(out, l->dir, sizeof l->dir);
	else
		vec3_unit_toward(p, l->pos, out);
}

void littable_view_dir(const struct pov_view *v, const double p[3], double out[3])
{
	if (v->ortho)
		memcpy(out, v->dir, sizeof v->dir);
	else
		vec3_unit_toward(p, v->pos, out);
}

void littable_brdf_analytic(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3])
{
	static const double rho[3] = { 0.62, 0.42, 0.33 };
	const double n = 1.4, a2 = 0.35 * 0.35;
	(void)ctx;
	double ci = cos(theta_i), co = cos(theta_o);
	double wi[3] = { sin(theta_i), 0, ci }, wo[3] = { sin(theta_o) * cos(dphi), sin(theta_o) * sin(dphi), co };
	double h[3] = { wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2] }, hn = sqrt(vec3_dot(h, h));
	double t = (1 - specular_schlick(ci, n)) * (1 - specular_schlick(co, n)) / M_PI, spec = 0;
	if (hn > 1e-12 && ci > 1e-6 && co > 1e-6) {
		double ch = h[2] / hn, cd = vec3_dot(wi, h) / hn;
		spec = specular_schlick(cd, n) * specular_ggx_d(ch, a2) * specular_smith_g1(ci, a2)
		    * specular_smith_g1(co, a2) / (4 * ci * co);
	}
	for (int c = 0; c < 3; c++)
		rgb[c] = rho[c] * t + spec;
}

double littable_cos_gamma(const struct pov_light *l, const struct pov_view *v, const double p[3])
{
	double a[3], b[3];
	littable_light_dir(l, p, a);
	littable_view_dir(v, p, b);
	return vec3_dot(a, b);
}

double littable_dphi(double theta_i, double theta_o, double cos_gamma)
{
	double ss = sin(theta_i) * sin(theta_o);
	if (ss < 1e-9)
		return 0.0;	/* at the pole delta_phi does not matter */
	double c = (cos_gamma - cos(theta_i) * cos(theta_o)) / ss;
	return acos(c < -1 ? -1 : c > 1 ? 1 : c);
}

void littable_cos_gamma_range(const struct pov_light *l, const struct pov_view *v, const double lo[3],
    const double hi[3], double *cmin, double *cmax)
{
	*cmin = 2;
	*cmax = -2;
	for (int i = 0; i <= 8; i++)
		for (int j = 0; j <= 8; j++)
			for (int k = 0; k <= 8; k++) {
				double p[3] = { lo[0] + (hi[0] - lo[0]) * i / 8, lo[1] + (hi[1] - lo[1]) * j / 8,
					lo[2] + (hi[2] - lo[2]) * k / 8 };
				double c = littable_cos_gamma(l, v, p);
				*cmin = fmin(*cmin, c);
				*cmax = fmax(*cmax, c);
			}
}

int littable_axis(const double *hint, int n_hint, int n, double *out)
{
	int m = 0;
	out[m++] = 0;
	if (n_hint + 2 <= n)
		for (int i = 0; i < n_hint; i++)
			if (hint[i] > 1e-6 && hint[i] < M_PI / 2 - 1e-6)
				out[m++] = hint[i];
	out[m++] = M_PI / 2;
	/* sort (small n) and drop duplicates */
	for (int i = 1; i < m; i++)
		for (int j = i; j > 0 && out[j - 1] > out[j]; j--) {
			double t = out[j];
			out[j] = out[j - 1];
			out[j - 1] = t;
		}
	int u = 1;
	for (int i = 1; i < m; i++)
		if (out[i] - out[u - 1] > 1e-6)
			out[u++] = out[i];
	m = u;
	while (m < n) {
		int g = 0;
		for (int i = 1; i < m - 1; i++)
			if (out[i + 1] - out[i] > out[g + 1] - out[g] + 1e-12)
				g = i;
		memmove(&out[g + 2], &out[g + 1], sizeof(double) * (size_t)(m - g - 1));
		out[g + 1] = 0.5 * (out[g] + out[g + 2]);
		m++;
	}
	return m;
}

/* The theta_i and theta_o axes of a table for f. */
struct axes {
	int n_ti, n_to;
	double ti[LITTABLE_MAX_NODES], to[LITTABLE_MAX_NODES];	/* ascending [rad] */
};

static void make_axes(const struct pov_brdf *f, int n, struct axes *a)
{
	a->n_ti = littable_axis(f->ti_hint, f->n_ti_hint, n, a->ti);
	a->n_to = littable_axis(f->to_hint, f->n_to_hint, n, a->to);
}

/* `aoi color_map { ... }` for one theta_i row at fixed cos gamma.  The extra
 * entry at 0 covers aoi < 0.5 (theta_o > 90 degrees on bumped or
 * interpolated normals). */
static void aoi_row(FILE *fp, const struct pov_brdf *f, double ti, double cg, const struct axes *a)
{
	fputs("aoi color_map {", fp);
	for (int m = 0; m < a->n_to; m++) {
		double to = a->to[a->n_to - 1 - m], rgb[3]; /* descending angle: ascending aoi */
		f->f_rgb(f->ctx, ti, to, littable_dphi(ti, to, cg), rgb);
		for (int c = 0; c < 3; c++)
			rgb[c] *= M_PI;
		sdl_aoi_entry(fp, m == 0, to, rgb);
	}
	fputs(" }", fp);
}

static void slope_head(FILE *fp, const struct pov_light *l)
{
	if (l->parallel) {
		fputs("slope { ", fp);
		sdl_vec(fp, l->dir);
	} else {
		fputs("slope { point_at ", fp);
		sdl_vec(fp, l->pos);
	}
	fputs(" }", fp);
}

/* slope x aoi at one cos gamma.  Rows only for theta_i <= 90 degrees:
 * values below the first entry take its colour, and POV-Ray's diffuse term
 * is zero there anyway. */
static void table_2d(FILE *fp, const struct pov_brdf *f, const struct pov_light *l, double cg, const struct axes *a)
{
	slope_head(fp, l);
	fputs(" pigment_map {\n", fp);
	for (int k = 0; k < a->n_ti; k++) {
		double ti = a->ti[a->n_ti - 1 - k];
		fprintf(fp, "  [%.8f ", 1 - ti / M_PI);
		aoi_row(fp, f, ti, cg, a);
		fputs("]\n", fp);
	}
	fputs(" }", fp);
}

/* One component of a unit vector toward the light or camera as an SDL
 * expression in x, y, z (texture space = world space: the exporter
 * attaches textures after object transforms). */
static void dir_expr(char *buf, size_t len, int fixed, const double fixed_dir[3], const double pos[3], int i)
{
	static const char axis[] = "xyz";
	if (fixed)
		snprintf(buf, len, "(" SDL_G ")", fixed_dir[i]);
	else
		snprintf(buf, len, "(" SDL_G "-%c)", pos[i], axis[i]);
}

static void gamma_function(FILE *fp, const struct pov_light *l, const struct pov_view *v)
{
	char a[3][64], b[3][64];
	for (int i = 0; i < 3; i++) {
		dir_expr(a[i], sizeof a[i], l->parallel, l->dir, l->pos, i);
		dir_expr(b[i], sizeof b[i], v->ortho, v->dir, v->pos, i);
	}
	fprintf(fp, "function { 0.5+0.5*(%s*%s+%s*%s+%s*%s)", a[0], b[0], a[1], b[1], a[2], b[2]);
	if (!l->parallel)
		fprintf(fp, "/sqrt(%s*%s+%s*%s+%s*%s)", a[0], a[0], a[1], a[1], a[2], a[2]);
	if (!v->ortho)
		fprintf(fp, "/sqrt(%s*%s+%s*%s+%s*%s)", b[0], b[0], b[1], b[1], b[2], b[2]);
	fputs(" }", fp);
}

int littable_write_key(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light *l,
    const struct pov_view *v, const double lo[3], const double hi[3], int n_theta, int n_gamma)
{
	double cmin, cmax;
	struct axes ax;
	make_axes(f, n_theta, &ax);
	littable_cos_gamma_range(l, v, lo, hi, &cmin, &cmax);
	double gspan = acos(fmax(-1, fmin(1, cmin))) - acos(fmax(-1, fmin(1, cmax)));
	fprintf(fp, "#declare %s = pigment {\n", name);
	if (gspan < 0.05 * M_PI / 180 || n_gamma < 2) {
		fprintf(fp, " // one light-view angle: gamma = %.4f deg\n ", acos(0.5 * (cmin + cmax)) * 180 / M_PI);
		table_2d(fp, f, l, 0.5 * (cmin + cmax), &ax);
		fputs("\n}\n", fp);
		return 1;
	}
	/* Uniform nodes in the pattern value 0.5 + 0.5 cos(gamma), padded a
	 * little so the sampled range is covered. */
	double vlo = 0.5 + 0.5 * cmin, vhi = 0.5 + 0.5 * cmax, pad = 0.02 * (vhi - vlo) + 1e-5;
	vlo = fmax(0, vlo - pad);
	vhi = fmin(1, vhi + pad);
	fprintf(fp, " // gamma axis: %.4f to %.4f deg over %d nodes\n ", acos(2 * vhi - 1) * 180 / M_PI,
	    acos(2 * vlo - 1) * 180 / M_PI, n_gamma);
	gamma_function(fp, l, v);
	fputs(" pigment_map {\n", fp);
	for (int g = 0; g < n_gamma; g++) {
		double val = vlo + (vhi - vlo) * g / (n_gamma - 1);
		fprintf(fp, " [%.8f ", val);
		table_2d(fp, f, l, 2 * val - 1, &ax);
		fputs("]\n", fp);
	}
	fputs(" }\n}\n", fp);
	return n_gamma;
}

void littable_mixture_value(const struct pov_brdf *f, const struct pov_light l[2], const double ti[2], double to,
    const double cg[2], double val[3])
{
	double num[3] = { 0 }, den[3] = { 0 }, avg[3] = { 0 };
	for (int j = 0; j < 2; j++) {
		double fj[3], cj = cos(ti[j]);
		f->f_rgb(f->ctx, ti[j], to, littable_dphi(ti[j], to, cg[j]), fj);
		for (int c = 0; c < 3; c++) {
			num[c] += l[j].rgb[c] * cj * fj[c];
			den[c] += l[j].rgb[c] * cj;
			avg[c] += 0.5 * fj[c];
		}
	}
	for (int c = 0; c < 3; c++)
		val[c] = M_PI * (den[c] > 1e-12 ? num[c] / den[c] : avg[c]);
}

void littable_write_mixture(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light l[2],
    const struct pov_view *v, const double lo[3], const double hi[3], int n, double *gamma_spread)
{
	double cg[2], mid[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
	struct axes ax;
	make_axes(f, n, &ax);
	*gamma_spread = 0;
	for (int k = 0; k < 2; k++) {
		double cmin, cmax;
		cg[k] = littable_cos_gamma(&l[k], v, mid);
		littable_cos_gamma_range(&l[k], v, lo, hi, &cmin, &cmax);
		*gamma_spread = fmax(*gamma_spread, acos(fmax(-1, fmin(1, cmin))) - acos(fmax(-1, fmin(1, cmax))));
	}
	fprintf(fp, "#declare %s = pigment {\n // two-light mixture: gamma = %.4f, %.4f deg\n ", name,
	    acos(cg[0]) * 180 / M_PI, acos(cg[1]) * 180 / M_PI);
	slope_head(fp, &l[0]);
	fputs(" pigment_map {\n", fp);
	for (int k1 = 0; k1 < ax.n_ti; k1++) {
		double t1 = ax.ti[ax.n_ti - 1 - k1];
		fprintf(fp, " [%.8f ", 1 - t1 / M_PI);
		slope_head(fp, &l[1]);
		fputs(" pigment_map {\n", fp);
		for (int k2 = 0; k2 < ax.n_ti; k2++) {
			double t2 = ax.ti[ax.n_ti - 1 - k2], ti[2] = { t1, t2 };
			fprintf(fp, "  [%.8f aoi color_map {", 1 - t2 / M_PI);
			for (int m = 0; m < ax.n_to; m++) {
				double to = ax.to[ax.n_to - 1 - m], val[3];
				littable_mixture_value(f, l, ti, to, cg, val);
				sdl_aoi_entry(fp, m == 0, to, val);
			}
			fputs(" }]\n", fp);
		}
		fputs(" }]\n", fp);
	}
	fputs(" }\n}\n", fp);
}
