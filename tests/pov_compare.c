/* pov_compare: numeric checks of POV-Ray renders for tests/pov_render.sh.
 *
 *   pov_compare expect --scene S (--analytic | --bake DIR) --render R.png [--tol T] [--only LIGHT]
 *       Traces the scene's spheres and planes per pixel in C (POV-Ray's
 *       camera conventions: rays through pixel centres, row 0 at the top),
 *       computes the expected linear value sum_lights E cos(theta_i) pi f_r
 *       with hard shadows, and compares it with the 16-bit linear render.
 *       Mask: pixels whose 3x3 neighbourhood hits one object with one shadow
 *       state per light (no silhouette or shadow edges), expected value above
 *       1 % of the image maximum, not clipped.  Prints the mean relative error
 *       and the shadow check; fails if the error exceeds T (default 0.005) or
 *       a shadowed pixel is lit (or a lit pixel dark).
 *       With --ad (and --bake), the expected value does not come from the
 *       bake's interpolation (eval) but from adding-doubling point values of
 *       the bake's own layer stacks (the manifest's), solved at each pixel's
 *       incidence angle, plus the analytic specular, summed to RGB with the
 *       bake's weights; with --min-theta-out DEG only pixels whose exit angle
 *       is at least DEG count (the silhouettes, where the table is grazing).
 *   pov_compare sum --render R.png --parts A.png B.png [...] [--tol T] [--interior]
 *       Mean relative difference of R against the sum of the parts over
 *       pixels above 1 % of the maximum; with --interior only where every
 *       part is smooth over 3x3 pixels (no silhouette or shadow edge, as in
 *       `expect`), printing the all-pixel figure too.
 *   pov_compare differ --render A.png --other B.png --min D
 *       Fails unless the images differ by a mean relative D or more.
 *   pov_compare seam --render R.png --column X [--max RATIO]
 *       Mean |I(x) - I(x-1)| across column X against the median over all
 *       columns: a seam at a tile boundary shows as a large ratio.
 *   pov_compare mkheight --out DIR --kind sine|ramp [--size N]
 *       A 16-bit height map like `skinbake texture` writes (height.png with
 *       its tEXt keys; tile 4 mm, 50 um relief): "sine" tiles, "ramp" does
 *       not (a negative control for the seam check). */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ad_points.h"
#include "export/source.h"
#include "io/pngio.h"
#include "export/pov/littable.h"
#include "scene/placement.h"
#include "scene/scene.h"
#include "scene/scene_load.h"
#include "base/util.h"

static float *load(const char *path, int *w, int *h)
{
	int ch, bits;
	char *cause = NULL;
	uint16_t *px = pngio_read(path, w, h, &ch, &bits, &cause);
	if (px == NULL) {
		fprintf(stderr, "pov_compare: %s\n", cause);
		exit(2);
	}
	if (ch < 3) {
		fprintf(stderr, "pov_compare: %s: expected RGB\n", path);
		exit(2);
	}
	float *img = xmalloc(sizeof(float) * 3 * (size_t)*w * *h);
	for (int i = 0; i < *w * *h; i++)
		for (int c = 0; c < 3; c++)
			img[3 * i + c] = px[ch * i + c] == 65535 ? -1.0f : px[ch * i + c] / 65535.0f; /* -1: clipped */
	free(px);
	return img;
}

static double dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void norm(double a[3])
{
	double n = sqrt(dot(a, a));
	for (int i = 0; i < 3; i++)
		a[i] /= n;
}

/* Nearest hit along o + t d, t > tmin; object index or -1. */
static int trace(const struct scene *s, const double o[3], const double d[3], double tmin, double *tout)
{
	int best = -1;
	double bt = INFINITY;
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *ob = &s->objects[i];
		double t = INFINITY;
		if (ob->shape == SCENE_SPHERE) {
			double oc[3] = { o[0] - ob->center[0] - ob->translate[0], o[1] - ob->center[1] - ob->translate[1],
				o[2] - ob->center[2] - ob->translate[2] };
			double b = dot(oc, d), c = dot(oc, oc) - ob->radius * ob->radius, disc = b * b - c;
			if (disc < 0)
				continue;
			double sq = sqrt(disc);
			t = -b - sq > tmin ? -b - sq : -b + sq > tmin ? -b + sq : INFINITY;
		} else if (ob->shape == SCENE_PLANE) {
			double dn = dot(d, ob->normal);
			if (fabs(dn) < 1e-12)
				continue;
			t = (ob->offset - dot(o, ob->normal)) / dn;
			if (t <= tmin)
				continue;
		} else {
			fprintf(stderr, "pov_compare: object %s: only spheres and planes are supported\n", ob->name);
			exit(2);
		}
		if (t < bt)
			bt = t, best = i;
	}
	*tout = bt;
	return best;
}

struct pixel {
	int obj;		/* object hit or -1 */
	unsigned shadow;	/* bit k: light k blocked */
	double v[3];		/* expected value */
	double co;		/* cosine of the exit angle */
};

/* --ad: adding-doubling point values of the bake's stacks (see the top,
 * tests/ad_points.h).  Two passes over the pixels: the first records the
 * angles asked (in call order), which are then solved together; the second
 * returns their values, call by call in the same order. */
struct ad_ref {
	struct bake *b;
	const char *dir;
	double min_to;		/* [rad]: 0 returned below (pixels not counted) */
	int pass;		/* 0: record, 1: evaluate */
	long n, cap, next;	/* angles recorded; the next call's index */
	double *ti, *to, *dphi;	/* [n] */
	double *rgb;		/* [n][3] */
	long solves;
};

static void ad_solve_all(struct ad_ref *a)
{
	char *cause = NULL;
	a->rgb = xmalloc(sizeof(double) * 3 * (size_t)(a->n + 1));
	if (ad_points_rgb(a->dir, a->b, a->n, a->ti, a->to, a->dphi, a->rgb, &a->solves, &cause)) {
		fprintf(stderr, "pov_compare: adding-doubling: %s\n", cause);
		exit(2);
	}
	a->pass = 1;
	a->next = 0;
}

static void ad_rgb(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	struct ad_ref *a = ctx;
	rgb[0] = rgb[1] = rgb[2] = 0.0;
	if (to < a->min_to || ti >= 0.5 * M_PI)
		return;
	if (a->pass == 0) {
		if (a->n == a->cap) {
			a->cap = a->cap ? 2 * a->cap : 1024;
			a->ti = xreallocarray(a->ti, (size_t)a->cap, sizeof(double));
			a->to = xreallocarray(a->to, (size_t)a->cap, sizeof(double));
			a->dphi = xreallocarray(a->dphi, (size_t)a->cap, sizeof(double));
		}
		a->ti[a->n] = ti;
		a->to[a->n] = to;
		a->dphi[a->n++] = dphi;
		return;
	}
	long i = a->next++;
	for (int c = 0; c < 3; c++)
		rgb[c] = a->rgb[3 * i + c];
}

static void shade(const struct scene *s, const struct pov_brdf *f, int only, const double o[3], const double d[3],
    struct pixel *px)
{
	double t;
	px->obj = trace(s, o, d, 1e-9, &t);
	px->shadow = 0;
	px->v[0] = px->v[1] = px->v[2] = 0;
	if (px->obj < 0)
		return;
	const struct scene_object *ob = &s->objects[px->obj];
	double p[3], n[3], v[3] = { -d[0], -d[1], -d[2] };
	for (int i = 0; i < 3; i++)
		p[i] = o[i] + t * d[i];
	if (ob->shape == SCENE_SPHERE) {
		for (int i = 0; i < 3; i++)
			n[i] = p[i] - ob->center[i] - ob->translate[i];
		norm(n);
	} else {
		memcpy(n, ob->normal, sizeof n);
		if (dot(n, v) < 0)
			for (int i = 0; i < 3; i++)
				n[i] = -n[i];
	}
	double co = dot(n, v);
	px->co = co;
	for (int k = 0; k < s->n_lights; k++) {
		if (only >= 0 && k != only)
			continue;
		const struct scene_light *l = &s->lights[k];
		double L[3], ts, lim = INFINITY;
		placement_light_dir(l, p, L);
		double ci = dot(n, L);
		if (ci <= 0)
			continue;
		if (l->type == SCENE_LIGHT_POINT)
			lim = sqrt((l->position[0] - p[0]) * (l->position[0] - p[0]) + (l->position[1] - p[1]) * (l->position[1] - p[1])
			    + (l->position[2] - p[2]) * (l->position[2] - p[2]));
		if (trace(s, p, L, 1e-6, &ts) >= 0 && ts < lim) {
			px->shadow |= 1u << k;
			continue;
		}
		double rgb[3];
		if (ob->material == SCENE_MAT_PLAIN) {
			for (int c = 0; c < 3; c++)
				rgb[c] = ob->color[c] / M_PI;
		} else {
			/* delta_phi between the tangent-plane projections of L and V. */
			double lt[3], vt[3], dphi = 0;
			for (int i = 0; i < 3; i++)
				lt[i] = L[i] - ci * n[i], vt[i] = v[i] - co * n[i];
			double a = sqrt(dot(lt, lt)), b = sqrt(dot(vt, vt));
			if (a > 1e-9 && b > 1e-9)
				dphi = acos(fmax(-1, fmin(1, dot(lt, vt) / (a * b))));
			f->f_rgb(f->ctx, acos(fmin(1, ci)), acos(fmax(0, fmin(1, co))), dphi, rgb);
		}
		for (int c = 0; c < 3; c++)
			px->v[c] += l->color[c] * ci * M_PI * rgb[c];
	}
}

static int cmd_expect(int argc, char **argv)
{
	const char *scene_path = NULL, *bake_dir = NULL, *render = NULL, *only_name = NULL;
	int analytic = 0, only = -1, ad = 0;
	double tol = 0.005, min_to_deg = 0.0;
	for (int i = 2; i < argc; i++) {
		if (!strcmp(argv[i], "--scene") && i + 1 < argc)
			scene_path = argv[++i];
		else if (!strcmp(argv[i], "--bake") && i + 1 < argc)
			bake_dir = argv[++i];
		else if (!strcmp(argv[i], "--analytic"))
			analytic = 1;
		else if (!strcmp(argv[i], "--render") && i + 1 < argc)
			render = argv[++i];
		else if (!strcmp(argv[i], "--tol") && i + 1 < argc)
			tol = atof(argv[++i]);
		else if (!strcmp(argv[i], "--only") && i + 1 < argc)
			only_name = argv[++i];
		else if (!strcmp(argv[i], "--ad"))
			ad = 1;
		else if (!strcmp(argv[i], "--min-theta-out") && i + 1 < argc)
			min_to_deg = atof(argv[++i]);
		else
			return fprintf(stderr, "pov_compare expect: bad argument '%s'\n", argv[i]), 2;
	}
	if (!scene_path || !render || (!analytic && !bake_dir))
		return fprintf(stderr, "pov_compare expect: need --scene, --render and --analytic or --bake\n"), 2;
	char *cause = NULL;
	struct scene *s = scene_load(scene_path, &cause);
	if (s == NULL)
		return fprintf(stderr, "pov_compare: %s\n", cause), 2;
	if (only_name)
		for (int k = 0; k < s->n_lights; k++)
			if (!strcmp(s->lights[k].name, only_name))
				only = k;
	struct brdf_source *b = NULL;
	struct pov_brdf f = { .f_rgb = littable_brdf_analytic };
	if (!analytic) {
		b = brdf_source_open(bake_dir, &cause);
		if (b == NULL)
			return fprintf(stderr, "pov_compare: %s\n", cause), 2;
		f = (struct pov_brdf){ .f_rgb = b->f_rgb, .ctx = b->ctx };
	}
	struct ad_ref ar = { .b = b ? b->bake : NULL, .dir = bake_dir };
	ar.min_to = min_to_deg * M_PI / 180.0;
	if (ad) {
		if (b == NULL)
			return fprintf(stderr, "pov_compare: --ad needs --bake\n"), 2;
		f = (struct pov_brdf){ .f_rgb = ad_rgb, .ctx = &ar };
	}
	int w, h;
	float *img = load(render, &w, &h);
	if (w != s->width || h != s->height)
		return fprintf(stderr, "pov_compare: render is %dx%d, scene %dx%d\n", w, h, s->width, s->height), 2;

	/* Camera frame as POV-Ray builds it from location/look_at (sky +y). */
	const struct scene_camera *cam = &s->camera;
	double fwd[3] = { cam->look_at[0] - cam->location[0], cam->look_at[1] - cam->location[1],
		cam->look_at[2] - cam->location[2] }, right[3], up[3];
	norm(fwd);
	right[0] = fwd[2], right[1] = 0, right[2] = -fwd[0]; /* y x fwd */
	norm(right);
	up[0] = fwd[1] * right[2] - fwd[2] * right[1], up[1] = fwd[2] * right[0] - fwd[0] * right[2],
	up[2] = fwd[0] * right[1] - fwd[1] * right[0];
	double aspect = (double)w / h;
	double half_w = cam->ortho ? 0.5 * cam->width : tan(0.5 * cam->angle), half_h = half_w / aspect;
	struct pixel *px = xcalloc((size_t)w * h, sizeof *px);
	double vmax = 0;
	for (int pass = ad ? 0 : 1; pass < 2; pass++) {
		if (pass == 1 && ad)
			ad_solve_all(&ar);
		vmax = 0;
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				double u = (2.0 * (x + 0.5) / w - 1) * half_w, v = (1 - 2.0 * (y + 0.5) / h) * half_h, o[3], d[3];
				for (int i = 0; i < 3; i++) {
					if (cam->ortho) {
						o[i] = cam->location[i] + u * right[i] + v * up[i];
						d[i] = fwd[i];
					} else {
						o[i] = cam->location[i];
						d[i] = fwd[i] + u * right[i] + v * up[i];
					}
				}
				norm(d);
				shade(s, &f, only, o, d, &px[y * w + x]);
				for (int c = 0; c < 3; c++)
					vmax = fmax(vmax, px[y * w + x].v[c]);
			}
	}
	double sum_rel = 0, sum_abs = 0, sum_ref = 0;
	long n_rel = 0, n_px = 0, n_shadow = 0, shadow_bad = 0, n_clip = 0;
	for (int y = 1; y < h - 1; y++)
		for (int x = 1; x < w - 1; x++) {
			const struct pixel *p = &px[y * w + x];
			int edge = 0;
			for (int dy = -1; dy <= 1; dy++)
				for (int dx = -1; dx <= 1; dx++) {
					const struct pixel *q = &px[(y + dy) * w + x + dx];
					edge |= q->obj != p->obj || q->shadow != p->shadow;
				}
			if (edge || p->obj < 0 || acos(fmax(-1, fmin(1, p->co))) < ar.min_to)
				continue;
			const float *r = &img[3 * (y * w + x)];
			if (r[0] < 0 || r[1] < 0 || r[2] < 0) {
				n_clip++;
				continue;
			}
			if (p->shadow && p->v[0] + p->v[1] + p->v[2] < 1e-9) {
				/* Fully shadowed: must render black. */
				n_shadow++;
				if (r[0] + r[1] + r[2] > 0.01 * vmax)
					shadow_bad++;
				continue;
			}
			if (p->shadow)
				n_shadow++;
			n_px++;
			for (int c = 0; c < 3; c++) {
				if (p->v[c] < 0.01 * vmax)
					continue;
				sum_rel += fabs(r[c] - p->v[c]) / p->v[c];
				n_rel++;
				sum_abs += fabs(r[c] - p->v[c]);
				sum_ref += p->v[c];
			}
		}
	double mre = n_rel ? sum_rel / n_rel : INFINITY;
	printf("mean_rel_err %.5f  abs_over_mean %.5f  pixels %ld  shadowed %ld  shadow_mismatch %ld  clipped %ld  max %.4f\n",
	    mre, sum_ref > 0 ? sum_abs / sum_ref : INFINITY, n_px, n_shadow, shadow_bad, n_clip, vmax);
	if (ad)
		printf("(adding-doubling reference: %ld solves, exit angles from %g deg)\n", ar.solves, min_to_deg);
	free(px);
	free(img);
	free(ar.ti);
	free(ar.to);
	free(ar.dphi);
	free(ar.rgb);
	brdf_source_free(b);
	scene_free(s);
	return mre <= tol && shadow_bad == 0 && n_px > 100 ? 0 : 1;
}

/* Whether pixel (x, y) channel c of image p sits inside a smooth region:
 * its 3x3 neighbours within 20 % (of it, or of 1 % of vmax when darker). */
static int smooth_at(const float *p, int w, int h, int x, int y, int c, double vmax)
{
	if (x < 1 || y < 1 || x >= w - 1 || y >= h - 1)
		return 0;
	double v = p[3 * (y * w + x) + c], tol = 0.2 * fmax(v, 0.01 * vmax);
	for (int j = -1; j <= 1; j++)
		for (int i = -1; i <= 1; i++)
			if (fabs(p[3 * ((y + j) * w + x + i) + c] - v) > tol)
				return 0;
	return 1;
}

static int cmd_sum(int argc, char **argv)
{
	const char *render = NULL, *parts[16];
	int np = 0, interior = 0;
	double tol = 0.01;
	for (int i = 2; i < argc; i++) {
		if (!strcmp(argv[i], "--render") && i + 1 < argc)
			render = argv[++i];
		else if (!strcmp(argv[i], "--tol") && i + 1 < argc)
			tol = atof(argv[++i]);
		else if (!strcmp(argv[i], "--interior"))
			interior = 1;
		else if (!strcmp(argv[i], "--parts"))
			while (i + 1 < argc && argv[i + 1][0] != '-' && np < 16)
				parts[np++] = argv[++i];
		else
			return fprintf(stderr, "pov_compare sum: bad argument '%s'\n", argv[i]), 2;
	}
	if (!render || np == 0)
		return fprintf(stderr, "pov_compare sum: need --render and --parts\n"), 2;
	int w, h, w2, h2;
	float *r = load(render, &w, &h), *p[16];
	double *sum = xcalloc(3 * (size_t)w * h, sizeof(double)), vmax = 0;
	char *clip = xcalloc((size_t)w * h, 1);
	for (int k = 0; k < np; k++) {
		p[k] = load(parts[k], &w2, &h2);
		if (w2 != w || h2 != h)
			return fprintf(stderr, "pov_compare sum: %s has another size\n", parts[k]), 2;
		for (int i = 0; i < 3 * w * h; i++) {
			if (p[k][i] < 0)
				clip[i / 3] = 1;
			sum[i] += p[k][i];
			vmax = fmax(vmax, sum[i]);
		}
	}
	double acc = 0, acc_all = 0;
	long n = 0, n_all = 0;
	for (int i = 0; i < 3 * w * h; i++) {
		if (clip[i / 3] || r[i] < 0 || sum[i] < 0.01 * vmax)
			continue;
		double e = fabs(r[i] - sum[i]) / sum[i];
		acc_all += e;
		n_all++;
		int in = 1;
		for (int k = 0; interior && k < np && in; k++)
			in = smooth_at(p[k], w, h, (i / 3) % w, (i / 3) / w, i % 3, vmax);
		if (!in)
			continue;
		acc += e;
		n++;
	}
	double mre = n ? acc / n : INFINITY;
	printf("mean_rel_err %.5f  samples %ld  max %.4f", mre, n, vmax);
	if (interior)
		printf("  (all pixels, edges too: %.5f over %ld)", n_all ? acc_all / n_all : INFINITY, n_all);
	printf("\n");
	for (int k = 0; k < np; k++)
		free(p[k]);
	free(r);
	free(sum);
	free(clip);
	return mre <= tol && n > 100 ? 0 : 1;
}

static int cmd_differ(int argc, char **argv)
{
	const char *a = NULL, *b = NULL;
	double min = 0.01;
	for (int i = 2; i < argc; i++) {
		if (!strcmp(argv[i], "--render") && i + 1 < argc)
			a = argv[++i];
		else if (!strcmp(argv[i], "--other") && i + 1 < argc)
			b = argv[++i];
		else if (!strcmp(argv[i], "--min") && i + 1 < argc)
			min = atof(argv[++i]);
		else
			return fprintf(stderr, "pov_compare differ: bad argument '%s'\n", argv[i]), 2;
	}
	if (!a || !b)
		return fprintf(stderr, "pov_compare differ: need --render and --other\n"), 2;
	int w, h, w2, h2;
	float *x = load(a, &w, &h), *y = load(b, &w2, &h2);
	if (w != w2 || h != h2)
		return fprintf(stderr, "pov_compare differ: sizes differ\n"), 2;
	double d = 0, m = 0;
	for (int i = 0; i < 3 * w * h; i++)
		d += fabs(fabs(x[i]) - fabs(y[i])), m += fabs(y[i]);
	double rel = m > 0 ? d / m : 0;
	printf("mean_rel_diff %.5f\n", rel);
	free(x);
	free(y);
	return rel >= min ? 0 : 1;
}

static int cmd_seam(int argc, char **argv)
{
	const char *a = NULL;
	int col = -1;
	double maxr = 2.0;
	for (int i = 2; i < argc; i++) {
		if (!strcmp(argv[i], "--render") && i + 1 < argc)
			a = argv[++i];
		else if (!strcmp(argv[i], "--column") && i + 1 < argc)
			col = atoi(argv[++i]);
		else if (!strcmp(argv[i], "--max") && i + 1 < argc)
			maxr = atof(argv[++i]);
		else
			return fprintf(stderr, "pov_compare seam: bad argument '%s'\n", argv[i]), 2;
	}
	int w, h;
	float *x = a ? load(a, &w, &h) : NULL;
	if (!x || col < 1 || col >= w)
		return fprintf(stderr, "pov_compare seam: need --render and --column in [1, width)\n"), 2;
	double *g = xcalloc((size_t)w, sizeof(double)), *sorted = xcalloc((size_t)w, sizeof(double));
	for (int c = 1; c < w; c++) {
		for (int y = 0; y < h; y++)
			for (int k = 0; k < 3; k++)
				g[c] += fabs(fabs(x[3 * (y * w + c) + k]) - fabs(x[3 * (y * w + c - 1) + k]));
		sorted[c - 1] = g[c];
	}
	/* median by insertion sort (w is small) */
	for (int i = 1; i < w - 1; i++)
		for (int j = i; j > 0 && sorted[j - 1] > sorted[j]; j--) {
			double t = sorted[j];
			sorted[j] = sorted[j - 1], sorted[j - 1] = t;
		}
	double med = sorted[(w - 1) / 2], ratio = med > 0 ? g[col] / med : INFINITY;
	printf("seam_ratio %.3f (column %d: %.4g, median %.4g)\n", ratio, col, g[col], med);
	free(g);
	free(sorted);
	free(x);
	return ratio <= maxr ? 0 : 1;
}

static int cmd_mkheight(int argc, char **argv)
{
	const char *dir = NULL, *kind = "sine";
	int n = 64;
	for (int i = 2; i < argc; i++) {
		if (!strcmp(argv[i], "--out") && i + 1 < argc)
			dir = argv[++i];
		else if (!strcmp(argv[i], "--kind") && i + 1 < argc)
			kind = argv[++i];
		else if (!strcmp(argv[i], "--size") && i + 1 < argc)
			n = atoi(argv[++i]);
		else
			return fprintf(stderr, "pov_compare mkheight: bad argument '%s'\n", argv[i]), 2;
	}
	char *cause = NULL;
	if (!dir || n < 4 || util_mkdirs(dir, &cause) != 0)
		return fprintf(stderr, "pov_compare mkheight: need --out DIR and --size >= 4\n"), 2;
	uint16_t *px = xmalloc(sizeof(uint16_t) * (size_t)n * n);
	int ramp = !strcmp(kind, "ramp");
	for (int y = 0; y < n; y++)
		for (int x = 0; x < n; x++) {
			double h = ramp ? (double)x / (n - 1)
					: 0.5 + 0.25 * sin(2 * M_PI * 3 * x / n) + 0.25 * cos(2 * M_PI * 2 * y / n);
			px[y * n + x] = (uint16_t)lround(h * 65535);
		}
	struct png_text_kv kv[3] = { { "skinbake:tile_mm", "4" }, { "skinbake:height_min_um", "0" },
		{ "skinbake:height_max_um", "50" } };
	char *path = xasprintf("%s/height.png", dir);
	int rc = pngio_write(path, n, n, 1, 16, px, 0, 3, kv, &cause);
	if (rc != 0)
		fprintf(stderr, "pov_compare mkheight: %s\n", cause);
	free(path);
	free(px);
	return rc ? 2 : 0;
}

int main(int argc, char **argv)
{
	if (argc >= 2 && !strcmp(argv[1], "mkheight"))
		return cmd_mkheight(argc, argv);
	if (argc >= 2 && !strcmp(argv[1], "expect"))
		return cmd_expect(argc, argv);
	if (argc >= 2 && !strcmp(argv[1], "sum"))
		return cmd_sum(argc, argv);
	if (argc >= 2 && !strcmp(argv[1], "differ"))
		return cmd_differ(argc, argv);
	if (argc >= 2 && !strcmp(argv[1], "seam"))
		return cmd_seam(argc, argv);
	fprintf(stderr, "usage: pov_compare expect|sum|differ|seam ... (see the source)\n");
	return 2;
}
