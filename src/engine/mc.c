/* mc: Monte Carlo tables through the solver interface: rounds of photon
 * batches over all jobs, merged in (job, batch) order (see mc.h). */
#include "config.h"
#include "engine/mc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/check.h"
#include "base/util.h"
#include "engine/nee.h"
#include "engine/transport.h"

/* Quantities kept per batch, in this order: the totals, absorption per
 * layer, then the exit bins and the radial bins. */
enum { Q_RD, Q_RDU, Q_TT, Q_A, Q_LOST, Q_RSP, Q_FLOSS, Q_AL, Q_NSCAL = Q_AL + SLAB_MAX_LAYERS + 2 };

struct mc_state {
	struct solver_problem p;	/* arrays borrowed from the caller */
	struct mc_settings st;
	struct transport_opts opts;
	int nj, nq;			/* jobs; quantities per batch */
	struct batchstat *acc;		/* [nj] running sums of the batch means */
	double *events;			/* [nj] scattering events */
	struct launch *ln;		/* [nj] entry state of each job */
	long *want;			/* [nj] batches wanted so far */
	long bp;			/* photons per batch now */
	long offset;			/* photon index of batch 0 in every job (after a pilot) */
	int pilot;			/* 1 while the round is the pilot */
	long pilot_photons;		/* photons of the pilot set aside */
	long job_cap;			/* batches per job the budget allows */
	long done_photons, budget;	/* for progress */
};

/* Flatten one batch's tally into per-photon fractions. */
static void batch_values(const struct mc_state *m, const struct tally *t, double *q)
{
	const struct tally_grid *g = &m->p.grid;
	double inv = 1.0 / (double)m->bp;
	q[Q_RD] = t->rd * inv;
	q[Q_RDU] = t->rd_unscat * inv;
	q[Q_TT] = t->tt * inv;
	double a = 0.0;
	for (int i = 0; i < SLAB_MAX_LAYERS + 2; i++) {
		a += t->a[i];
		q[Q_AL + i] = t->a[i] * inv;
	}
	q[Q_A] = a * inv;
	q[Q_LOST] = t->lost * inv;
	q[Q_RSP] = t->rsp * inv;
	q[Q_FLOSS] = t->facet_loss * inv;
	int ne = g->n_theta * g->n_phi;
	for (int i = 0; i < ne; i++)
		q[Q_NSCAL + i] = t->exit[i] * inv;
	for (int i = 0; i < g->n_r; i++)
		q[Q_NSCAL + ne + i] = t->radial[i] * inv;
}

/* Solid-angle-weighted RMS relative error of one job's exit bins: num and
 * den of its square.  An empty bin counts as 100%, or not at all with skip_empty. */
static void job_rms_parts(const struct tally_grid *g, const struct batchstat *a, int skip_empty, double *num,
    double *den)
{
	*num = *den = 0.0;
	for (int it = 0; it < g->n_theta; it++)
		for (int ip = 0; ip < g->n_phi; ip++) {
			int k = Q_NSCAL + it * g->n_phi + ip;
			double m = batchstat_mean(a, k), e = batchstat_err(a, k), w = tally_bin_omega(g, it);
			if (m <= 0.0 && skip_empty)
				continue;
			double rel = m > 0.0 ? e / m : 1.0;
			*num += w * rel * rel;
			*den += w;
		}
}

static double job_rms(const struct tally_grid *g, const struct batchstat *a)
{
	double num, den;
	job_rms_parts(g, a, 0, &num, &den);
	return sqrt(num / den);
}

void mc_settings_default(struct mc_settings *s)
{
	struct transport_opts o;
	transport_opts_default(&o);
	*s = (struct mc_settings){ .seed = 1, .batch_photons = MC_BATCH_PHOTONS, .min_batches = 8, .pilot_photons = 250,
		.sized_batches = 32, .max_photons = 200000000L,
		.nee = 1, .roulette_w = o.roulette_w, .roulette_chance = o.roulette_chance, .max_steps = o.max_steps };
}

static void *mc_begin(const struct solver_problem *p, const void *settings, char **cause)
{
	const struct mc_settings *st = settings;
	(void)cause;
	CHECK(st->batch_photons >= 0 && st->min_batches >= 2);
	struct mc_state *m = xcalloc(1, sizeof *m);
	m->p = *p;
	m->st = *st;
	m->opts = (struct transport_opts){ .fresnel = p->fresnel, .roulette_w = st->roulette_w,
		.roulette_chance = st->roulette_chance, .max_steps = st->max_steps };
	m->nj = p->n_wl * p->n_ti;
	m->nq = Q_NSCAL + p->grid.n_theta * p->grid.n_phi + p->grid.n_r;
	m->acc = xcalloc((size_t)m->nj, sizeof *m->acc);
	m->events = xcalloc((size_t)m->nj, sizeof *m->events);
	m->ln = xcalloc((size_t)m->nj, sizeof *m->ln);
	m->want = xcalloc((size_t)m->nj, sizeof *m->want);
	m->bp = st->batch_photons;
	if (m->bp == 0) {
		CHECK(st->pilot_photons >= 1 && st->sized_batches >= 2);
		m->pilot = p->target_error > 0.0;
		m->bp = m->pilot ? st->pilot_photons : MC_BATCH_PHOTONS;
	}
	m->job_cap = st->max_photons / m->nj / m->bp;
	if (m->job_cap < st->min_batches)
		m->job_cap = st->min_batches;
	for (int j = 0; j < m->nj; j++) {
		CHECK(p->slab[j / p->n_ti].n_layers >= 1);
		CHECK(p->theta_i[j % p->n_ti] >= 0.0 && p->theta_i[j % p->n_ti] < 0.5 * M_PI);
		batchstat_init(&m->acc[j], m->nq);
		transport_launch(&p->slab[j / p->n_ti], p->theta_i[j % p->n_ti], p->fresnel, &m->ln[j]);
		m->want[j] = p->target_error > 0.0 ? st->min_batches : m->job_cap;
	}
	m->budget = (long)m->nj * (m->pilot ? st->min_batches : m->job_cap) * m->bp;
	return m;
}

/* Trace the units (job uj[u], batch ub[u]) of this rank into vals[u][nq + 1]
 * (the last value: scattering events); other ranks' rows stay 0. */
static void run_units(struct mc_state *m, const struct solver_run *run, long nu, const int *uj, const long *ub,
    double *vals)
{
	const struct solver_problem *p = &m->p;
	const struct tally_grid *g = &p->grid;
	const long bp = m->bp;
	const int nq = m->nq;
#ifdef _OPENMP
	int nthreads = run->threads > 0 ? run->threads : omp_get_max_threads();
#endif
#pragma omp parallel num_threads(nthreads)
	{
		struct tally t;
		struct nee ne;
		tally_alloc(&t, g);
		if (m->st.nee)
			nee_alloc(&ne, g->n_theta, g->n_phi, SLAB_MAX_LAYERS);
#pragma omp for schedule(dynamic, 1)
		for (long u = 0; u < nu; u++) {
			if (u % run->n_ranks != run->rank)
				continue;
			int j = uj[u];
			tally_zero(&t, g);
			/* nee follows smooth refraction: rough stacks score their escapes. */
			const struct slab *sl = &p->slab[j / p->n_ti];
			transport_run(sl, &m->ln[j], &m->opts, g, m->st.nee && !sl->rough_any ? &ne : NULL, m->st.seed,
			    m->st.stream0 + (uint32_t)j, (uint64_t)m->offset + (uint64_t)ub[u] * (uint64_t)bp, (uint64_t)bp, &t);
			batch_values(m, &t, vals + (size_t)u * (size_t)(nq + 1));
			vals[(size_t)u * (size_t)(nq + 1) + nq] = t.events;
			if (run->progress) {
#pragma omp critical(mc_progress)
				{
					m->done_photons += bp;
					run->progress(run->progress_user, m->done_photons, m->budget);
				}
			}
		}
		tally_free(&t);
		if (m->st.nee)
			nee_free(&ne);
	}
}

/* The table's RMS error over the jobs (skip_empty: over the bins with light). */
static double table_rms(const struct mc_state *m, int skip_empty)
{
	double num = 0.0, den = 0.0;
	for (int j = 0; j < m->nj; j++) {
		double a, b;
		job_rms_parts(&m->p.grid, &m->acc[j], skip_empty, &a, &b);
		num += a;
		den += b;
	}
	return den > 0.0 ? sqrt(num / den) : 1.0;
}

/* After the pilot: set it aside and size the first round from it (see
 * mc.h).  1 when that round is wanted, 0 when the pilot met the target. */
static int size_from_pilot(struct mc_state *m, double E)
{
	m->pilot = 0;
	if (E <= m->p.target_error)
		return 0;
	/* Empty bins say nothing about the variance per photon: leave them out
	 * here (the later rounds count them again). */
	double Es = table_rms(m, 1), target = m->p.target_error;
	long per_job = m->acc[0].batches * m->bp, nb = m->st.sized_batches;
	double n = (double)per_job * (Es / target) * (Es / target) * 1.1;
	long left = m->st.max_photons / m->nj - per_job;
	if (n > (double)left)
		n = (double)left;
	m->pilot_photons = per_job * m->nj;
	m->offset = per_job;
	m->bp = (long)ceil(n / (double)nb);
	if (m->bp < 1)
		m->bp = 1;
	m->job_cap = left / m->bp;
	if (m->job_cap < 2)
		m->job_cap = 2;
	for (int j = 0; j < m->nj; j++) {
		batchstat_free(&m->acc[j]);
		batchstat_init(&m->acc[j], m->nq);
		m->events[j] = 0.0;
		m->want[j] = nb < m->job_cap ? nb : m->job_cap;
	}
	m->budget = m->done_photons + (long)m->nj * m->want[0] * m->bp;
	return 1;
}

/* After a round: more batches per job where the table's error is above the
 * target.  1 when another round is wanted. */
static int plan_round(struct mc_state *m)
{
	double target = m->p.target_error;
	if (target <= 0.0)
		return 0;
	/* The criterion is the whole table's RMS error (a mean of the jobs'
	 * squared errors, all on one grid).  Scaling every job's photons by
	 * (E / target)^2 brings it to the target in one more round when the
	 * estimate is right; 5% margin for its noise. */
	double e2 = 0.0;
	for (int j = 0; j < m->nj; j++) {
		double e = job_rms(&m->p.grid, &m->acc[j]);
		e2 += e * e;
	}
	double E = sqrt(e2 / m->nj);
	if (m->pilot)
		return size_from_pilot(m, E);
	if (E <= target)
		return 0;
	double f = (E / target) * (E / target) * 1.05;
	int more = 0;
	for (int j = 0; j < m->nj; j++) {
		long nw = (long)ceil((double)m->acc[j].batches * f);
		if (nw > m->job_cap)
			nw = m->job_cap;
		if (nw > m->acc[j].batches) {
			m->want[j] = nw;
			more = 1;
		}
	}
	if (!more)
		return 0;
	long left = 0;
	for (int j = 0; j < m->nj; j++)
		left += (m->want[j] - m->acc[j].batches) * m->bp;
	m->budget = m->done_photons + left;
	return 1;
}

/* A step runs at most this many batches of each job: a round of a large
 * budget is cut into steps that a checkpoint can stop after.  Each job's
 * batches still merge in batch order, so the sums (and the table) are
 * those of the whole round at once. */
enum { STEP_BATCHES = 32 };

static long step_end(const struct mc_state *m, int j)
{
	long end = m->acc[j].batches + STEP_BATCHES;
	return end < m->want[j] ? end : m->want[j];
}

/* The next part of a round: up to STEP_BATCHES of every (job, batch)
 * wanted and not yet run; when the round is complete, plan the next. */
static int mc_step(void *state, const struct solver_run *run)
{
	struct mc_state *m = state;
	long nu = 0;
	for (int j = 0; j < m->nj; j++)
		nu += step_end(m, j) - m->acc[j].batches;
	if (nu <= 0)
		return 0;
	int *uj = xmalloc(sizeof(int) * (size_t)nu);
	long *ub = xmalloc(sizeof(long) * (size_t)nu);
	long k = 0;
	for (int j = 0; j < m->nj; j++)
		for (long b = m->acc[j].batches, end = step_end(m, j); b < end; b++) {
			uj[k] = j;
			ub[k++] = b;
		}
	CHECK(k == nu);
	double *vals = xcalloc((size_t)nu * (size_t)(m->nq + 1), sizeof(double));
	run_units(m, run, nu, uj, ub, vals);
	/* Units of other ranks are zero here; the sum brings them in. */
	if (run->allreduce)
		run->allreduce(vals, nu * (long)(m->nq + 1));
	/* Merge in (job, batch) order: the same sums for any thread count. */
	for (long u = 0; u < nu; u++) {
		const double *q = vals + (size_t)u * (size_t)(m->nq + 1);
		batchstat_add(&m->acc[uj[u]], q);
		m->events[uj[u]] += q[m->nq];
	}
	free(vals);
	free(uj);
	free(ub);
	for (int j = 0; j < m->nj; j++)
		if (m->acc[j].batches < m->want[j])
			return 1;
	return plan_round(m);
}

static struct estimate est(const struct batchstat *a, int k)
{
	return (struct estimate){ batchstat_mean(a, k), batchstat_err(a, k) };
}

/* One job's entry from its sums. */
static void fill_entry(const struct mc_state *m, int j, struct brdf_entry *o)
{
	const struct tally_grid *g = &m->p.grid;
	const struct batchstat *a = &m->acc[j];
	int ne = g->n_theta * g->n_phi;
	o->batches = a->batches;
	o->photons = a->batches * m->bp;
	o->events = m->events[j];
	o->rsp = m->ln[j].rsp + batchstat_mean(a, Q_RSP);	/* + 0 unless the top is rough */
	o->albedo = (struct estimate){ batchstat_mean(a, Q_RD) - batchstat_mean(a, Q_RDU), batchstat_err(a, Q_RD) };
	o->rd_unscat = est(a, Q_RDU);
	o->tt = est(a, Q_TT);
	o->a_total = est(a, Q_A);
	for (int i = 0; i < SLAB_MAX_LAYERS + 2; i++)
		o->a[i] = est(a, Q_AL + i);
	o->lost = est(a, Q_LOST);
	o->facet_loss = est(a, Q_FLOSS);
	double dth = 0.5 * M_PI / g->n_theta;
	for (int it = 0; it < g->n_theta; it++) {
		double co = tally_cos_omega(it * dth, (it + 1) * dth, M_PI / g->n_phi);
		for (int ip = 0; ip < g->n_phi; ip++) {
			int e = it * g->n_phi + ip;
			o->fr[e] = batchstat_mean(a, Q_NSCAL + e) / co;
			o->fr_err[e] = batchstat_err(a, Q_NSCAL + e) / co;
		}
	}
	o->rms_rel_err = job_rms(g, a);
	o->method = "mc";
	for (int i = 0; i < g->n_r; i++) {
		double area = tally_annulus_area(g->dr, i);
		o->rd_r[i] = batchstat_mean(a, Q_NSCAL + ne + i) / area;
		o->rd_r_err[i] = batchstat_err(a, Q_NSCAL + ne + i) / area;
	}
}

static void mc_finish(void *state, struct brdf_table *out)
{
	struct mc_state *m = state;
	brdf_table_init(out, &m->p);
	for (int j = 0; j < m->nj; j++) {
		fill_entry(m, j, &out->entry[j]);
		out->photons += out->entry[j].photons;
		batchstat_free(&m->acc[j]);
	}
	out->pilot_photons = m->pilot_photons;
	out->rms_rel_err = brdf_table_rms(out);
	out->target_met = m->p.target_error <= 0.0 || out->rms_rel_err <= m->p.target_error;
	free(m->acc);
	free(m->events);
	free(m->ln);
	free(m->want);
	free(m);
}

/* The scalars of the state that change between steps, in this order. */
#define MC_PACKED_LONGS(m) { &(m)->bp, &(m)->offset, &(m)->pilot_photons, &(m)->job_cap, &(m)->done_photons, &(m)->budget }

static void *mc_pack(const void *state, size_t *len)
{
	const struct mc_state *m = state;
	struct solver_buf b = { 0 };
	long *const l[] = MC_PACKED_LONGS((struct mc_state *)m);
	for (size_t i = 0; i < sizeof l / sizeof l[0]; i++)
		solver_buf_put(&b, l[i], sizeof(long));
	solver_buf_put(&b, &m->pilot, sizeof m->pilot);
	solver_buf_put(&b, m->want, sizeof(long) * (size_t)m->nj);
	solver_buf_put(&b, m->events, sizeof(double) * (size_t)m->nj);
	for (int j = 0; j < m->nj; j++) {
		solver_buf_put(&b, &m->acc[j].batches, sizeof(long));
		solver_buf_put(&b, m->acc[j].s1, sizeof(double) * (size_t)m->nq);
		solver_buf_put(&b, m->acc[j].s2, sizeof(double) * (size_t)m->nq);
	}
	*len = b.len;
	return b.p;
}

static int mc_unpack(void *state, const void *buf, size_t len)
{
	struct mc_state *m = state;
	struct solver_buf b = { .p = (unsigned char *)buf, .len = len };
	long *const l[] = MC_PACKED_LONGS(m);
	for (size_t i = 0; i < sizeof l / sizeof l[0]; i++)
		solver_buf_get(&b, l[i], sizeof(long));
	solver_buf_get(&b, &m->pilot, sizeof m->pilot);
	solver_buf_get(&b, m->want, sizeof(long) * (size_t)m->nj);
	solver_buf_get(&b, m->events, sizeof(double) * (size_t)m->nj);
	for (int j = 0; j < m->nj; j++) {
		solver_buf_get(&b, &m->acc[j].batches, sizeof(long));
		solver_buf_get(&b, m->acc[j].s1, sizeof(double) * (size_t)m->nq);
		solver_buf_get(&b, m->acc[j].s2, sizeof(double) * (size_t)m->nq);
	}
	return b.bad || b.pos != len || m->bp < 1 ? -1 : 0;
}

/* Every sampling knob as given (a bake states them all). */
static void *mc_settings(const struct solver_knobs *k)
{
	struct mc_settings *st = xmalloc(sizeof *st);
	mc_settings_default(st);
	st->seed = k->seed;
	st->batch_photons = k->batch_photons;
	st->min_batches = k->min_batches;
	st->max_photons = k->max_photons;
	st->nee = k->nee;
	st->roulette_w = k->roulette_w;
	st->roulette_chance = k->roulette_chance;
	st->max_steps = k->max_steps;
	return st;
}

/* simulate: sim_run, which c configures whole. */
static int mc_simulate(const struct sim_config *c, const struct solver_knobs *k,
    struct sim_result *r, struct sim_solve_info *info, solver_progress *progress, void *user,
    char **cause)
{
	(void)k;
	(void)info;
	(void)cause;
	sim_run(c, r, progress, user);
	return 0;
}

const struct solver_ops mc_solver = {
	.name = "mc",
	.title = "Monte Carlo",
	.provides = SOLVER_BRDF | SOLVER_RADIAL,
	.traits = SOLVER_SAMPLED,
	.error_doc = "standard errors (batch means)",
	.settings = mc_settings,
	.simulate = mc_simulate,
	.begin = mc_begin,
	.step = mc_step,
	.finish = mc_finish,
	.pack = mc_pack,
	.unpack = mc_unpack,
};
