#include "config.h"
#include "bake/bake.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "engine/nee.h"
#include "engine/sim.h"
#include "engine/tally.h"
#include "base/util.h"

/* Running sums over a job's batches, per quantity: batch means and squares. */
struct acc {
	long batches;
	double *s1, *s2;	/* [nq] */
	double events;
};

/* Quantities kept per batch, in this order. */
enum { Q_RD, Q_RDU, Q_TT, Q_A, Q_LOST, Q_NSCAL };

static int n_quant(const struct bake_spec *s)
{
	return Q_NSCAL + s->n_to * s->n_phi + s->n_r;
}

/* Flatten one batch's tally into per-photon fractions. */
static void batch_values(const struct bake_spec *s, const struct tally *t, double *q)
{
	double inv = 1.0 / (double)s->batch_photons;
	q[Q_RD] = t->rd * inv;
	q[Q_RDU] = t->rd_unscat * inv;
	q[Q_TT] = t->tt * inv;
	double a = 0.0;
	for (int i = 0; i < SLAB_MAX_LAYERS + 2; i++)
		a += t->a[i];
	q[Q_A] = a * inv;
	q[Q_LOST] = t->lost * inv;
	int ne = s->n_to * s->n_phi;
	for (int i = 0; i < ne; i++)
		q[Q_NSCAL + i] = t->exit[i] * inv;
	for (int i = 0; i < s->n_r; i++)
		q[Q_NSCAL + ne + i] = t->radial[i] * inv;
}

static double mean_of(const struct acc *a, int k)
{
	return a->s1[k] / (double)a->batches;
}

static double err_of(const struct acc *a, int k)
{
	double B = (double)a->batches, m = a->s1[k] / B;
	double var = (a->s2[k] - B * m * m) / (B - 1.0);
	return var > 0.0 ? sqrt(var / B) : 0.0;
}

/* Bin geometry: integral of cos d(omega) over bin (it, ip), both sides of
 * the incidence plane, and its plain solid angle. */
static double bin_cos_omega(const struct bake_spec *s, int it)
{
	double dth = 0.5 * M_PI / s->n_to;
	return sim_cos_solid_angle(it * dth, (it + 1) * dth, M_PI / s->n_phi);
}

static double bin_omega(const struct bake_spec *s, int it)
{
	double dth = 0.5 * M_PI / s->n_to;
	return (cos(it * dth) - cos((it + 1) * dth)) * 2.0 * M_PI / s->n_phi;
}

static double job_rms(const struct bake_spec *s, const struct acc *a)
{
	double num = 0.0, den = 0.0;
	for (int it = 0; it < s->n_to; it++)
		for (int ip = 0; ip < s->n_phi; ip++) {
			int k = Q_NSCAL + it * s->n_phi + ip;
			double m = mean_of(a, k), e = err_of(a, k), w = bin_omega(s, it);
			double rel = m > 0.0 ? e / m : 1.0;	/* an empty bin counts as 100% */
			num += w * rel * rel;
			den += w;
		}
	return sqrt(num / den);
}

void bake_specular_stack(const struct slab *s, enum optics_fresnel model, struct specular_stack *out)
{
	out->model = model;
	out->n = 0;
	int last = s->first_turbid <= s->n_layers ? s->first_turbid : s->n_layers + 1;
	for (int i = 0; i <= last && out->n < SPECULAR_MAX_IFACES; i++)
		out->n_list[out->n++] = s->layer[i].n;
}

double bake_mean_radius(const double *rd_r, int n_r, double dr)
{
	double num = 0.0, den = 0.0;
	for (int i = 0; i < n_r; i++) {
		double rc = (i + 0.5) * dr, area = M_PI * dr * dr * (2 * i + 1);
		num += rc * rd_r[i] * area;
		den += rd_r[i] * area;
	}
	return den > 0.0 ? num / den : 0.0;
}

void bake_run(const struct bake_spec *s, struct bake_result *r)
{
	int nj = s->n_wl * s->n_ti, nq = n_quant(s);
	struct tally_grid g = { .n_theta = s->n_to, .n_phi = s->n_phi, .n_r = s->n_r, .dr = s->dr };
	struct acc *acc = xcalloc((size_t)nj, sizeof *acc);
	struct launch *ln = xcalloc((size_t)nj, sizeof *ln);
	long *want = xcalloc((size_t)nj, sizeof *want);
	long job_cap = s->max_photons / nj / s->batch_photons;	/* batches per job */
	if (job_cap < s->min_batches)
		job_cap = s->min_batches;
	for (int j = 0; j < nj; j++) {
		acc[j].s1 = xcalloc((size_t)nq, sizeof(double));
		acc[j].s2 = xcalloc((size_t)nq, sizeof(double));
		const struct slab *sl = &s->slab[j / s->n_ti];
		transport_launch(sl, s->theta_i[j % s->n_ti], s->opts.fresnel, &ln[j]);
		want[j] = s->target_error > 0.0 ? s->min_batches : job_cap;
	}
	double t0 = util_now();
	long done_photons = 0, budget = (long)nj * job_cap * s->batch_photons;
#ifdef _OPENMP
	int nthreads = s->threads > 0 ? s->threads : omp_get_max_threads();
#endif
	for (;;) {
		/* The units of this round: (job, batch) for batches not yet run. */
		long nu = 0;
		for (int j = 0; j < nj; j++)
			nu += want[j] - acc[j].batches;
		if (nu <= 0)
			break;
		int *uj = xmalloc(sizeof(int) * (size_t)nu);
		long *ub = xmalloc(sizeof(long) * (size_t)nu);
		long k = 0;
		for (int j = 0; j < nj; j++)
			for (long b = acc[j].batches; b < want[j]; b++)
				uj[k] = j, ub[k++] = b;
		double *vals = xcalloc((size_t)nu * (size_t)(nq + 1), sizeof(double));
#pragma omp parallel num_threads(nthreads)
		{
			struct tally t;
			struct nee ne;
			tally_alloc(&t, &g);
			if (s->nee)
				nee_alloc(&ne, s->n_to, s->n_phi, SLAB_MAX_LAYERS);
#pragma omp for schedule(dynamic, 1)
			for (long u = 0; u < nu; u++) {
				if (u % s->n_ranks != s->rank)
					continue;
				int j = uj[u];
				const struct slab *sl = &s->slab[j / s->n_ti];
				tally_zero(&t, &g);
				transport_run(sl, &ln[j], &s->opts, &g, s->nee ? &ne : NULL, s->seed, (uint32_t)j,
				    (uint64_t)ub[u] * (uint64_t)s->batch_photons, (uint64_t)s->batch_photons, &t);
				batch_values(s, &t, vals + (size_t)u * (size_t)(nq + 1));
				vals[(size_t)u * (size_t)(nq + 1) + nq] = t.events;
				if (s->progress) {
#pragma omp critical(bake_progress)
					{
						done_photons += s->batch_photons;
						s->progress(s->progress_user, done_photons, budget);
					}
				}
			}
			tally_free(&t);
			if (s->nee)
				nee_free(&ne);
		}
		/* Units of other ranks are zero here; the sum brings them in. */
		if (s->allreduce)
			s->allreduce(vals, nu * (long)(nq + 1));
		/* Merge in (job, batch) order: the same sums for any thread count. */
		for (long u = 0; u < nu; u++) {
			struct acc *a = &acc[uj[u]];
			const double *q = vals + (size_t)u * (size_t)(nq + 1);
			for (int i = 0; i < nq; i++) {
				a->s1[i] += q[i];
				a->s2[i] += q[i] * q[i];
			}
			a->events += q[nq];
			a->batches++;
		}
		free(vals);
		free(uj);
		free(ub);
		if (s->target_error <= 0.0)
			break;
		/* The criterion is the whole table's RMS error (a mean of the jobs'
		 * squared errors, all on one grid).  Scaling every job's photons by
		 * (E / target)^2 brings it to the target in one more round when the
		 * estimate is right; 5% margin for its noise. */
		double e2 = 0.0;
		for (int j = 0; j < nj; j++) {
			double e = job_rms(s, &acc[j]);
			e2 += e * e;
		}
		double E = sqrt(e2 / nj);
		if (E <= s->target_error)
			break;
		double f = (E / s->target_error) * (E / s->target_error) * 1.05;
		int more = 0;
		for (int j = 0; j < nj; j++) {
			long nw = (long)ceil((double)acc[j].batches * f);
			if (nw > job_cap)
				nw = job_cap;
			if (nw > acc[j].batches) {
				want[j] = nw;
				more = 1;
			}
		}
		if (!more)
			break;
		long left = 0;
		for (int j = 0; j < nj; j++)
			left += (want[j] - acc[j].batches) * s->batch_photons;
		budget = done_photons + left;
	}

	memset(r, 0, sizeof *r);
	r->n_jobs = nj;
	r->job = xcalloc((size_t)nj, sizeof *r->job);
	r->seconds = util_now() - t0;
	double num = 0.0, den = 0.0;
	int ne = s->n_to * s->n_phi;
	for (int j = 0; j < nj; j++) {
		struct bake_job *o = &r->job[j];
		struct acc *a = &acc[j];
		o->wl_nm = s->wl_nm[j / s->n_ti];
		o->theta_i = s->theta_i[j % s->n_ti];
		o->batches = a->batches;
		o->photons = a->batches * s->batch_photons;
		o->events = a->events;
		o->rsp = ln[j].rsp;
		o->albedo = mean_of(a, Q_RD) - mean_of(a, Q_RDU);
		o->albedo_err = err_of(a, Q_RD);
		o->rd_unscat = mean_of(a, Q_RDU);
		o->tt = mean_of(a, Q_TT);
		o->tt_err = err_of(a, Q_TT);
		o->a_total = mean_of(a, Q_A);
		o->lost = mean_of(a, Q_LOST);
		o->fr = xcalloc((size_t)ne, sizeof(double));
		o->fr_err = xcalloc((size_t)ne, sizeof(double));
		for (int it = 0; it < s->n_to; it++) {
			double co = bin_cos_omega(s, it), w = bin_omega(s, it);
			for (int ip = 0; ip < s->n_phi; ip++) {
				int e = it * s->n_phi + ip;
				o->fr[e] = mean_of(a, Q_NSCAL + e) / co;
				o->fr_err[e] = err_of(a, Q_NSCAL + e) / co;
				double rel = o->fr[e] > 0.0 ? o->fr_err[e] / o->fr[e] : 1.0;
				num += w * rel * rel;
				den += w;
			}
		}
		o->rms_rel_err = job_rms(s, a);
		if (s->n_r > 0) {
			o->rd_r = xcalloc((size_t)s->n_r, sizeof(double));
			o->rd_r_err = xcalloc((size_t)s->n_r, sizeof(double));
			for (int i = 0; i < s->n_r; i++) {
				double area = M_PI * s->dr * s->dr * (2 * i + 1);
				o->rd_r[i] = mean_of(a, Q_NSCAL + ne + i) / area;
				o->rd_r_err[i] = err_of(a, Q_NSCAL + ne + i) / area;
			}
		}
		r->photons += o->photons;
		free(a->s1);
		free(a->s2);
	}
	r->rms_rel_err = sqrt(num / den);
	r->target_met = s->target_error <= 0.0 || r->rms_rel_err <= s->target_error;
	free(acc);
	free(ln);
	free(want);
}

void bake_result_free(struct bake_result *r)
{
	for (int j = 0; j < r->n_jobs; j++) {
		free(r->job[j].fr);
		free(r->job[j].fr_err);
		free(r->job[j].rd_r);
		free(r->job[j].rd_r_err);
	}
	free(r->job);
	memset(r, 0, sizeof *r);
}
