/* solver: run a method through its table of functions, and the table it
 * fills (see solver.h). */
#include "config.h"
#include "engine/solver.h"

#include <math.h>
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
	double t0 = util_now();
	while (ops->step(st, run))
		;
	double t1 = util_now();
	ops->finish(st, out);
	out->seconds = t1 - t0;
	return 0;
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
				double rel = o->fr[e] > 0.0 ? o->fr_err[e] / o->fr[e] : 1.0;
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
