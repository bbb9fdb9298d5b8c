/* fitlut: the per-colour solver of maps fit (method in fit.h): the
 * family's CIELAB on a dense grid uniform in each axis' coordinate, a
 * bucket grid over a coarse subset of it for the nearest node, and damped
 * Gauss-Newton on the grid's multilinear interpolant.  A colour's result
 * depends on the colour and, with a warm start, the previous solution
 * only (fit.c solves colours in fixed chunks). */
#ifndef SKINBAKE_FITLUT_H
#define SKINBAKE_FITLUT_H
#include "family/family.h"

/* The family's CIELAB on a dense grid, and buckets over CIELAB. */
struct fit_lut {
	const struct family *f;
	int k;				/* axes */
	int g[FAMILY_MAX_AXES];		/* grid points per axis */
	double c0[FAMILY_MAX_AXES];	/* axis coordinate at the grid's start */
	double c1[FAMILY_MAX_AXES];	/* and at its end */
	int n;				/* grid points */
	double *lab;			/* [n][3] */
	int n_coarse;			/* grid points in the buckets: every step-th, the last */
	double lo[3], cell;		/* bucket grid origin and cell size (CIELAB units) */
	int dim[3];
	int *start, *item;		/* CSR: bucket b holds item[start[b] .. start[b + 1]) */
};

/* Tabulate f (family_albedo_prepare'd) on threads OpenMP threads. */
void fit_lut_build(struct fit_lut *t, const struct family *f, int threads);
void fit_lut_free(struct fit_lut *t);
/* Parameter values x at grid coordinates g (continuous, in grid units). */
void fit_lut_params(const struct fit_lut *t, const double *g, double *x);
/* The family's CIELAB (D65) at parameters x, by its exact interpolation. */
void fit_lut_lab(const struct family *f, const double *x, double lab[3]);
/* One colour's grid coordinates g: from the coarse nearest point and the
 * refinement, or when warm from g's value if that reaches an exact match
 * (within 0.02 CIELAB). */
void fit_lut_solve(const struct fit_lut *t, const double target[3], double *g, int warm);
#endif
