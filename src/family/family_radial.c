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

/* Relative standard error of the mean radius of profile k of w. */
static double rel_err(const struct wmc_radial *w, int k)
{
	const double *x = w->rd_r + (size_t)k * (size_t)w->n_r, *e = w->rd_r_err + (size_t)k * (size_t)w->n_r;
	double m = tally_mean_radius(x, w->n_r, w->dr);
	return m > 0.0 ? tally_mean_radius_err(x, e, w->n_r, w->dr) / m : INFINITY;
}

/* Wavelength wl: the pilot, the sized run, the members' profiles into fr.
 * vs[n] are the members' slabs at wl. */
static void share_wavelength(const struct bake_spec *s, const struct slab *vs, int n, int wl, struct family_radial *fr)
{
	double target = s->radial_error > 0.0 ? s->radial_error : BAKE_RADIAL_ERROR;
	long cap = s->radial_photons > 0 ? s->radial_photons : BAKE_RADIAL_PHOTONS;
	struct slab ref;
	double *dmua = xmalloc(sizeof(double) * NS * (size_t)n);
	wmc_reference(vs, n, &ref, dmua);
	struct wmc_radial w;
	long pilot = cap < FAMILY_RADIAL_PILOT ? cap : FAMILY_RADIAL_PILOT;
	wmc_radial_run(&ref, dmua, n, s->theta_i[0], &s->opts, s->n_r, s->dr, pilot, BATCHES, s->seed,
	    (uint32_t)(2 * wl), s->threads, &w);
	fr->photons += w.photons;
	fr->seconds += w.seconds;
	long need = 0;
	for (int m = 0; m < n; m++) {
		double e = rel_err(&w, m);
		double want = (double)w.photons * (e / target) * (e / target) * 1.2;
		fr->ok[(size_t)wl * (size_t)n + (size_t)m] = e <= target || want <= (double)cap;
		if (e > target && want <= (double)cap && (long)ceil(want) > need)
			need = (long)ceil(want);
	}
	if (need > 0) {
		wmc_radial_free(&w);
		wmc_radial_run(&ref, dmua, n, s->theta_i[0], &s->opts, s->n_r, s->dr, need, BATCHES, s->seed,
		    (uint32_t)(2 * wl + 1), s->threads, &w);
		fr->photons += w.photons;
		fr->seconds += w.seconds;
	}
	size_t nr = (size_t)s->n_r, off = (size_t)wl * (size_t)n * nr;
	memcpy(fr->rd_r + off, w.rd_r, sizeof(double) * (size_t)n * nr);
	memcpy(fr->rd_r_err + off, w.rd_r_err, sizeof(double) * (size_t)n * nr);
	wmc_radial_free(&w);
	free(dmua);
}

int family_radial_run(const struct bake_spec *s, const struct slab *slabs, int n_members, struct family_radial *fr)
{
	memset(fr, 0, sizeof *fr);
	if (s->method == BAKE_SOLVER_MC || s->n_r <= 0 || n_members < 2)
		return 0;
	fr->n_members = n_members;
	fr->n_wl = s->n_wl;
	fr->n_r = s->n_r;
	size_t nv = (size_t)s->n_wl * (size_t)n_members;
	fr->rd_r = xcalloc(nv * (size_t)s->n_r, sizeof(double));
	fr->rd_r_err = xcalloc(nv * (size_t)s->n_r, sizeof(double));
	fr->ok = xcalloc(nv, 1);
	struct slab *vs = xmalloc(sizeof *vs * (size_t)n_members);
	int shared = 0;
	for (int wl = 0; wl < s->n_wl; wl++) {
		int same = 1;
		for (int m = 0; m < n_members; m++) {
			vs[m] = slabs[(size_t)m * (size_t)s->n_wl + (size_t)wl];
			same &= wmc_same_scattering(&vs[0], &vs[m]);
		}
		if (!same)
			continue;
		share_wavelength(s, vs, n_members, wl, fr);
		shared = 1;
	}
	free(vs);
	if (!shared)
		family_radial_free(fr);
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
