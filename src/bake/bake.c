/* bake: the driver from a bake spec to a solver's table (the method chosen
 * here, with its fallback and its radial run) plus the specular stacks and
 * subsurface radii the bake directory records (see bake.h). */
#include "config.h"
#include "bake/bake.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/check.h"
#include "base/util.h"
#include "bake/checkpoint.h"
#include "bake/radial.h"
#include "engine/mc.h"
#include "engine/solvers.h"
#include "skin/colour.h"
#include "skin/preset.h"

/* Every method's settings from the spec (solver_knobs). */
static void knobs_of(const struct bake_spec *s, struct solver_knobs *k)
{
	*k = (struct solver_knobs){
		.seed = s->seed, .batch_photons = s->batch_photons, .min_batches = s->min_batches,
		.max_photons = s->max_photons, .nee = s->nee, .roulette_w = s->opts.roulette_w,
		.roulette_chance = s->opts.roulette_chance, .max_steps = s->opts.max_steps,
		.tol = s->ad_tol, .n_quad = s->ad_quad, .n_quad_max = s->ad_quad_max, .n_orders = s->ad_orders,
		.strict = s->method != BAKE_SOLVER_AUTO,
	};
}

/* Solve p (or its n wavelengths w[] when w is not NULL) with ops, its
 * settings from the spec, into t. */
static int solve_with(const struct solver_ops *ops, const struct bake_spec *s,
    const struct solver_problem *p, const struct solver_run *run, const int *w, int n,
    struct brdf_table *t, char **cause);

/* The wavelengths (indices) of a table whose entry at angle 0 passes keep(). */
static int pick(const struct bake_spec *s, const struct brdf_table *t, int (*keep)(const struct brdf_entry *),
    int *w_out)
{
	int n = 0;
	for (int w = 0; w < s->n_wl; w++)
		if (keep(&t->entry[w * s->n_ti]))
			w_out[n++] = w;
	return n;
}

static int not_solved(const struct brdf_entry *e)
{
	return e->method == NULL;
}

/* Filled by a method that gives no Rd(r) (solver_ops.provides). */
static int no_radial(const struct brdf_entry *e)
{
	const struct solver_ops *ops = solvers_find(e->method);
	return ops != NULL && !(ops->provides & SOLVER_RADIAL);
}

static int solve_with(const struct solver_ops *ops, const struct bake_spec *s,
    const struct solver_problem *p, const struct solver_run *run, const int *w, int n,
    struct brdf_table *t, char **cause)
{
	struct solver_knobs k;
	knobs_of(s, &k);
	void *settings = ops->settings(&k);
	struct solver_problem q = *p;
	double wl[BAKE_MAX_WL];
	struct slab *sl = NULL;
	if (w != NULL) {
		sl = xcalloc((size_t)n, sizeof *sl);
		for (int i = 0; i < n; i++) {
			wl[i] = p->wl_nm[w[i]];
			sl[i] = p->slab[w[i]];
		}
		q.n_wl = n;
		q.wl_nm = wl;
		q.slab = sl;
	}
	int rc = solver_solve(ops, settings, &q, run, t, cause);
	free(sl);
	free(settings);
	return rc;
}

/* The fallback method fb for the n wavelengths w[] that ops refused. */
static int fallback(const struct solver_ops *ops, const struct solver_ops *fb,
    const struct bake_spec *s, const struct solver_problem *p, const struct solver_run *run,
    const int *w, int n, struct bake_result *r, char **cause)
{
	struct brdf_table t;
	if (solve_with(fb, s, p, run, w, n, &t, cause) != 0)
		return -1;
	for (int i = 0; i < n; i++) {
		struct brdf_entry *dst = &r->table.entry[w[i] * s->n_ti];
		const char *why = dst->refused ? dst->refused : "not solved";
		char *line = xasprintf("%s%s cannot solve %g nm (%s); %s instead (target error %g)\n",
		    r->notes ? r->notes : "", ops->title, s->wl_nm[w[i]], why, fb->title, s->target_error);
		free(r->notes);
		r->notes = line;
		if (r->fallback_cause == NULL)
			r->fallback_cause = xcalloc((size_t)s->n_wl, sizeof *r->fallback_cause);
		r->fallback_cause[w[i]] = xstrdup(why);
		for (int k = 0; k < s->n_ti; k++) {
			struct brdf_entry tmp = r->table.entry[w[i] * s->n_ti + k];
			r->table.entry[w[i] * s->n_ti + k] = t.entry[i * s->n_ti + k];
			t.entry[i * s->n_ti + k] = tmp;
		}
	}
	r->table.photons += t.photons;
	r->table.pilot_photons += t.pilot_photons;
	r->table.seconds += t.seconds;
	r->table.target_met &= t.target_met;
	brdf_table_free(&t);
	r->solver = n == s->n_wl ? fb->name : solvers_union(ops->name, fb->name);
	return 0;
}

/* Copy the given profiles (bake_spec.radial_given) among the n wavelengths
 * w[]; returns how many are left, compacted in w[]. */
static int take_given(const struct bake_spec *s, struct bake_result *r, int *w, int n)
{
	const struct bake_radial_given *g = s->radial_given;
	if (g == NULL)
		return n;
	int left = 0;
	for (int i = 0; i < n; i++) {
		struct brdf_entry *e = &r->table.entry[w[i] * s->n_ti];
		if (g->rd_r[w[i]] == NULL) {
			w[left++] = w[i];
			continue;
		}
		memcpy(e->rd_r, g->rd_r[w[i]], sizeof(double) * (size_t)s->n_r);
		memcpy(e->rd_r_err, g->rd_r_err[w[i]], sizeof(double) * (size_t)s->n_r);
		r->radial_shared = g->n_shared;
	}
	if (r->radial_shared) {
		r->radial_photons += g->photons;
		r->radial_seconds += g->seconds;
	}
	return left;
}

/* Rd(r) for the wavelengths whose method gave none (bake.h, radial.h), one
 * after the other (random streams by wavelength).  Under MPI the ranks split
 * them (the i-th left to rank i % n_ranks) and sum what each found: a value
 * is nonzero on its own rank only, so the sum is exact and the profiles are
 * the same over any number of ranks. */
static int radial_mc(const struct bake_spec *s, const struct solver_problem *p, const struct solver_run *run,
    struct bake_result *r, char **cause)
{
	(void)cause;
	int w[BAKE_MAX_WL], n = pick(s, &r->table, no_radial, w);
	if (n == 0 || s->n_r <= 0)
		return 0;
	n = take_given(s, r, w, n);
	if (n == 0)
		return 0;
	long cap = s->radial_photons > 0 ? s->radial_photons : BAKE_RADIAL_PHOTONS;
	struct radial_spec sp = {
		.theta_in = p->theta_i[0], .opts = &s->opts, .n_r = s->n_r, .dr = s->dr,
		.target = s->radial_error > 0.0 ? s->radial_error : BAKE_RADIAL_ERROR,
		.pilot = cap < BAKE_RADIAL_PILOT ? cap : BAKE_RADIAL_PILOT, .cap = cap,
		.margin = BAKE_RADIAL_MARGIN, .rounds = BAKE_RADIAL_ROUNDS, .seed = s->seed,
		.threads = run->threads,
	};
	if (r->radial_err_cm == NULL)
		r->radial_err_cm = xcalloc((size_t)s->n_wl, sizeof *r->radial_err_cm);
	int R = run->n_ranks > 1 && run->allreduce ? run->n_ranks : 1;
	/* Per wavelength: rd_r, rd_r_err, then the mean radius's error, photons,
	 * seconds and controls. */
	size_t per = 2 * (size_t)s->n_r + 4;
	double *v = xcalloc(per * (size_t)n, sizeof *v);
	for (int i = 0; i < n; i++) {
		if (i % R != run->rank % R)
			continue;
		double *vi = v + per * (size_t)i;
		const struct brdf_entry *e = &r->table.entry[w[i] * s->n_ti];
		sp.slab = &p->slab[w[i]];
		sp.stream = (uint32_t)w[i];
		sp.rd0 = e->albedo.v;
		sp.rd0_err = e->albedo.err;
		struct radial_out o = { .rd_r = vi, .rd_r_err = vi + s->n_r };
		radial_solve(&sp, &o);
		double *t = vi + 2 * s->n_r;
		t[0] = o.mean_radius_err_cm;
		t[1] = (double)o.photons;
		t[2] = o.seconds;
		t[3] = o.controls;
	}
	if (R > 1)
		run->allreduce(v, (long)(per * (size_t)n));
	for (int i = 0; i < n; i++) {
		const double *vi = v + per * (size_t)i, *t = vi + 2 * s->n_r;
		struct brdf_entry *e = &r->table.entry[w[i] * s->n_ti];
		memcpy(e->rd_r, vi, sizeof(double) * (size_t)s->n_r);
		memcpy(e->rd_r_err, vi + s->n_r, sizeof(double) * (size_t)s->n_r);
		r->radial_err_cm[w[i]] = t[0];
		r->radial_photons += (long)t[1];
		r->radial_seconds += t[2];
		if (r->radial_controls == 0 || (int)t[3] < r->radial_controls)
			r->radial_controls = (int)t[3];
	}
	free(v);
	return 0;
}

/* The method, with its fallback where it refuses (auto), and Rd(r) by
 * Monte Carlo where it gives none. */
static int bake_method(const struct bake_spec *s, const struct solver_problem *p,
    const struct solver_run *run, struct bake_result *r, char **cause)
{
	const struct solver_ops *ops = bake_method_ops(s->method);
	if (ops->tol) {
		struct solver_knobs k;
		knobs_of(s, &k);
		void *settings = ops->settings(&k);
		r->tol = ops->tol(settings, p);
		free(settings);
	}
	if (solve_with(ops, s, p, run, NULL, 0, &r->table, cause) != 0)
		return -1;
	r->solver = ops->name;
	int w[BAKE_MAX_WL], n = pick(s, &r->table, not_solved, w);
	const struct solver_ops *fb = solvers_find(ops->fallback);
	if (n > 0 && (s->method != BAKE_SOLVER_AUTO || fb == NULL)) {
		for (int j = 0; j < s->n_wl * s->n_ti; j++)
			if (r->table.entry[j].refused) {
				*cause = xasprintf("--solver %s at %g nm: %s (--solver auto or %s bakes it by %s)", ops->name,
				    r->table.entry[j].wl_nm, r->table.entry[j].refused, fb ? fb->name : "another method",
				    fb ? fb->title : "it");
				break;
			}
		return -1;
	}
	if (n > 0 && fallback(ops, fb, s, p, run, w, n, r, cause) != 0)
		return -1;
	if (radial_mc(s, p, run, r, cause) != 0)
		return -1;
	r->table.rms_rel_err = brdf_table_rms(&r->table);
	return 0;
}

int bake_method_at(int i)
{
	if (i == 0)
		return BAKE_SOLVER_AUTO;
	/* auto's chain of fallbacks, then the rest in table order */
	int chain[SOLVERS_MAX], n = 0;
	const struct solver_ops *o = solvers_find(solvers_auto);
	for (; o && n < SOLVERS_MAX; o = solvers_find(o->fallback))
		chain[n++] = solvers_index(o->name);
	for (int j = 0; solvers[j] != NULL; j++) {
		int in = 0;
		for (int c = 0; c < n; c++)
			in |= chain[c] == j;
		if (!in && n < SOLVERS_MAX)
			chain[n++] = j;
	}
	return i > 0 && i <= n ? chain[i - 1] : BAKE_SOLVER_NONE;
}

const char *bake_method_name(int id)
{
	if (id == BAKE_SOLVER_AUTO)
		return "auto";
	CHECK(id >= 0 && id < SOLVERS_MAX && solvers[id] != NULL);
	return solvers[id]->name;
}

int bake_method_named(const char *name)
{
	for (int i = 0; bake_method_at(i) != BAKE_SOLVER_NONE; i++)
		if (strcmp(bake_method_name(bake_method_at(i)), name) == 0)
			return bake_method_at(i);
	return BAKE_SOLVER_NONE;
}

const char *bake_method_choices(void)
{
	static char buf[128];
	if (buf[0] == '\0')
		for (int i = 0; bake_method_at(i) != BAKE_SOLVER_NONE; i++) {
			size_t n = strlen(buf);
			snprintf(buf + n, sizeof buf - n, "%s%s", i ? "|" : "", bake_method_name(bake_method_at(i)));
		}
	return buf;
}

const struct solver_ops *bake_method_ops(int id)
{
	if (id == BAKE_SOLVER_AUTO)
		return solvers_find(solvers_auto);
	CHECK(id >= 0 && id < SOLVERS_MAX && solvers[id] != NULL);
	return solvers[id];
}

/* The method's code in the identity: auto was 2 when Monte Carlo (0) and
 * adding-doubling (1) were the only methods; later ones come after it. */
static int identity_code(int method)
{
	if (method == BAKE_SOLVER_AUTO)
		return 2;
	return method < 2 ? method : method + 1;
}

#define HASH(h, x) ((h) = checkpoint_hash((h), &(x), sizeof(x)))

uint64_t bake_spec_identity(const struct bake_spec *s)
{
	uint64_t h = checkpoint_seed();
	HASH(h, s->n_wl);
	for (int w = 0; w < s->n_wl; w++) {
		const struct slab *sl = &s->slab[w];
		HASH(h, s->wl_nm[w]);
		HASH(h, sl->n_layers);
		HASH(h, sl->n_above);
		HASH(h, sl->n_below);
		for (int i = 0; i < sl->n_layers + 2; i++) {
			const struct layer *l = &sl->layer[i];
			HASH(h, l->d);
			HASH(h, l->n);
			HASH(h, l->mu_a);
			HASH(h, l->mu_s);
			HASH(h, l->g);
			HASH(h, l->rough);
		}
	}
	HASH(h, s->n_ti);
	for (int k = 0; k < s->n_ti; k++)
		HASH(h, s->theta_i[k]);
	HASH(h, s->n_to);
	HASH(h, s->n_phi);
	HASH(h, s->n_r);
	HASH(h, s->dr);
	HASH(h, s->opts.fresnel);
	HASH(h, s->opts.roulette_w);
	HASH(h, s->opts.roulette_chance);
	HASH(h, s->opts.max_steps);
	int code = identity_code(s->method);
	HASH(h, code);
	HASH(h, s->ad_tol);
	HASH(h, s->ad_quad);
	if (s->ad_quad_max > 0)	/* identities of bakes without it unchanged */
		HASH(h, s->ad_quad_max);
	if (s->ad_orders > 0)	/* the same */
		HASH(h, s->ad_orders);
	HASH(h, s->radial_error);
	HASH(h, s->radial_photons);
	HASH(h, s->seed);
	HASH(h, s->batch_photons);
	HASH(h, s->min_batches);
	HASH(h, s->target_error);
	HASH(h, s->max_photons);
	HASH(h, s->nee);
	return h;
}

static int bake_solve(const struct bake_spec *s, const struct solver_run *run, struct bake_result *r, char **cause);
static int bake_solve_p(const struct bake_spec *s, const struct solver_problem *pp, const struct solver_run *run0,
    struct bake_result *r, char **cause);

/* With a checkpoint (bake.h): open it, run, say what it restored and
 * whether it could be written. */
int bake_run(const struct bake_spec *s, struct bake_result *r, char **cause)
{
	CHECK(s->n_wl >= 1 && s->n_wl <= BAKE_MAX_WL && s->n_ti >= 1 && s->n_ti <= BAKE_MAX_TI);
	memset(r, 0, sizeof *r);
	struct solver_run run = {
		.threads = s->threads, .rank = s->rank, .n_ranks = s->n_ranks > 0 ? s->n_ranks : 1,
		.allreduce = s->allreduce, .progress = s->progress, .progress_user = s->progress_user,
	};
	if (s->resume && run.n_ranks > 1) {
		*cause = xstrdup("--resume works in one process only (skinbake, not skinbake-mpi under mpirun)");
		return -1;
	}
	struct checkpoint *ck = NULL;
	if (s->checkpoint_out) {
		ck = checkpoint_open(s->checkpoint_out, bake_spec_identity(s), s->resume, run.n_ranks == 1, s->checkpoint_s, cause);
		if (ck == NULL)
			return -1;
		run.ckpt = checkpoint_hooks(ck);
	}
	int rc = bake_solve(s, &run, r, cause);
	if (rc == 0 && ck && (*checkpoint_note(ck) || checkpoint_write_error(ck))) {
		const char *e = checkpoint_write_error(ck);
		char *line = xasprintf("%s%s%s%s", checkpoint_note(ck), e ? "checkpoint not written: " : "", e ? e : "",
		    e ? "\n" : "");
		char *all = xasprintf("%s%s", line, r->notes ? r->notes : "");
		free(line);
		free(r->notes);
		r->notes = all;
	}
	checkpoint_close(ck);
	return rc;
}

static int bake_solve(const struct bake_spec *s, const struct solver_run *run0, struct bake_result *r, char **cause)
{
	struct solver_problem p = {
		.n_wl = s->n_wl, .wl_nm = s->wl_nm, .slab = s->slab, .n_ti = s->n_ti, .theta_i = s->theta_i,
		.grid = { .n_theta = s->n_to, .n_phi = s->n_phi, .n_r = s->n_r, .dr = s->dr },
		.fresnel = s->opts.fresnel, .target_error = s->target_error,
		.ad_cache = s->ad_cache,
	};
	double *pto = NULL, *pph = NULL;
	if (bake_spec_points(s)) {
		pto = xmalloc(sizeof(double) * (size_t)s->n_to);
		pph = xmalloc(sizeof(double) * (size_t)s->n_phi);
		bake_nodes_theta(s->n_to, pto);
		bake_nodes_phi(s->n_phi, pph);
		p.point_theta_o = pto;
		p.point_phi = pph;
	}
	int rc = bake_solve_p(s, &p, run0, r, cause);
	free(pto);
	free(pph);
	return rc;
}

static int bake_solve_p(const struct bake_spec *s, const struct solver_problem *pp, const struct solver_run *run0,
    struct bake_result *r, char **cause)
{
	struct solver_problem p = *pp;
	struct solver_run run = *run0;
	if (bake_method(s, &p, &run, r, cause) != 0) {
		bake_result_free(r);
		return -1;
	}
	r->stack = xcalloc((size_t)s->n_wl, sizeof *r->stack);
	r->mean_radius_cm = xcalloc((size_t)s->n_wl, sizeof *r->mean_radius_cm);
	r->mean_radius_err_cm = xcalloc((size_t)s->n_wl, sizeof *r->mean_radius_err_cm);
	for (int w = 0; w < s->n_wl; w++) {
		specular_stack_of_slab(&s->slab[w], s->opts.fresnel, &r->stack[w]);
		const struct brdf_entry *e = &r->table.entry[w * s->n_ti];
		r->mean_radius_cm[w] = tally_mean_radius(e->rd_r, s->n_r, s->dr);
		if (r->radial_err_cm && r->radial_err_cm[w] > 0.0)
			r->mean_radius_err_cm[w] = r->radial_err_cm[w];
		else
			r->mean_radius_err_cm[w] =
			    tally_mean_radius_err(e->rd_r, e->rd_r_err, s->n_r, s->dr);
	}
	/* A Monte Carlo mean radius of light that came back (diffuse albedo
	 * above 0) always has a spread: a stated error of exactly 0 (or not a
	 * number) means that no photon was scored in the bins, or that the
	 * estimator failed, and the bake is refused rather than written. */
	for (int w = 0; w < s->n_wl && s->n_r > 0; w++) {
		double err = r->mean_radius_err_cm[w];
		const struct brdf_entry *e = &r->table.entry[w * s->n_ti];
		if (e->albedo.v > 0.0 && !(err > 0.0 && isfinite(err))) {
			*cause = xasprintf("Rd(r) at %g nm: the mean radius %g cm has a stated "
			    "error of %g (diffuse albedo %g): a Monte Carlo estimate without "
			    "spread, so no photon was scored in the %d bins of %g cm or the "
			    "estimator failed; bake refused", s->wl_nm[w], r->mean_radius_cm[w],
			    err, e->albedo.v, s->n_r, s->dr);
			bake_result_free(r);
			return -1;
		}
	}
	return 0;
}

void bake_result_free(struct bake_result *r)
{
	if (r->fallback_cause)
		for (int w = 0; w < r->table.n_wl; w++)
			free(r->fallback_cause[w]);
	free(r->fallback_cause);
	brdf_table_free(&r->table);
	free(r->stack);
	free(r->mean_radius_cm);
	free(r->mean_radius_err_cm);
	free(r->radial_err_cm);
	free(r->notes);
	memset(r, 0, sizeof *r);
}

int bake_spec_layers(struct bake_spec *s, const struct skin_params *p, const char *label, char **cause)
{
	for (int w = 0; w < s->n_wl; w++) {
		char *why = NULL;
		if (tissue_slab(p, s->wl_nm[w], &s->slab[w], &why) != 0) {
			*cause = xasprintf("%s at %.0f nm: %s", label, s->wl_nm[w], why);
			free(why);
			return -1;
		}
	}
	return 0;
}

const char *bake_rgb_weights(const struct bake_spec *s, double *rgb_from_wl)
{
	colour_rgb_weights(s->n_wl, s->wl_nm, rgb_from_wl);
	int three = s->n_wl == 3 && s->wl_nm[0] == 470 && s->wl_nm[1] == 550 && s->wl_nm[2] == 656;
	return three ? "the paper's three wavelengths map directly: 656 nm -> R, 550 nm -> G, 470 nm -> B"
		     : "CIE 1931 2-degree colour matching under D65, reflectance normalised to the perfect white";
}

struct skin_params *bake_spec_preset(struct bake_spec *s, const char *name, const char *pfile, char **cause)
{
	const char *label = name ? name : pfile;
	struct skin_params *p = name ? preset_load_builtin(name, cause) : preset_load_file(pfile, cause);
	if (p == NULL)
		return NULL;
	if (s->n_wl == 0 && p->n_wl > BAKE_MAX_WL)
		*cause = xasprintf("preset %s lists %d wavelengths; a bake takes at most %d (choose with --wavelengths "
		    "or --spectral)", label, p->n_wl, BAKE_MAX_WL);
	else {
		if (s->n_wl == 0)
			s->n_wl = preset_default_wavelengths(p, s->wl_nm, BAKE_MAX_WL);
		/* Monte Carlo's first round (the pilot's size without batch_photons, mc.h). */
		long bp = s->batch_photons > 0 ? s->batch_photons : s->target_error > 0 ? 250 : MC_BATCH_PHOTONS;
		int sampled = bake_method_ops(s->method)->traits & SOLVER_SAMPLED;
		if (sampled && (long)s->n_wl * s->n_ti * s->min_batches * bp > s->max_photons)
			*cause = xasprintf("--max-photons = %ld is below the first round of the bake (%d wavelengths x %d "
			    "angles x %d batches x %ld photons)", s->max_photons, s->n_wl, s->n_ti, s->min_batches, bp);
		else if (bake_spec_layers(s, p, label, cause) == 0)
			return p;
	}
	preset_free(p);
	return NULL;
}

void bake_spec_axes(struct bake_spec *s, const double *wl_nm, int n_wl, const double *theta_deg, int n_theta,
    int nodes)
{
	CHECK(n_wl >= 0 && n_wl <= BAKE_MAX_WL && n_theta >= 0 && n_theta <= BAKE_MAX_TI && nodes <= BAKE_MAX_TI);
	s->n_wl = n_wl;
	if (n_wl > 0)
		memcpy(s->wl_nm, wl_nm, sizeof(double) * (size_t)n_wl);
	if (n_theta == 0 && nodes == 0 && s->n_to >= 3 && s->n_to - 1 <= BAKE_MAX_TI) {
		double th[BAKE_MAX_TI + 1];
		bake_nodes_theta(s->n_to, th);
		s->n_ti = s->n_to - 1;
		memcpy(s->theta_i, th, sizeof(double) * (size_t)s->n_ti);
		return;
	}
	s->n_ti = n_theta > 0 ? n_theta : nodes > 0 ? nodes : 10;
	for (int k = 0; k < s->n_ti; k++)
		s->theta_i[k] = n_theta > 0 ? theta_deg[k] * M_PI / 180.0 : 0.5 * M_PI * k / s->n_ti;
}

int bake_budget(const struct bake_spec *s, int n_bakes, const char *out, char **cause)
{
	double cells = (double)s->n_wl * s->n_ti * s->n_to * s->n_phi;
	char *what = n_bakes > 1 ? xasprintf("a family of %d members of %d wavelengths x %d angles x %dx%d", n_bakes,
	    s->n_wl, s->n_ti, s->n_to, s->n_phi) : xasprintf("a bake of %d wavelengths x %d angles x %dx%d", s->n_wl, s->n_ti,
	    s->n_to, s->n_phi);
	int rc = budget_check(what, BAKE_MEM_PER_CELL * cells * (n_bakes > 1 ? 2 : 1) + 64e6,
	    BAKE_DISK_PER_CELL * cells * n_bakes, out, "lower --resolution, --theta-nodes or the number of wavelengths"
	    " (or of members)", cause);
	free(what);
	return rc;
}

void bake_nodes_theta(int n, double *theta)
{
	for (int k = 0; k < n; k++)
		theta[k] = n == 1 ? 0.0 : 0.25 * M_PI * (1.0 - cos(k * M_PI / (n - 1)));
	if (n > 1)
		theta[n - 1] = 0.5 * M_PI;	/* exactly */
}

void bake_nodes_phi(int n, double *phi)
{
	for (int j = 0; j < n; j++)
		phi[j] = n == 1 ? 0.0 : M_PI * j / (n - 1);
}

int bake_spec_points(const struct bake_spec *s)
{
	int points = bake_method_ops(s->method)->traits & SOLVER_POINTS;
	return points && !s->bin_means && s->n_to >= 3 && s->n_phi >= 2;
}

