/* wmc: white Monte Carlo Rd(r) of absorption variants (wmc.h). */
#include "config.h"
#include "engine/wmc.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "engine/batchstat.h"
#include "engine/tally.h"
#include "base/check.h"
#include "base/util.h"

enum { NS = SLAB_MAX_LAYERS + 2 };

int wmc_same_scattering(const struct slab *s, const struct slab *v)
{
	if (s->n_layers != v->n_layers || s->n_above != v->n_above || s->n_below != v->n_below ||
	    s->rough_ms != v->rough_ms)
		return 0;
	for (int l = 1; l <= s->n_layers; l++) {
		const struct layer *a = &s->layer[l], *b = &v->layer[l];
		if (a->d != b->d || a->n != b->n || a->mu_s != b->mu_s || a->g != b->g ||
		    a->rough != b->rough || slab_layer_clear(s, l) != slab_layer_clear(v, l))
			return 0;
	}
	return 1;
}

void wmc_reference(const struct slab *vs, int n, struct slab *ref, double *dmua)
{
	CHECK(n >= 1);
	*ref = vs[0];
	for (int l = 1; l <= ref->n_layers; l++)
		for (int k = 1; k < n; k++)
			ref->layer[l].mu_a = fmin(ref->layer[l].mu_a, vs[k].layer[l].mu_a);
	slab_prepare(ref);
	for (int k = 0; k < n; k++)
		for (int l = 0; l < NS; l++)
			dmua[(size_t)k * NS + (size_t)l] = l >= 1 && l <= ref->n_layers ?
			    vs[k].layer[l].mu_a - ref->layer[l].mu_a : 0.0;
}

void wmc_radial_run(const struct slab *ref, const double *dmua, int n_var, double theta_in,
    const struct transport_opts *o, int n_r, double dr, long photons, int batches, uint64_t seed,
    uint32_t stream, int threads, struct wmc_radial *out)
{
	CHECK(n_var >= 1 && n_r >= 1 && batches >= 2 && photons >= 1);
	struct tally_variants var = { .n = n_var, .dmua = dmua };
	struct tally_grid g = { .n_theta = 1, .n_phi = 1, .n_r = n_r, .dr = dr, .var = &var };
	struct launch ln;
	transport_launch(ref, theta_in, o->fresnel, &ln);
	long bp = (photons + batches - 1) / batches;
	size_t nq = (size_t)n_var * (size_t)n_r;
	/* Per batch the variants' bins as weight per photon. */
	double *q = xcalloc((size_t)batches * nq, sizeof(double));
	double t0 = util_now();
	int nthreads = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel num_threads(nthreads)
	{
		struct tally t;
		tally_alloc(&t, &g);
#pragma omp for schedule(dynamic, 1)
		for (int b = 0; b < batches; b++) {
			tally_zero(&t, &g);
			uint64_t first = (uint64_t)b * (uint64_t)bp;
			transport_run(ref, &ln, o, &g, NULL, seed, stream, first, (uint64_t)bp, &t);
			for (size_t i = 0; i < nq; i++)
				q[(size_t)b * nq + i] = t.radial_var[i] / (double)bp;
		}
		tally_free(&t);
	}
	struct batchstat st;
	batchstat_init(&st, (int)nq);
	for (int b = 0; b < batches; b++)
		batchstat_add(&st, q + (size_t)b * nq);
	out->n_var = n_var;
	out->n_r = n_r;
	out->dr = dr;
	out->rd_r = xmalloc(sizeof(double) * nq);
	out->rd_r_err = xmalloc(sizeof(double) * nq);
	for (size_t i = 0; i < nq; i++) {
		double area = tally_annulus_area(dr, (int)(i % (size_t)n_r));
		out->rd_r[i] = batchstat_mean(&st, (int)i) / area;
		out->rd_r_err[i] = batchstat_err(&st, (int)i) / area;
	}
	out->photons = bp * batches;
	out->seconds = util_now() - t0;
	batchstat_free(&st);
	free(q);
}

void wmc_radial_free(struct wmc_radial *w)
{
	free(w->rd_r);
	free(w->rd_r_err);
	w->rd_r = w->rd_r_err = NULL;
}

void wmc_batches(const struct slab *ref, const double *dmua, int n_var, double theta_in,
    const struct transport_opts *o, int n_r, double dr, long bp, int b0, int nb, uint64_t seed,
    uint32_t stream, int threads, double *prof, double *tot)
{
	CHECK(n_var >= 1 && n_r >= 1 && bp >= 1 && nb >= 1 && b0 >= 0);
	struct tally_variants var = { .n = n_var, .dmua = dmua };
	struct tally_grid g = { .n_theta = 1, .n_phi = 1, .n_r = n_r, .dr = dr, .var = &var };
	struct launch ln;
	transport_launch(ref, theta_in, o->fresnel, &ln);
	int nthreads = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel num_threads(nthreads)
	{
		struct tally t;
		tally_alloc(&t, &g);
#pragma omp for schedule(dynamic, 1)
		for (int b = 0; b < nb; b++) {
			tally_zero(&t, &g);
			uint64_t first = (uint64_t)(b0 + b) * (uint64_t)bp;
			transport_run(ref, &ln, o, &g, NULL, seed, stream, first, (uint64_t)bp, &t);
			double *pb = prof + (size_t)b * (size_t)n_r;
			double *tb = tot + (size_t)b * (size_t)n_var;
			for (int i = 0; i < n_r; i++)
				pb[i] = t.radial_var[i] / (double)bp;
			for (int v = 0; v < n_var; v++)
				tb[v] = t.var_total[v] / (double)bp;
		}
		tally_free(&t);
	}
}
