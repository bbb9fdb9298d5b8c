/* Relief height fields: periodicity (shifted windows, derivatives across
 * the wrap-around edges), determinism, thread independence, the normal-map
 * convention against analytic derivatives, anisotropy and bad parameters. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <stdlib.h>
#include <string.h>

#include "geom/relief.h"
#include "geom/relief_impl.h"
#include "geom/relief_stats.h"
#include "geom/sites.h"

static struct relief_params params(const char *site)
{
	struct texture_config c;
	char *cause = NULL;
	assert_int_equal(sites_load(site, &c, &cause), 0);
	return c.relief;
}

static float *render(const struct relief *r, int n, double x0, double y0, int which)
{
	float *p = malloc(sizeof(float) * (size_t)n * n), *f = malloc(sizeof(float) * (size_t)n * n);
	relief_render(r, n, x0, y0, p, f);
	for (size_t i = 0; i < (size_t)n * n; i++)
		p[i] = which == 0 ? p[i] : which == 1 ? f[i] : p[i] + f[i];
	free(f);
	return p;
}

/* A window shifted by whole periods is the same map, bit for bit; a window
 * shifted by half a period is the map rolled by n/2 pixels, so the tile
 * border, now in the middle, is drawn like any interior line. */
static void test_shifted_windows(void **state)
{
	(void)state;
	const char *sites[] = { "face", "hand", "back", "forearm" };
	/* The last one with a direction map that is not periodic itself (a
	 * ramp of angles): the relief still is. */
	enum { DN = 64 };
	float *dir = malloc(sizeof *dir * DN * DN);
	for (int i = 0; i < DN * DN; i++)
		dir[i] = (float)(3.0 * (i % DN) / DN + 2.0 * (i / DN) / DN);
	for (size_t s = 0; s < 4; s++) {
		struct relief_params p = params(sites[s]);
		if (s == 3) {
			p.direction = dir;
			p.direction_n = DN;
		}
		char *cause = NULL;
		struct relief *r = relief_new(&p, 11, &cause);
		assert_non_null(r);
		int n = 256;
		float *a = render(r, n, 0, 0, 2);
		float *b = render(r, n, 1, -2, 2);
		assert_memory_equal(a, b, sizeof(float) * (size_t)n * n);
		float *c = render(r, n, 0.5, 0.5, 2);
		double maxabs = 0, maxdiff = 0;
		for (int row = 0; row < n; row++)
			for (int col = 0; col < n; col++) {
				/* Window origin +0.5 in x moves content left; +0.5 in y
				 * (up) moves it down in rows. */
				float va = a[(size_t)((row + n / 2) % n) * n + (col + n / 2) % n];
				float vc = c[(size_t)row * n + col];
				maxabs = fmax(maxabs, fabs(va));
				maxdiff = fmax(maxdiff, fabs(va - vc));
			}
		assert_true(maxabs > 0);
		assert_true(maxdiff <= 1e-5 * maxabs);
		free(a);
		free(b);
		free(c);
		relief_free(r);
	}
	free(dir);
}

/* RMS of the differences between column c and column c+1 (wrapping). */
static double col_rms(const float *h, int n, int c)
{
	double s = 0;
	for (int row = 0; row < n; row++) {
		double d = h[(size_t)row * n + (c + 1) % n] - h[(size_t)row * n + c];
		s += d * d;
	}
	return sqrt(s / n);
}

static double row_rms(const float *h, int n, int r)
{
	double s = 0;
	for (int col = 0; col < n; col++) {
		double d = h[(size_t)((r + 1) % n) * n + col] - h[(size_t)r * n + col];
		s += d * d;
	}
	return sqrt(s / n);
}

/* The derivative across the wrap-around edge (last column to first, last
 * row to first) lies within the spread of the interior ones: no seam. */
static void test_wrap_derivatives(void **state)
{
	(void)state;
	const char *sites[] = { "face", "cheek", "forehead", "nose", "hand", "forearm", "back" };
	for (size_t s = 0; s < sizeof sites / sizeof sites[0]; s++) {
		struct relief_params p = params(sites[s]);
		char *cause = NULL;
		struct relief *r = relief_new(&p, 3, &cause);
		assert_non_null(r);
		int n = 384;
		float *h = render(r, n, 0, 0, 2);
		double cmin = INFINITY, cmax = 0, rmin = INFINITY, rmax = 0, csum = 0, rsum = 0;
		for (int k = 0; k < n - 1; k++) {
			double cr = col_rms(h, n, k), rr = row_rms(h, n, k);
			cmin = fmin(cmin, cr), cmax = fmax(cmax, cr), csum += cr;
			rmin = fmin(rmin, rr), rmax = fmax(rmax, rr), rsum += rr;
		}
		double cw = col_rms(h, n, n - 1), rw = row_rms(h, n, n - 1);
		assert_true(cw >= cmin && cw <= cmax);
		assert_true(rw >= rmin && rw <= rmax);
		/* And not at an extreme: within a factor 2 of the interior mean. */
		assert_true(cw > 0.5 * csum / (n - 1) && cw < 2 * csum / (n - 1));
		assert_true(rw > 0.5 * rsum / (n - 1) && rw < 2 * rsum / (n - 1));
		free(h);
		relief_free(r);
	}
}

/* Without OpenMP (./configure --disable-openmp) there is one thread only. */
static void set_threads(int n)
{
#ifdef _OPENMP
	omp_set_num_threads(n);
#else
	(void)n;
#endif
}

static void test_deterministic(void **state)
{
	(void)state;
	struct relief_params p = params("forearm");
	char *cause = NULL;
	struct relief *a = relief_new(&p, 5, &cause), *b = relief_new(&p, 5, &cause);
	struct relief *c = relief_new(&p, 6, &cause);
	int n = 200;
	set_threads(1);
	float *ha = render(a, n, 0, 0, 2);
	set_threads(3);
	float *hb = render(b, n, 0, 0, 2);
	float *hc = render(c, n, 0, 0, 2);
	assert_memory_equal(ha, hb, sizeof(float) * (size_t)n * n);
	assert_memory_not_equal(ha, hc, sizeof(float) * (size_t)n * n);
	free(ha);
	free(hb);
	free(hc);
	relief_free(a);
	relief_free(b);
	relief_free(c);
}

/* Analytic periodic height: the normals follow n = (-hx, -hy, 1)/norm with
 * x to the right and y up (toward row 0). */
static void test_normals_convention(void **state)
{
	(void)state;
	int n = 128;
	double tile = 0.5, pitch = tile / n, A = 0.003;	/* cm */
	float *h = malloc(sizeof(float) * (size_t)n * n);
	float *nx = malloc(sizeof(float) * (size_t)n * n), *ny = malloc(sizeof(float) * (size_t)n * n);
	float *nz = malloc(sizeof(float) * (size_t)n * n);
	for (int row = 0; row < n; row++)
		for (int col = 0; col < n; col++) {
			double x = (col + 0.5) / n, y = (n - row - 0.5) / n;
			h[(size_t)row * n + col] = (float)(A * sin(2 * M_PI * x) + 0.5 * A * sin(4 * M_PI * y));
		}
	relief_normals(n, pitch, h, nx, ny, nz);
	double worst = 0;
	for (int row = 0; row < n; row++)
		for (int col = 0; col < n; col++) {
			double x = (col + 0.5) / n, y = (n - row - 0.5) / n;
			double hx = A * 2 * M_PI / tile * cos(2 * M_PI * x);
			double hy = 0.5 * A * 4 * M_PI / tile * cos(4 * M_PI * y);
			double norm = sqrt(hx * hx + hy * hy + 1);
			size_t i = (size_t)row * n + col;
			worst = fmax(worst, fabs(nx[i] + hx / norm));
			worst = fmax(worst, fabs(ny[i] + hy / norm));
			worst = fmax(worst, fabs(nz[i] - 1 / norm));
			assert_float_equal(nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i], 1.0, 1e-5);
		}
	/* Central differences: error ~ (2 pi k / n)^2 / 6 of the slope. */
	assert_true(worst < 3e-3);
	/* Height rising toward the top of the image tilts the normal down
	 * (-y); rising to the right tilts it left (-x). */
	for (int row = 0; row < n; row++)
		for (int col = 0; col < n; col++)
			h[(size_t)row * n + col] = (float)(1e-4 * sin(2 * M_PI * (n - row - 0.5) / n));
	relief_normals(n, pitch, h, nx, ny, nz);
	assert_true(ny[(size_t)(n - 1) * n] < 0);	/* bottom row: y ~ 0, rising */
	assert_true(fabs(nx[(size_t)(n - 1) * n]) < 1e-6);
	free(h);
	free(nx);
	free(ny);
	free(nz);
}

/* Gradient energy in x and y of the furrow map. */
static void grad_energy(const float *h, int n, double *ex, double *ey)
{
	*ex = *ey = 0;
	for (int row = 0; row < n; row++)
		for (int col = 0; col < n; col++) {
			double dx = h[(size_t)row * n + (col + 1) % n] - h[(size_t)row * n + col];
			double dy = h[(size_t)((row + 1) % n) * n + col] - h[(size_t)row * n + col];
			*ex += dx * dx;
			*ey += dy * dy;
		}
}

/* Cells stretched along x make furrows run along x, so heights change
 * mostly in y; turned by 90 degrees, the other way round. */
static void test_anisotropy(void **state)
{
	(void)state;
	struct relief_params p = params("hand");
	p.pore_density = 0;
	p.levels = 1;
	p.stretch = 3;
	int n = 256;
	double ex, ey;
	char *cause = NULL;
	p.orientation = 0;
	struct relief *r = relief_new(&p, 2, &cause);
	assert_non_null(r);
	float *h = render(r, n, 0, 0, 1);
	grad_energy(h, n, &ex, &ey);
	assert_true(ey > 1.5 * ex);
	free(h);
	relief_free(r);
	p.orientation = M_PI / 2;
	r = relief_new(&p, 2, &cause);
	h = render(r, n, 0, 0, 1);
	grad_energy(h, n, &ex, &ey);
	assert_true(ex > 1.5 * ey);
	free(h);
	relief_free(r);
	/* Isotropic cells and no direction gain: neither direction dominates. */
	p.stretch = 1;
	p.direction_gain = 1;
	r = relief_new(&p, 2, &cause);
	h = render(r, n, 0, 0, 1);
	grad_energy(h, n, &ex, &ey);
	assert_true(ex < 1.3 * ey && ey < 1.3 * ex);
	free(h);
	relief_free(r);
	/* Isotropic cells, furrows along y 3 times deeper than across. */
	p.direction_gain = 3;
	p.orientation = M_PI / 2;
	r = relief_new(&p, 2, &cause);
	h = render(r, n, 0, 0, 1);
	grad_energy(h, n, &ex, &ey);
	assert_true(ex > 1.5 * ey);
	free(h);
	relief_free(r);
}

/* Pores: the count follows the density, the depth scale the parameter, and
 * a map without pores or furrows is flat. */
static void test_components(void **state)
{
	(void)state;
	struct relief_params p = params("face");
	char *cause = NULL;
	struct relief *r = relief_new(&p, 9, &cause);
	assert_int_equal(relief_n_pores(r), (int)nearbyint(p.pore_density * p.tile * p.tile));
	int n = 256;
	float *pores = render(r, n, 0, 0, 0), *furrows = render(r, n, 0, 0, 1);
	float pmin = 0, pmax = -1, fmin_ = 0;
	for (size_t i = 0; i < (size_t)n * n; i++) {
		pmin = fminf(pmin, pores[i]);
		pmax = fmaxf(pmax, pores[i]);
		fmin_ = fminf(fmin_, furrows[i]);
	}
	assert_true(pmax == 0.0f);	/* dimples only */
	assert_true(pmin < -0.3 * p.pore_depth);
	assert_true(fmin_ < -0.5 * p.furrow_depth);
	free(pores);
	free(furrows);
	relief_free(r);
	p.pore_density = 0;
	p.levels = 0;
	p.plateau_roughness = 0;
	r = relief_new(&p, 9, &cause);
	float *flat = render(r, 64, 0, 0, 2);
	for (size_t i = 0; i < 64 * 64; i++)
		assert_true(flat[i] == 0.0f);
	free(flat);
	relief_free(r);
	/* The plateau texture alone: 48 waves with whole cycles per tile, all
	 * below the Nyquist limit (<= 33 e^0.5 = 55 of 128), so its mean is 0
	 * and, the wave vectors being distinct for this seed, its RMS the
	 * parameter (Parseval) up to float rounding. */
	p.tile = 0.1;
	p.plateau_roughness = 1e-4;
	p.plateau_scale = 30e-4;
	r = relief_new(&p, 9, &cause);
	flat = render(r, 256, 0, 0, 2);
	double sum = 0, sum2 = 0;
	for (size_t i = 0; i < 256 * 256; i++) {
		sum += flat[i];
		sum2 += (double)flat[i] * flat[i];
	}
	assert_true(fabs(sum / (256 * 256)) < 1e-3 * p.plateau_roughness);
	assert_true(fabs(sqrt(sum2 / (256 * 256)) - p.plateau_roughness) < 1e-3 * p.plateau_roughness);
	free(flat);
	relief_free(r);
}

/* Pores alone, all of one size: each is a funnel of the set depth, its
 * equivalent diameter at a tenth of that depth is 2 (1 - sqrt(0.08 (1 -
 * b))) r (where (1 - s)^2 / (1 - b) = 0.1), and its steepest wall, at the
 * rounded bottom's edge, has the slope 2 depth / r; --stats measures them. */
static void test_pore_funnel(void **state)
{
	(void)state;
	struct relief_params p = params("face");
	p.levels = 0;
	p.plateau_roughness = 0;
	p.pore_radius_sd = 0;
	p.pore_depth_sd = 0;
	p.pore_aspect = 1;
	p.tile = 0.1;	/* 1 mm: 2 pores of 45 um radius, 60 um deep */
	p.pore_depth = 60e-4;
	char *cause = NULL;
	struct relief *r = relief_new(&p, 3, &cause);
	assert_non_null(r);
	int n = 512;	/* 1.95 um pixels */
	float *pores = render(r, n, 0, 0, 0);
	struct relief_stats st;
	assert_int_equal(relief_stats_for(&p, n, pores, pores, pores, &st), 0);
	double pitch = p.tile / n, b = RELIEF_PORE_BOTTOM;
	assert_int_equal(st.pores, relief_n_pores(r));
	/* The deepest pixel is within half a diagonal of the centre: funnel
	 * 1 - s^2 / b there. */
	double ds = 0.5 * sqrt(2.0) * pitch / p.pore_radius;
	assert_true(st.pore_depth <= p.pore_depth && st.pore_depth >= p.pore_depth * (1 - ds * ds / b));
	double d10 = 2 * (1 - sqrt(0.1 * (1 - b))) * p.pore_radius;
	assert_true(fabs(st.pore_diameter - d10) <= sqrt(2.0) * pitch);
	double smax = 0;
	for (int row = 1; row < n - 1; row++)
		for (int c = 1; c < n - 1; c++) {
			double gx = (pores[row * n + c + 1] - pores[row * n + c - 1]) / (2 * pitch);
			double gy = (pores[(row - 1) * n + c] - pores[(row + 1) * n + c]) / (2 * pitch);
			smax = fmax(smax, sqrt(gx * gx + gy * gy));
		}
	/* A central difference averages the slope over +-1 px (h = pitch / r
	 * of s): the slope rises at 2 / b and falls at 2 / (1 - b) from its
	 * peak 2 (depth / r) at s = b, so the best window loses h (2/b)(2/(1-b))
	 * / (2/b + 2/(1-b)) = 2h: the largest difference is 2 (1 - h) depth / r
	 * for a pixel at the best place, a little less for the real pixels. */
	double want = 2 * p.pore_depth / p.pore_radius, h = pitch / p.pore_radius;
	if (smax > want * 1.001 || smax < want * (1 - 1.5 * h))
		fail_msg("steepest pore wall %g, expected 2 depth / r (1 - h) = %g (h = %g)", smax,
		    want * (1 - h), h);
	free(pores);
	relief_free(r);
}

static void expect_bad(struct relief_params p, const char *word)
{
	char *cause = NULL;
	assert_null(relief_new(&p, 1, &cause));
	assert_non_null(cause);
	if (strstr(cause, word) == NULL)
		fail_msg("message '%s' lacks '%s'", cause, word);
	free(cause);
}

static void test_bad_params(void **state)
{
	(void)state;
	struct relief_params p = params("hand"), q;
	q = p, q.tile = 0;
	expect_bad(q, "tile");
	q = p, q.pore_density = -1;
	expect_bad(q, "pore density");
	q = p, q.levels = 7;
	expect_bad(q, "levels");
	q = p;
	q.bend = 0.5;
	expect_bad(q, "bend");
	q = p;
	q.hierarchy = 2;
	expect_bad(q, "hierarchy");
	q = p;
	q.direction_gain = 0.5;
	expect_bad(q, "direction gain");
	q = p;
	q.plateau_scale = 0;
	expect_bad(q, "plateau scale");
	q = p;
	q.region_sd = 2;
	expect_bad(q, "region sigma");
	q = p, q.furrow_cell = p.tile;
	expect_bad(q, "furrow cell");
	q = p, q.level_scale = 1.5;
	expect_bad(q, "level scale");
	q = p, q.stretch = 0.5;
	expect_bad(q, "stretch");
	q = p, q.furrow_cell = 0.0005, q.tile = 5;
	expect_bad(q, "junctions");
	q = p, q.pore_aspect = 0.5;
	expect_bad(q, "aspect");

	/* The parameter table: a range error names the option and the range. */
	struct texture_config c;
	char *cause = NULL;
	assert_int_equal(sites_load("hand", &c, &cause), 0);
	assert_int_equal(sites_set(&c, sites_param_find("size"), "--size", "3", &cause), -1);
	assert_string_equal(cause, "--size = 3 is out of range [16, 16384] px");
	free(cause);
	assert_int_equal(sites_set(&c, sites_param_find("pore_depth"), "pore_depth", "x1", &cause), -1);
	assert_non_null(strstr(cause, "not a decimal number"));
	free(cause);
	assert_int_equal(sites_set(&c, sites_param_find("levels"), "--levels", "1.5", &cause), -1);
	free(cause);
	assert_int_equal(sites_load("elbow", &c, &cause), -1);
	assert_non_null(strstr(cause, "hand"));
	free(cause);
	assert_int_equal(sites_set(&c, sites_param_find("orientation"), "--orientation", "90", &cause), 0);
	assert_float_equal(c.relief.orientation, M_PI / 2, 1e-15);
	assert_float_equal(sites_get(&c, sites_param_find("orientation")), 90, 1e-12);
}

/* The primary net is drawn as long lines (relief_lines.c): with every
 * random depth factor off, a primary furrow end is at full depth where its
 * line goes on through the junction and at exp(-2 fade) where the line
 * ends, nothing else; continuing ends pair up, so each junction has an even
 * number of them, and most ends continue (a Poisson-disk Delaunay junction
 * has about six edges, nearly opposite in pairs). */
static void test_long_lines(void **state)
{
	(void)state;
	struct relief_params p = params("face");
	p.levels = 1;
	p.bend = 0;
	p.furrow_depth_sd = 0;
	p.region_sd = 0;
	p.direction_gain = 1;
	p.stretch = 1;
	char *cause = NULL;
	struct relief *r = relief_new(&p, 3, &cause);
	assert_non_null(r);
	const struct level *l = &r->level[0];
	double d = l->info.depth, dend = d * exp(-2 * p.furrow_fade);
	int np = l->info.points, full = 0, ends = 0;
	int *at = calloc((size_t)np, sizeof *at);
	for (int f = 0; f < l->n_furrows; f++) {
		const struct furrow *q = &l->furrows[f];
		double x[2] = { q->x0, q->x1 }, y[2] = { q->y0, q->y1 }, dd[2] = { q->depth, q->depth1 };
		for (int e = 0; e < 2; e++) {
			int is_full = fabs(dd[e] - d) < 1e-9 * d;
			assert_true(is_full || fabs(dd[e] - dend) < 1e-9 * d);
			full += is_full;
			ends++;
			int v = 0;
			for (; v < np; v++) {
				double ex = x[e] - l->xy[2 * v], ey = y[e] - l->xy[2 * v + 1];
				if (fabs(ex - nearbyint(ex)) < 1e-9 && fabs(ey - nearbyint(ey)) < 1e-9)
					break;
			}
			assert_true(v < np);
			at[v] += is_full;
		}
	}
	for (int v = 0; v < np; v++)
		assert_int_equal(at[v] % 2, 0);
	assert_true(full > 0.75 * ends);
	assert_true(full < ends);
	free(at);
	relief_free(r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_shifted_windows),
		cmocka_unit_test(test_wrap_derivatives),
		cmocka_unit_test(test_deterministic),
		cmocka_unit_test(test_normals_convention),
		cmocka_unit_test(test_anisotropy),
		cmocka_unit_test(test_components),
		cmocka_unit_test(test_bad_params),
		cmocka_unit_test(test_long_lines),
		cmocka_unit_test(test_pore_funnel),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
