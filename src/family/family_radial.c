/* family_radial: shared white Monte Carlo Rd(r) of a family (family_radial.h). */
#include "config.h"
#include "family/family_radial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine/tally.h"
#include "engine/wmc.h"
#include "base/util.h"

enum { NS = SLAB_MAX_LAYERS + 2, BATCHES = 16 };
/* The sized run's error over the target beyond which a member runs its own. */
#define RERUN_SLACK 1.25
#define GROUP_SPREAD 4.0	/* the largest need over the least in a group, but the last */

/* Relative standard error of the mean radius of profile k of w. */
static double rel_err(const struct wmc_radial *w, int k)
{
	size_t off = (size_t)k * (size_t)w->n_r;
	const double *x = w->rd_r + off, *e = w->rd_r_err + off;
	double m = tally_mean_radius(x, w->n_r, w->dr);
	return m > 0.0 ? tally_mean_radius_err(x, e, w->n_r, w->dr) / m : INFINITY;
}

/* One group of members at wavelength wl: idx[n] (members), vs (all
 * members' slabs at wl).  The pilot sizes each member's need; unless this
 * is the last group, the members needing over GROUP_SPREAD times the least
 * need are left for a later group (their own, more absorbing walk) into
 * left[*n_left].  The rest share a run sized to their largest need, which
 * replaces the pilot, walked with the least absorption among them. */
static void share_group(const struct bake_spec *s, const struct slab *vs, const int *idx, int n,
    int wl, int grp, int last, struct family_radial *fr, int *left, int *n_left)
{
	double target = s->radial_error > 0.0 ? s->radial_error : BAKE_RADIAL_ERROR;
	long cap = s->radial_photons > 0 ? s->radial_photons : BAKE_RADIAL_PHOTONS;
	long pilot = cap < FAMILY_RADIAL_PILOT ? cap : FAMILY_RADIAL_PILOT;
	struct slab *sub = xmalloc(sizeof *sub * (size_t)n), ref;
	double *dmua = xmalloc(sizeof(double) * NS * (size_t)n);
	double *want = xmalloc(sizeof(double) * (size_t)n);
	for (int k = 0; k < n; k++)
		sub[k] = vs[idx[k]];
	wmc_reference(sub, n, &ref, dmua);
	struct wmc_radial w;
	/* Far roulette beyond the bins (engine/transport.h), as bake/radial.c. */
	struct transport_opts o = s->opts;
	o.far_cm = fmax(s->n_r * s->dr, TRANSPORT_FAR_MIN_CM);
	uint32_t stream = (uint32_t)(wl * 2 * FAMILY_RADIAL_GROUPS + 2 * grp);
	wmc_radial_run(&ref, dmua, n, s->theta_i[0], &o, s->n_r, s->dr, pilot, BATCHES,
	    s->seed, stream, s->threads, &w);
	fr->photons += w.photons;
	fr->seconds += w.seconds;
	double least = INFINITY;
	for (int k = 0; k < n; k++) {
		double e = rel_err(&w, k);
		want[k] = e <= target ? 0.0 : (double)w.photons * (e / target) * (e / target) * 1.2;
		least = fmin(least, want[k]);
	}
	int kept = 0, *keep = xmalloc(sizeof(int) * (size_t)n);
	long need = 0;
	for (int k = 0; k < n; k++) {
		if (!last && want[k] > GROUP_SPREAD * fmax(least, (double)pilot)) {
			left[(*n_left)++] = idx[k];
			continue;
		}
		size_t at = (size_t)wl * (size_t)fr->n_members + (size_t)idx[k];
		fr->ok[at] = want[k] <= (double)cap;
		if (want[k] <= (double)cap && (long)ceil(want[k]) > need)
			need = (long)ceil(want[k]);
		sub[kept] = vs[idx[k]];
		keep[kept++] = k;
	}
	if (need > 0 || kept < n) {
		wmc_radial_free(&w);
		wmc_reference(sub, kept, &ref, dmua);
		long photons = need > pilot ? need : pilot;
		wmc_radial_run(&ref, dmua, kept, s->theta_i[0], &o, s->n_r, s->dr, photons,
		    BATCHES, s->seed, stream + 1, s->threads, &w);
		fr->photons += w.photons;
		fr->seconds += w.seconds;
	}
	size_t nr = (size_t)s->n_r;
	for (int j = 0; j < kept; j++) {
		/* The run's variant j: member idx[keep[j]] (the pilot's order when it was kept). */
		size_t off = ((size_t)wl * (size_t)fr->n_members + (size_t)idx[keep[j]]) * nr;
		size_t from = (size_t)(w.n_var == n ? keep[j] : j) * nr;
		memcpy(fr->rd_r + off, w.rd_r + from, sizeof(double) * nr);
		memcpy(fr->rd_r_err + off, w.rd_r_err + from, sizeof(double) * nr);
		/* A pilot can miss a heavy tail of the weights: a member still
		 * well above the target runs its own. */
		if (rel_err(&w, (int)(from / nr)) > RERUN_SLACK * target)
			fr->ok[(size_t)wl * (size_t)fr->n_members + (size_t)idx[keep[j]]] = 0;
	}
	wmc_radial_free(&w);
	free(keep);
	free(want);
	free(dmua);
	free(sub);
}

/* Wavelength wl: the members (slabs vs[n]) in groups of like absorption. */
static void share_wavelength(const struct bake_spec *s, const struct slab *vs, int n, int wl,
    struct family_radial *fr)
{
	int *idx = xmalloc(sizeof(int) * (size_t)n), *left = xmalloc(sizeof(int) * (size_t)n);
	for (int m = 0; m < n; m++)
		idx[m] = m;
	int G = FAMILY_RADIAL_GROUPS;
	for (int grp = 0; grp < G && n > 0; grp++) {
		int n_left = 0;
		share_group(s, vs, idx, n, wl, grp, grp == G - 1 || n == 1, fr, left, &n_left);
		memcpy(idx, left, sizeof(int) * (size_t)n_left);
		n = n_left;
	}
	free(left);
	free(idx);
}

/* Under MPI each rank made the wavelengths wl % n_ranks == rank (the
 * others are zero): the sum over ranks gathers them all on every rank. */
static void gather(const struct bake_spec *s, struct family_radial *fr)
{
	size_t nv = (size_t)fr->n_wl * (size_t)fr->n_members, np = nv * (size_t)fr->n_r;
	size_t n = 2 * np + nv + 2;
	double *v = xmalloc(sizeof(double) * n);
	memcpy(v, fr->rd_r, sizeof(double) * np);
	memcpy(v + np, fr->rd_r_err, sizeof(double) * np);
	for (size_t i = 0; i < nv; i++)
		v[2 * np + i] = fr->ok[i];
	v[n - 2] = (double)fr->photons;
	v[n - 1] = fr->seconds;
	s->allreduce(v, (long)n);
	memcpy(fr->rd_r, v, sizeof(double) * np);
	memcpy(fr->rd_r_err, v + np, sizeof(double) * np);
	for (size_t i = 0; i < nv; i++)
		fr->ok[i] = v[2 * np + i] != 0.0;
	fr->photons = (long)v[n - 2];
	fr->seconds = v[n - 1];
	free(v);
}

int family_radial_run(const struct bake_spec *s, const struct slab *slabs, int n_members,
    struct family_radial *fr)
{
	memset(fr, 0, sizeof *fr);
	if ((bake_method_ops(s->method)->provides & SOLVER_RADIAL) || s->n_r <= 0 || n_members < 2)
		return 0;
	fr->n_members = n_members;
	fr->n_wl = s->n_wl;
	fr->n_r = s->n_r;
	size_t nv = (size_t)s->n_wl * (size_t)n_members;
	fr->rd_r = xcalloc(nv * (size_t)s->n_r, sizeof(double));
	fr->rd_r_err = xcalloc(nv * (size_t)s->n_r, sizeof(double));
	fr->ok = xcalloc(nv, 1);
	struct slab *vs = xmalloc(sizeof *vs * (size_t)n_members);
	int shared = 0, R = s->n_ranks > 1 && s->allreduce ? s->n_ranks : 1;
	for (int wl = 0; wl < s->n_wl; wl++) {
		int same = 1;
		for (int m = 0; m < n_members; m++) {
			vs[m] = slabs[(size_t)m * (size_t)s->n_wl + (size_t)wl];
			same &= wmc_same_scattering(&vs[0], &vs[m]);
		}
		if (!same)
			continue;
		shared = 1;
		if (wl % R == s->rank)
			share_wavelength(s, vs, n_members, wl, fr);
	}
	free(vs);
	if (!shared)
		family_radial_free(fr);
	else if (R > 1)
		gather(s, fr);
	return shared;
}

void family_radial_given(const struct family_radial *fr, int m, struct bake_radial_given *g)
{
	memset(g, 0, sizeof *g);
	size_t nr = (size_t)fr->n_r;
	for (int wl = 0; wl < fr->n_wl; wl++) {
		size_t k = (size_t)wl * (size_t)fr->n_members + (size_t)m;
		if (!fr->ok[k])
			continue;
		g->rd_r[wl] = fr->rd_r + k * nr;
		g->rd_r_err[wl] = fr->rd_r_err + k * nr;
	}
	g->photons = fr->photons;
	g->seconds = fr->seconds;
	g->n_shared = fr->n_members;
}

void family_radial_free(struct family_radial *fr)
{
	free(fr->rd_r);
	free(fr->rd_r_err);
	free(fr->ok);
	memset(fr, 0, sizeof *fr);
}
