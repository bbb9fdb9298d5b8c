/* batchstat: batch means and their standard errors (see batchstat.h). */
#include "config.h"
#include "engine/batchstat.h"

#include <math.h>
#include <stdlib.h>

#include "base/check.h"
#include "base/util.h"

void batchstat_init(struct batchstat *b, int n_q)
{
	CHECK(n_q >= 1);
	b->n_q = n_q;
	b->batches = 0;
	b->s1 = xcalloc((size_t)n_q, sizeof(double));
	b->s2 = xcalloc((size_t)n_q, sizeof(double));
}

void batchstat_free(struct batchstat *b)
{
	free(b->s1);
	free(b->s2);
	b->s1 = b->s2 = NULL;
}

void batchstat_add(struct batchstat *b, const double *q)
{
	for (int i = 0; i < b->n_q; i++) {
		b->s1[i] += q[i];
		b->s2[i] += q[i] * q[i];
	}
	b->batches++;
}

double batchstat_mean(const struct batchstat *b, int k)
{
	CHECK(b->batches >= 1 && k >= 0 && k < b->n_q);
	return b->s1[k] / (double)b->batches;
}

double batchstat_err(const struct batchstat *b, int k)
{
	CHECK(b->batches >= 2 && k >= 0 && k < b->n_q);
	double B = (double)b->batches, m = b->s1[k] / B;
	double var = (b->s2[k] - B * m * m) / (B - 1.0);
	return var > 0.0 ? sqrt(var / B) : 0.0;
}

struct estimate batchstat_weighted(const double *x, size_t stride, const long *n, int nb, long total)
{
	CHECK(nb >= 1 && total >= 1);
	double sum = 0.0;
	for (int b = 0; b < nb; b++)
		sum += x[(size_t)b * stride];
	double mean = sum / (double)total, ss = 0.0;
	for (int b = 0; b < nb; b++) {
		if (n[b] == 0)
			continue;
		double d = x[(size_t)b * stride] / (double)n[b] - mean;
		ss += (double)n[b] * d * d;
	}
	struct estimate v = { mean, nb > 1 ? sqrt(ss / ((double)(nb - 1) * (double)total)) : NAN };
	return v;
}
