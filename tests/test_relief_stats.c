/* relief_stats against height maps whose statistics are known in closed
 * form: a sinusoid (Sa, furrow crossings and depth, anisotropy 1), two
 * crossed sinusoids (isotropic and stretched: the discrete structure tensor
 * exactly), a diagonal sinusoid (direction) and flat-bottomed discs (pore
 * count, density, diameter to the lattice bound) and a triangle wave (the
 * developed area ratio Sdr); the cavity map against a flat map, a tilted
 * plane and a round hole. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "geom/relief_cavity.h"
#include "geom/relief_far.h"
#include "geom/relief_stats.h"

enum { N = 256 };
static const double PITCH = 1e-4;	/* 1 um [cm] */
static const double A = 10e-4;	/* amplitude [cm] */

/* h at pixel (row, col) = sum of sines of wavelengths lx, ly [px] along x,
 * y (0: none) and ld along x + y; x = col + 0.5, y = N - row - 0.5. */
static float *waves(double lx, double ly, double ld)
{
	float *h = malloc(sizeof *h * N * N);
	for (int r = 0; r < N; r++) {
		for (int c = 0; c < N; c++) {
			double x = c + 0.5, y = N - r - 0.5, v = 0;
			if (lx > 0)
				v += sin(2 * M_PI * x / lx);
			if (ly > 0)
				v += sin(2 * M_PI * y / ly);
			if (ld > 0)
				v += sin(2 * M_PI * (x + y) / ld);
			h[r * N + c] = (float)(A * v);
		}
	}
	return h;
}

static struct relief_stats stats_of(const float *h, const float *pores)
{
	struct relief_stats_spec spec = { PITCH, A / 2, 1e-4 };
	struct relief_stats st;
	char *cause = NULL;
	assert_int_equal(relief_stats_compute(N, h, NULL, pores, &spec, &st, &cause), 0);
	return st;
}

static void test_sinusoid(void **state)
{
	(void)state;
	const int L = 64;	/* px per period */
	float *h = waves(L, 0, 0);
	struct relief_stats st = stats_of(h, NULL);
	/* Midpoint samples: mean |sin| = 2 / (L sin(pi / L)) exactly, within
	 * pi^2 / (6 L^2) = 4e-4 relative of the continuous 2 / pi. */
	double sa = 2 * A / (L * sin(M_PI / L));
	assert_true(fabs(st.sa - sa) < 1e-6 * sa);	/* float storage */
	assert_true(fabs(st.sa - 2 * A / M_PI) < 5e-4 * 2 * A / M_PI);
	assert_true(fabs(st.sz - 2 * A * cos(M_PI / L)) < 1e-6 * A);
	/* One furrow per period along rows and, stretched by sqrt 2, along the
	 * diagonals; none along columns. */
	double per_len = 1.0 / (L * PITCH);
	assert_true(fabs(st.furrow_density - per_len * (1 + sqrt(2.0)) / 4) < 1e-9 * per_len);
	assert_true(fabs(st.furrow_depth - A * cos(M_PI / L)) < 1e-6 * A);
	assert_true(fabs(st.anisotropy - 1) < 1e-12);
	assert_true(fabs(st.direction - M_PI / 2) < 1e-9);
	free(h);
}

static void test_isotropic_and_stretched(void **state)
{
	(void)state;
	float *h = waves(32, 32, 0);
	struct relief_stats st = stats_of(h, NULL);
	/* Cross terms sum to zero over whole periods; float rounding only. */
	assert_true(st.anisotropy < 1e-5);
	free(h);
	h = waves(32, 64, 0);
	st = stats_of(h, NULL);
	/* Central differences scale sin(kx) by sin(k p) / p. */
	double ratio = pow(sin(2 * M_PI / 64) / sin(2 * M_PI / 32), 2);
	assert_true(fabs(st.anisotropy - (1 - ratio)) < 1e-5);
	assert_true(fabs(st.direction - M_PI / 2) < 1e-5);
	free(h);
	h = waves(0, 0, 64);
	st = stats_of(h, NULL);
	/* Gradient along (1, 1): the furrows run along (1, -1). */
	assert_true(fabs(st.anisotropy - 1) < 1e-5);
	assert_true(fabs(st.direction - 3 * M_PI / 4) < 1e-5);
	free(h);
}

static void test_discs(void **state)
{
	(void)state;
	/* Five discs of radius R px, one across the left/right seam and one
	 * across the top/bottom seam (each must count once). */
	const double R = 12, cx[5] = { 40, 128, 200, 2, 128 }, cy[5] = { 40, 128, 60, 128, 250 };
	float *p = calloc(N * N, sizeof *p);
	for (int r = 0; r < N; r++) {
		for (int c = 0; c < N; c++) {
			for (int k = 0; k < 5; k++) {
				double dx = fabs(c + 0.5 - cx[k]), dy = fabs(r + 0.5 - cy[k]);
				dx = fmin(dx, N - dx);
				dy = fmin(dy, N - dy);
				if (dx * dx + dy * dy < R * R)
					p[r * N + c] = -5e-4f;
			}
		}
	}
	struct relief_stats st = stats_of(p, p);
	assert_int_equal(st.pores, 5);
	double area = (double)N * N * PITCH * PITCH;
	assert_true(fabs(st.pore_density - 5 / area) < 1e-9 / area);
	/* The pixels with centres inside a disc cover between pi (R - sqrt2/2)^2
	 * and pi (R + sqrt2/2)^2: the diameter is 2R within sqrt 2 px. */
	assert_true(fabs(st.pore_diameter - 2 * R * PITCH) <= sqrt(2.0) * PITCH);
	free(p);
}

/* A triangle wave of slope +-s along x, kinks on pixel boundaries: the
 * central difference is +-s except at the 4 samples per period next to a
 * kink, where it is +-s/2, so Sdr is known exactly; the continuous surface
 * has sqrt(1 + s^2) - 1. */
static void test_developed_area(void **state)
{
	(void)state;
	const int L = 64;	/* px per period */
	const double s = 0.5;	/* slope [1] */
	float *h = malloc(sizeof *h * N * N);
	for (int r = 0; r < N; r++) {
		for (int c = 0; c < N; c++) {
			double x = fmod(c + 0.5, L);
			double up = x < L / 2.0 ? x : L - x;	/* distance from the last valley [px] */
			h[r * N + c] = (float)(s * up * PITCH);
		}
	}
	struct relief_stats st = stats_of(h, NULL);
	double exact = ((L - 4) * (sqrt(1 + s * s) - 1) + 4 * (sqrt(1 + s * s / 4) - 1)) / L;
	assert_true(fabs(st.sdr - exact) < 1e-5 * exact);	/* float storage */
	assert_true(fabs(st.sdr - (sqrt(1 + s * s) - 1)) < 4.0 / L * (sqrt(1 + s * s) - 1));
	free(h);
}

/* Toksvig roughness of averaged normals: 0 on a flat map; on the triangle
 * wave above (normals by relief_normals) the x components cancel over a
 * period and |N| is the mean of 1/sqrt(1 + g^2) over its slopes, exactly;
 * blocks of one period each all give that value. */
static void test_far_alpha(void **state)
{
	(void)state;
	const int L = 64;
	const double s = 0.5;
	float *h = malloc(sizeof *h * N * N), *nx = malloc(sizeof *nx * N * N);
	float *ny = malloc(sizeof *ny * N * N), *nz = malloc(sizeof *nz * N * N);
	float alpha[16];
	for (int i = 0; i < N * N; i++)
		h[i] = 0;
	relief_normals(N, PITCH, h, nx, ny, nz);
	relief_far_alpha(N, nx, ny, nz, 4, alpha);
	for (int i = 0; i < 16; i++)
		assert_true(alpha[i] == 0.0f);
	for (int r = 0; r < N; r++) {
		for (int c = 0; c < N; c++) {
			double x = fmod(c + 0.5, L);
			h[r * N + c] = (float)(s * (x < L / 2.0 ? x : L - x) * PITCH);
		}
	}
	relief_normals(N, PITCH, h, nx, ny, nz);
	double len = ((L - 4) / sqrt(1 + s * s) + 4 / sqrt(1 + s * s / 4)) / L;
	double exact = sqrt(2 * (1 - len) / len);
	relief_far_alpha(N, nx, ny, nz, 1, alpha);
	assert_true(fabs(alpha[0] - exact) < 1e-4 * exact);
	relief_far_alpha(N, nx, ny, nz, 4, alpha);	/* 64 px blocks: one period each */
	for (int i = 0; i < 16; i++)
		assert_true(fabs(alpha[i] - exact) < 1e-4 * exact);
	/* About one block per primary cell: 2 mm at 256 px, cell 0.35 mm. */
	assert_int_equal(relief_far_size(256, 0.2 / 256, 0.035), 6);
	assert_int_equal(relief_far_size(16, 0.2 / 16, 1.0), 1);
	free(h);
	free(nx);
	free(ny);
	free(nz);
}

/* A round flat-bottomed hole of radius R px and depth D centred on pixel
 * (r0, c0), wrapped. */
static void hole(float *h, int r0, int c0, double R, double D)
{
	for (int r = 0; r < N; r++)
		for (int c = 0; c < N; c++) {
			int dr = abs(r - r0), dc = abs(c - c0);
			dr = dr > N / 2 ? N - dr : dr;
			dc = dc > N / 2 ? N - dc : dc;
			h[r * N + c] = dr * dr + dc * dc < R * R ? (float)-D : 0.0f;
		}
}

/* cavity: 1 on flat and on tilted planes (the horizon is taken from the
 * tangent plane); at the centre of a round hole of radius R and depth D the
 * horizon is at atan(D / R) all round, so cavity = R^2 / (R^2 + D^2), here
 * 1/2; the one-pixel wall of the sampled hole puts the rim up to a pixel
 * further (0.49 to 0.53 accepted).  A hole across the corner of the tile gives the
 * same value as one in the middle (no seam). */
static void test_cavity(void **state)
{
	(void)state;
	float *h = malloc(sizeof *h * N * N), *cav = malloc(sizeof *cav * N * N);
	for (int i = 0; i < N * N; i++)
		h[i] = 0;
	relief_cavity(N, PITCH, h, 20 * PITCH, cav);
	for (int i = 0; i < N * N; i++)
		assert_true(cav[i] == 1.0f);
	for (int r = 0; r < N; r++)
		for (int c = 0; c < N; c++)
			h[r * N + c] = (float)(0.7 * c * PITCH);
	relief_cavity(N, PITCH, h, 8 * PITCH, cav);
	for (int r = 0; r < N; r++)
		for (int c = 10; c < N - 10; c++)
			assert_true(fabs(cav[r * N + c] - 1) < 1e-6);
	const double R = 16;
	hole(h, N / 2, N / 2, R, R * PITCH);
	relief_cavity(N, PITCH, h, 40 * PITCH, cav);
	double mid = cav[(N / 2) * N + N / 2];
	assert_true(mid > 0.49 && mid < (R + 1) * (R + 1) / ((R + 1) * (R + 1) + R * R));
	assert_true(cav[3 * N + 3] == 1.0f);	/* far from the hole */
	hole(h, 0, 0, R, R * PITCH);
	relief_cavity(N, PITCH, h, 40 * PITCH, cav);
	assert_true(fabs(cav[0] - mid) < 1e-5);
	assert_true(fabs(relief_cavity_radius(0.035, 0.2) - 0.035) < 1e-15);
	assert_true(fabs(relief_cavity_radius(0.5, 0.2) - 0.1) < 1e-15);
	free(h);
	free(cav);
}

static void test_bad_input(void **state)
{
	(void)state;
	float h[9] = { 0 };
	struct relief_stats_spec spec = { 0, 1, 1 };
	struct relief_stats st;
	char *cause = NULL;
	assert_int_equal(relief_stats_compute(3, h, NULL, NULL, &spec, &st, &cause), -1);
	assert_non_null(cause);
	free(cause);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sinusoid),
		cmocka_unit_test(test_isotropic_and_stretched),
		cmocka_unit_test(test_discs),
		cmocka_unit_test(test_developed_area),
		cmocka_unit_test(test_far_alpha),
		cmocka_unit_test(test_cavity),
		cmocka_unit_test(test_bad_input),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
