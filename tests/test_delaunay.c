/* Periodic Delaunay: Euler counts on the torus, the empty-circumcircle
 * property across the tile border, determinism and bad input. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/delaunay.h"
#include "base/rng.h"

static double *random_points(int n, uint64_t seed)
{
	struct rng r;
	rng_seed(&r, seed, 7, 0);
	double *xy = malloc(sizeof(double) * 2 * (size_t)n);
	for (int k = 0; k < 2 * n; k++)
		xy[k] = rng_uniform(&r);
	return xy;
}

/* E = 3N and F = 2N for small N (where a thin band fails, see
 * dependencies.md section 5) up to thousands of points. */
static void test_euler_counts(void **state)
{
	(void)state;
	int ns[] = { 3, 4, 5, 7, 10, 30, 100, 499, 500, 2000, 10000 };
	for (size_t t = 0; t < sizeof ns / sizeof ns[0]; t++) {
		for (uint64_t seed = 1; seed <= 3; seed++) {
			int n = ns[t];
			double *xy = random_points(n, seed * 1000 + (uint64_t)n);
			char *cause = NULL;
			struct delaunay *d = delaunay_periodic(n, xy, NULL, &cause);
			if (d == NULL)
				fail_msg("n=%d seed=%d: %s", n, (int)seed, cause);
			assert_int_equal(d->n_edges, 3 * n);
			assert_int_equal(d->n_tris, 2 * n);
			/* Each edge borders exactly two triangles; vertex degrees sum to 2E. */
			int *deg = calloc((size_t)n, sizeof *deg);
			for (int e = 0; e < d->n_edges; e++) {
				deg[d->edges[e].i]++;
				deg[d->edges[e].j]++;
			}
			long sum = 0;
			for (int k = 0; k < n; k++) {
				assert_true(deg[k] >= 3);
				sum += deg[k];
			}
			assert_int_equal(sum, 6L * n);
			free(deg);
			delaunay_free(d);
			free(xy);
		}
	}
}

/* No point (in any of the 3x3 tile copies) lies strictly inside a
 * triangle's circumcircle: the triangulation is Delaunay on the torus,
 * including triangles that cross the tile border. */
static void empty_circles(int n, const double *xy, const double *m, const struct delaunay *d)
{
	for (int t = 0; t < d->n_tris; t++) {
		double px[3], py[3];
		for (int k = 0; k < 3; k++) {
			double x = xy[2 * d->tris[t].v[k]] + d->tris[t].sx[k];
			double y = xy[2 * d->tris[t].v[k] + 1] + d->tris[t].sy[k];
			px[k] = m[0] * x + m[1] * y;
			py[k] = m[2] * x + m[3] * y;
		}
		double ax = px[0], ay = py[0], bx = px[1], by = py[1], cx = px[2], cy = py[2];
		double dd = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by));
		double ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay)
		    + (cx * cx + cy * cy) * (ay - by)) / dd;
		double uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx)
		    + (cx * cx + cy * cy) * (bx - ax)) / dd;
		double r2 = (ax - ux) * (ax - ux) + (ay - uy) * (ay - uy);
		for (int a = -2; a <= 2; a++)
			for (int b = -2; b <= 2; b++)
				for (int k = 0; k < n; k++) {
					double x = xy[2 * k] + a, y = xy[2 * k + 1] + b;
					double qx = m[0] * x + m[1] * y, qy = m[2] * x + m[3] * y;
					double q2 = (qx - ux) * (qx - ux) + (qy - uy) * (qy - uy);
					assert_true(q2 >= r2 * (1 - 1e-9));
				}
		/* Counter-clockwise in tile coordinates. */
		double tx[3], ty[3];
		for (int k = 0; k < 3; k++) {
			tx[k] = xy[2 * d->tris[t].v[k]] + d->tris[t].sx[k];
			ty[k] = xy[2 * d->tris[t].v[k] + 1] + d->tris[t].sy[k];
		}
		assert_true((tx[1] - tx[0]) * (ty[2] - ty[0]) - (ty[1] - ty[0]) * (tx[2] - tx[0]) > 0);
		double gx = (tx[0] + tx[1] + tx[2]) / 3, gy = (ty[0] + ty[1] + ty[2]) / 3;
		assert_true(gx >= 0 && gx < 1 && gy >= 0 && gy < 1);
	}
}

static void test_empty_circumcircles(void **state)
{
	(void)state;
	static const double id[4] = { 1, 0, 0, 1 };
	int n = 200;
	double *xy = random_points(n, 42);
	char *cause = NULL;
	struct delaunay *d = delaunay_periodic(n, xy, NULL, &cause);
	assert_non_null(d);
	empty_circles(n, xy, id, d);
	delaunay_free(d);

	/* Anisotropic metric (squeeze 3x along 30 degrees): still E = 3N and
	 * Delaunay in the metric space. */
	double c = cos(M_PI / 6), s = sin(M_PI / 6), k1 = 1 / sqrt(3.0), k2 = sqrt(3.0);
	double m[4] = { k1 * c * c + k2 * s * s, (k1 - k2) * c * s, (k1 - k2) * c * s,
		k1 * s * s + k2 * c * c };
	d = delaunay_periodic(n, xy, m, &cause);
	assert_non_null(d);
	assert_int_equal(d->n_edges, 3 * n);
	assert_int_equal(d->n_tris, 2 * n);
	empty_circles(n, xy, m, d);
	delaunay_free(d);
	free(xy);
}

static void test_deterministic(void **state)
{
	(void)state;
	int n = 3000;
	double *xy = random_points(n, 5);
	char *cause = NULL;
	struct delaunay *a = delaunay_periodic(n, xy, NULL, &cause);
	struct delaunay *b = delaunay_periodic(n, xy, NULL, &cause);
	assert_non_null(a);
	assert_non_null(b);
	assert_memory_equal(a->edges, b->edges, sizeof *a->edges * (size_t)a->n_edges);
	assert_memory_equal(a->tris, b->tris, sizeof *a->tris * (size_t)a->n_tris);
	delaunay_free(a);
	delaunay_free(b);
	free(xy);
}

static void test_bad_input(void **state)
{
	(void)state;
	double xy[8] = { 0.1, 0.2, 0.5, 0.5, 0.7, 0.1, 1.0, 0.3 };
	char *cause = NULL;
	assert_null(delaunay_periodic(2, xy, NULL, &cause));
	assert_non_null(strstr(cause, "at least 3"));
	free(cause);
	cause = NULL;
	assert_null(delaunay_periodic(4, xy, NULL, &cause));
	assert_non_null(strstr(cause, "outside [0, 1)"));
	free(cause);
	cause = NULL;
	double sing[4] = { 1, 2, 2, 4 };
	assert_null(delaunay_periodic(3, xy, sing, &cause));
	assert_non_null(strstr(cause, "singular"));
	free(cause);
	cause = NULL;
	/* Duplicate points cannot form a triangulation of the torus. */
	double dup[8] = { 0.1, 0.2, 0.1, 0.2, 0.6, 0.7, 0.3, 0.8 };
	assert_null(delaunay_periodic(4, dup, NULL, &cause));
	assert_non_null(cause);
	free(cause);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_euler_counts),
		cmocka_unit_test(test_empty_circumcircles),
		cmocka_unit_test(test_deterministic),
		cmocka_unit_test(test_bad_input),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
