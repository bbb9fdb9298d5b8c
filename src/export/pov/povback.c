/* povback: the back light through thin parts of translucent meshes: the
 * thickness per vertex, the stack's transmittance, the emitting copy (see
 * povback.h). */
#include "config.h"
#include "export/pov/povback.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "export/pov/meshray.h"
#include "export/pov/sdl.h"
#include "export/pov/vec3.h"
#include "export/sss_tt.h"
#include "geom/mesh.h"

const double povback_d_mm[POVBACK_N] = { 0.25, 0.5, 0.75, 1, 1.5, 2, 3, 4, 6, 8, 12, 16 };

void povback_setup(struct pov_back *pb, const struct bake *b, const struct sss_fit *f)
{
	char *cause = NULL;
	memset(pb, 0, sizeof *pb);
	if (sss_stack_tt(b, povback_d_mm, POVBACK_N, pb->tt, &cause) != 0) {
		snprintf(pb->why, sizeof pb->why, "no transmittance: %s", cause ? cause : "?");
		free(cause);
		return;
	}
	for (int k = 0; k < POVBACK_N; k++)
		for (int c = 0; c < 3; c++)
			pb->closure[k][c] = POVBACK_KAPPA
			    * sss_fit_ring(f, c, povback_d_mm[k], 1e4);
	pb->on = 1;
}

static double extra_at(const struct pov_back *pb, int c, int k)
{
	return fmax(pb->tt[k][c] - pb->closure[k][c], 0.0);
}

double povback_extra(const struct pov_back *pb, int c, double d_mm)
{
	if (!pb->on || d_mm > povback_d_mm[POVBACK_N - 1])
		return 0.0;
	if (d_mm <= povback_d_mm[0])
		return extra_at(pb, c, 0);
	int k = 1;
	while (povback_d_mm[k] < d_mm)
		k++;
	double a = extra_at(pb, c, k - 1), b = extra_at(pb, c, k);
	double x = (d_mm - povback_d_mm[k - 1]) / (povback_d_mm[k] - povback_d_mm[k - 1]);
	if (a <= 0 || b <= 0)
		return a + x * (b - a);
	return exp(log(a) + x * (log(b) - log(a)));
}

/* The irradiance of the scene's lights at Q (unit outward normal N) past
 * the mesh (POV-Ray light colour: irradiance at normal incidence). */
static void irradiance(const struct scene *s, const struct meshray *g, const double q[3],
    const double n[3], double eps, double e[3])
{
	e[0] = e[1] = e[2] = 0;
	for (int i = 0; i < s->n_lights; i++) {
		const struct scene_light *l = &s->lights[i];
		double dir[3], far = INFINITY;
		if (l->type == SCENE_LIGHT_PARALLEL)
			vec3_unit_toward(l->point_at, l->position, dir);
		else {
			vec3_unit_toward(q, l->position, dir);
			double v[3];
			for (int j = 0; j < 3; j++)
				v[j] = l->position[j] - q[j];
			far = sqrt(vec3_dot(v, v));
		}
		double cosi = vec3_dot(n, dir);
		if (cosi <= 0)
			continue;
		double o[3] = { q[0] + eps * n[0], q[1] + eps * n[1], q[2] + eps * n[2] };
		struct meshray_hit h;
		if (meshray_cast(g, o, dir, eps, far, 1, &h))
			continue;
		for (int c = 0; c < 3; c++)
			e[c] += l->color[c] * cosi;
	}
}

/* The hit triangle's normal at the hit, unit. */
static void hit_normal(const struct mesh *m, const struct meshray_hit *h, double n[3])
{
	const int *t = m->triangle[h->tri];
	double b0 = 1 - h->b1 - h->b2;
	for (int i = 0; i < 3; i++)
		n[i] = b0 * m->normal[t[0]][i] + h->b1 * m->normal[t[1]][i]
		    + h->b2 * m->normal[t[2]][i];
	double len = sqrt(vec3_dot(n, n));
	for (int i = 0; i < 3; i++)
		n[i] = len > 0 ? n[i] / len : 0;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

/* T E per vertex into out[3 v] (0 where nothing comes through); the
 * thicknesses of the hit vertices into *st. */
static void transmitted(const struct scene *s, const struct mesh *m, const struct pov_back *pb,
    float *out, struct povback_stats *st)
{
	struct meshray g;
	meshray_make(&g, m);
	double diag[3];
	for (int i = 0; i < 3; i++)
		diag[i] = g.hi[i] - g.lo[i];
	double eps = 1e-5 * sqrt(vec3_dot(diag, diag));
	double dmax = povback_d_mm[POVBACK_N - 1] / s->unit_mm;
	double *ds = xmalloc(sizeof(double) * ((size_t)m->n_vertices + 1));
	for (int v = 0; v < m->n_vertices; v++) {
		const double *p = m->position[v], *nv = m->normal[v];
		double in[3] = { -nv[0], -nv[1], -nv[2] }, nq[3], e[3];
		struct meshray_hit h;
		out[3 * v] = out[3 * v + 1] = out[3 * v + 2] = 0;
		if (!meshray_cast(&g, p, in, eps, dmax, 0, &h))
			continue;
		hit_normal(m, &h, nq);
		if (vec3_dot(nq, in) <= 0)	/* not the mesh's other side */
			continue;
		double d_mm = h.t * s->unit_mm, q[3];
		ds[st->n_vertices++] = d_mm;
		for (int i = 0; i < 3; i++)
			q[i] = p[i] + h.t * in[i];
		irradiance(s, &g, q, nq, eps, e);
		for (int c = 0; c < 3; c++)
			out[3 * v + c] = (float)(povback_extra(pb, c, d_mm) * e[c]);
		st->n_lit += out[3 * v] > 0 || out[3 * v + 1] > 0 || out[3 * v + 2] > 0;
	}
	if (st->n_vertices > 0) {
		qsort(ds, (size_t)st->n_vertices, sizeof(double), cmp_double);
		st->d_min_mm = ds[0];
		st->d_median_mm = ds[st->n_vertices / 2];
	}
	free(ds);
	meshray_free(&g);
}

static int lit(const float *te, int v)
{
	return te[3 * v] > 0 || te[3 * v + 1] > 0 || te[3 * v + 2] > 0;
}

/* The copy's mesh2: the vertices of triangles with a lit vertex (new index
 * in idx), one texture per triangle, the mean of its vertices' emission.
 * Not one texture per vertex: POV-Ray 3.7 shades each of a triangle's three
 * textures on its own, and with a clear copy each traces on into the
 * subsurface skin; on the MakeHuman head lit from behind that took an 80x60
 * render from 2.4 s to over 300 s of CPU. */
static void write_copy(FILE *fp, const struct mesh *m, const float *te, const int *keep, int *idx,
    double lift)
{
	int nv = 0, nt = 0;
	for (int v = 0; v < m->n_vertices; v++)
		idx[v] = -1;
	/* Numbered in vertex order, the order vertex_vectors lists them in. */
	for (int t = 0; t < m->n_triangles; t++)
		for (int j = 0; j < 3 && keep[t]; j++)
			idx[m->triangle[t][j]] = 0;
	for (int v = 0; v < m->n_vertices; v++)
		if (idx[v] == 0)
			idx[v] = nv++;
	for (int t = 0; t < m->n_triangles; t++)
		nt += keep[t];
	fprintf(fp, "mesh2 {\n  vertex_vectors { %d", nv);
	for (int v = 0; v < m->n_vertices; v++)
		if (idx[v] >= 0) {
			double p[3];
			for (int i = 0; i < 3; i++)
				p[i] = m->position[v][i] + lift * m->normal[v][i];
			fputs(",\n    ", fp);
			sdl_vec(fp, p);
		}
	fprintf(fp, " }\n  normal_vectors { %d", nv);
	for (int v = 0; v < m->n_vertices; v++)
		if (idx[v] >= 0) {
			fputs(",\n    ", fp);
			sdl_vec(fp, m->normal[v]);
		}
	fprintf(fp, " }\n  texture_list { %d", nt);
	double k = 1 / (1 - POVBACK_CLEAR);
	for (int t = 0; t < m->n_triangles; t++) {
		if (!keep[t])
			continue;
		const int *tr = m->triangle[t];
		double e[3];
		for (int c = 0; c < 3; c++)
			e[c] = k * (te[3 * tr[0] + c] + te[3 * tr[1] + c] + te[3 * tr[2] + c]) / 3;
		fprintf(fp, ",\n    texture { pigment { rgbt <" SDL_G "," SDL_G "," SDL_G ","
		    SDL_G "> } "
		    "finish { diffuse 0 ambient 0 emission 1 specular 0 } }", e[0], e[1], e[2],
		    POVBACK_CLEAR);
	}
	fprintf(fp, " }\n  face_indices { %d", nt);
	int n = 0;
	for (int t = 0; t < m->n_triangles; t++)
		if (keep[t]) {
			const int *tr = m->triangle[t];
			fprintf(fp, ",\n    <%d,%d,%d>, %d", idx[tr[0]], idx[tr[1]], idx[tr[2]],
			    n++);
		}
	fputs(" }\n  no_shadow\n}\n", fp);
}

void povback_write(FILE *fp, const struct scene *s, const struct scene_object *o,
    const struct pov_back *pb, double lift, struct povback_stats *st)
{
	const struct mesh *m = o->mesh;
	memset(st, 0, sizeof *st);
	if (!pb->on) {
		fprintf(fp, "// object %s: no back light through it (%s)\n", o->name, pb->why);
		return;
	}
	float *te = xmalloc(sizeof(float) * 3 * ((size_t)m->n_vertices + 1));
	transmitted(s, m, pb, te, st);
	int *keep = xcalloc((size_t)m->n_triangles + 1, sizeof(int));
	for (int t = 0; t < m->n_triangles; t++) {
		const int *tr = m->triangle[t];
		keep[t] = lit(te, tr[0]) || lit(te, tr[1]) || lit(te, tr[2]);
		st->n_triangles += keep[t];
	}
	fprintf(fp, "// object %s: the back light through its thin parts (povback.h): "
	    "%d of %d vertices lit through,\n// thickness from %.3g mm (median %.3g mm) "
	    "over the %d whose inward ray meets its other side\n", o->name, st->n_lit,
	    m->n_vertices, st->d_min_mm, st->d_median_mm, st->n_vertices);
	if (st->n_triangles > 0) {
		int *idx = xmalloc(sizeof(int) * (size_t)m->n_vertices);
		write_copy(fp, m, te, keep, idx, lift);
		free(idx);
	}
	free(keep);
	free(te);
}
