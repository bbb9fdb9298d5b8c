/* strategy: choose the light strategy and convert the scene's lights and
 * camera for the table writers. */
#include "config.h"

#include "export/pov/strategy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/mesh.h"

#include "scene/placement.h"
#include "export/pov/vec3.h"

/* One surface point: the exact two-light radiance and the mixture table's. */
static void mixture_point(const struct pov_brdf *f, const struct pov_light pl[2], const struct pov_view *v,
    const double cg_table[2], const double p[3], const double n[3], double *err, double *sum)
{
	double w[3], l[2][3], ti[2], ci[2], cg[2];
	littable_view_dir(v, p, w);
	double co = vec3_dot(n, w);
	if (co <= 0.02)
		return;	/* facing away, or so grazing it hardly shows */
	for (int j = 0; j < 2; j++) {
		littable_light_dir(&pl[j], p, l[j]);
		ci[j] = vec3_dot(n, l[j]);
		ti[j] = acos(fmax(0, fmin(1, ci[j])));
		cg[j] = vec3_dot(l[j], w);
	}
	if (ci[0] <= 0 && ci[1] <= 0)
		return;
	double to = acos(fmin(1, co)), mix[3], exact[3] = { 0, 0, 0 };
	littable_mixture_value(f, pl, ti, to, cg_table, mix);
	for (int j = 0; j < 2; j++) {
		double fj[3];
		if (ci[j] <= 0)
			continue;
		f->f_rgb(f->ctx, ti[j], to, littable_dphi(ti[j], to, cg[j]), fj);
		for (int c = 0; c < 3; c++)
			exact[c] += pl[j].rgb[c] * ci[j] * M_PI * fj[c];
	}
	for (int c = 0; c < 3; c++) {
		double m = (pl[0].rgb[c] * fmax(ci[0], 0) + pl[1].rgb[c] * fmax(ci[1], 0)) * mix[c];
		*err += fabs(m - exact[c]);
		*sum += exact[c];
	}
}

enum scene_strategy strategy_resolve(const struct scene *s, const struct pov_brdf *const *brdf, double *mix_error)
{
	if (mix_error)
		*mix_error = -1;
	if (s->lights_strategy != SCENE_LIGHTS_AUTO)
		return s->lights_strategy;
	if (s->n_lights == 1)
		return SCENE_LIGHTS_KEY;
	if (s->n_lights > 2)
		return SCENE_LIGHTS_PASSES;
	double e = strategy_mixture_error(s, brdf);
	if (mix_error)
		*mix_error = e;
	return e < STRATEGY_MIX_MAX ? SCENE_LIGHTS_MIXTURE : SCENE_LIGHTS_PASSES;
}

/* Sample points (world position and unit normal) of object o: at most
 * about `want` of them. */
static int object_points(const struct scene *s, const struct scene_object *o, int want, double (*p)[3], double (*n)[3])
{
	int k = 0;
	if (o->shape == SCENE_MESH) {
		/* Vertices in view, evenly thinned. */
		int seen = 0;
		for (int v = 0; v < o->mesh->n_vertices; v++)
			seen += strategy_in_view(s, o->mesh->position[v], 0);
		int step = seen / want + 1, i = 0;
		for (int v = 0; v < o->mesh->n_vertices && k < want; v++)
			if (strategy_in_view(s, o->mesh->position[v], 0) && i++ % step == 0) {
				memcpy(p[k], o->mesh->position[v], sizeof p[k]);
				memcpy(n[k], o->mesh->normal[v], sizeof n[k]);
				k++;
			}
		return k;
	}
	double h[3] = { 0.5 * o->size[0], 0.5 * o->size[1], 0.5 * o->size[2] };
	for (int i = 0; i < want; i++) {
		double d[3], q[3];
		/* Fibonacci sphere: even directions. */
		double z = 1 - (2.0 * i + 1) / want, r = sqrt(1 - z * z), a = i * M_PI * (3 - sqrt(5));
		d[0] = r * cos(a);
		d[1] = r * sin(a);
		d[2] = z;
		switch (o->shape) {
		case SCENE_SPHERE:
			for (int j = 0; j < 3; j++)
				q[j] = o->center[j] + o->radius * d[j];
			break;
		case SCENE_BOX:
		case SCENE_PATCH: {
			/* The point of the box's surface along d (the patch: its front). */
			int ax = fabs(d[0]) > fabs(d[1]) ? (fabs(d[0]) > fabs(d[2]) ? 0 : 2) : (fabs(d[1]) > fabs(d[2]) ? 1 : 2);
			if (o->shape == SCENE_PATCH) {
				ax = 2;
				d[2] = -1;
			}
			double t = h[ax] / fabs(d[ax]);
			for (int j = 0; j < 3; j++)
				q[j] = o->center[j] + (j == ax ? (d[j] < 0 ? -h[j] : h[j]) : fmax(-h[j], fmin(h[j], t * d[j])));
			if (o->shape == SCENE_PATCH)
				q[2] = o->center[2];
			memset(d, 0, sizeof d);
			d[ax] = q[ax] < o->center[ax] ? -1 : 1;
			break;
		}
		case SCENE_PLANE:
			/* Around the origin's foot on the plane, within a few units. */
			for (int j = 0; j < 3; j++)
				q[j] = o->normal[j] * o->offset + 2 * (d[j] - vec3_dot(d, o->normal) * o->normal[j]);
			memcpy(d, o->normal, sizeof d);
			break;
		default:	/* hand, head: the sphere they fit in */
			for (int j = 0; j < 3; j++)
				q[j] = 1.5 * d[j];
			break;
		}
		if (o->shape == SCENE_PLANE) {
			memcpy(p[k], q, sizeof q);
			memcpy(n[k], d, sizeof d);
		} else {
			placement_point(o, q, p[k]);
			placement_dir(o, d, n[k]);
		}
		k++;
	}
	return k;
}

double strategy_mixture_error(const struct scene *s, const struct pov_brdf *const *brdf)
{
	enum { WANT = 1500 };
	struct pov_light pl[2];
	struct pov_view v;
	double (*p)[3] = malloc(sizeof *p * WANT), (*n)[3] = malloc(sizeof *n * WANT), err = 0, sum = 0;
	struct pov_brdf analytic = { .f_rgb = littable_brdf_analytic };
	if (p == NULL || n == NULL || s->n_lights != 2) {
		free(p);
		free(n);
		return s->n_lights == 2 ? 1 : 0;
	}
	strategy_light(&s->lights[0], &pl[0]);
	strategy_light(&s->lights[1], &pl[1]);
	strategy_view(&s->camera, &v);
	for (int k = 0; k < s->n_skins; k++) {
		const struct pov_brdf *f = brdf && brdf[k] ? brdf[k] : &analytic;
		double lo[3], hi[3], cg[2];
		strategy_skin_bounds(s, k, lo, hi);
		double mid[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
		for (int j = 0; j < 2; j++)	/* what the table takes */
			cg[j] = littable_cos_gamma(&pl[j], &v, mid);
		int any = 0;
		for (int i = 0; i <= s->n_objects; i++) {
			/* Without skin objects (include only): a unit sphere at the
			 * look_at point, where the tables are made for. */
			struct scene_object ball = { .shape = SCENE_SPHERE, .material = SCENE_MAT_SKIN, .skin = k,
				.radius = 1, .scale = 1 };
			memcpy(ball.center, s->camera.look_at, sizeof ball.center);
			const struct scene_object *o = i < s->n_objects ? &s->objects[i] : any ? NULL : &ball;
			if (o == NULL || o->material != SCENE_MAT_SKIN || o->skin != k)
				continue;
			any = 1;
			int np = object_points(s, o, WANT, p, n);
			for (int q = 0; q < np; q++)
				if (strategy_in_view(s, p[q], 0))
					mixture_point(f, pl, &v, cg, p[q], n[q], &err, &sum);
		}
	}
	free(p);
	free(n);
	return sum > 0 ? err / sum : 0;
}

void strategy_light(const struct scene_light *sl, struct pov_light *l)
{
	*l = (struct pov_light){ .parallel = sl->type == SCENE_LIGHT_PARALLEL };
	memcpy(l->pos, sl->position, sizeof l->pos);
	memcpy(l->rgb, sl->color, sizeof l->rgb);
	double o[3] = { 0, 0, 0 };
	placement_light_dir(sl, o, l->dir);
}

void strategy_view(const struct scene_camera *c, struct pov_view *v)
{
	*v = (struct pov_view){ .ortho = c->ortho };
	memcpy(v->pos, c->location, sizeof v->pos);
	vec3_unit_toward(c->look_at, c->location, v->dir);
}

int strategy_in_view(const struct scene *s, const double p[3], double margin)
{
	const struct scene_camera *c = &s->camera;
	double d[3], sky[3] = { 0, 1, 0 }, r[3], up[3], q[3];
	vec3_unit_toward(c->location, c->look_at, d);
	vec3_cross(sky, d, r);
	double rn = sqrt(vec3_dot(r, r));
	for (int i = 0; i < 3; i++) {
		r[i] = rn > 0 ? r[i] / rn : (i == 0);
		q[i] = p[i] - c->location[i];
	}
	vec3_cross(d, r, up);
	double hx = (1 + margin) * (c->ortho ? 0.5 * c->width : tan(0.5 * c->angle)), hy = hx * s->height / s->width;
	double z = vec3_dot(q, d), x = vec3_dot(q, r), y = vec3_dot(q, up);
	if (c->ortho)
		return fabs(x) <= hx && fabs(y) <= hy;
	return z > 0 && fabs(x) <= hx * z && fabs(y) <= hy * z;
}

int strategy_skin_bounds(const struct scene *s, int k, double lo[3], double hi[3])
{
	int any = 0;
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		double a[3], b[3];
		if (o->material != SCENE_MAT_SKIN || o->skin != k)
			continue;
		if (o->shape == SCENE_MESH) {
			/* Only what the camera sees: a whole figure seen as a head
			 * would otherwise spread the tables over the body. */
			int seen = 0;
			for (int v = 0; v < o->mesh->n_vertices; v++) {
				const double *p = o->mesh->position[v];
				if (!strategy_in_view(s, p, 0.1))
					continue;
				for (int j = 0; j < 3; j++) {
					a[j] = seen ? fmin(a[j], p[j]) : p[j];
					b[j] = seen ? fmax(b[j], p[j]) : p[j];
				}
				seen = 1;
			}
			if (!seen)
				continue;
		} else
			placement_bounds(o, a, b);
		for (int j = 0; j < 3; j++) {
			lo[j] = any ? fmin(lo[j], a[j]) : a[j];
			hi[j] = any ? fmax(hi[j], b[j]) : b[j];
		}
		any = 1;
	}
	if (!any) /* include-only export: around the look_at point */
		for (int j = 0; j < 3; j++) {
			lo[j] = s->camera.look_at[j] - 1;
			hi[j] = s->camera.look_at[j] + 1;
		}
	return any;
}
