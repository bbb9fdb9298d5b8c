/* povao: the fill's occlusion, traced per mesh vertex and rasterised into
 * UV space (povao.h). */
#include "config.h"

#include "export/pov/povao.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/rng.h"
#include "base/util.h"
#include "export/pov/vec3.h"
#include "geom/mesh.h"
#include "io/pngio.h"

int povao_wanted(const struct scene *s, const struct scene_object *o)
{
	return s->fill_occlusion > 0 && (s->fill[0] > 0 || s->fill[1] > 0 || s->fill[2] > 0) &&
	    o->shape == SCENE_MESH && o->mesh != NULL && o->mesh->uv != NULL &&
	    (o->material == SCENE_MAT_SKIN || o->material == SCENE_MAT_MODEL);
}

char *povao_name(const char *base, const struct scene_object *o)
{
	return xasprintf("%s_ao_%s.png", base, o->name);
}

/* Every mesh triangle of the scene in a uniform grid (cells listed CSR). */
struct grid {
	int n_tri;
	double (*a)[3], (*e1)[3], (*e2)[3];	/* corner and edges per triangle */
	double lo[3], h;			/* origin, cell size */
	double eps;				/* rays start this far off the surface; nearer hits
						 * are ignored */
	int n[3];				/* cells per axis */
	int *start, *tri;			/* cell c holds tri[start[c] .. start[c + 1]) */
};

static void cell_range(const struct grid *g, const double lo[3], const double hi[3], int c0[3],
    int c1[3])
{
	for (int k = 0; k < 3; k++) {
		c0[k] = (int)floor((lo[k] - g->lo[k]) / g->h);
		c1[k] = (int)floor((hi[k] - g->lo[k]) / g->h);
		c0[k] = c0[k] < 0 ? 0 : c0[k] >= g->n[k] ? g->n[k] - 1 : c0[k];
		c1[k] = c1[k] < 0 ? 0 : c1[k] >= g->n[k] ? g->n[k] - 1 : c1[k];
	}
}

static void tri_bounds(const struct grid *g, int t, double lo[3], double hi[3])
{
	for (int k = 0; k < 3; k++) {
		double p0 = g->a[t][k], p1 = p0 + g->e1[t][k], p2 = p0 + g->e2[t][k];
		lo[k] = fmin(p0, fmin(p1, p2));
		hi[k] = fmax(p0, fmax(p1, p2));
	}
}

static void grid_make(const struct scene *s, struct grid *g)
{
	*g = (struct grid){ 0 };
	for (int i = 0; i < s->n_objects; i++)
		if (s->objects[i].shape == SCENE_MESH && s->objects[i].mesh)
			g->n_tri += s->objects[i].mesh->n_triangles;
	g->a = xmalloc(sizeof *g->a * (size_t)g->n_tri);
	g->e1 = xmalloc(sizeof *g->e1 * (size_t)g->n_tri);
	g->e2 = xmalloc(sizeof *g->e2 * (size_t)g->n_tri);
	double lo[3] = { INFINITY, INFINITY, INFINITY };
	double hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	int t = 0;
	for (int i = 0; i < s->n_objects; i++) {
		const struct mesh *m = s->objects[i].mesh;
		if (s->objects[i].shape != SCENE_MESH || m == NULL)
			continue;
		for (int f = 0; f < m->n_triangles; f++, t++)
			for (int k = 0; k < 3; k++) {
				const double *p0 = m->position[m->triangle[f][0]];
				g->a[t][k] = p0[k];
				g->e1[t][k] = m->position[m->triangle[f][1]][k] - p0[k];
				g->e2[t][k] = m->position[m->triangle[f][2]][k] - p0[k];
				for (int c = 0; c < 3; c++) {
					lo[k] = fmin(lo[k], m->position[m->triangle[f][c]][k]);
					hi[k] = fmax(hi[k], m->position[m->triangle[f][c]][k]);
				}
			}
	}
	/* Cells of twice the mean edge (a few triangles each where the mesh is
	 * fine), at most 256 per axis. */
	double d[3], edge = 0;
	for (int f = 0; f < g->n_tri; f++)
		edge += sqrt(vec3_dot(g->e1[f], g->e1[f])) + sqrt(vec3_dot(g->e2[f], g->e2[f]));
	g->h = edge / fmax(g->n_tri, 1);
	for (int k = 0; k < 3; k++) {
		d[k] = fmax(hi[k] - lo[k], 1e-9);
		g->h = fmax(g->h, d[k] / 256);
		g->lo[k] = lo[k] - 1e-6 * d[k];
	}
	g->eps = 1e-4 * sqrt(vec3_dot(d, d));
	for (int k = 0; k < 3; k++)
		g->n[k] = (int)ceil(d[k] * (1 + 2e-6) / g->h) + 1;
	size_t nc = (size_t)g->n[0] * g->n[1] * g->n[2];
	g->start = xcalloc(nc + 1, sizeof *g->start);
	for (int pass = 0; pass < 2; pass++) {
		for (int f = 0; f < g->n_tri; f++) {
			double blo[3], bhi[3];
			int c0[3], c1[3];
			tri_bounds(g, f, blo, bhi);
			cell_range(g, blo, bhi, c0, c1);
			for (int z = c0[2]; z <= c1[2]; z++)
				for (int y = c0[1]; y <= c1[1]; y++)
					for (int x = c0[0]; x <= c1[0]; x++) {
						size_t c = ((size_t)z * g->n[1] + y) * g->n[0] + x;
						if (pass == 0)
							g->start[c + 1]++;
						else
							g->tri[g->start[c]++] = f;
					}
		}
		if (pass == 0) {
			for (size_t c = 0; c < nc; c++)
				g->start[c + 1] += g->start[c];
			g->tri = xmalloc(sizeof *g->tri * (size_t)(g->start[nc] + 1));
		} else {
			/* start[c] moved to the end of cell c: shift back. */
			memmove(g->start + 1, g->start, sizeof *g->start * nc);
			g->start[0] = 0;
		}
	}
}

static void grid_free(struct grid *g)
{
	free(g->a);
	free(g->e1);
	free(g->e2);
	free(g->start);
	free(g->tri);
}

/* Moeller-Trumbore: a hit of either side at t > tmin. */
static int hit(const struct grid *g, int t, const double o[3], const double d[3], double tmin)
{
	double p[3], q[3], s[3];
	vec3_cross(d, g->e2[t], p);
	double det = vec3_dot(g->e1[t], p);
	if (fabs(det) < 1e-300)
		return 0;
	double inv = 1 / det;
	for (int k = 0; k < 3; k++)
		s[k] = o[k] - g->a[t][k];
	double u = vec3_dot(s, p) * inv;
	if (u < 0 || u > 1)
		return 0;
	vec3_cross(s, g->e1[t], q);
	double v = vec3_dot(d, q) * inv;
	if (v < 0 || u + v > 1)
		return 0;
	double tt = vec3_dot(g->e2[t], q) * inv;
	return tt > tmin;
}

/* Does the ray from o along unit d hit anything beyond tmin?  Cell walk
 * (Amanatides & Woo 1987) from o's cell to the grid's end. */
static int occluded(const struct grid *g, const double o[3], const double d[3], double tmin)
{
	int c[3], step[3];
	double tmax[3], tdelta[3];
	for (int k = 0; k < 3; k++) {
		double x = (o[k] - g->lo[k]) / g->h;
		if (x < 0 || x >= g->n[k])
			return 0;	/* vertices lie inside; a point outside sees the sky */
		c[k] = (int)x;
		step[k] = d[k] > 0 ? 1 : -1;
		double next = d[k] > 0 ? c[k] + 1 : c[k];
		tmax[k] = d[k] != 0 ? (next - x) * g->h / d[k] : INFINITY;
		tdelta[k] = d[k] != 0 ? g->h / fabs(d[k]) : INFINITY;
	}
	for (;;) {
		size_t cell = ((size_t)c[2] * g->n[1] + c[1]) * g->n[0] + c[0];
		for (int i = g->start[cell]; i < g->start[cell + 1]; i++)
			if (hit(g, g->tri[i], o, d, tmin))
				return 1;
		int k = tmax[0] < tmax[1] ? (tmax[0] < tmax[2] ? 0 : 2)
		    : (tmax[1] < tmax[2] ? 1 : 2);
		c[k] += step[k];
		if (c[k] < 0 || c[k] >= g->n[k])
			return 0;
		tmax[k] += tdelta[k];
	}
}

/* Cosine-weighted visibility of vertex v of m, n rays in sqrt(n) x sqrt(n) strata. */
static double visibility(const struct grid *g, const struct mesh *m, int v, int n, double eps,
    uint64_t seed)
{
	const double *nv = m->normal[v];
	double t[3], b[3], a[3] = { 1, 0, 0 };
	if (fabs(nv[0]) > 0.9) {
		a[0] = 0;
		a[1] = 1;
	}
	vec3_cross(nv, a, t);
	double l = sqrt(vec3_dot(t, t));
	for (int k = 0; k < 3; k++)
		t[k] /= l;
	vec3_cross(nv, t, b);
	double o[3];
	for (int k = 0; k < 3; k++)
		o[k] = m->position[v][k] + eps * nv[k];
	int side = (int)floor(sqrt((double)n)), seen = 0, total = 0;
	side = side < 1 ? 1 : side;
	struct rng r;
	rng_seed(&r, seed, 0x616f, (uint64_t)v);
	for (int i = 0; i < side; i++)
		for (int j = 0; j < side; j++) {
			double u1 = (i + rng_uniform(&r)) / side, u2 = (j + rng_uniform(&r)) / side;
			double sr = sqrt(u1), ph = 2 * M_PI * u2, cz = sqrt(1 - u1), d[3];
			for (int k = 0; k < 3; k++)
				d[k] = sr * cos(ph) * t[k] + sr * sin(ph) * b[k] + cz * nv[k];
			seen += !occluded(g, o, d, eps);
			total++;
		}
	return (double)seen / total;
}

/* Is p in the camera's view (with a margin of a tenth)?  Vertices out of it
 * are not traced (visibility 1). */
static int in_view(const struct scene *s, const double p[3])
{
	const struct scene_camera *c = &s->camera;
	double f[3], r[3], u[3], d[3], up[3] = { 0, 1, 0 };
	vec3_unit_toward(c->location, c->look_at, f);
	if (fabs(f[1]) > 0.999) {
		up[1] = 0;
		up[2] = 1;
	}
	vec3_cross(up, f, r);
	double l = sqrt(vec3_dot(r, r));
	for (int k = 0; k < 3; k++)
		r[k] /= l;
	vec3_cross(f, r, u);
	for (int k = 0; k < 3; k++)
		d[k] = p[k] - c->location[k];
	double z = vec3_dot(d, f), x = fabs(vec3_dot(d, r)), y = fabs(vec3_dot(d, u));
	double aspect = (double)s->width / s->height;
	if (c->ortho)
		return x <= 0.55 * c->width && y <= 0.55 * c->width / aspect;
	double th = 1.1 * tan(0.5 * c->angle);
	return z > 0 && x <= th * z && y <= th / aspect * z;
}

/* Barycentric fill of one UV triangle with the corners' values. */
static void raster(float *img, int sz, const double uv[3][2], const double val[3])
{
	double x[3], y[3];
	for (int c = 0; c < 3; c++) {
		x[c] = uv[c][0] * sz - 0.5;
		y[c] = (1 - uv[c][1]) * sz - 0.5;
	}
	double den = (y[1] - y[2]) * (x[0] - x[2]) + (x[2] - x[1]) * (y[0] - y[2]);
	if (fabs(den) < 1e-12)
		return;
	int x0 = (int)floor(fmin(x[0], fmin(x[1], x[2])));
	int x1 = (int)ceil(fmax(x[0], fmax(x[1], x[2])));
	int y0 = (int)floor(fmin(y[0], fmin(y[1], y[2])));
	int y1 = (int)ceil(fmax(y[0], fmax(y[1], y[2])));
	x0 = x0 < 0 ? 0 : x0;
	y0 = y0 < 0 ? 0 : y0;
	x1 = x1 >= sz ? sz - 1 : x1;
	y1 = y1 >= sz ? sz - 1 : y1;
	for (int py = y0; py <= y1; py++)
		for (int px = x0; px <= x1; px++) {
			double ex = px - x[2], ey = py - y[2];
			double w0 = ((y[1] - y[2]) * ex + (x[2] - x[1]) * ey) / den;
			double w1 = ((y[2] - y[0]) * ex + (x[0] - x[2]) * ey) / den;
			double w2 = 1 - w0 - w1;
			if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9)
				continue;
			double a = w0 * val[0] + w1 * val[1] + w2 * val[2];
			img[(size_t)py * sz + px] = (float)a;
		}
}

/* Unwritten texels (< 0) next to written ones take their mean, `rings` times
 * (bilinear lookups across UV seams read real values); the rest 1. */
static void dilate(float *img, int sz, int rings)
{
	float *next = xmalloc(sizeof *next * (size_t)sz * sz);
	for (int r = 0; r < rings; r++) {
		memcpy(next, img, sizeof *next * (size_t)sz * sz);
		for (int y = 0; y < sz; y++)
			for (int x = 0; x < sz; x++) {
				if (img[(size_t)y * sz + x] >= 0)
					continue;
				double s = 0;
				int n = 0;
				for (int dy = -1; dy <= 1; dy++)
					for (int dx = -1; dx <= 1; dx++) {
						int xx = x + dx, yy = y + dy;
						if (xx < 0 || yy < 0 || xx >= sz || yy >= sz)
							continue;
						float w = img[(size_t)yy * sz + xx];
						if (w >= 0) {
							s += w;
							n++;
						}
					}
				if (n > 0)
					next[(size_t)y * sz + x] = (float)(s / n);
			}
		memcpy(img, next, sizeof *next * (size_t)sz * sz);
	}
	free(next);
	for (size_t i = 0; i < (size_t)sz * sz; i++)
		if (img[i] < 0)
			img[i] = 1;
}

int povao_write(const struct scene *s, const char *dir, const char *base, struct povao_stats *st,
    char **cause)
{
	int side = (int)floor(sqrt((double)s->fill_occlusion));
	*st = (struct povao_stats){ .n_rays = side * side };
	int any = 0;
	for (int i = 0; i < s->n_objects; i++)
		any |= povao_wanted(s, &s->objects[i]);
	if (!any)
		return 0;
	double t0 = util_now(), sum = 0;
	struct grid g;
	grid_make(s, &g);
	int sz = POVAO_SIZE, rc = 0;
	float *img = xmalloc(sizeof *img * (size_t)sz * sz);
	uint16_t *px = xmalloc(sizeof *px * (size_t)sz * sz);
	for (int i = 0; i < s->n_objects && rc == 0; i++) {
		const struct scene_object *o = &s->objects[i];
		if (!povao_wanted(s, o))
			continue;
		const struct mesh *m = o->mesh;
		/* Rays start 1e-4 of the scene's diagonal off the surface (0.2 mm
		 * on a standing figure) and ignore nearer hits. */
		double eps = g.eps;
		double *v = xmalloc(sizeof *v * (size_t)m->n_vertices);
		int n_traced = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : sum, n_traced)
		for (int k = 0; k < m->n_vertices; k++) {
			v[k] = 1;
			if (in_view(s, m->position[k])) {
				v[k] = visibility(&g, m, k, s->fill_occlusion, eps,
				    0x736b696e62616b65ull);
				sum += v[k];
				n_traced++;
			}
		}
		st->n_vertices += n_traced;
		for (size_t k = 0; k < (size_t)sz * sz; k++)
			img[k] = -1;
		for (int f = 0; f < m->n_triangles; f++) {
			double uv[3][2], val[3];
			for (int c = 0; c < 3; c++) {
				int w = m->triangle[f][c];
				uv[c][0] = m->uv[w][0];
				uv[c][1] = m->uv[w][1];
				val[c] = v[w];
			}
			raster(img, sz, uv, val);
		}
		free(v);
		dilate(img, sz, 8);
		for (size_t k = 0; k < (size_t)sz * sz; k++)
			px[k] = (uint16_t)lround(fmin(fmax(img[k], 0), 1) * 65535.0);
		char *name = povao_name(base, o), *path = xasprintf("%s/%s", dir, name);
		rc = pngio_write(path, sz, sz, 1, 16, px, 0, 0, NULL, cause);
		free(name);
		free(path);
	}
	free(img);
	free(px);
	grid_free(&g);
	st->mean_v = st->n_vertices > 0 ? sum / st->n_vertices : 0;
	st->seconds = util_now() - t0;
	return rc;
}
