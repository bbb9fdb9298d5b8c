/* sim: one Monte Carlo run of a slab at one incidence angle, in batches
 * (see sim.h). */
#include "config.h"
#include "engine/sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/check.h"
#include "base/util.h"

void sim_config_default(struct sim_config *c)
{
	memset(c, 0, sizeof *c);
	slab_init(&c->slab, 1.0, 1.0);
	transport_opts_default(&c->opts);
	c->grid = (struct tally_grid){ .n_theta = 18, .n_phi = 36, .n_r = 100, .dr = 0.005 };
	c->photons = 1000000;
	c->batches = 32;
	c->seed = 1;
}

void sim_run(const struct sim_config *c, struct sim_result *res,
    void (*progress)(void *user, long done, long total), void *user)
{
	CHECK(c->photons >= 1 && c->batches >= 1 && c->theta_in >= 0.0 && c->theta_in < 0.5 * M_PI);
	const struct tally_grid *g = &c->grid;
	int nb = c->batches;
	if ((long)nb > c->photons)
		nb = (int)c->photons;
	struct launch ln;
	transport_launch(&c->slab, c->theta_in, c->opts.fresnel, &ln);

	struct tally *bt = xcalloc((size_t)nb, sizeof *bt);
	long *bn = xcalloc((size_t)nb, sizeof *bn);
	for (int b = 0; b < nb; b++) {
		tally_alloc(&bt[b], g);
		bn[b] = c->photons * (b + 1) / nb - c->photons * b / nb;
	}
	double t0 = util_now();
	long done = 0;
#ifdef _OPENMP
	int nthreads = c->threads > 0 ? c->threads : omp_get_max_threads();
#endif
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads)
	for (int b = 0; b < nb; b++) {
		uint64_t first = (uint64_t)(c->photons * b / nb);
		transport_run(&c->slab, &ln, &c->opts, g, NULL, c->seed, c->stream, first, (uint64_t)bn[b], &bt[b]);
		if (progress) {
#pragma omp critical(sim_progress)
			{
				done += bn[b];
				progress(user, done, c->photons);
			}
		}
	}
	memset(res, 0, sizeof *res);
	res->seconds = util_now() - t0;
	res->photons = c->photons;
	res->rsp = ln.rsp;
	res->n_layers = c->slab.n_layers;
	res->grid = *g;

	/* Gather per-batch scalars in batch order, then reduce. */
	enum { RD, RDU, TT, TTU, LOST, RSP, FLOSS, NSCAL };
	int na = SLAB_MAX_LAYERS + 2, nsc = NSCAL + na;
	double *sc = xcalloc((size_t)nb * (size_t)nsc, sizeof *sc);
	for (int b = 0; b < nb; b++) {
		double *row = sc + (size_t)b * nsc;
		row[RD] = bt[b].rd;
		row[RDU] = bt[b].rd_unscat;
		row[TT] = bt[b].tt;
		row[TTU] = bt[b].tt_unscat;
		row[LOST] = bt[b].lost;
		row[RSP] = bt[b].rsp;
		row[FLOSS] = bt[b].facet_loss;
		for (int i = 0; i < na; i++)
			row[NSCAL + i] = bt[b].a[i];
		res->events += bt[b].events;
	}
	res->rd = batchstat_weighted(sc + RD, nsc, bn, nb, c->photons);
	res->rd_unscat = batchstat_weighted(sc + RDU, nsc, bn, nb, c->photons);
	res->tt = batchstat_weighted(sc + TT, nsc, bn, nb, c->photons);
	res->tt_unscat = batchstat_weighted(sc + TTU, nsc, bn, nb, c->photons);
	res->lost = batchstat_weighted(sc + LOST, nsc, bn, nb, c->photons);
	struct estimate rsp_mc = batchstat_weighted(sc + RSP, nsc, bn, nb, c->photons);	/* 0 unless the top is rough */
	res->rsp += rsp_mc.v;
	res->rsp_err = rsp_mc.err;
	res->facet_loss = batchstat_weighted(sc + FLOSS, nsc, bn, nb, c->photons);
	double bal = res->rsp + res->rd.v + res->tt.v + res->lost.v + res->facet_loss.v;
	for (int i = 0; i < na; i++) {
		res->a[i] = batchstat_weighted(sc + NSCAL + i, nsc, bn, nb, c->photons);
		bal += res->a[i].v;
	}
	res->balance = bal - 1.0;
	free(sc);

	/* Angular and radial tallies. */
	int ne = g->n_theta * g->n_phi;
	double dth = 0.5 * M_PI / g->n_theta, dph = M_PI / g->n_phi;
	double *col = xcalloc((size_t)nb, sizeof *col);
	res->fr = xcalloc((size_t)ne, sizeof(double));
	res->fr_err = xcalloc((size_t)ne, sizeof(double));
	res->fr_az = xcalloc((size_t)g->n_theta, sizeof(double));
	res->fr_az_err = xcalloc((size_t)g->n_theta, sizeof(double));
	for (int it = 0; it < g->n_theta; it++) {
		double band = tally_cos_omega(it * dth, (it + 1) * dth, M_PI);
		double bin = tally_cos_omega(it * dth, (it + 1) * dth, dph);
		for (int b = 0; b < nb; b++) {
			col[b] = 0.0;
			for (int ip = 0; ip < g->n_phi; ip++)
				col[b] += bt[b].exit[it * g->n_phi + ip];
		}
		struct estimate v = batchstat_weighted(col, 1, bn, nb, c->photons);
		res->fr_az[it] = v.v / band;
		res->fr_az_err[it] = v.err / band;
		for (int ip = 0; ip < g->n_phi; ip++) {
			for (int b = 0; b < nb; b++)
				col[b] = bt[b].exit[it * g->n_phi + ip];
			v = batchstat_weighted(col, 1, bn, nb, c->photons);
			res->fr[it * g->n_phi + ip] = v.v / bin;
			res->fr_err[it * g->n_phi + ip] = v.err / bin;
		}
	}
	if (g->n_r > 0) {
		res->rd_r = xcalloc((size_t)g->n_r, sizeof(double));
		res->rd_r_err = xcalloc((size_t)g->n_r, sizeof(double));
		for (int ir = 0; ir < g->n_r; ir++) {
			double area = tally_annulus_area(g->dr, ir);
			for (int b = 0; b < nb; b++)
				col[b] = bt[b].radial[ir];
			struct estimate v = batchstat_weighted(col, 1, bn, nb, c->photons);
			res->rd_r[ir] = v.v / area;
			res->rd_r_err[ir] = v.err / area;
		}
	}
	free(col);
	for (int b = 0; b < nb; b++)
		tally_free(&bt[b]);
	free(bt);
	free(bn);
}

void sim_result_free(struct sim_result *res)
{
	free(res->fr);
	free(res->fr_err);
	free(res->fr_az);
	free(res->fr_az_err);
	free(res->rd_r);
	free(res->rd_r_err);
	memset(res, 0, sizeof *res);
}
