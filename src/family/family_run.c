/* family_run: the family bake (family.h): member parameters, the members baked one by one (spread
 * over MPI ranks, gathered to rank 0 through the bake's allreduce hook)
 * and written into the staging directory, then moved into place; finished
 * members saved in DIR.checkpoint for --resume. */
#include "config.h"
#include "family/family.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/check.h"
#include "base/outdir.h"
#include "base/util.h"
#include "bake/checkpoint.h"
#include "family/family_pack.h"
#include "family/family_radial.h"
#include "bake/manifest.h"
#include "engine/ad_cache.h"
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
		outdir_fail(od, cause);
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
	free(b.preset);
	free(b.wl_nm);
	free(b.theta_i);
	free(b.theta_o);
	free(b.phi);
	free(b.rgb_from_wl);
	free(b.stack);
	free(b.sss_radius_cm);
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
	char solver[FAMILY_SOLVER_NAME_MAX + 1];
	struct bake_result r;
	family_unpack(s, v, solver, &r);
	if (f->solver == NULL)
		f->solver = xstrdup(solver);
	else if (strcmp(f->solver, solver) != 0) {
		char *u = xstrdup(solvers_union(f->solver, solver));
		free(f->solver);
		f->solver = u;
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
		.roughness = preset_surface_roughness(p), .macro_slope = p->macro_slope,
		.rgb_from_wl = w,
		.rgb_note = bake_rgb_weights(s, w), .command = pl->command };
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
    const struct family_radial *fr, char **cause)
{
	struct skin_params *p = member_spec(pl, f, m, s, cause);
	struct bake_result r;
	struct bake_radial_given given;
	s->rank = 0;
	s->n_ranks = 1;
	s->allreduce = NULL;
	s->progress = NULL;
	if (fr) {
		family_radial_given(fr, m, &given);
		s->radial_given = &given;
	}
	int rc = p == NULL ? -1 : bake_run(s, &r, cause);
	s->radial_given = NULL;
	if (rc != 0) {
		v[0] = -1.0;
		preset_free(p);
		return;
	}
	family_pack(s, &r, v);
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

/* The members' Rd(r) shared by white Monte Carlo (family_radial.h); under
 * MPI the ranks split the wavelengths and all end with the same profiles
 * (their random streams do not depend on the rank), so members come out
 * the same over any number of ranks.  1 with fr filled. */
static int shared_radial(const struct family_plan *pl, const struct family *f,
    struct family_radial *fr, char **cause)
{
	if ((bake_method_ops(pl->spec.method)->provides & SOLVER_RADIAL) || pl->spec.n_r <= 0)
		return 0;
	int n = f->n_members, nw = pl->spec.n_wl;
	struct bake_spec *s = xmalloc(sizeof *s);
	*s = pl->spec;
	struct slab *slabs = xmalloc(sizeof *slabs * (size_t)n * (size_t)nw);
	int rc = 1;
	for (int m = 0; m < n && rc == 1; m++) {
		struct skin_params *p = member_spec(pl, f, m, s, cause);
		if (p == NULL)
			rc = -1;
		else
			memcpy(slabs + (size_t)m * (size_t)nw, s->slab, sizeof *slabs * (size_t)nw);
		preset_free(p);
	}
	if (rc == 1)
		rc = family_radial_run(s, slabs, n, fr);
	free(slabs);
	free(s);
	return rc;
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
		if (m >= f->n_members || len != sizeof(double) * family_pack_len(&pl->spec) || v[0] != 1.0) {
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
	if (bake_budget(&pl->spec, n_members, dir, cause) != 0)
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
			outdir_fail(&od, cause);
		family_free(f);
		return -1;
	}
	/* Ranks go round by round in lockstep: each bakes one member of the
	 * round, the sum over ranks gathers them, rank 0 writes them.  The slot
	 * after the members carries rank 0's write failure to the others, so
	 * that all stop at the same round.  Members the checkpoint restored
	 * (one process only) are written from it, not baked again. */
	struct family_radial fr;
	int shared = n_done < n_members ? shared_radial(pl, f, &fr, cause) : 0;
	if (shared < 0) {
		if (rank == 0)
			outdir_fail(&od, cause);
		checkpoint_close(ck);
		family_free(f);
		return -1;
	}
	size_t L = family_pack_len(&pl->spec), nbuf = L * (size_t)R + 1, len;
	double *buf = xmalloc(sizeof(double) * nbuf);
	struct bake_spec *s = xmalloc(sizeof *s);
	*s = pl->spec;
	/* The members' unchanged layers solve the same from member to member:
	 * kept in a bounded block (engine/ad_cache.h; outputs unchanged). */
	void *cblock = xmalloc(FAMILY_AD_CACHE_BYTES);
	struct ad_cache cache;
	ad_cache_init(&cache, cblock, FAMILY_AD_CACHE_BYTES);
	s->ad_cache = &cache;
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
			bake_member(pl, f, m, s, buf + (size_t)rank * L, shared ? &fr : NULL, &why);
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
	free(cblock);
	if (shared)
		family_radial_free(&fr);
	if (rank == 0 && rc == 0)
		rc = family_write_index(stage, f, pl->command, cause) || outdir_commit(&od, cause) ||
		    checkpoint_remove(dir, cause) ? -2 : 0;
	if (rank == 0 && rc != 0)
		outdir_fail(&od, cause);
	if (rc == 0 && rank == 0 && out) {
		family_ckpt_note(f, ck);
		f->dir = xstrdup(dir);
		*out = f;
	} else
		family_free(f);
	checkpoint_close(ck);
	return rc;
}
