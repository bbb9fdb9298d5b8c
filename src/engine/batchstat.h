/* batchstat: the mean of a Monte Carlo quantity and its standard error from
 * the spread between independent batches of photons (the batch-means
 * method).  Two estimators share this module:
 * - running sums over batches of equal size (struct batchstat), which the
 *   bake adds to round by round and which could be saved and resumed;
 * - a two-pass estimate over batches of unequal size (batchstat_weighted),
 *   for `simulate`, whose photons are split into a fixed number of batches.
 * For equal batches both give the same numbers up to rounding; they are kept
 * apart because each one's rounding is part of its command's output. */
#ifndef SKINBAKE_BATCHSTAT_H
#define SKINBAKE_BATCHSTAT_H
#include <stddef.h>

/* A quantity with its standard error (same unit as the quantity). */
struct estimate {
	double v;	/* mean */
	double err;	/* standard error of the mean; NAN when it cannot be estimated */
};

/* Running sums over equal batches, n_q quantities per batch. */
struct batchstat {
	int n_q;	/* quantities per batch */
	long batches;	/* batches added */
	double *s1;	/* [n_q] sum of the batch means */
	double *s2;	/* [n_q] sum of their squares */
};

void batchstat_init(struct batchstat *b, int n_q);
void batchstat_free(struct batchstat *b);
/* Add one batch: q[n_q] are its means (e.g. weight per photon). */
void batchstat_add(struct batchstat *b, const double *q);
/* Mean of quantity k over the batches added (at least one). */
double batchstat_mean(const struct batchstat *b, int k);
/* Standard error of that mean (at least two batches; 0 if the spread is 0). */
double batchstat_err(const struct batchstat *b, int k);

/* Unequal batches: x[b * stride] is batch b's sum over its n[b] photons,
 * total = sum of n[b].  Returns the mean per photon and its standard error
 * sqrt(sum_b n_b (x_b / n_b - mean)^2 / ((nb - 1) total)), NAN for nb < 2. */
struct estimate batchstat_weighted(const double *x, size_t stride, const long *n, int nb, long total);
#endif
