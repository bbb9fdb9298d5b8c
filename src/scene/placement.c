/* placement: where a scene's lights and objects are in POV-Ray's world:
 * light directions, object bounds, object transforms, and meshes read in
 * their files' right-handed coordinates placed there. */
#include "config.h"

#include "scene/placement.h"

#include <math.h>
#include <string.h>

#include "geom/mesh.h"

static double dist3(const double a[3], const double b[3])
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

void placement_light_dir(const struct scene_light *l, const double p[3], double out[3])
{
	const double *from = l->position, *to = l->type == SCENE_LIGHT_PARALLEL ? l->point_at : p;
	double n = dist3(from, to);
	for (int i = 0; i < 3; i++)
		out[i] = n > 0 ? (from[i] - to[i]) / n : (i == 2 ? -1 : 0);
}
void placement_bounds(const struct scene_object *o, double lo[3], double hi[3])
{
	double r;
	switch (o->shape) {
	case SCENE_SPHERE:
		for (int i = 0; i < 3; i++) {
			lo[i] = o->center[i] - o->radius;
			hi[i] = o->center[i] + o->radius;
		}
		return;
	case SCENE_BOX:
	case SCENE_PATCH:
		r = 0.5 * sqrt(o->size[0] * o->size[0] + o->size[1] * o->size[1] + o->size[2] * o->size[2]);
		break;
	case SCENE_PLANE:
		for (int i = 0; i < 3; i++) {
			lo[i] = -1e3;
			hi[i] = 1e3;
		}
		return;
	case SCENE_MESH:
		memcpy(lo, o->mesh_lo, sizeof o->mesh_lo);
		memcpy(hi, o->mesh_hi, sizeof o->mesh_hi);
		return;
	case SCENE_HAND:
	case SCENE_HEAD:
	default:
		/* The shape macros fit in a sphere of radius 1.5 about the origin
		 * before scale (exporters/pov/skinbake_shapes.inc). */
		r = 1.5;
		break;
	}
	r *= o->scale;
	const double *c = o->shape == SCENE_BOX || o->shape == SCENE_PATCH ? o->center : o->translate;
	for (int i = 0; i < 3; i++) {
		double ci = c[i] + (o->shape == SCENE_BOX || o->shape == SCENE_PATCH ? o->translate[i] : 0);
		lo[i] = ci - r;
		hi[i] = ci + r;
	}
}
void placement_dir(const struct scene_object *o, const double d[3], double out[3])
{
	/* POV-Ray's rotate: about x, then y, then z (left-handed). */
	double a = o->rotate[0], b = o->rotate[1], c = o->rotate[2], t[3], u[3];
	t[0] = d[0];
	t[1] = d[1] * cos(a) - d[2] * sin(a);
	t[2] = d[1] * sin(a) + d[2] * cos(a);
	u[0] = t[0] * cos(b) + t[2] * sin(b);
	u[1] = t[1];
	u[2] = -t[0] * sin(b) + t[2] * cos(b);
	out[0] = u[0] * cos(c) - u[1] * sin(c);
	out[1] = u[0] * sin(c) + u[1] * cos(c);
	out[2] = u[2];
}
void placement_point(const struct scene_object *o, const double p[3], double out[3])
{
	double q[3] = { p[0] * o->scale, p[1] * o->scale, p[2] * o->scale };
	placement_dir(o, q, out);
	for (int i = 0; i < 3; i++)
		out[i] += o->translate[i];
}

void placement_mesh(struct scene_object *o)
{
	/* The file is right-handed, POV-Ray left-handed: mirror z (a model
	 * facing +z faces the default POV-Ray camera at -z); then scale,
	 * rotate, translate. */
	struct mesh *m = o->mesh;
	for (int v = 0; v < m->n_vertices; v++) {
		double q[3] = { m->position[v][0], m->position[v][1], -m->position[v][2] };
		double n[3] = { m->normal[v][0], m->normal[v][1], -m->normal[v][2] };
		placement_point(o, q, m->position[v]);
		placement_dir(o, n, m->normal[v]);
		if (m->tangent) {
			double t[3] = { m->tangent[v][0], m->tangent[v][1], -m->tangent[v][2] };
			placement_dir(o, t, m->tangent[v]);
			m->tangent[v][3] = -m->tangent[v][3];	/* the mirror flips the frame */
		}
	}
	mesh_bounds(m, o->mesh_lo, o->mesh_hi);
}

int placement_load_mesh(struct scene_object *o, char **cause)
{
	o->mesh = mesh_load(o->file, o->mesh_name, cause);
	if (o->mesh == NULL)
		return -1;
	for (int i = 0; i < o->subdivide; i++)
		mesh_subdivide(o->mesh);
	placement_mesh(o);
	return 0;
}
