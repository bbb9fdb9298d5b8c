/* solver: run a method through its table of functions, and the table it
 * fills (see solver.h). */
#include "config.h"
#include "engine/solver.h"

#include <assert.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/util.h"

int solver_solve(const struct solver_ops *ops, const void *settings, const struct solver_problem *p,
    const struct solver_run *run, struct brdf_table *out, char **cause)
{
	CHECK(p->n_wl >= 1 && p->n_ti >= 1 && p->grid.n_theta >= 1 && p->grid.n_phi >= 1);
	void *st = ops->begin(p, settings, cause);
	if (st == NULL)
		return -1;
	const struct solver_ckpt *ck = run->ckpt;
	int done = ck ? ck->restore(ck->user, ops, st, cause) : 0;
	if (done < 0) {
		ops->finish(st, out);
		brdf_table_free(out);
		return -1;
	}
	double t0 = util_now();
	while (!done) {
		done = !ops->step(st, run);
		if (ck)
			ck->save(ck->user, ops, st, done);
	}
	double t1 = util_now();
	ops->finish(st, out);
	out->seconds = t1 - t0;
	return 0;
}

void solver_buf_put(struct solver_buf *b, const void *v, size_t n)
{
	if (b->len + n > b->cap) {
		b->cap = 2 * (b->len + n) + 256;
		b->p = xreallocarray(b->p, b->cap, 1);
	}
	memcpy(b->p + b->len, v, n);
	b->len += n;
}

void solver_buf_get(struct solver_buf *b, void *v, size_t n)
{
	if (b->bad || n > b->len - b->pos) {
		b->bad = 1;
		memset(v, 0, n);
		return;
	}
	memcpy(v, b->p + b->pos, n);
	b->pos += n;
}

/* The estimates of an entry in one order, for put and get. */
static struct estimate *entry_estimates(struct brdf_entry *e, int *n)
{
	static_assert(offsetof(struct brdf_entry, facet_loss) - offsetof(struct brdf_entry, albedo) ==
	    (SLAB_MAX_LAYERS + 7) * sizeof(struct estimate), "estimates of brdf_entry are contiguous");
	*n = SLAB_MAX_LAYERS + 8;
	return &e->albedo;
}

void solver_entry_put(struct solver_buf *b, const struct brdf_entry *e, const struct tally_grid *g)
{
	int ne;
	const struct estimate *est = entry_estimates((struct brdf_entry *)e, &ne);
	size_t nb = (size_t)g->n_theta * (size_t)g->n_phi, nr = e->rd_r ? (size_t)g->n_r : 0;
	unsigned char has_method = e->method != NULL;
	size_t nref = e->refused ? strlen(e->refused) + 1 : 0;
	solver_buf_put(b, &e->rsp, sizeof e->rsp);
	solver_buf_put(b, est, sizeof *est * (size_t)ne);
	solver_buf_put(b, e->fr, sizeof(double) * nb);
	solver_buf_put(b, e->fr_err, sizeof(double) * nb);
	if (nr) {
		solver_buf_put(b, e->rd_r, sizeof(double) * nr);
		solver_buf_put(b, e->rd_r_err, sizeof(double) * nr);
	}
	solver_buf_put(b, &e->rms_rel_err, sizeof e->rms_rel_err);
	solver_buf_put(b, &has_method, 1);
	solver_buf_put(b, &nref, sizeof nref);
	if (nref)
		solver_buf_put(b, e->refused, nref);
	solver_buf_put(b, &e->batches, sizeof e->batches);
	solver_buf_put(b, &e->photons, sizeof e->photons);
	solver_buf_put(b, &e->events, sizeof e->events);
	solver_buf_put(b, &e->n_quad, sizeof e->n_quad);
	solver_buf_put(b, &e->n_orders, sizeof e->n_orders);
}

void solver_entry_get(struct solver_buf *b, struct brdf_entry *e, const struct tally_grid *g, const char *method)
{
	int ne;
	struct estimate *est = entry_estimates(e, &ne);
	size_t nb = (size_t)g->n_theta * (size_t)g->n_phi, nr = e->rd_r ? (size_t)g->n_r : 0, nref;
	unsigned char has_method;
	solver_buf_get(b, &e->rsp, sizeof e->rsp);
	solver_buf_get(b, est, sizeof *est * (size_t)ne);
	solver_buf_get(b, e->fr, sizeof(double) * nb);
	solver_buf_get(b, e->fr_err, sizeof(double) * nb);
	if (nr) {
		solver_buf_get(b, e->rd_r, sizeof(double) * nr);
		solver_buf_get(b, e->rd_r_err, sizeof(double) * nr);
	}
	solver_buf_get(b, &e->rms_rel_err, sizeof e->rms_rel_err);
	solver_buf_get(b, &has_method, 1);
	e->method = has_method ? method : NULL;
	solver_buf_get(b, &nref, sizeof nref);
	free(e->refused);
	e->refused = NULL;
	if (nref > 0 && !b->bad && nref <= b->len - b->pos && b->p[b->pos + nref - 1] == '\0') {
		e->refused = xstrdup((const char *)b->p + b->pos);
		b->pos += nref;
	} else if (nref > 0)
		b->bad = 1;
	solver_buf_get(b, &e->batches, sizeof e->batches);
	solver_buf_get(b, &e->photons, sizeof e->photons);
	solver_buf_get(b, &e->events, sizeof e->events);
	solver_buf_get(b, &e->n_quad, sizeof e->n_quad);
	solver_buf_get(b, &e->n_orders, sizeof e->n_orders);
}

void brdf_table_init(struct brdf_table *t, const struct solver_problem *p)
{
	memset(t, 0, sizeof *t);
	t->n_wl = p->n_wl;
	t->n_ti = p->n_ti;
	t->grid = p->grid;
	size_t n = (size_t)p->n_wl * (size_t)p->n_ti, nb = (size_t)p->grid.n_theta * (size_t)p->grid.n_phi;
	t->entry = xcalloc(n, sizeof *t->entry);
	for (size_t j = 0; j < n; j++) {
		struct brdf_entry *e = &t->entry[j];
		e->wl_nm = p->wl_nm[j / (size_t)p->n_ti];
		e->theta_i = p->theta_i[j % (size_t)p->n_ti];
		e->fr = xcalloc(nb, sizeof(double));
		e->fr_err = xcalloc(nb, sizeof(double));
		if (p->grid.n_r > 0) {
			e->rd_r = xcalloc((size_t)p->grid.n_r, sizeof(double));
			e->rd_r_err = xcalloc((size_t)p->grid.n_r, sizeof(double));
		}
	}
}

double brdf_table_rms(const struct brdf_table *t)
{
	const struct tally_grid *g = &t->grid;
	double num = 0.0, den = 0.0;
	for (int j = 0; j < t->n_wl * t->n_ti; j++) {
		const struct brdf_entry *o = &t->entry[j];
		for (int it = 0; it < g->n_theta; it++) {
			double w = tally_bin_omega(g, it);
			for (int ip = 0; ip < g->n_phi; ip++) {
				int e = it * g->n_phi + ip;
				/* An empty bin counts as 100%; a deterministic 0 with error 0
				 * is exact (adding-doubling's point value at grazing exit):
				 * an entry a method filled without photons. */
				int exact = o->fr_err[e] == 0.0 && o->method && o->photons == 0;
				double rel = o->fr[e] > 0.0 ? o->fr_err[e] / o->fr[e] : exact ? 0.0 : 1.0;
				num += w * rel * rel;
				den += w;
			}
		}
	}
	return sqrt(num / den);
}

void brdf_table_free(struct brdf_table *t)
{
	for (int j = 0; j < t->n_wl * t->n_ti; j++) {
		free(t->entry[j].fr);
		free(t->entry[j].fr_err);
		free(t->entry[j].rd_r);
		free(t->entry[j].rd_r_err);
		free(t->entry[j].refused);
	}
	free(t->entry);
	memset(t, 0, sizeof *t);
}
