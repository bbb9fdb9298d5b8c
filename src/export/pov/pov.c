/* pov: write POV-Ray 3.7 SDL that evaluates a baked BRDF: lit tables (2-D,
 * or 3-D with the light-view angle), two-light mixture tables, per-light
 * passes with a combining scene, the separable fallback, bump maps, and the
 * scene itself.  The pattern facts used (slope/aoi values linear in angle,
 * blend maps <= 256 entries, bump_size per pixel, uv-mapped bumps wrong on
 * rotated meshes) were measured in /work/shared/notes/pov.md. */
#include "config.h"

#include "export/pov/pov.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

/* Numbers in SDL: %.9g keeps doubles well past 16-bit output precision. */
#define G "%.7g"

static double dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void unit_toward(const double from[3], const double to[3], double out[3])
{
	double d[3] = { to[0] - from[0], to[1] - from[1], to[2] - from[2] };
	double n = sqrt(dot3(d, d));
	for (int i = 0; i < 3; i++)
		out[i] = n > 0 ? d[i] / n : 0;
}

static void light_dir_at(const struct pov_light *l, const double p[3], double out[3])
{
	if (l->parallel)
		memcpy(out, l->dir, sizeof l->dir);
	else
		unit_toward(p, l->pos, out);
}

static void view_dir_at(const struct pov_view *v, const double p[3], double out[3])
{
	if (v->ortho)
		memcpy(out, v->dir, sizeof v->dir);
	else
		unit_toward(p, v->pos, out);
}

static double schlick(double c, double n)
{
	double r0 = (n - 1) / (n + 1);
	r0 *= r0;
	return r0 + (1 - r0) * pow(1 - c, 5);
}

static double smith_g1(double c, double a2)
{
	return 2 * c / (c + sqrt(a2 + (1 - a2) * c * c));
}

void pov_brdf_analytic(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3])
{
	static const double rho[3] = { 0.62, 0.42, 0.33 };
	const double n = 1.4, a2 = 0.35 * 0.35;
	(void)ctx;
	double ci = cos(theta_i), co = cos(theta_o);
	double wi[3] = { sin(theta_i), 0, ci }, wo[3] = { sin(theta_o) * cos(dphi), sin(theta_o) * sin(dphi), co };
	double h[3] = { wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2] }, hn = sqrt(dot3(h, h));
	double t = (1 - schlick(ci, n)) * (1 - schlick(co, n)) / M_PI, spec = 0;
	if (hn > 1e-12 && ci > 1e-6 && co > 1e-6) {
		double ch = h[2] / hn, cd = dot3(wi, h) / hn, q = ch * ch * (a2 - 1) + 1;
		double d = a2 / (M_PI * q * q);
		spec = schlick(cd, n) * d * smith_g1(ci, a2) * smith_g1(co, a2) / (4 * ci * co);
	}
	for (int c = 0; c < 3; c++)
		rgb[c] = rho[c] * t + spec;
}

double pov_cos_gamma(const struct pov_light *l, const struct pov_view *v, const double p[3])
{
	double a[3], b[3];
	light_dir_at(l, p, a);
	view_dir_at(v, p, b);
	return dot3(a, b);
}

double pov_dphi(double theta_i, double theta_o, double cos_gamma)
{
	double ss = sin(theta_i) * sin(theta_o);
	if (ss < 1e-9)
		return 0.0;	/* at the pole delta_phi does not matter */
	double c = (cos_gamma - cos(theta_i) * cos(theta_o)) / ss;
	return acos(c < -1 ? -1 : c > 1 ? 1 : c);
}

void pov_cos_gamma_range(const struct pov_light *l, const struct pov_view *v, const double lo[3],
    const double hi[3], double *cmin, double *cmax)
{
	*cmin = 2, *cmax = -2;
	for (int i = 0; i <= 8; i++)
		for (int j = 0; j <= 8; j++)
			for (int k = 0; k <= 8; k++) {
				double p[3] = { lo[0] + (hi[0] - lo[0]) * i / 8, lo[1] + (hi[1] - lo[1]) * j / 8,
					lo[2] + (hi[2] - lo[2]) * k / 8 };
				double c = pov_cos_gamma(l, v, p);
				*cmin = fmin(*cmin, c);
				*cmax = fmax(*cmax, c);
			}
}

static void put_rgb(FILE *fp, const double c[3])
{
	fprintf(fp, "rgb <" G "," G "," G ">", c[0], c[1], c[2]);
}

/* One aoi color_map entry for exit angle to [rad]; the first entry of a
 * map (first = 1) also pins the value at aoi 0, below grazing. */
static void put_aoi_entry(FILE *fp, int first, double to, const double rgb[3])
{
	if (first) {
		fputs(" [0 ", fp);
		put_rgb(fp, rgb);
		fputs("]", fp);
	}
	fprintf(fp, " [%.8f ", 1 - to / M_PI);
	put_rgb(fp, rgb);
	fputs("]", fp);
}

static void put_vec(FILE *fp, const double v[3])
{
	fprintf(fp, "<" G "," G "," G ">", v[0], v[1], v[2]);
}

int pov_axis(const double *hint, int n_hint, int n, double *out)
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
			out[j] = out[j - 1], out[j - 1] = t;
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
	double ti[POV_MAX_NODES], to[POV_MAX_NODES];	/* ascending [rad] */
};

static void make_axes(const struct pov_brdf *f, int n, struct axes *a)
{
	a->n_ti = pov_axis(f->ti_hint, f->n_ti_hint, n, a->ti);
	a->n_to = pov_axis(f->to_hint, f->n_to_hint, n, a->to);
}

/* `aoi color_map { ... }` for one theta_i row at fixed cos gamma.  The extra
 * entry at 0 covers aoi < 0.5 (theta_o > 90 degrees on bumped or
 * interpolated normals). */
static void aoi_row(FILE *fp, const struct pov_brdf *f, double ti, double cg, const struct axes *a)
{
	fputs("aoi color_map {", fp);
	for (int m = 0; m < a->n_to; m++) {
		double to = a->to[a->n_to - 1 - m], rgb[3]; /* descending angle: ascending aoi */
		f->f_rgb(f->ctx, ti, to, pov_dphi(ti, to, cg), rgb);
		for (int c = 0; c < 3; c++)
			rgb[c] *= M_PI;
		put_aoi_entry(fp, m == 0, to, rgb);
	}
	fputs(" }", fp);
}

static void slope_head(FILE *fp, const struct pov_light *l)
{
	if (l->parallel) {
		fputs("slope { ", fp);
		put_vec(fp, l->dir);
	} else {
		fputs("slope { point_at ", fp);
		put_vec(fp, l->pos);
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
		snprintf(buf, len, "(" G ")", fixed_dir[i]);
	else
		snprintf(buf, len, "(" G "-%c)", pos[i], axis[i]);
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

int pov_write_key_pigment(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light *l,
    const struct pov_view *v, const double lo[3], const double hi[3], int n_theta, int n_gamma)
{
	double cmin, cmax;
	struct axes ax;
	make_axes(f, n_theta, &ax);
	pov_cos_gamma_range(l, v, lo, hi, &cmin, &cmax);
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
	vlo = fmax(0, vlo - pad), vhi = fmin(1, vhi + pad);
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

void pov_write_mixture_pigment(FILE *fp, const char *name, const struct pov_brdf *f, const struct pov_light l[2],
    const struct pov_view *v, const double lo[3], const double hi[3], int n, double *gamma_spread)
{
	double cg[2], mid[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
	struct axes ax;
	make_axes(f, n, &ax);
	*gamma_spread = 0;
	for (int k = 0; k < 2; k++) {
		double cmin, cmax;
		cg[k] = pov_cos_gamma(&l[k], v, mid);
		pov_cos_gamma_range(&l[k], v, lo, hi, &cmin, &cmax);
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
				double to = ax.to[ax.n_to - 1 - m], num[3] = { 0 }, den[3] = { 0 }, avg[3] = { 0 }, val[3];
				for (int j = 0; j < 2; j++) {
					double fj[3], cj = cos(ti[j]);
					f->f_rgb(f->ctx, ti[j], to, pov_dphi(ti[j], to, cg[j]), fj);
					for (int c = 0; c < 3; c++) {
						num[c] += l[j].rgb[c] * cj * fj[c];
						den[c] += l[j].rgb[c] * cj;
						avg[c] += 0.5 * fj[c];
					}
				}
				for (int c = 0; c < 3; c++)
					val[c] = M_PI * (den[c] > 1e-12 ? num[c] / den[c] : avg[c]);
				put_aoi_entry(fp, m == 0, to, val);
			}
			fputs(" }]\n", fp);
		}
		fputs(" }]\n", fp);
	}
	fputs(" }\n}\n", fp);
}

/* Squared error of the separable model with brilliance b; fills a[][]
 * (the optimal pigment for that b, in closed form per theta_o node and
 * channel) and the target's squared norm. */
#define SEP_NI 24
/* Fit and error over theta_i, theta_o <= 80 degrees: toward grazing the
 * specular lobe grows without bound (1/cos) and would decide everything,
 * while it covers only silhouettes and terminators in an image. */
#define SEP_TMAX (80 * M_PI / 180)
#define SEP_NP 24
static double sep_error(const double *t, double b, double a[POV_SEP_NODES][3], double *norm, double *mean_rel)
{
	double err = 0, tn = 0, ea = 0, ta = 0;
	for (int m = 0; m < POV_SEP_NODES; m++) {
		double to = (M_PI / 2) * m / (POV_SEP_NODES - 1), wo = fmax(sin(to), 1e-3);
		for (int c = 0; c < 3; c++) {
			double num = 0, den = 0;
			for (int i = 0; i < SEP_NI; i++) {
				double ti = (i + 0.5) * SEP_TMAX / SEP_NI, ci = cos(ti), w = sin(ti), cb = pow(ci, b);
				for (int p = 0; p < SEP_NP; p++) {
					double tv = t[((m * SEP_NI + i) * SEP_NP + p) * 3 + c];
					num += w * tv * cb;
					den += w * cb * cb;
				}
			}
			a[m][c] = num / den;
			for (int i = 0; i < SEP_NI; i++) {
				double ti = (i + 0.5) * SEP_TMAX / SEP_NI, ci = cos(ti), w = sin(ti) * wo * (to <= SEP_TMAX);
				for (int p = 0; p < SEP_NP; p++) {
					double tv = t[((m * SEP_NI + i) * SEP_NP + p) * 3 + c], d = a[m][c] * pow(ci, b) - tv;
					err += w * d * d;
					tn += w * tv * tv;
					ea += w * fabs(d);
					ta += w * fabs(tv);
				}
			}
		}
	}
	*norm = tn;
	*mean_rel = ta > 0 ? ea / ta : 0;
	return err;
}

void pov_fit_separable(const struct pov_brdf *f, struct pov_separable *out)
{
	/* Target pi f cos(theta_i) on a grid over both hemispheres, weighted
	 * by solid angle (sin theta_i sin theta_o). */
	double *t = xmalloc(sizeof(double) * POV_SEP_NODES * SEP_NI * SEP_NP * 3);
	for (int m = 0; m < POV_SEP_NODES; m++)
		for (int i = 0; i < SEP_NI; i++)
			for (int p = 0; p < SEP_NP; p++) {
				double to = (M_PI / 2) * m / (POV_SEP_NODES - 1), ti = (i + 0.5) * SEP_TMAX / SEP_NI;
				double dp = (p + 0.5) * M_PI / SEP_NP, rgb[3];
				f->f_rgb(f->ctx, ti, to, dp, rgb);
				for (int c = 0; c < 3; c++)
					t[((m * SEP_NI + i) * SEP_NP + p) * 3 + c] = M_PI * rgb[c] * cos(ti);
			}
	/* Golden-section search for the brilliance. */
	double lo = 0.3, hi = 4.0, gr = 0.5 * (sqrt(5) - 1), norm, mr;
	double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
	double e1 = sep_error(t, x1, out->a, &norm, &mr), e2 = sep_error(t, x2, out->a, &norm, &mr);
	for (int it = 0; it < 40; it++) {
		if (e1 < e2) {
			hi = x2, x2 = x1, e2 = e1, x1 = hi - gr * (hi - lo);
			e1 = sep_error(t, x1, out->a, &norm, &mr);
		} else {
			lo = x1, x1 = x2, e1 = e2, x2 = lo + gr * (hi - lo);
			e2 = sep_error(t, x2, out->a, &norm, &mr);
		}
	}
	out->brilliance = 0.5 * (lo + hi);
	double e = sep_error(t, out->brilliance, out->a, &norm, &out->mean);
	out->rms = norm > 0 ? sqrt(e / norm) : 0;
	free(t);
}

void pov_write_separable_pigment(FILE *fp, const char *name, const struct pov_separable *sep)
{
	fprintf(fp, "#declare %s = pigment { // separable fit: brilliance %.4f, mean error %.1f %%, rms %.1f %%\n"
	    " aoi color_map {", name, sep->brilliance, 100 * sep->mean, 100 * sep->rms);
	for (int k = 0; k < POV_SEP_NODES; k++) {
		int m = POV_SEP_NODES - 1 - k;
		double to = (M_PI / 2) * m / (POV_SEP_NODES - 1);
		put_aoi_entry(fp, k == 0, to, sep->a[m]);
	}
	fputs(" }\n}\n", fp);
}

double pov_bump_size(double h_range_um, int n_px, double tile_mm)
{
	return h_range_um * 1e-3 * n_px / tile_mm;
}

uint16_t *pov_filter_height(const uint16_t *px, int n, double h_min, double h_max, int f, double *o_min,
    double *o_max)
{
	int m = n / f;
	double *h = xmalloc(sizeof(double) * (size_t)m * m), scale = (h_max - h_min) / 65535.0;
	*o_min = INFINITY, *o_max = -INFINITY;
	for (int y = 0; y < m; y++)
		for (int x = 0; x < m; x++) {
			double sum = 0;
			for (int j = 0; j < f; j++)
				for (int i = 0; i < f; i++)
					sum += px[(size_t)(y * f + j) * n + x * f + i];
			double v = h_min + scale * sum / (f * f);
			h[y * m + x] = v;
			*o_min = fmin(*o_min, v);
			*o_max = fmax(*o_max, v);
		}
	uint16_t *out = xmalloc(sizeof(uint16_t) * (size_t)m * m);
	double range = *o_max - *o_min;
	for (int i = 0; i < m * m; i++)
		out[i] = range > 0 ? (uint16_t)lround((h[i] - *o_min) / range * 65535.0) : 0;
	free(h);
	return out;
}

int pov_filter_factor(int n, double texel_units, double pixel_units)
{
	int f = 1;
	while (texel_units * f * 4 <= pixel_units && n % (f * 2) == 0 && n / (f * 2) >= 16)
		f *= 2;
	return f;
}

/* ---- scene export ---- */

void pov_report_free(struct pov_report *r)
{
	for (int i = 0; i < r->n_files; i++)
		free(r->files[i]);
	r->n_files = 0;
}

enum scene_strategy pov_strategy(const struct scene *s)
{
	if (s->lights_strategy != SCENE_LIGHTS_AUTO)
		return s->lights_strategy;
	return s->n_lights == 1 ? SCENE_LIGHTS_KEY : s->n_lights == 2 ? SCENE_LIGHTS_MIXTURE : SCENE_LIGHTS_PASSES;
}

static void to_pov_light(const struct scene_light *sl, struct pov_light *l)
{
	*l = (struct pov_light){ .parallel = sl->type == SCENE_LIGHT_PARALLEL };
	memcpy(l->pos, sl->position, sizeof l->pos);
	memcpy(l->rgb, sl->color, sizeof l->rgb);
	double o[3] = { 0, 0, 0 };
	scene_light_dir(sl, o, l->dir);
}

static void to_pov_view(const struct scene_camera *c, struct pov_view *v)
{
	*v = (struct pov_view){ .ortho = c->ortho };
	memcpy(v->pos, c->location, sizeof v->pos);
	unit_toward(c->look_at, c->location, v->dir);
}

/* Bounds of the objects that use skin k (the region the gamma axis must
 * cover). */
static int skin_bounds(const struct scene *s, int k, double lo[3], double hi[3])
{
	int any = 0;
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		double a[3], b[3];
		if (o->material != SCENE_MAT_SKIN || o->skin != k)
			continue;
		scene_object_bounds(o, a, b);
		for (int j = 0; j < 3; j++) {
			lo[j] = any ? fmin(lo[j], a[j]) : a[j];
			hi[j] = any ? fmax(hi[j], b[j]) : b[j];
		}
		any = 1;
	}
	if (!any) /* include-only export: around the look_at point */
		for (int j = 0; j < 3; j++)
			lo[j] = s->camera.look_at[j] - 1, hi[j] = s->camera.look_at[j] + 1;
	return any;
}

/* SDL identifiers: POV-Ray needs a leading letter; names are [A-Za-z0-9_]. */
static char *ident(const char *base)
{
	char *s = xasprintf("Skinbake_%s", base);
	for (char *c = s; *c; c++)
		if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9')))
			*c = '_';
	return s;
}

static void write_light(FILE *fp, const struct scene_light *l)
{
	fprintf(fp, "#declare SKIN_Light_%s = light_source { ", l->name);
	put_vec(fp, l->position);
	fputs(" color ", fp);
	put_rgb(fp, l->color);
	if (l->type == SCENE_LIGHT_PARALLEL) {
		fputs(" parallel point_at ", fp);
		put_vec(fp, l->point_at);
	}
	if (l->area_size > 0)
		fprintf(fp, "\n  area_light <" G ",0,0>, <0," G ",0>, %d, %d adaptive 1 circular orient", l->area_size,
		    l->area_size, l->area_samples, l->area_samples);
	fputs(" }\n", fp);
}

#define FINISH_LIT "diffuse 1 brilliance 1 ambient 0 emission 0 specular 0"

static void write_include(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const struct pov_options *o, enum scene_strategy st, struct pov_report *r)
{
	char *guard = ident(o->base);
	struct pov_view v;
	to_pov_view(&s->camera, &v);
	fprintf(fp, "// Generated by skinbake " PACKAGE_VERSION " from %s: baked skin BRDF as POV-Ray lit tables.\n"
	    "// Lights strategy: %s.  The pigments hold pi*f_r; they are right only with the\n"
	    "// SKIN_Light_* lights below and the camera of the scene (see docs/pov.md).\n",
	    s->path ? s->path : "the command line", scene_strategy_name(st));
	fprintf(fp, "#ifndef (%s_Inc)\n#declare %s_Inc = 1;\n#local Skinbake_Saved_Version = version;\n"
	    "#version 3.7;\n\n", guard, guard);
	for (int i = 0; i < s->n_lights; i++)
		write_light(fp, &s->lights[i]);
	fputs("\n", fp);
	struct pov_light pl[SCENE_MAX_LIGHTS];
	for (int i = 0; i < s->n_lights; i++)
		to_pov_light(&s->lights[i], &pl[i]);
	r->n_gamma_used = 1;
	for (int k = 0; k < s->n_skins; k++) {
		const struct scene_skin *sk = &s->skins[k];
		const struct pov_skin *ps = &skins[k];
		double lo[3], hi[3];
		char *nm;
		skin_bounds(s, k, lo, hi);
		fprintf(fp, "// ---- skin '%s' (preset %s) ----\n", sk->name, sk->preset);
		fprintf(fp, "#declare SKIN_%s_Finish = finish { " FINISH_LIT, sk->name);
		if (sk->reflection)
			fputs(" reflection { 0, 1 fresnel on } conserve_energy", fp);
		fputs(" }\n", fp);
		fprintf(fp, "#declare SKIN_%s_Interior = interior { ior " G " }\n", sk->name, ps->ior);
		if (st == SCENE_LIGHTS_KEY) {
			nm = xasprintf("SKIN_%s_Pigment", sk->name);
			int g = pov_write_key_pigment(fp, nm, &ps->brdf, &pl[0], &v, lo, hi, o->n_theta, o->n_gamma);
			r->n_gamma_used = g > r->n_gamma_used ? g : r->n_gamma_used;
			free(nm);
		} else if (st == SCENE_LIGHTS_MIXTURE) {
			double spread;
			nm = xasprintf("SKIN_%s_Pigment", sk->name);
			pov_write_mixture_pigment(fp, nm, &ps->brdf, pl, &v, lo, hi, o->n_mix, &spread);
			r->mix_gamma_spread = fmax(r->mix_gamma_spread, spread);
			free(nm);
		}
		if (st == SCENE_LIGHTS_PASSES)
			for (int i = 0; i < s->n_lights; i++) {
				nm = xasprintf("SKIN_%s_Pigment_%s", sk->name, s->lights[i].name);
				int g = pov_write_key_pigment(fp, nm, &ps->brdf, &pl[i], &v, lo, hi, o->n_theta,
				    o->n_gamma);
				r->n_gamma_used = g > r->n_gamma_used ? g : r->n_gamma_used;
				free(nm);
			}
		if (st == SCENE_LIGHTS_PASSES || st == SCENE_LIGHTS_SEPARABLE) {
			struct pov_separable sep;
			pov_fit_separable(&ps->brdf, &sep);
			r->sep_rms = fmax(r->sep_rms, sep.rms);
			r->sep_mean = fmax(r->sep_mean, sep.mean);
			nm = xasprintf("SKIN_%s_Pigment%s", sk->name, st == SCENE_LIGHTS_PASSES ? "_Separable" : "");
			pov_write_separable_pigment(fp, nm, &sep);
			free(nm);
			fprintf(fp, "#declare SKIN_%s_Finish_Separable = finish { diffuse 1 brilliance %.6f ambient 0 "
			    "emission 0 specular 0%s }\n", sk->name, sep.brilliance,
			    sk->reflection ? " reflection { 0, 1 fresnel on } conserve_energy" : "");
		}
		if (ps->height_png != NULL)
			fprintf(fp, "// bump_size = H_range * n_px / tile = " G "; one tile = " G " units, planar\n"
			    "// (map_type 0) projection along z: attach with the object's or the view's orientation.\n"
			    "#declare SKIN_%s_Normal = normal { bump_map { png \"%s\" map_type 0 interpolate 2 "
			    "bump_size " G " } scale " G " }\n", ps->bump_size, ps->tile_units, sk->name, ps->height_png,
			    ps->bump_size, ps->tile_units);
		/* Stand-ins for comparison scenes (paper figure 7): the skin's
		 * normal-incidence albedo as Lambert and as Phong. */
		fprintf(fp, "#declare SKIN_%s_Lambert = texture { pigment { ", sk->name);
		put_rgb(fp, ps->albedo_rgb);
		fputs(" } finish { " FINISH_LIT " } }\n", fp);
		fprintf(fp, "#declare SKIN_%s_Phong = texture { pigment { ", sk->name);
		put_rgb(fp, ps->albedo_rgb);
		fputs(" } finish { " FINISH_LIT " phong 0.5 phong_size 40 } }\n\n", fp);
	}
	fputs("#version Skinbake_Saved_Version;\n#end\n", fp);
	free(guard);
}

static void write_camera(FILE *fp, const struct scene *s)
{
	const struct scene_camera *c = &s->camera;
	double aspect = (double)s->width / s->height;
	if (c->ortho)
		fprintf(fp, "camera { orthographic location ");
	else
		fprintf(fp, "camera { perspective location ");
	put_vec(fp, c->location);
	fputs(" look_at ", fp);
	put_vec(fp, c->look_at);
	if (c->ortho)
		fprintf(fp, " right x*" G " up y*" G " }\n", c->width, c->width / aspect);
	else
		fprintf(fp, " right x*" G " up y angle " G " }\n", aspect, c->angle * 180 / M_PI);
}

/* Rows of a matrix taking z to the unit vector d (and x, y to a right-handed
 * frame around it): planar bump maps project along z. */
static void write_align(FILE *fp, const double d[3])
{
	double up[3] = { 0, 1, 0 }, u[3], w[3], n;
	if (fabs(d[1]) > 0.99)
		up[1] = 0, up[2] = 1;
	u[0] = up[1] * d[2] - up[2] * d[1], u[1] = up[2] * d[0] - up[0] * d[2], u[2] = up[0] * d[1] - up[1] * d[0];
	n = sqrt(dot3(u, u));
	for (int i = 0; i < 3; i++)
		u[i] /= n;
	w[0] = d[1] * u[2] - d[2] * u[1], w[1] = d[2] * u[0] - d[0] * u[2], w[2] = d[0] * u[1] - d[1] * u[0];
	fprintf(fp, " matrix <" G "," G "," G ", " G "," G "," G ", " G "," G "," G ", 0,0,0>", u[0], u[1], u[2], w[0], w[1],
	    w[2], d[0], d[1], d[2]);
}

static void write_xform(FILE *fp, const struct scene_object *o)
{
	if (o->scale != 1)
		fprintf(fp, " scale " G, o->scale);
	if (o->rotate[0] != 0 || o->rotate[1] != 0 || o->rotate[2] != 0)
		fprintf(fp, " rotate <" G "," G "," G ">", o->rotate[0] * 180 / M_PI, o->rotate[1] * 180 / M_PI,
		    o->rotate[2] * 180 / M_PI);
	if (o->translate[0] != 0 || o->translate[1] != 0 || o->translate[2] != 0) {
		fputs(" translate ", fp);
		put_vec(fp, o->translate);
	}
}

static void write_shape(FILE *fp, const struct scene_object *o)
{
	double h[3] = { 0.5 * o->size[0], 0.5 * o->size[1], 0.5 * o->size[2] };
	switch (o->shape) {
	case SCENE_SPHERE:
		fputs("sphere { ", fp);
		put_vec(fp, o->center);
		fprintf(fp, ", " G, o->radius);
		break;
	case SCENE_BOX:
		fprintf(fp, "box { <" G "," G "," G ">, <" G "," G "," G "> translate ", -h[0], -h[1], -h[2], h[0], h[1], h[2]);
		put_vec(fp, o->center);
		break;
	case SCENE_PATCH:
		/* Front face at z = 0 facing -z (toward a default camera). */
		fprintf(fp, "box { <" G "," G ",0>, <" G "," G "," G "> translate ", -h[0], -h[1], h[0], h[1],
		    fmin(h[0], h[1]) * 0.02);
		put_vec(fp, o->center);
		break;
	case SCENE_PLANE:
		fputs("plane { ", fp);
		put_vec(fp, o->normal);
		fprintf(fp, ", " G, o->offset);
		break;
	case SCENE_HAND:
		fputs("object { SkinbakeHand()", fp);
		break;
	case SCENE_HEAD:
		fputs("object { SkinbakeHead()", fp);
		break;
	}
	write_xform(fp, o);
}

/* The texture of a skin object; pigment/finish names depend on the pass. */
static void write_skin_texture(FILE *fp, const struct scene *s, const struct scene_object *o,
    const struct pov_skin *ps, const char *pigment, const char *finish)
{
	const struct scene_skin *sk = &s->skins[o->skin];
	fprintf(fp, "\n  texture { pigment { %s }", pigment);
	if (ps->height_png != NULL && sk->bumps) {
		fprintf(fp, "\n    normal { SKIN_%s_Normal", sk->name);
		if (o->shape == SCENE_PATCH || o->shape == SCENE_BOX) {
			fputs(" translate ", fp);
			put_vec(fp, o->center);
			write_xform(fp, o);
		} else {
			/* Curved shapes: project along the view axis (no
			 * uv_mapping, see docs/pov.md). */
			double d[3];
			unit_toward(s->camera.location, s->camera.look_at, d);
			write_align(fp, d);
		}
		fputs(" }", fp);
	}
	fprintf(fp, "\n    finish { %s } }", finish);
	if (sk->reflection)
		fprintf(fp, "\n  interior { SKIN_%s_Interior }", sk->name);
}

static void write_objects(FILE *fp, const struct scene *s, const struct pov_skin *skins, enum scene_strategy st,
    int pass)
{
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		const char *sn = o->skin >= 0 ? s->skins[o->skin].name : "";
		fprintf(fp, "// object %s\n", o->name);
		write_shape(fp, o);
		/* Textures attach after the object's transforms, so texture space
		 * is world space (the gamma function uses x, y, z). */
		if (o->material == SCENE_MAT_PLAIN) {
			fputs("\n  texture { pigment { ", fp);
			put_rgb(fp, o->color);
			fputs(" } finish { " FINISH_LIT " } }", fp);
		} else if (o->material == SCENE_MAT_LAMBERT)
			fprintf(fp, "\n  texture { SKIN_%s_Lambert }", sn);
		else if (o->material == SCENE_MAT_PHONG)
			fprintf(fp, "\n  texture { SKIN_%s_Phong }", sn);
		else {
			char *pig, *fin;
			if (st == SCENE_LIGHTS_PASSES && pass > 0) {
				pig = xasprintf("SKIN_%s_Pigment_%s", sn, s->lights[pass - 1].name);
				fin = xasprintf("SKIN_%s_Finish", sn);
			} else if (st == SCENE_LIGHTS_PASSES) {
				pig = xasprintf("SKIN_%s_Pigment_Separable", sn);
				fin = xasprintf("SKIN_%s_Finish_Separable", sn);
			} else {
				pig = xasprintf("SKIN_%s_Pigment", sn);
				fin = xasprintf(st == SCENE_LIGHTS_SEPARABLE ? "SKIN_%s_Finish_Separable" : "SKIN_%s_Finish",
				    sn);
			}
			write_skin_texture(fp, s, o, &skins[o->skin], pig, fin);
			free(pig);
			free(fin);
		}
		fputs(" }\n", fp);
	}
}

static void write_scene(FILE *fp, const struct scene *s, const struct pov_skin *skins, const struct pov_options *o,
    enum scene_strategy st)
{
	fprintf(fp, "#version 3.7;\n// %s\n// Generated by skinbake " PACKAGE_VERSION " from %s.\n", s->title ? s->title : o->base,
	    s->path);
	if (st == SCENE_LIGHTS_PASSES)
		fprintf(fp, "// Per-light passes: `povray %s.ini` renders frame k with light k only and its\n"
		    "// own table to %s_passK.hdr; then `povray %s_combine.ini` sums them into %s.png.\n"
		    "// Rendered without animation (frame 0) it shows all lights with the separable fit.\n",
		    o->base, o->base, o->base, o->base);
	else
		fprintf(fp, "// Render: povray %s.ini   (or povray +I%s.pov +W%d +H%d)\n", o->base, o->base, s->width,
		    s->height);
	fprintf(fp, "global_settings { assumed_gamma 1.0 ambient_light 0 max_trace_level 5 }\n");
	if (o->shapes_inc)
		fprintf(fp, "#include \"%s\"\n", o->shapes_inc);
	fprintf(fp, "#include \"%s.inc\"\n", o->base);
	fputs("background { ", fp);
	if (st == SCENE_LIGHTS_PASSES) /* passes are summed: background in pass 1 only */
		fputs("#if (frame_number < 2) ", fp);
	put_rgb(fp, s->background);
	if (st == SCENE_LIGHTS_PASSES)
		fputs(" #else rgb 0 #end", fp);
	fputs(" }\n", fp);
	write_camera(fp, s);
	if (st == SCENE_LIGHTS_PASSES) {
		fputs("#switch (frame_number)\n", fp);
		for (int i = 0; i < s->n_lights; i++) {
			fprintf(fp, "#case (%d)\nlight_source { SKIN_Light_%s }\n", i + 1, s->lights[i].name);
			write_objects(fp, s, skins, st, i + 1);
			fputs("#break\n", fp);
		}
		fputs("#else\n", fp);
	}
	for (int i = 0; i < s->n_lights; i++)
		fprintf(fp, "light_source { SKIN_Light_%s }\n", s->lights[i].name);
	write_objects(fp, s, skins, st, 0);
	if (st == SCENE_LIGHTS_PASSES)
		fputs("#end\n", fp);
}

/* Name of POV-Ray's frame k output: the frame number is padded to the
 * digits of the last frame. */
static char *pass_name(const char *base, int k, int n)
{
	int digits = n >= 100 ? 3 : n >= 10 ? 2 : 1;
	return xasprintf("%s_pass%0*d.hdr", base, digits, k);
}

static void write_combine(FILE *fp, const struct scene *s, const struct pov_options *o)
{
	fprintf(fp, "#version 3.7;\n// Sum of the per-light passes of %s.pov (POV-Ray does the sum: each .hdr is\n"
	    "// shown 1:1 on a unit square, averaged, times the number of passes).\n"
	    "// Render without antialiasing: povray %s_combine.ini\n", o->base, o->base);
	fputs("global_settings { assumed_gamma 1.0 ambient_light 0 }\n"
	    "camera { orthographic location <0.5,0.5,-1> look_at <0.5,0.5,0> right x up y }\n", fp);
	for (int i = 0; i < s->n_lights; i++) {
		char *p = pass_name(o->base, i + 1, s->n_lights);
		fprintf(fp, "#declare Skinbake_Pass%d = pigment { image_map { hdr \"%s\" } }\n", i + 1, p);
		free(p);
	}
	fputs("plane { z, 0 texture { pigment { average pigment_map {", fp);
	for (int i = 0; i < s->n_lights; i++)
		fprintf(fp, " [1 Skinbake_Pass%d]", i + 1);
	fprintf(fp, " } }\n  finish { emission %d diffuse 0 ambient 0 specular 0 } } }\n", s->n_lights);
}

static void write_ini(FILE *fp, const struct scene *s, const char *input, const char *output, const char *type,
    int antialias, int frames)
{
	fprintf(fp, "; POV-Ray settings: povray THIS_FILE\nInput_File_Name=%s\nOutput_File_Name=%s\n"
	    "Output_File_Type=%s\nWidth=%d\nHeight=%d\nDisplay=off\nOutput_Alpha=off\n", input, output, type, s->width,
	    s->height);
	if (antialias && s->antialias > 0)
		fprintf(fp, "Antialias=on\nAntialias_Threshold=%g\n", s->antialias);
	else
		fputs("Antialias=off\n", fp);
	if (frames > 0)
		fprintf(fp, "Initial_Frame=1\nFinal_Frame=%d\n", frames);
}

int pov_export(const struct scene *s, const struct pov_skin *skins, const struct pov_options *o,
    const char *outdir, struct pov_report *r, char **cause)
{
	enum scene_strategy st = pov_strategy(s);
	struct outfile of[6];
	int n = 0, rc = -1;
	char *name[6] = { 0 };
	*r = (struct pov_report){ .strategy = st };
	if (st == SCENE_LIGHTS_MIXTURE && s->n_lights != 2) {
		*cause = xasprintf("lights = mixture needs exactly 2 lights, the scene has %d", s->n_lights);
		return -1;
	}
	if (o->n_theta < 2 || o->n_theta > POV_MAX_NODES || o->n_mix < 2 || o->n_mix > POV_MAX_NODES || o->n_gamma < 1
	    || o->n_gamma > 256) {
		*cause = xasprintf("table nodes out of range (theta %d, mix %d: [2, %d]; gamma %d: [1, 256])", o->n_theta,
		    o->n_mix, POV_MAX_NODES, o->n_gamma);
		return -1;
	}
	name[n++] = xasprintf("%s.inc", o->base);
	if (o->write_scene) {
		name[n++] = xasprintf("%s.pov", o->base);
		name[n++] = xasprintf("%s.ini", o->base);
		if (st == SCENE_LIGHTS_PASSES) {
			name[n++] = xasprintf("%s_combine.pov", o->base);
			name[n++] = xasprintf("%s_combine.ini", o->base);
		}
	}
	int opened = 0;
	for (int i = 0; i < n; i++) {
		char *path = xasprintf("%s/%s", outdir, name[i]);
		int e = outfile_open(&of[i], path, cause);
		free(path);
		if (e != 0)
			goto out;
		opened++;
	}
	write_include(of[0].fp, s, skins, o, st, r);
	if (o->write_scene) {
		char *png = xasprintf("%s.png", o->base), *pov = xasprintf("%s.pov", o->base);
		write_scene(of[1].fp, s, skins, o, st);
		if (st == SCENE_LIGHTS_PASSES) {
			char *cpov = xasprintf("%s_combine.pov", o->base), *hdr = xasprintf("%s_pass.hdr", o->base);
			write_ini(of[2].fp, s, pov, hdr, "H", 1, s->n_lights);
			write_combine(of[3].fp, s, o);
			write_ini(of[4].fp, s, cpov, png, "N", 0, 0);
			free(cpov);
			free(hdr);
		} else
			write_ini(of[2].fp, s, pov, png, "N", 1, 0);
		free(png);
		free(pov);
	}
	for (int i = 0; i < n; i++) {
		if (outfile_commit(&of[i], cause) != 0)
			goto out;	/* aborting committed files below is a no-op */
		r->files[r->n_files++] = xstrdup(name[i]);
	}
	rc = 0;
out:
	for (int i = 0; i < opened; i++)
		outfile_abort(&of[i]);
	for (int i = 0; i < n; i++)
		free(name[i]);
	return rc;
}
