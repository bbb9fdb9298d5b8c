/* ad_solver: adding-doubling tables through the solver interface, a few
 * wavelengths per step, and one stack as sim_run gives it (see ad_solver.h). */
#include "config.h"
#include "engine/ad_solver.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/check.h"
#include "base/util.h"
#include "engine/ad_err.h"
#include "io/json.h"

/* Wavelengths per step and thread: enough for dynamic scheduling to even
 * out their costs, few enough to stop (and later checkpoint) often. */
#define WL_PER_THREAD 4

struct ad_state {
	struct solver_problem p;	/* arrays borrowed from the caller */
	struct ad_solver_settings st;	/* tol already the smaller of settings and target */
	struct brdf_table t;		/* filled as the steps go */
	int *met;			/* [n_wl] 1 when the wavelength's estimates meet tol */
	int next;			/* first wavelength not yet solved */
};

void ad_solver_settings_default(struct ad_solver_settings *s)
{
	memset(s, 0, sizeof *s);
	ad_opts_default(&s->ad);
}

double ad_solver_tol(const struct ad_solver_settings *s, const struct solver_problem *p)
{
	return p->target_error > 0.0 && p->target_error < s->ad.tol ? p->target_error : s->ad.tol;
}

static void *ad_begin(const struct solver_problem *p, const void *settings, char **cause)
{
	const struct ad_solver_settings *st = settings;
	if (p->n_ti > AD_MAX_BEAMS) {
		*cause = xasprintf("adding-doubling takes at most %d incidence angles (%d asked)", AD_MAX_BEAMS, p->n_ti);
		return NULL;
	}
	struct ad_state *a = xcalloc(1, sizeof *a);
	a->p = *p;
	a->st = *st;
	a->st.ad.tol = ad_solver_tol(st, p);
	a->st.ad.n_to = p->grid.n_theta;
	a->st.ad.n_phi = p->grid.n_phi;
	a->st.ad.cache = p->ad_cache;
	CHECK(a->st.ad.tol > 0.0 && a->st.ad.tol <= 0.1);
	brdf_table_init(&a->t, p);
	a->met = xcalloc((size_t)p->n_wl, sizeof *a->met);
	return a;
}

/* The seam's RMS relative error of one entry (brdf_table_rms's definition:
 * a 0 with error 0 is exact). */
static double entry_rms(const struct tally_grid *g, const struct brdf_entry *e)
{
	double num = 0.0, den = 0.0;
	for (int it = 0; it < g->n_theta; it++) {
		double w = tally_bin_omega(g, it);
		for (int ip = 0; ip < g->n_phi; ip++) {
			int k = it * g->n_phi + ip;
			double rel = e->fr[k] > 0.0 ? e->fr_err[k] / e->fr[k] : e->fr_err[k] == 0.0 ? 0.0 : 1.0;
			num += w * rel * rel;
			den += w;
		}
	}
	return sqrt(num / den);
}

/* Wavelength w's entries from the solver's beams. */
static void fill(struct ad_state *a, int w, const struct ad_result *r)
{
	size_t nb = (size_t)a->p.grid.n_theta * (size_t)a->p.grid.n_phi;
	for (int k = 0; k < a->p.n_ti; k++) {
		struct brdf_entry *e = &a->t.entry[w * a->p.n_ti + k];
		const struct ad_beam *b = &r->beam[k];
		e->rsp = b->rsp;
		/* Monte Carlo's albedo: what returns scattered (rd includes the
		 * unscattered return); the error is that of all returned light. */
		e->albedo = (struct estimate){ b->rd.v - b->rd_unscat, b->rd.err };
		e->rd_unscat = (struct estimate){ b->rd_unscat, 0.0 };
		e->tt = (struct estimate){ b->tt.v, b->tt.err };
		e->a_total = (struct estimate){ 0.0, 0.0 };
		for (int i = 0; i < SLAB_MAX_LAYERS + 2; i++) {
			e->a[i] = (struct estimate){ b->a[i].v, b->a[i].err };
			e->a_total.v += b->a[i].v;
			e->a_total.err += b->a[i].err;	/* the estimates are bounds: they add */
		}
		e->lost = (struct estimate){ 0.0, 0.0 };
		e->facet_loss = (struct estimate){ b->facet_loss.v, b->facet_loss.err };
		if (a->p.point_theta_o)
			ad_brdf_points(r, k, a->p.point_theta_o, a->p.grid.n_theta, a->p.point_phi, a->p.grid.n_phi, e->fr,
			    e->fr_err);
		else {
			memcpy(e->fr, b->fr, nb * sizeof(double));
			memcpy(e->fr_err, b->fr_err, nb * sizeof(double));
		}
		e->rms_rel_err = entry_rms(&a->p.grid, e);
		e->method = "ad";
		e->events = (double)r->doublings;
		e->n_quad = r->n_quad;
		e->n_orders = r->n_orders;
	}
}

static void solve_one(struct ad_state *a, int w, int threads)
{
	struct ad_opts o = a->st.ad;
	o.threads = threads;
	struct ad_result r;
	char *cause = NULL;
	if (ad_solve(&a->p.slab[w], a->p.fresnel, a->p.theta_i, a->p.n_ti, &o, &r, &cause) != 0) {
		for (int k = 0; k < a->p.n_ti; k++)
			a->t.entry[w * a->p.n_ti + k].refused = k == 0 ? cause : xstrdup(cause);
		return;
	}
	fill(a, w, &r);
	a->met[w] = ad_err_meets(&r, o.tol);
	ad_result_free(&r);
}

static int ad_step(void *state, const struct solver_run *run)
{
	struct ad_state *a = state;
	int nt = run->threads > 0 ? run->threads : 1;
#ifdef _OPENMP
	if (run->threads <= 0)
		nt = omp_get_max_threads();
#endif
	int w0 = a->next, left = a->p.n_wl - w0;
	int k = left < WL_PER_THREAD * nt ? left : WL_PER_THREAD * nt;
	if (k == 1)
		solve_one(a, w0, nt);	/* alone: its Fourier orders over the threads */
	else {
#pragma omp parallel for num_threads(k < nt ? k : nt) schedule(dynamic, 1)
		for (int i = 0; i < k; i++)
			solve_one(a, w0 + i, 1);
	}
	a->next += k;
	if (run->progress)
		run->progress(run->progress_user, a->next, a->p.n_wl);
	if (a->st.strict)
		for (int w = w0; w < w0 + k; w++)
			if (a->t.entry[w * a->p.n_ti].refused)
				return 0;
	return a->next < a->p.n_wl;
}

static void ad_finish(void *state, struct brdf_table *out)
{
	struct ad_state *a = state;
	*out = a->t;
	out->rms_rel_err = brdf_table_rms(out);
	out->target_met = 1;
	for (int w = 0; w < a->next; w++)	/* the wavelengths it filled */
		if (!out->entry[w * a->p.n_ti].refused)
			out->target_met &= a->met[w];
	free(a->met);
	free(a);
}

/* The wavelengths solved so far: next, then met[] and the entries of each. */
static void *ad_pack(const void *state, size_t *len)
{
	const struct ad_state *a = state;
	struct solver_buf b = { 0 };
	solver_buf_put(&b, &a->next, sizeof a->next);
	solver_buf_put(&b, a->met, sizeof(int) * (size_t)a->next);
	for (int j = 0; j < a->next * a->p.n_ti; j++)
		solver_entry_put(&b, &a->t.entry[j], &a->p.grid);
	*len = b.len;
	return b.p;
}

static int ad_unpack(void *state, const void *buf, size_t len)
{
	struct ad_state *a = state;
	struct solver_buf b = { .p = (unsigned char *)buf, .len = len };
	int next;
	solver_buf_get(&b, &next, sizeof next);
	if (b.bad || next < 0 || next > a->p.n_wl)
		return -1;
	a->next = next;
	solver_buf_get(&b, a->met, sizeof(int) * (size_t)next);
	for (int j = 0; j < next * a->p.n_ti; j++)
		solver_entry_get(&b, &a->t.entry[j], &a->p.grid, "ad");
	return b.bad || b.pos != len ? -1 : 0;
}

static void *ad_settings(const struct solver_knobs *k)
{
	struct ad_solver_settings *st = xmalloc(sizeof *st);
	ad_solver_settings_default(st);
	if (k->tol > 0.0)
		st->ad.tol = k->tol;
	st->ad.n_quad = k->n_quad;
	if (k->n_quad_max > 0)
		st->ad.n_quad_max = k->n_quad_max;
	if (k->n_orders > 0)
		st->ad.max_orders = k->n_orders;
	st->strict = k->strict;
	return st;
}

static double ad_tol(const void *settings, const struct solver_problem *p)
{
	return ad_solver_tol(settings, p);
}

/* The manifest's solver.ad: the quadrature's settings (max_orders: the
 * default, as it was written before n_orders could be set). */
static json_object *ad_manifest(const struct solver_knobs *k, double tol)
{
	struct ad_solver_settings d;
	ad_solver_settings_default(&d);
	json_object *ad = json_object_new_object();
	const char *how = "adding-doubling, Fourier series in delta_phi (src/engine/ad.h)";
	json_object_object_add(ad, "method", json_object_new_string(how));
	json_object_object_add(ad, "tol", json_num(tol));
	json_object *nq = json_object_new_string("auto");
	if (k->n_quad > 0) {
		json_object_put(nq);
		nq = json_object_new_int(k->n_quad);
	}
	json_object_object_add(ad, "n_quad", nq);
	int nq_max = k->n_quad_max > 0 ? k->n_quad_max : d.ad.n_quad_max;
	json_object_object_add(ad, "n_quad_max", json_object_new_int(nq_max));
	json_object_object_add(ad, "dtau_frac", json_num(d.ad.dtau_frac));
	json_object_object_add(ad, "dm_terms", json_num(d.ad.dm_terms));
	json_object_object_add(ad, "max_orders", json_object_new_int(d.ad.max_orders));
	return ad;
}

static int ad_simulate(const struct sim_config *c, const struct solver_knobs *k,
    struct sim_result *r, struct sim_solve_info *info, solver_progress *progress, void *user,
    char **cause)
{
	(void)progress;
	(void)user;
	return ad_sim_run(c, k->tol, k->n_quad, r, info, cause);
}

/* simulate's options of Monte Carlo alone (r-bins refused only above 0). */
static const char *const ad_sim_ignores[] = {
	"photons", "seed", "batches", "r-step", "r-bins", "roulette-w", "roulette-chance",
	"max-steps", NULL
};

const struct solver_ops ad_solver = {
	.name = "ad",
	.title = "adding-doubling",
	.provides = SOLVER_BRDF,
	.traits = SOLVER_POINTS,
	.fallback = "mc",
	.error_doc = "the adding-doubling error estimates (|X_N - X_N/2| from a solve at half "
	    "the quadrature nodes, scaled up where convergence is slow, plus the Fourier series' "
	    "tail: bounds, not standard errors; src/engine/ad.h)",
	.settings = ad_settings,
	.tol = ad_tol,
	.manifest = ad_manifest,
	.simulate = ad_simulate,
	.sim_ignores = ad_sim_ignores,
	.begin = ad_begin,
	.step = ad_step,
	.finish = ad_finish,
	.pack = ad_pack,
	.unpack = ad_unpack,
};

/* Beam 0 of a as a sim_result on grid g (no Rd(r)). */
static void sim_of_ad(const struct ad_result *a, int n_layers, const struct tally_grid *g, struct sim_result *out)
{
	const struct ad_beam *b = &a->beam[0];
	int ne = g->n_theta * g->n_phi;
	memset(out, 0, sizeof *out);
	out->seconds = a->seconds;
	out->rsp = b->rsp;
	out->rd = (struct estimate){ b->rd.v, b->rd.err };
	out->rd_unscat = (struct estimate){ b->rd_unscat, 0.0 };
	out->tt = (struct estimate){ b->tt.v, b->tt.err };
	out->tt_unscat = (struct estimate){ b->tt_unscat, 0.0 };
	for (int i = 0; i < SLAB_MAX_LAYERS + 2; i++)
		out->a[i] = (struct estimate){ b->a[i].v, b->a[i].err };
	out->n_layers = n_layers;
	out->grid = *g;
	out->grid.n_r = 0;
	out->fr = xmalloc(sizeof(double) * (size_t)ne);
	out->fr_err = xmalloc(sizeof(double) * (size_t)ne);
	out->fr_az = xmalloc(sizeof(double) * (size_t)g->n_theta);
	out->fr_az_err = xmalloc(sizeof(double) * (size_t)g->n_theta);
	memcpy(out->fr, b->fr, sizeof(double) * (size_t)ne);
	memcpy(out->fr_err, b->fr_err, sizeof(double) * (size_t)ne);
	memcpy(out->fr_az, b->fr_az, sizeof(double) * (size_t)g->n_theta);
	memcpy(out->fr_az_err, b->fr_az_err, sizeof(double) * (size_t)g->n_theta);
	out->facet_loss = (struct estimate){ b->facet_loss.v, b->facet_loss.err };
	out->balance = b->balance;
}

int ad_sim_run(const struct sim_config *c, double tol, int n_quad, struct sim_result *r,
    struct sim_solve_info *info, char **cause)
{
	struct ad_opts o;
	struct ad_result a;
	ad_opts_default(&o);
	o.tol = tol, o.n_quad = n_quad, o.n_to = c->grid.n_theta, o.n_phi = c->grid.n_phi, o.threads = c->threads;
	if (ad_solve(&c->slab, c->opts.fresnel, &c->theta_in, 1, &o, &a, cause) != 0)
		return -1;
	*info = (struct sim_solve_info){ ad_solver.name, tol, a.n_quad, a.n_orders, a.rms_rel_err };
	sim_of_ad(&a, c->slab.n_layers, &c->grid, r);
	ad_result_free(&a);
	return 0;
}
