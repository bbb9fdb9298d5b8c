/* family_pack: one family member's bake result as doubles (family_pack.h),
 * the record the MPI gather sends and the family checkpoint keeps. */
#include "config.h"

#include "family/family_pack.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/util.h"
#include "engine/solvers.h"

/* Characters kept of a wavelength's fallback cause (bake_result.fallback_cause). */
#define CAUSE_MAX 240

static size_t entry_len(const struct bake_spec *s)
{
	return 3 + 2 * (6 + SLAB_MAX_LAYERS + 2) + 2 * (size_t)s->n_to * s->n_phi + 2 * (size_t)s->n_r + 7;
}

size_t family_pack_len(const struct bake_spec *s)
{
	return 1 + FAMILY_SOLVER_NAME_MAX + 8 + (size_t)s->n_wl * s->n_ti * entry_len(s) + (size_t)s->n_wl * (2 + CAUSE_MAX);
}

/* The entry's method as a number: 1 + its index in engine/solvers.h's
 * table, 0 for none (the names are static strings). */
static double method_code(const char *m)
{
	if (m == NULL)
		return 0.0;
	return 1.0 + solvers_index(m);
}

static const char *method_name(double c)
{
	int i = (int)c - 1;
	if (i < 0)
		return NULL;
	return solvers[i]->name;
}

static int by_name(const void *a, const void *b)
{
	return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* The methods that made a table (bake_result.solver: "mc", "ad", "ad+mc",
 * names of engine/solvers.h joined by '+' in alphabetical order) as a bit
 * mask over that table, and back into buf[FAMILY_SOLVER_NAME_MAX + 1]. */
static double solver_mask(const char *joined)
{
	unsigned mask = 0;
	char buf[FAMILY_SOLVER_NAME_MAX + 1];
	snprintf(buf, sizeof buf, "%s", joined);
	char *save = NULL;
	for (char *t = strtok_r(buf, "+", &save); t != NULL; t = strtok_r(NULL, "+", &save)) {
		int i = solvers_index(t);
		CHECK(i >= 0);
		mask |= 1u << i;
	}
	return (double)mask;
}

static void solver_joined(unsigned mask, char *buf)
{
	const char *names[8];
	int n = 0;
	for (int i = 0; solvers[i] != NULL && n < 8; i++)
		if (mask & (1u << i))
			names[n++] = solvers[i]->name;
	qsort(names, (size_t)n, sizeof names[0], by_name);
	buf[0] = '\0';
	for (int i = 0; i < n; i++) {
		size_t len = strlen(buf);
		snprintf(buf + len, FAMILY_SOLVER_NAME_MAX + 1 - len, "%s%s", i ? "+" : "", names[i]);
	}
}

static void put_text(double **p, const char *t)
{
	size_t n = t ? strlen(t) : 0;
	for (size_t i = 0; i < CAUSE_MAX; i++)
		*(*p)++ = i < n && i + 1 < CAUSE_MAX ? (double)(unsigned char)t[i] : 0.0;
}

/* NULL for an empty text. */
static char *get_text(const double **p)
{
	char t[CAUSE_MAX];
	for (size_t i = 0; i < CAUSE_MAX; i++)
		t[i] = (char)(*p)[i];
	t[CAUSE_MAX - 1] = '\0';
	*p += CAUSE_MAX;
	return t[0] ? xstrdup(t) : NULL;
}

static void put_est(double **p, struct estimate e)
{
	*(*p)++ = e.v;
	*(*p)++ = e.err;
}

static struct estimate get_est(const double **p)
{
	struct estimate e = { (*p)[0], (*p)[1] };
	*p += 2;
	return e;
}

void family_pack(const struct bake_spec *s, const struct bake_result *r, double *v)
{
	double *p = v;
	*p++ = 1.0;	/* status: baked */
	*p++ = solver_mask(r->solver);
	*p++ = (double)r->radial_shared;	/* in the room kept below */
	for (int i = 2; i < FAMILY_SOLVER_NAME_MAX; i++)
		*p++ = 0.0;	/* room kept: the record's length is unchanged */
	*p++ = r->table.rms_rel_err;
	*p++ = r->table.target_met;
	*p++ = (double)r->table.photons;
	*p++ = r->table.seconds;
	*p++ = (double)r->table.pilot_photons;
	*p++ = r->tol;
	*p++ = (double)r->radial_photons;
	*p++ = r->radial_seconds;
	size_t nb = (size_t)s->n_to * s->n_phi;
	for (int j = 0; j < s->n_wl * s->n_ti; j++) {
		const struct brdf_entry *e = &r->table.entry[j];
		*p++ = e->wl_nm;
		*p++ = e->theta_i;
		*p++ = e->rsp;
		put_est(&p, e->albedo);
		put_est(&p, e->rd_unscat);
		put_est(&p, e->tt);
		put_est(&p, e->a_total);
		for (int k = 0; k < SLAB_MAX_LAYERS + 2; k++)
			put_est(&p, e->a[k]);
		put_est(&p, e->lost);
		put_est(&p, e->facet_loss);
		memcpy(p, e->fr, nb * sizeof(double));
		p += nb;
		memcpy(p, e->fr_err, nb * sizeof(double));
		p += nb;
		for (int k = 0; k < s->n_r; k++) {
			p[k] = e->rd_r ? e->rd_r[k] : 0.0;
			p[s->n_r + k] = e->rd_r_err ? e->rd_r_err[k] : 0.0;
		}
		p += 2 * (size_t)s->n_r;
		*p++ = e->rms_rel_err;
		*p++ = (double)e->batches;
		*p++ = (double)e->photons;
		*p++ = e->events;
		*p++ = method_code(e->method);
		*p++ = e->n_quad;
		*p++ = e->n_orders;
	}
	memcpy(p, r->mean_radius_cm, sizeof(double) * (size_t)s->n_wl);
	p += s->n_wl;
	for (int w = 0; w < s->n_wl; w++)
		*p++ = r->mean_radius_err_cm ? r->mean_radius_err_cm[w] : 0.0;
	for (int w = 0; w < s->n_wl; w++)
		put_text(&p, r->fallback_cause ? r->fallback_cause[w] : NULL);
	CHECK((size_t)(p - v) == family_pack_len(s));
}

/* The result back from doubles; the specular stacks as bake_run makes
 * them (from the member's slabs in s). */
void family_unpack(const struct bake_spec *s, const double *v, char *solver, struct bake_result *r)
{
	const double *p = v + 1;
	memset(r, 0, sizeof *r);
	int n_solvers = 0;
	while (solvers[n_solvers] != NULL)
		n_solvers++;
	if (p[0] < (double)(1u << n_solvers)) {
		solver_joined((unsigned)p[0], solver);
		r->radial_shared = (int)p[1];
	} else {
		/* A checkpoint from before the mask kept the name's characters. */
		for (int i = 0; i < FAMILY_SOLVER_NAME_MAX; i++)
			solver[i] = (char)p[i];
		solver[FAMILY_SOLVER_NAME_MAX] = '\0';
	}
	p += FAMILY_SOLVER_NAME_MAX;
	r->solver = solver;
	struct solver_problem pr = { .n_wl = s->n_wl, .wl_nm = s->wl_nm, .slab = s->slab, .n_ti = s->n_ti,
		.theta_i = s->theta_i, .grid = { .n_theta = s->n_to, .n_phi = s->n_phi, .n_r = s->n_r, .dr = s->dr } };
	brdf_table_init(&r->table, &pr);
	r->table.rms_rel_err = p[0];
	r->table.target_met = (int)p[1];
	r->table.photons = (long)p[2];
	r->table.seconds = p[3];
	r->table.pilot_photons = (long)p[4];
	r->tol = p[5];
	r->radial_photons = (long)p[6];
	r->radial_seconds = p[7];
	p += 8;
	size_t nb = (size_t)s->n_to * s->n_phi;
	for (int j = 0; j < s->n_wl * s->n_ti; j++) {
		struct brdf_entry *e = &r->table.entry[j];
		e->wl_nm = p[0];
		e->theta_i = p[1];
		e->rsp = p[2];
		p += 3;
		e->albedo = get_est(&p);
		e->rd_unscat = get_est(&p);
		e->tt = get_est(&p);
		e->a_total = get_est(&p);
		for (int k = 0; k < SLAB_MAX_LAYERS + 2; k++)
			e->a[k] = get_est(&p);
		e->lost = get_est(&p);
		e->facet_loss = get_est(&p);
		memcpy(e->fr, p, nb * sizeof(double));
		p += nb;
		memcpy(e->fr_err, p, nb * sizeof(double));
		p += nb;
		for (int k = 0; k < s->n_r; k++) {
			e->rd_r[k] = p[k];
			e->rd_r_err[k] = p[s->n_r + k];
		}
		p += 2 * (size_t)s->n_r;
		e->rms_rel_err = p[0];
		e->batches = (long)p[1];
		e->photons = (long)p[2];
		e->events = p[3];
		e->method = method_name(p[4]);
		e->n_quad = (int)p[5];
		e->n_orders = (int)p[6];
		p += 7;
	}
	r->mean_radius_cm = xmalloc(sizeof(double) * (size_t)s->n_wl);
	memcpy(r->mean_radius_cm, p, sizeof(double) * (size_t)s->n_wl);
	p += s->n_wl;
	r->mean_radius_err_cm = xmalloc(sizeof(double) * (size_t)s->n_wl);
	memcpy(r->mean_radius_err_cm, p, sizeof(double) * (size_t)s->n_wl);
	p += s->n_wl;
	for (int w = 0; w < s->n_wl; w++) {
		char *c = get_text(&p);
		if (c && r->fallback_cause == NULL)
			r->fallback_cause = xcalloc((size_t)s->n_wl, sizeof *r->fallback_cause);
		if (c)
			r->fallback_cause[w] = c;
	}
	r->stack = xcalloc((size_t)s->n_wl, sizeof *r->stack);
	for (int w = 0; w < s->n_wl; w++)
		specular_stack_of_slab(&s->slab[w], s->opts.fresnel, &r->stack[w]);
}
