/* mesh2: write meshes as POV-Ray mesh2 objects with per-triangle bump maps
 * that follow the UVs. */
#include "config.h"

#include "export/pov/mesh2.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "export/pov/vec3.h"

static int root(int *parent, int a)
{
	while (parent[a] != a)
		a = parent[a] = parent[parent[a]];
	return a;
}

static double tri_area(const struct mesh *m, int t, double n[3])
{
	const double *p0 = m->position[m->triangle[t][0]], *p1 = m->position[m->triangle[t][1]],
		     *p2 = m->position[m->triangle[t][2]];
	double e1[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] }, e2[3] = { p2[0] - p0[0], p2[1] - p0[1],
		p2[2] - p0[2] };
	vec3_cross(e1, e2, n);
	return 0.5 * sqrt(vec3_dot(n, n));
}

static double uv_area(const struct mesh *m, int t)
{
	const double *a = m->uv[m->triangle[t][0]], *b = m->uv[m->triangle[t][1]], *c = m->uv[m->triangle[t][2]];
	return 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

void mesh2_uvmap_make(const struct mesh *m, struct mesh2_uvmap *u)
{
	*u = (struct mesh2_uvmap){ 0 };
	if (m->uv == NULL)
		return;
	int *parent = xmalloc(sizeof(int) * (size_t)m->n_vertices), *id = xmalloc(sizeof(int) * (size_t)m->n_vertices);
	for (int v = 0; v < m->n_vertices; v++) {
		parent[v] = v;
		id[v] = -1;
	}
	for (int t = 0; t < m->n_triangles; t++) {
		int a = root(parent, m->triangle[t][0]);
		for (int j = 1; j < 3; j++) {
			int b = root(parent, m->triangle[t][j]);
			if (a != b)
				parent[b] = a;
		}
	}
	u->island = xmalloc(sizeof(int) * (size_t)m->n_triangles);
	for (int t = 0; t < m->n_triangles; t++) {
		int r = root(parent, m->triangle[t][0]);
		if (id[r] < 0)
			id[r] = u->n_islands++;
		u->island[t] = id[r];
	}
	double *area = xcalloc((size_t)u->n_islands, sizeof(double)), *uva = xcalloc((size_t)u->n_islands, sizeof(double));
	u->scale = xmalloc(sizeof(double) * (size_t)u->n_islands);
	for (int t = 0; t < m->n_triangles; t++) {
		double n[3];
		area[u->island[t]] += tri_area(m, t, n);
		uva[u->island[t]] += uv_area(m, t);
	}
	for (int i = 0; i < u->n_islands; i++)
		u->scale[i] = uva[i] > 0 ? sqrt(area[i] / uva[i]) : 0;
	free(area);
	free(uva);
	free(parent);
	free(id);
}

void mesh2_uvmap_free(struct mesh2_uvmap *u)
{
	free(u->island);
	free(u->scale);
	*u = (struct mesh2_uvmap){ 0 };
}

int mesh2_bump_matrix(const struct mesh *m, const struct mesh2_uvmap *u, int t, double tile_units, double out[12])
{
	const int *tri = m->triangle[t];
	double n[3], s = u->scale[u->island[t]] / tile_units;
	double area = tri_area(m, t, n);
	const double *p0 = m->position[tri[0]], *q0 = m->uv[tri[0]];
	double e1[3], e2[3];
	for (int i = 0; i < 3; i++) {
		e1[i] = m->position[tri[1]][i] - p0[i];
		e2[i] = m->position[tri[2]][i] - p0[i];
	}
	/* Texture coordinates in tiles: x = u s, y = v s. */
	double du1 = (m->uv[tri[1]][0] - q0[0]) * s, dv1 = (m->uv[tri[1]][1] - q0[1]) * s;
	double du2 = (m->uv[tri[2]][0] - q0[0]) * s, dv2 = (m->uv[tri[2]][1] - q0[1]) * s;
	double det = du1 * dv2 - du2 * dv1;
	if (!(area > 0) || !(fabs(det) > 1e-9 * (du1 * du1 + dv1 * dv1 + du2 * du2 + dv2 * dv2)))
		return -1;
	/* Outward: the side the vertex normals are on. */
	const double *vn = m->normal[tri[0]];
	double out_sign = vec3_dot(n, vn) + vec3_dot(n, m->normal[tri[1]]) + vec3_dot(n, m->normal[tri[2]]) < 0 ? -1 : 1;
	double nl = 2 * area;
	for (int i = 0; i < 3; i++) {
		double T = (e1[i] * dv2 - e2[i] * dv1) / det, B = (e2[i] * du1 - e1[i] * du2) / det;
		out[i] = T;
		out[3 + i] = B;
		out[6 + i] = -out_sign * n[i] / nl * tile_units;
		out[9 + i] = p0[i] - T * q0[0] * s - B * q0[1] * s;
	}
	return 0;
}

void mesh2_visible(const struct mesh *m, const struct scene_camera *c, double aspect, unsigned char *on)
{
	double d[3], sky[3] = { 0, 1, 0 }, r[3], up[3];
	vec3_unit_toward(c->location, c->look_at, d);
	vec3_cross(sky, d, r);
	double rn = sqrt(vec3_dot(r, r));
	for (int i = 0; i < 3; i++)
		r[i] = rn > 0 ? r[i] / rn : (i == 0);
	vec3_cross(d, r, up);
	double hx = c->ortho ? 0.5 * c->width : tan(0.5 * c->angle), hy = hx / aspect;
	for (int t = 0; t < m->n_triangles; t++) {
		double ctr[3] = { 0, 0, 0 }, rad = 0, facing = -1;
		for (int j = 0; j < 3; j++)
			for (int i = 0; i < 3; i++)
				ctr[i] += m->position[m->triangle[t][j]][i] / 3;
		for (int j = 0; j < 3; j++) {
			const double *p = m->position[m->triangle[t][j]];
			double e[3] = { p[0] - ctr[0], p[1] - ctr[1], p[2] - ctr[2] }, toc[3];
			rad = fmax(rad, sqrt(vec3_dot(e, e)));
			if (c->ortho) {
				toc[0] = -d[0];
				toc[1] = -d[1];
				toc[2] = -d[2];
			} else
				vec3_unit_toward(p, c->location, toc);
			facing = fmax(facing, vec3_dot(toc, m->normal[m->triangle[t][j]]));
		}
		double q[3] = { ctr[0] - c->location[0], ctr[1] - c->location[1], ctr[2] - c->location[2] };
		double z = vec3_dot(q, d), x = vec3_dot(q, r), y = vec3_dot(q, up);
		int inside;
		if (c->ortho)
			inside = fabs(x) <= 1.1 * hx + rad && fabs(y) <= 1.1 * hy + rad;
		else
			inside = z > -rad && fabs(x) <= 1.1 * hx * fmax(z, 0) + 1.5 * rad
			    && fabs(y) <= 1.1 * hy * fmax(z, 0) + 1.5 * rad;
		on[t] = inside && facing > -0.2;
	}
}

/* One bumped triangle's texture, MAT its matrix.  With a cavity map the
 * texture's body (without its "texture {" and last "}") goes into a
 * texture_map over the map; the pattern's own matrix (inside
 * pigment_pattern) leaves the table's world-space pigments alone. */
static void write_texture(FILE *fp, const struct mesh2_textures *tex, const char *mat)
{
	const char *pre = tex->pre;
	size_t npost = strlen(tex->post);
	int cav = tex->cavity_png != NULL && strncmp(pre, "texture {", 9) == 0 && npost > 0
	    && tex->post[npost - 1] == '}';
	if (cav) {
		fprintf(fp, ",\n  texture { pigment_pattern { image_map { png \"%s\" "
		    "interpolate 2 }%s } texture_map { [0 SKIN_CavityBlack] [1",
		    tex->cavity_png, mat);
		pre += 9;
		npost--;
	} else
		fputs(",\n  ", fp);
	if (tex->mid)
		fprintf(fp, "%s%s%s%s%.*s", pre, mat, tex->mid, mat, (int)npost, tex->post);
	else
		fprintf(fp, "%s%s%.*s", pre, mat, (int)npost, tex->post);
	if (cav)
		fputs("] } }", fp);
}

int mesh2_write(FILE *fp, const char *name, const struct mesh *m, double inset, const struct mesh2_textures *tex)
{
	int nb = 0;
	fprintf(fp, "#declare %s = mesh2 {\n vertex_vectors { %d", name, m->n_vertices);
	for (int v = 0; v < m->n_vertices; v++) {
		const double *p = m->position[v], *n = m->normal[v];
		fprintf(fp, ",\n  <%.9g,%.9g,%.9g>", p[0] - inset * n[0], p[1] - inset * n[1], p[2] - inset * n[2]);
	}
	fprintf(fp, " }\n normal_vectors { %d", m->n_vertices);
	for (int v = 0; v < m->n_vertices; v++)
		fprintf(fp, ",\n  <%.7f,%.7f,%.7f>", m->normal[v][0], m->normal[v][1], m->normal[v][2]);
	fputs(" }\n", fp);
	if (m->uv != NULL) {
		fprintf(fp, " uv_vectors { %d", m->n_vertices);
		for (int v = 0; v < m->n_vertices; v++)
			fprintf(fp, ",\n  <%.9g,%.9g>", m->uv[v][0], m->uv[v][1]);
		fputs(" }\n", fp);
	}
	int *tx = NULL;
	if (tex != NULL) {
		/* Texture 0 is the plain one; each bump triangle gets its own. */
		tx = xcalloc((size_t)m->n_triangles, sizeof(int));
		double (*mx)[12] = xmalloc(sizeof *mx * (size_t)m->n_triangles);
		for (int t = 0; t < m->n_triangles; t++)
			if ((tex->on == NULL || tex->on[t]) && tex->uv->n_islands > 0
			    && mesh2_bump_matrix(m, tex->uv, t, tex->tile_units, mx[t]) == 0)
				tx[t] = ++nb;
		fprintf(fp, " texture_list { %d,\n  %s", nb + 1, tex->plain);
		for (int t = 0; t < m->n_triangles; t++) {
			if (!tx[t])
				continue;
			char mat[256];
			snprintf(mat, sizeof mat, " matrix <%.7g,%.7g,%.7g, %.7g,%.7g,%.7g, "
			    "%.7g,%.7g,%.7g, %.9g,%.9g,%.9g>",
			    mx[t][0], mx[t][1], mx[t][2], mx[t][3], mx[t][4], mx[t][5], mx[t][6],
			    mx[t][7], mx[t][8], mx[t][9], mx[t][10], mx[t][11]);
			write_texture(fp, tex, mat);
		}
		fputs(" }\n", fp);
		free(mx);
	}
	fprintf(fp, " face_indices { %d", m->n_triangles);
	for (int t = 0; t < m->n_triangles; t++) {
		fprintf(fp, ",\n  <%d,%d,%d>", m->triangle[t][0], m->triangle[t][1], m->triangle[t][2]);
		if (tx != NULL)
			fprintf(fp, ",%d", tx[t]);
	}
	fputs(" }\n}\n", fp);
	free(tx);
	return nb;
}
