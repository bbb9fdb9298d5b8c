/* family_run: the family bake (family.h): member parameters, the members baked one by one (spread
 * over MPI ranks, gathered to rank 0 through the bake's allreduce hook)
 * and written into the staging directory, then moved into place; finished
 * members saved in DIR.checkpoint for --resume. */
#include "config.h"
#include "bake/family.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/check.h"
#include "base/outdir.h"
#include "base/util.h"
#include "bake/checkpoint.h"
#include "bake/manifest.h"
#include "engine/solvers.h"
#include "skin/colour.h"
#include "skin/preset.h"

static int count_members(const struct family_plan *pl, int *n_members, char **cause)
{
	long m = 1;
	for (int a = 0; a < pl->n_axes; a++)
		m *= pl->axis[a].n;
	if (m > FAMILY_MAX_MEMBERS) {
		*cause = xasprintf("a family of %ld members is larger than %d (fewer nodes per axis)", m, FAMILY_MAX_MEMBERS);
		return -1;
	}
	*n_members = (int)m;
	return 0;
}

struct skin_params *family_params(const struct skin_params *base, const struct family_axis *axis, int n_axes,
    const double *x, char **cause)
{
	char *ini = preset_to_ini(base);
	struct skin_params *p = preset_load_string(ini, "family member", cause);
	free(ini);
	if (p == NULL)
		return NULL;
	for (int a = 0; a < n_axes; a++)
		if (preset_set_number(p, axis[a].key, x[a], cause) != 0) {
			preset_free(p);
			return NULL;
		}
	if (tissue_check(p, cause) != 0) {
		preset_free(p);
		return NULL;
	}
	return p;
}

/* ---- one member's result as doubles, for the gather over ranks ---- */

#define SOLVER_NAME_MAX 8
/* Characters kept of a wavelength's fallback cause (bake_result.fallback_cause). */
#define CAUSE_MAX 240

static size_t entry_len(const struct bake_spec *s)
{
	return 3 + 2 * (6 + SLAB_MAX_LAYERS + 2) + 2 * (size_t)s->n_to * s->n_phi + 2 * (size_t)s->n_r + 7;
}

static size_t pack_len(const struct bake_spec *s)
{
	return 1 + SOLVER_NAME_MAX + 8 + (size_t)s->n_wl * s->n_ti * entry_len(s) + (size_t)s->n_wl * (2 + CAUSE_MAX);
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
 * mask over that table, and back into buf[SOLVER_NAME_MAX + 1]. */
static double solver_mask(const char *joined)
{
	unsigned mask = 0;
	char buf[SOLVER_NAME_MAX + 1];
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
		snprintf(buf + len, SOLVER_NAME_MAX + 1 - len, "%s%s", i ? "+" : "", names[i]);
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

static void pack(const struct bake_spec *s, const struct bake_result *r, double *v)
{
	double *p = v;
	*p++ = 1.0;	/* status: baked */
	*p++ = solver_mask(r->solver);
	for (int i = 1; i < SOLVER_NAME_MAX; i++)
		*p++ = 0.0;	/* room kept: the record's length is unchanged */
	*p++ = r->table.rms_rel_err, *p++ = r->table.target_met, *p++ = (double)r->table.photons, *p++ = r->table.seconds;
	*p++ = (double)r->table.pilot_photons, *p++ = r->ad_tol, *p++ = (double)r->radial_photons, *p++ = r->radial_seconds;
	size_t nb = (size_t)s->n_to * s->n_phi;
	for (int j = 0; j < s->n_wl * s->n_ti; j++) {
		const struct brdf_entry *e = &r->table.entry[j];
		*p++ = e->wl_nm, *p++ = e->theta_i, *p++ = e->rsp;
		put_est(&p, e->albedo), put_est(&p, e->rd_unscat), put_est(&p, e->tt), put_est(&p, e->a_total);
		for (int k = 0; k < SLAB_MAX_LAYERS + 2; k++)
			put_est(&p, e->a[k]);
		put_est(&p, e->lost);
		put_est(&p, e->facet_loss);
		memcpy(p, e->fr, nb * sizeof(double)), p += nb;
		memcpy(p, e->fr_err, nb * sizeof(double)), p += nb;
		for (int k = 0; k < s->n_r; k++)
			p[k] = e->rd_r ? e->rd_r[k] : 0.0, p[s->n_r + k] = e->rd_r_err ? e->rd_r_err[k] : 0.0;
		p += 2 * (size_t)s->n_r;
		*p++ = e->rms_rel_err, *p++ = (double)e->batches, *p++ = (double)e->photons, *p++ = e->events;
		*p++ = method_code(e->method), *p++ = e->n_quad, *p++ = e->n_orders;
	}
	memcpy(p, r->mean_radius_cm, sizeof(double) * (size_t)s->n_wl), p += s->n_wl;
	for (int w = 0; w < s->n_wl; w++)
		*p++ = r->mean_radius_err_cm ? r->mean_radius_err_cm[w] : 0.0;
	for (int w = 0; w < s->n_wl; w++)
		put_text(&p, r->fallback_cause ? r->fallback_cause[w] : NULL);
	CHECK((size_t)(p - v) == pack_len(s));
}

/* The result back from doubles; the specular stacks as bake_run makes
 * them (from the member's slabs in s). */
static void unpack(const struct bake_spec *s, const double *v, char *solver, struct bake_result *r)
{
	const double *p = v + 1;
	memset(r, 0, sizeof *r);
	int n_solvers = 0;
	while (solvers[n_solvers] != NULL)
		n_solvers++;
	if (p[0] < (double)(1u << n_solvers)) {
		solver_joined((unsigned)p[0], solver);
	} else {
		/* A checkpoint from before the mask kept the name's characters. */
		for (int i = 0; i < SOLVER_NAME_MAX; i++)
			solver[i] = (char)p[i];
		solver[SOLVER_NAME_MAX] = '\0';
	}
	p += SOLVER_NAME_MAX;
	r->solver = solver;
	struct solver_problem pr = { .n_wl = s->n_wl, .wl_nm = s->wl_nm, .slab = s->slab, .n_ti = s->n_ti,
		.theta_i = s->theta_i, .grid = { .n_theta = s->n_to, .n_phi = s->n_phi, .n_r = s->n_r, .dr = s->dr } };
	brdf_table_init(&r->table, &pr);
	r->table.rms_rel_err = p[0], r->table.target_met = (int)p[1], r->table.photons = (long)p[2];
	r->table.seconds = p[3], r->table.pilot_photons = (long)p[4], r->ad_tol = p[5], r->radial_photons = (long)p[6];
	r->radial_seconds = p[7];
	p += 8;
	size_t nb = (size_t)s->n_to * s->n_phi;
	for (int j = 0; j < s->n_wl * s->n_ti; j++) {
		struct brdf_entry *e = &r->table.entry[j];
		e->wl_nm = p[0], e->theta_i = p[1], e->rsp = p[2];
		p += 3;
		e->albedo = get_est(&p), e->rd_unscat = get_est(&p), e->tt = get_est(&p), e->a_total = get_est(&p);
		for (int k = 0; k < SLAB_MAX_LAYERS + 2; k++)
			e->a[k] = get_est(&p);
		e->lost = get_est(&p);
		e->facet_loss = get_est(&p);
		memcpy(e->fr, p, nb * sizeof(double)), p += nb;
		memcpy(e->fr_err, p, nb * sizeof(double)), p += nb;
		for (int k = 0; k < s->n_r; k++)
			e->rd_r[k] = p[k], e->rd_r_err[k] = p[s->n_r + k];
		p += 2 * (size_t)s->n_r;
		e->rms_rel_err = p[0], e->batches = (long)p[1], e->photons = (long)p[2], e->events = p[3];
		e->method = method_name(p[4]), e->n_quad = (int)p[5], e->n_orders = (int)p[6];
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

/* ---- the directory ---- */

/* The staging directory (base/outdir.h), with the base preset in it. */
static int stage_open(struct outdir *od, const char *dir, const struct skin_params *base, char **cause)
{
	if (outdir_begin(od, dir, &family_outdir_kind, cause) != 0)
		return -1;
	char *ini = preset_to_ini(base), *ip = xasprintf("%s/preset.ini", outdir_path(od));
	int rc = outfile_write_text(ip, ini, cause);
	free(ini);
	free(ip);
	if (rc != 0)
		outdir_abort(od);
	return rc;
}

/* The family record of member m from its result (rank 0): albedo at the
 * first incidence node, colour, and the radius per R, G, B as the member's
 * manifest states it. */
static int member_record(struct family *f, int m, const struct bake_spec *s, const struct bake_result *r,
    const char *mdir, char **cause)
{
	struct family_member *fm = &f->member[m];
	int idx[FAMILY_MAX_AXES];
	family_member_index(f, m, idx);
	for (int a = 0; a < f->n_axes; a++)
		fm->param[a] = f->axis[a].node[idx[a]];
	fm->albedo_wl = xcalloc((size_t)s->n_wl, sizeof(double));
	for (int w = 0; w < s->n_wl; w++)
		fm->albedo_wl[w] = r->table.entry[w * s->n_ti].albedo.v;
	for (int c = 0; c < 3; c++) {
		fm->albedo_rgb[c] = 0.0;
		for (int w = 0; w < s->n_wl; w++)
			fm->albedo_rgb[c] += f->rgb_from_wl[c * s->n_wl + w] * fm->albedo_wl[w];
	}
	colour_linear_srgb_to_lab(fm->albedo_rgb, fm->albedo_lab);
	fm->rms_rel_err = r->table.rms_rel_err;
	fm->seconds = r->table.seconds;
	if (fm->rms_rel_err > f->rms_rel_err)
		f->rms_rel_err = fm->rms_rel_err;
	struct bake b = { 0 };
	int rc = bake_manifest_read(mdir, &b, cause);
	if (rc == 0)
		memcpy(fm->sss_radius_rgb_cm, b.sss_radius_rgb_cm, sizeof fm->sss_radius_rgb_cm);
	free(b.preset), free(b.wl_nm), free(b.theta_i), free(b.theta_o), free(b.phi), free(b.rgb_from_wl);
	free(b.stack), free(b.sss_radius_cm);
	return rc;
}

/* The family as it will be written: axes, wavelengths, weights, settings. */
static struct family *family_new(const struct family_plan *pl, int n_members)
{
	struct family *f = xcalloc(1, sizeof *f);
	f->preset = xstrdup(pl->preset ? pl->preset : "");
	f->preset_ini = preset_to_ini(pl->base);
	f->n_axes = pl->n_axes;
	memcpy(f->axis, pl->axis, sizeof f->axis);
	f->n_members = n_members;
	f->member = xcalloc((size_t)n_members, sizeof *f->member);
	f->n_wl = pl->spec.n_wl;
	f->wl_nm = xmalloc(sizeof(double) * (size_t)f->n_wl);
	memcpy(f->wl_nm, pl->spec.wl_nm, sizeof(double) * (size_t)f->n_wl);
	f->rgb_from_wl = xmalloc(sizeof(double) * 3 * (size_t)f->n_wl);
	bake_rgb_weights(&pl->spec, f->rgb_from_wl);
	f->albedo_theta_i = pl->spec.theta_i[0];
	f->spec = xmalloc(sizeof *f->spec);
	*f->spec = pl->spec;
	return f;
}

/* Member m's parameters and its spec with the layer stacks filled. */
static struct skin_params *member_spec(const struct family_plan *pl, const struct family *f, int m,
    struct bake_spec *s, char **cause)
{
	int idx[FAMILY_MAX_AXES];
	double x[FAMILY_MAX_AXES];
	family_member_index(f, m, idx);
	for (int a = 0; a < pl->n_axes; a++)
		x[a] = pl->axis[a].node[idx[a]];
	struct skin_params *p = family_params(pl->base, pl->axis, pl->n_axes, x, cause);
	char label[32];
	snprintf(label, sizeof label, "member m%04d", m);
	if (p && bake_spec_layers(s, p, label, cause) != 0) {
		preset_free(p);
		return NULL;
	}
	return p;
}

/* Write member m (rank 0) from its packed result. */
static int write_member(const struct family_plan *pl, struct family *f, int m, const double *v, struct bake_spec *s,
    const char *stage, char **cause)
{
	struct skin_params *p = member_spec(pl, f, m, s, cause);
	if (p == NULL)
		return -1;
	char solver[SOLVER_NAME_MAX + 1];
	struct bake_result r;
	unpack(s, v, solver, &r);
	if (f->solver == NULL)
		f->solver = xstrdup(solver);
	else if (strcmp(f->solver, solver) != 0) {
		free(f->solver);
		f->solver = xstrdup("ad+mc");
	}
	for (int w = 0; r.fallback_cause && w < s->n_wl; w++)
		if (r.fallback_cause[w]) {
			char *l = xasprintf("%smember m%04d at %g nm: Monte Carlo made the table (%s)\n", f->notes ? f->notes : "",
			    m, s->wl_nm[w], r.fallback_cause[w]);
			free(f->notes);
			f->notes = l;
		}
	double *w = xmalloc(sizeof(double) * 3 * (size_t)s->n_wl);
	struct bake_meta meta = { .preset = pl->preset, .ior = preset_surface_ior(p),
		.roughness = preset_surface_roughness(p), .rgb_from_wl = w, .rgb_note = bake_rgb_weights(s, w),
		.command = pl->command };
	char *mdir = xasprintf("%s/m%04d", stage, m);
	int rc = util_mkdirs(mdir, cause) || bake_write_files(mdir, s, &r, &meta, cause) ||
	    member_record(f, m, s, &r, mdir, cause) ? -1 : 0;
	free(mdir);
	free(w);
	bake_result_free(&r);
	preset_free(p);
	return rc;
}

/* Bake member m on this process into v (status 1), or mark v failed (-1). */
static void bake_member(const struct family_plan *pl, const struct family *f, int m, struct bake_spec *s, double *v,
    char **cause)
{
	struct skin_params *p = member_spec(pl, f, m, s, cause);
	struct bake_result r;
	s->rank = 0, s->n_ranks = 1, s->allreduce = NULL, s->progress = NULL;
	if (p == NULL || bake_run(s, &r, cause) != 0) {
		v[0] = -1.0;
		preset_free(p);
		return;
	}
	pack(s, &r, v);
	bake_result_free(&r);
	preset_free(p);
}

int family_plan_check(const struct family_plan *pl, int *n_members, char **cause)
{
	if (count_members(pl, n_members, cause) != 0)
		return -1;
	struct family *f = family_new(pl, *n_members);
	struct bake_spec *s = xmalloc(sizeof *s);
	*s = pl->spec;
	int rc = 0;
	for (int m = 0; m < *n_members && rc == 0; m++) {
		struct skin_params *p = member_spec(pl, f, m, s, cause);
		rc = p ? 0 : -1;
		preset_free(p);
	}
	free(s);
	family_free(f);
	return rc;
}

/* The identity of the family's checkpoint: the axes (keys and nodes) and
 * every member's bake identity (checkpoint.h: its layer stacks, angles,
 * grid, solver settings, seed). */
static uint64_t family_identity(const struct family_plan *pl, const struct family *f, struct bake_spec *s)
{
	uint64_t h = checkpoint_hash(0, "skinbake family", 15);
	for (int a = 0; a < pl->n_axes; a++) {
		h = checkpoint_hash(h, pl->axis[a].key, strlen(pl->axis[a].key) + 1);
		h = checkpoint_hash(h, pl->axis[a].node, sizeof(double) * (size_t)pl->axis[a].n);
	}
	for (int m = 0; m < f->n_members; m++) {
		char *why = NULL;
		struct skin_params *p = member_spec(pl, f, m, s, &why);
		uint64_t id = p ? bake_spec_identity(s) : 0;
		h = checkpoint_hash(h, &id, sizeof id);
		preset_free(p);
		free(why);
	}
	return h;
}

/* Open DIR.checkpoint (rank 0 writes it, one process only); *n_done the
 * members it restores, each checked to be a packed result of this spec. */
static struct checkpoint *family_ckpt_open(const struct family_plan *pl, const struct family *f, const char *dir,
    int *n_done, char **cause)
{
	int R = pl->spec.n_ranks > 1 ? pl->spec.n_ranks : 1;
	if (pl->spec.resume && R > 1) {
		*cause = xstrdup("--resume works in one process only (skinbake, not skinbake-mpi under mpirun)");
		return NULL;
	}
	struct bake_spec *s = xmalloc(sizeof *s);
	*s = pl->spec;
	uint64_t id = family_identity(pl, f, s);
	free(s);
	struct checkpoint *ck = checkpoint_open_units(dir, id, pl->spec.resume, R == 1 && pl->spec.rank == 0,
	    pl->spec.checkpoint_s, cause);
	*n_done = ck ? checkpoint_units(ck) : 0;
	for (int m = 0; m < *n_done; m++) {
		size_t len;
		const double *v = checkpoint_unit(ck, m, &len);
		if (m >= f->n_members || len != sizeof(double) * pack_len(&pl->spec) || v[0] != 1.0) {
			*cause = xasprintf("%s.checkpoint: member m%04d does not fit this family; remove the file to bake from "
			    "the start", dir, m);
			checkpoint_close(ck);
			return NULL;
		}
	}
	return ck;
}

/* After the family is written: the checkpoint's note first in f->notes. */
static void family_ckpt_note(struct family *f, const struct checkpoint *ck)
{
	const char *e = checkpoint_write_error(ck);
	if (*checkpoint_note(ck) == '\0' && e == NULL)
		return;
	char *all = xasprintf("%s%s%s%s%s", checkpoint_note(ck), e ? "checkpoint not written: " : "", e ? e : "",
	    e ? "\n" : "", f->notes ? f->notes : "");
	free(f->notes);
	f->notes = all;
}

int family_bake(const struct family_plan *pl, const char *dir, struct family **out, char **cause)
{
	int n_members, n_done, rank = pl->spec.rank, R = pl->spec.n_ranks > 1 ? pl->spec.n_ranks : 1;
	if (out)
		*out = NULL;
	if (count_members(pl, &n_members, cause) != 0)
		return -1;
	/* The output and its lock first: a second run on DIR is refused
	 * before it reads DIR.checkpoint, which the first is writing. */
	struct outdir od;
	const char *stage = NULL;
	if (rank == 0) {
		if (stage_open(&od, dir, pl->base, cause) != 0)
			return -1;
		stage = outdir_path(&od);
	}
	struct family *f = family_new(pl, n_members);
	struct checkpoint *ck = family_ckpt_open(pl, f, dir, &n_done, cause);
	if (ck == NULL) {
		if (rank == 0)
			outdir_abort(&od);
		family_free(f);
		return -1;
	}
	/* Ranks go round by round in lockstep: each bakes one member of the
	 * round, the sum over ranks gathers them, rank 0 writes them.  The slot
	 * after the members carries rank 0's write failure to the others, so
	 * that all stop at the same round.  Members the checkpoint restored
	 * (one process only) are written from it, not baked again. */
	size_t L = pack_len(&pl->spec), nbuf = L * (size_t)R + 1, len;
	double *buf = xmalloc(sizeof(double) * nbuf);
	struct bake_spec *s = xmalloc(sizeof *s);
	*s = pl->spec;
	int rc = 0;
	for (int round = 0; round * R < n_members; round++) {
		memset(buf, 0, sizeof(double) * nbuf);
		int m = round * R + rank;
		char *why = NULL;
		if (rc != 0)
			buf[nbuf - 1] = 1.0;
		else if (m < n_done)
			memcpy(buf + (size_t)rank * L, checkpoint_unit(ck, m, &len), sizeof(double) * L);
		else if (m < n_members)
			bake_member(pl, f, m, s, buf + (size_t)rank * L, &why);
		if (R > 1 && pl->spec.allreduce)
			pl->spec.allreduce(buf, (long)nbuf);
		if (buf[nbuf - 1] != 0.0) {
			free(why);
			break;
		}
		for (int j = 0; j < R && rc == 0; j++) {
			int mj = round * R + j;
			if (mj < n_members && buf[(size_t)j * L] != 1.0) {
				*cause = why && j == rank ? xstrdup(why) : xasprintf("member m%04d: its bake failed on rank %d", mj, j);
				rc = -1;
			}
		}
		for (int j = 0; j < R && rc == 0 && rank == 0; j++) {
			int mj = round * R + j;
			if (mj >= n_members)
				continue;
			rc = write_member(pl, f, mj, buf + (size_t)j * L, s, stage, cause) ? -2 : 0;
			if (rc == 0 && mj >= n_done)
				checkpoint_unit_add(ck, buf + (size_t)j * L, sizeof(double) * L);
			if (rc == 0 && pl->progress)
				pl->progress(pl->progress_user, mj + 1, n_members);
		}
		free(why);
		if (rc == -1)
			break;	/* every rank saw the same failed member */
	}
	free(buf);
	free(s);
	if (rank == 0 && rc == 0)
		rc = family_write_index(stage, f, pl->command, cause) || outdir_commit(&od, cause) ||
		    checkpoint_remove(dir, cause) ? -2 : 0;
	if (rank == 0 && rc != 0)
		outdir_abort(&od);
	if (rc == 0 && rank == 0 && out) {
		family_ckpt_note(f, ck);
		f->dir = xstrdup(dir);
		*out = f;
	} else
		family_free(f);
	checkpoint_close(ck);
	return rc;
}
