/* Meshes from model files (geom/mesh) and their POV-Ray form (export/pov/mesh2):
 * the same square read from OBJ, PLY, glTF and Collada; a file without UVs;
 * bad, unknown and missing files; choosing a mesh by name; the MakeHuman
 * model of assimp-testmodels (skipped when absent); UV islands and the
 * per-triangle bump matrices that make bump maps follow the UVs. */
#include "config.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/util.h"
#include "export/pov/mesh2.h"
#include "geom/mesh.h"

#define HUMAN "/usr/share/assimp/models/Collada/human.zae"

static char *fixture(const char *name)
{
	const char *top = getenv("top_srcdir");
	return xasprintf("%s/tests/data/mesh/%s", top ? top : ".", name);
}

static struct mesh *load(const char *name, const char *mesh, char **cause)
{
	char *p = fixture(name);
	*cause = NULL;
	struct mesh *m = mesh_load(p, mesh, cause);
	free(p);
	return m;
}

/* The unit square facing +z with u along +x, v along +y. */
static void check_square(const struct mesh *m)
{
	assert_int_equal(m->n_triangles, 2);
	assert_true(m->n_vertices >= 4 && m->n_vertices <= 6);
	assert_non_null(m->uv);
	assert_non_null(m->tangent);
	double lo[3], hi[3];
	mesh_bounds(m, lo, hi);
	for (int i = 0; i < 2; i++) {
		assert_float_equal(lo[i], 0, 1e-6);
		assert_float_equal(hi[i], 1, 1e-6);
	}
	assert_float_equal(lo[2], 0, 1e-6);
	assert_float_equal(hi[2], 0, 1e-6);
	assert_float_equal(mesh_area(m), 1, 1e-6);
	assert_float_equal(mesh_uv_area(m), 1, 1e-6);
	for (int v = 0; v < m->n_vertices; v++) {
		/* UVs follow the position; normal +z; tangent +x, bitangent +y. */
		assert_float_equal(m->uv[v][0], m->position[v][0], 1e-6);
		assert_float_equal(m->uv[v][1], m->position[v][1], 1e-6);
		assert_float_equal(m->normal[v][2], 1, 1e-6);
		assert_float_equal(m->tangent[v][0], 1, 1e-6);
		assert_float_equal(m->tangent[v][3], 1, 0);
	}
	/* Counter-clockwise seen from the normal side. */
	for (int t = 0; t < m->n_triangles; t++) {
		const double *a = m->position[m->triangle[t][0]], *b = m->position[m->triangle[t][1]],
			     *c = m->position[m->triangle[t][2]];
		assert_true((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0);
	}
}

static void test_formats(void **state)
{
	(void)state;
	static const char *files[] = { "square.obj", "square.ply", "square.gltf", "square.dae" };
	for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
		char *cause;
		struct mesh *m = load(files[i], NULL, &cause);
		if (m == NULL)
			fail_msg("%s: %s", files[i], cause);
		check_square(m);
		mesh_free(m);
	}
}

static void test_no_uv(void **state)
{
	(void)state;
	char *cause;
	struct mesh *m = load("square-nouv.obj", NULL, &cause);
	assert_non_null(m);
	assert_int_equal(m->n_triangles, 2);
	assert_null(m->uv);
	assert_null(m->tangent);
	/* Smooth normals made from the faces. */
	for (int v = 0; v < m->n_vertices; v++)
		assert_float_equal(fabs(m->normal[v][2]), 1, 1e-6);
	struct mesh2_uvmap u;
	mesh2_uvmap_make(m, &u);
	assert_int_equal(u.n_islands, 0);
	mesh2_uvmap_free(&u);
	mesh_free(m);
}

static void test_bad_files(void **state)
{
	(void)state;
	char *cause;
	assert_null(load("broken.gltf", NULL, &cause));
	assert_non_null(strstr(cause, "broken.gltf"));
	assert_non_null(strstr(cause, "not a model libassimp can read"));
	free(cause);
	assert_null(load("square.xyz", NULL, &cause));
	assert_non_null(strstr(cause, "unknown model format '.xyz'"));
	assert_non_null(strstr(cause, ".obj"));	/* the list of what is read */
	free(cause);
	assert_null(load("no-such-file.obj", NULL, &cause));
	assert_non_null(strstr(cause, "no-such-file.obj: No such file"));
	free(cause);
}

static void test_names(void **state)
{
	(void)state;
	char *cause;
	struct mesh *m = load("two.obj", NULL, &cause);
	assert_non_null(m);
	assert_int_equal(m->n_triangles, 4);
	mesh_free(m);
	m = load("two.obj", "right", &cause);
	assert_non_null(m);
	assert_int_equal(m->n_triangles, 2);
	double lo[3], hi[3];
	mesh_bounds(m, lo, hi);
	assert_float_equal(lo[0], 2, 1e-6);
	assert_non_null(strstr(m->source, "two.obj: right"));
	mesh_free(m);
	assert_null(load("two.obj", "middle", &cause));
	assert_non_null(strstr(cause, "no mesh 'middle'"));
	assert_non_null(strstr(cause, "'left'"));
	assert_non_null(strstr(cause, "'right'"));
	free(cause);
}

static void test_human(void **state)
{
	(void)state;
	if (access(HUMAN, R_OK) != 0)
		skip();
	char *cause = NULL;
	struct mesh *m = mesh_load(HUMAN, "human-baseMesh", &cause);
	assert_non_null(m);
	/* Facts of /work/shared/notes/human-model.md: 26,756 triangles, metres,
	 * y up, the head's top at 1.66 m. */
	assert_int_equal(m->n_triangles, 26756);
	double lo[3], hi[3];
	mesh_bounds(m, lo, hi);
	assert_float_equal(hi[1], 1.66, 0.005);
	assert_float_equal(lo[1], 0, 0.005);
	assert_non_null(m->uv);
	mesh_free(m);
	m = mesh_load(HUMAN, "human-highpolyeyesMesh", &cause);
	assert_non_null(m);
	/* The eyes' texture is embedded in the .zae. */
	assert_non_null(m->texture);
	assert_string_equal(m->texture_type, "png");
	assert_true(m->texture_size > 1000 && !memcmp(m->texture, "\x89PNG", 4));
	mesh_free(m);
}

/* The bump matrix maps each corner's texture coordinates (u s / tile) onto
 * its position, and texture z onto the inward normal times the tile. */
static void test_bump_matrix(void **state)
{
	(void)state;
	char *cause;
	struct mesh *m = load("grid-turned.obj", NULL, &cause);
	assert_non_null(m);
	struct mesh2_uvmap u;
	mesh2_uvmap_make(m, &u);
	assert_int_equal(u.n_islands, 1);
	assert_float_equal(u.scale[0], 4, 1e-9);	/* 4 units per UV unit */
	double tile = 0.5, mx[12];
	for (int t = 0; t < m->n_triangles; t++) {
		assert_int_equal(mesh2_bump_matrix(m, &u, t, tile, mx), 0);
		for (int j = 0; j < 3; j++) {
			int v = m->triangle[t][j];
			double x = m->uv[v][0] * 4 / tile, y = m->uv[v][1] * 4 / tile;
			for (int i = 0; i < 3; i++)
				assert_float_equal(x * mx[i] + y * mx[3 + i] + mx[9 + i], m->position[v][i], 1e-9);
		}
		/* z: inward (the normals face +z) times the tile. */
		assert_float_equal(mx[6], 0, 1e-12);
		assert_float_equal(mx[7], 0, 1e-12);
		assert_float_equal(mx[8], -tile, 1e-12);
	}
	/* Turned UVs: texture x runs along +y (tile/4 per... 1/tile tiles per unit). */
	assert_float_equal(mx[0], 0, 1e-12);
	assert_float_equal(mx[1], tile, 1e-12);
	mesh2_uvmap_free(&u);
	mesh_free(m);
}

/* Smooth subdivision: on the flat square the new vertices are the edge
 * midpoints; on an octahedron with radial normals the PN edge point of the
 * edge (1,0,0)-(0,1,0) is (0.625, 0.625, 0), toward the sphere. */
static void test_subdivide(void **state)
{
	(void)state;
	char *cause;
	struct mesh *m = load("square.obj", NULL, &cause);
	assert_non_null(m);
	int nv = m->n_vertices;
	mesh_subdivide(m);
	assert_int_equal(m->n_triangles, 8);
	assert_int_equal(m->n_vertices, nv + 5);	/* 4 sides and the diagonal */
	assert_float_equal(mesh_area(m), 1, 1e-12);
	assert_float_equal(mesh_uv_area(m), 1, 1e-12);
	for (int v = 0; v < m->n_vertices; v++) {
		assert_float_equal(m->position[v][2], 0, 1e-12);
		assert_float_equal(m->uv[v][0], m->position[v][0], 1e-12);
		assert_float_equal(m->uv[v][1], m->position[v][1], 1e-12);
	}
	mesh_free(m);

	static const double p[6][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
	static const int f[8][3] = { { 0, 1, 4 }, { 1, 2, 4 }, { 2, 3, 4 }, { 3, 0, 4 }, { 1, 0, 5 }, { 2, 1, 5 }, { 3, 2, 5 },
		{ 0, 3, 5 } };
	struct mesh o = { .n_vertices = 6, .n_triangles = 8 };
	o.position = xmalloc(sizeof *o.position * 6);
	o.normal = xmalloc(sizeof *o.normal * 6);
	o.triangle = xmalloc(sizeof *o.triangle * 8);
	memcpy(o.position, p, sizeof p);
	memcpy(o.normal, p, sizeof p);
	memcpy(o.triangle, f, sizeof f);
	double a0 = mesh_area(&o);
	mesh_subdivide(&o);
	assert_int_equal(o.n_triangles, 32);
	assert_int_equal(o.n_vertices, 6 + 12);
	int found = 0;
	for (int v = 6; v < o.n_vertices; v++) {
		double r = sqrt(o.position[v][0] * o.position[v][0] + o.position[v][1] * o.position[v][1]
		    + o.position[v][2] * o.position[v][2]);
		assert_float_equal(r, 0.625 * sqrt(2), 1e-12);	/* every edge alike */
		found |= fabs(o.position[v][0] - 0.625) < 1e-12 && fabs(o.position[v][1] - 0.625) < 1e-12;
		/* Normals stay unit and point outward. */
		assert_float_equal(o.normal[v][0] * o.normal[v][0] + o.normal[v][1] * o.normal[v][1]
		    + o.normal[v][2] * o.normal[v][2], 1, 1e-12);
		assert_true(o.normal[v][0] * o.position[v][0] + o.normal[v][1] * o.position[v][1]
		    + o.normal[v][2] * o.position[v][2] > 0);
	}
	assert_true(found);
	assert_true(mesh_area(&o) > a0);	/* toward the sphere */
	free(o.position);
	free(o.normal);
	free(o.triangle);
}

static void test_visible(void **state)
{
	(void)state;
	char *cause;
	struct mesh *m = load("grid.obj", NULL, &cause);
	assert_non_null(m);
	unsigned char on[32];
	/* Seen from +z (the side the normals face) and from -z (behind). */
	struct scene_camera front = { .ortho = 0, .location = { 0, 0, 10 }, .angle = 0.5 };
	struct scene_camera back = { .ortho = 0, .location = { 0, 0, -10 }, .angle = 0.5 };
	struct scene_camera aside = { .ortho = 0, .location = { 0, 0, 10 }, .look_at = { 40, 0, 0 }, .angle = 0.5 };
	int n = 0;
	mesh2_visible(m, &front, 1, on);
	for (int t = 0; t < m->n_triangles; t++)
		n += on[t];
	assert_int_equal(n, m->n_triangles);
	mesh2_visible(m, &back, 1, on);
	for (int t = 0; t < m->n_triangles; t++)
		assert_int_equal(on[t], 0);
	mesh2_visible(m, &aside, 1, on);
	for (int t = 0; t < m->n_triangles; t++)
		assert_int_equal(on[t], 0);
	mesh_free(m);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_formats),
		cmocka_unit_test(test_no_uv),
		cmocka_unit_test(test_bad_files),
		cmocka_unit_test(test_names),
		cmocka_unit_test(test_human),
		cmocka_unit_test(test_bump_matrix),
		cmocka_unit_test(test_subdivide),
		cmocka_unit_test(test_visible),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
