/* The adding-doubling solver's entry: the slab as the solver sees it, the
 * solves at two quadratures, and the values with their error estimates
 * (method and conventions in ad.h). */
#include "config.h"
#include "engine/ad.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "engine/ad_err.h"
#include "engine/ad_eval.h"
#include "engine/ad_order.h"
#include "engine/ad_rough.h"
#include "base/util.h"

#ifdef HAVE_BLAS_THREAD_SHUTDOWN_
/* OpenBLAS's (pthreads builds; not in cblas.h): joins its worker threads. */
int blas_thread_shutdown_(void);
#endif

void ad_blas_init(void)
{
	openblas_set_num_threads(1);
#ifdef HAVE_BLAS_THREAD_SHUTDOWN_
	(void)blas_thread_shutdown_();
#endif
}

void ad_opts_default(struct ad_opts *o)
{
	memset(o, 0, sizeof *o);
	o->tol = 1e-3;
	o->n_quad = 0;
	o->n_quad_max = 256;
	o->error_estimate = 1;
	/* Diamond starts up to mu_min / 8: four doublings fewer per layer than
	 * mu_min / 128; the start's own error (second order in its thickness)
	 * stays below 1e-8 relative in Rd and the table bins (test_ad
	 * test_start_thickness; 1.2e-8 in the paper preset's Tt of 1e-6),
	 * under the estimates test_ad checks at tight tolerances (mu_min / 2
	 * was not). */
	o->dtau_frac = 1.0 / 8.0;
	o->dm_terms = 2.0;
	o->max_orders = 1000;
	o->n_to = 18;
	o->n_phi = 18;
	o->threads = 0;
}

static int check_opts(const struct ad_opts *o, const double *theta_i, int n_beams, char **cause)
{
	if (n_beams < 1 || n_beams > AD_MAX_BEAMS) {
		*cause = xasprintf("adding-doubling: %d incidence angles is out of range [1, %d]", n_beams, AD_MAX_BEAMS);
		return -1;
	}
	for (int k = 0; k < n_beams; k++)
		if (!(theta_i[k] >= 0.0 && theta_i[k] < 0.5 * M_PI)) {
			*cause = xasprintf("adding-doubling: incidence angle %g rad is out of range [0, pi/2)", theta_i[k]);
			return -1;
		}
	const char *bad = NULL;
	if (!(o->tol > 0.0 && o->tol <= 0.1))
		bad = "tol is out of range (0, 0.1]";
	else if (o->n_quad != 0 && (o->n_quad < 4 || o->n_quad > 1024))
		bad = "n_quad is out of range [4, 1024] (or 0)";
	else if (o->n_quad == 0 && (o->n_quad_max < 16 || o->n_quad_max > 1024))
		bad = "n_quad_max is out of range [16, 1024]";
	else if (!(o->dtau_frac > 0.0 && o->dtau_frac <= 1.0))
		bad = "dtau_frac is out of range (0, 1]";
	else if (!(o->dm_terms >= 1.0 && o->dm_terms <= 64.0))
		bad = "dm_terms is out of range [1, 64]";
	else if (o->max_orders < 1)
		bad = "max_orders must be >= 1";
	else if (o->n_to < 1 || o->n_phi < 1 || o->n_to > 10000 || o->n_phi > 10000)
		bad = "the table's bins are out of range [1, 10000]";
	if (bad) {
		*cause = xasprintf("adding-doubling: %s", bad);
		return -1;
	}
	return 0;
}

static int dcmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

#ifndef AD_NSTAR_TOP
#define AD_NSTAR_TOP 1
#endif
/* The lowest turbid medium that reaches grazing at or above piece k. */
static double nstar_lowest(const struct ad_model *md, int k)
{
	double ns = INFINITY;
	for (int l = 0; l < md->K; l++)
		if (md->n[l] >= md->sigma[k + 1] * (1.0 - 1e-12) && md->n[l] < ns)
			ns = md->n[l];
	return fmax(ns, md->sigma[k + 1]);
}

/* Quadrature pieces: s cut at every index below the largest turbid one
 * (with rough boundaries: the largest of all, since a rough interface sends
 * light into every direction its media have, e.g. those a film of higher
 * index traps by total internal reflection). */
static void model_pieces(const struct slab *s, struct ad_model *md)
{
	double nmax = 0.0, v[SLAB_MAX_LAYERS + 2];
	int nv = 0;
	for (int k = 0; k < md->K; k++)
		nmax = fmax(nmax, md->n[k]);
	for (int i = 0; s->rough_any && i <= s->n_layers + 1; i++)
		nmax = fmax(nmax, s->layer[i].n);
	for (int i = 0; i <= s->n_layers + 1; i++)
		if (s->layer[i].n < nmax * (1.0 - 1e-12))
			v[nv++] = s->layer[i].n;
	qsort(v, (size_t)nv, sizeof v[0], dcmp);
	md->sigma[0] = 0.0;
	md->n_iv = 0;
	for (int j = 0; j < nv; j++)
		if (md->sigma[md->n_iv] < v[j] * (1.0 - 1e-12))
			md->sigma[++md->n_iv] = v[j];
	md->sigma[++md->n_iv] = nmax;
	for (int k = 0; k < md->n_iv; k++)
		md->nstar[k] = AD_NSTAR_TOP ? md->sigma[k + 1] : nstar_lowest(md, k);
}

/* Turbid layers and the boundaries between them; K = 0 if all are clear. */
static void model_build(const struct slab *s, enum optics_fresnel fresnel, struct ad_model *md)
{
	memset(md, 0, sizeof *md);
	md->fresnel = fresnel;
	md->n_above = s->n_above;
	int cnt = 0;
	double *list = md->bn[0];
	list[cnt++] = s->n_above;
	md->rough_nu = 0;
	md->rough_walks = s->rough_ms ? AD_ROUGH_MS_WALKS : 0;
	for (int i = 1; i <= s->n_layers; i++) {
		const struct layer *l = &s->layer[i];
		md->balpha[md->K][cnt - 1] = l->rough;	/* layer i's top: the interface into it */
		md->brough[md->K] |= l->rough > 0.0;
		list[cnt++] = l->n;
		if (slab_layer_clear(s, i))
			continue;
		int k = md->K++;
		md->bcnt[k] = cnt;
		md->slab_layer[k] = i;
		md->n[k] = l->n;
		double mt = l->mu_a + l->mu_s;
		md->tau[k] = isinf(l->d) ? INFINITY : mt * l->d;
		md->omega[k] = l->mu_s / mt;
		md->g[k] = l->g;
		list = md->bn[k + 1];
		cnt = 0;
		list[cnt++] = l->n;
	}
	md->balpha[md->K][cnt - 1] = s->layer[s->n_layers + 1].rough;
	md->brough[md->K] |= s->layer[s->n_layers + 1].rough > 0.0;
	list[cnt++] = s->n_below;
	md->bcnt[md->K] = cnt;
	if (md->K > 0)
		model_pieces(s, md);
}

/* No turbid layer: the clear stack reflects and transmits, nothing scatters. */
static void solve_clear(const struct slab *s, enum optics_fresnel fresnel, const double *theta_i, int n_beams,
    struct ad_result *r)
{
	double nl[SLAB_MAX_LAYERS + 2], ct;
	for (int i = 0; i <= s->n_layers + 1; i++)
		nl[i] = s->layer[i].n;
	for (int k = 0; k < n_beams; k++) {
		struct ad_beam *b = &r->beam[k];
		b->rsp = optics_stack_reflectance(fresnel, nl, s->n_layers + 2, cos(theta_i[k]), &ct);
		b->tt.v = b->tt_unscat = 1.0 - b->rsp;
		b->balance = b->rsp + b->tt.v - 1.0;
	}
	r->series_complete = 1;
}

static int level_run(const struct ad_model *md, const double *se, int E, const struct ad_opts *o, int n_quad,
    int threads, struct ad_series **out, char **cause)
{
	struct ad_level_opts lo = {
		.density = n_quad, .n_min = n_quad / 16 > 1 ? n_quad / 16 : 1, .dtau_frac = o->dtau_frac,
		.dm_terms = o->dm_terms, .max_orders = o->max_orders, .tol_f = 0.1 * o->tol, .threads = threads,
		.doubling_only = o->doubling_only, .cache = o->cache,
	};
	struct ad_series *sr = xcalloc(1, sizeof *sr);
	sr->md = *md;
	if (ad_level_solve(md, se, E, &lo, &sr->lv, cause)) {
		ad_level_free(&sr->lv);
		free(sr);
		return -1;
	}
	*out = sr;
	return 0;
}

static void series_free(struct ad_series *sr)
{
	if (sr) {
		ad_level_free(&sr->lv);
		free(sr);
	}
}

static void result_alloc(struct ad_result *r, const double *theta_i, int n_beams, const struct ad_opts *o)
{
	memset(r, 0, sizeof *r);
	r->n_beams = n_beams;
	r->n_to = o->n_to;
	r->n_phi = o->n_phi;
	r->beam = xcalloc((size_t)n_beams, sizeof *r->beam);
	size_t nb = (size_t)o->n_to * o->n_phi;
	for (int k = 0; k < n_beams; k++) {
		struct ad_beam *b = &r->beam[k];
		b->theta_i = theta_i[k];
		b->fr = xcalloc(nb, sizeof(double));
		b->fr_err = xcalloc(nb, sizeof(double));
		b->fr_az = xcalloc((size_t)o->n_to, sizeof(double));
		b->fr_az_err = xcalloc((size_t)o->n_to, sizeof(double));
	}
}

int ad_solve(const struct slab *s, enum optics_fresnel model, const double *theta_i, int n_beams,
    const struct ad_opts *o, struct ad_result *r, char **cause)
{
	if (check_opts(o, theta_i, n_beams, cause))
		return -1;
	double t0 = util_now();
	struct ad_model md;
	model_build(s, model, &md);
	result_alloc(r, theta_i, n_beams, o);
	if (md.K == 0 && s->rough_any) {
		*cause = xasprintf("adding-doubling: rough boundaries need a turbid layer (use the Monte Carlo solver)");
		ad_result_free(r);
		return -1;
	}
	if (md.K == 0) {
		solve_clear(s, model, theta_i, n_beams, r);
		r->seconds = util_now() - t0;
		return 0;
	}
	double se[AD_MAX_BEAMS];
	for (int k = 0; k < n_beams; k++)
		se[k] = s->n_above * sin(theta_i[k]);
	int threads = o->threads;
#ifdef _OPENMP
	if (threads <= 0)
		threads = omp_get_max_threads();
#endif
	if (threads <= 0)
		threads = 1;
	/* The matrices are small (about 30 to 200 rows): BLAS threads cost more
	 * than they give; the orders run in parallel instead.  Only when not
	 * already so: after ad_blas_init ended OpenBLAS's workers, setting the
	 * count again starts a new worker, which spins in sched_yield (11 % of
	 * `bake --preset paper`'s CPU samples). */
	if (openblas_get_num_threads() != 1)
		openblas_set_num_threads(1);
	int nq = o->n_quad > 0 ? o->n_quad : 16, automatic = o->n_quad == 0;
	int est = o->error_estimate || automatic;
	double e_prev = 0.0;
	struct ad_series *hi = NULL, *lo = NULL, *lo2 = NULL;
	if (est && (level_run(&md, se, n_beams, o, nq / 2, threads, &lo, cause) ||
	    (nq / 4 >= 4 && level_run(&md, se, n_beams, o, nq / 4, threads, &lo2, cause))))
		goto fail;
	for (;;) {
		if (level_run(&md, se, n_beams, o, nq, threads, &hi, cause))
			goto fail;
		ad_err_assemble(hi, lo, lo2, r);
		r->n_quad = nq;
		r->doublings += hi->lv.doublings;
		if (!automatic || ad_err_meets(r, o->tol))
			break;
		/* Escalate to n_quad_max before refusing: slow falls at low node
		 * counts (peaks, thin layers) often speed up once the nodes resolve
		 * them (g = 0.99: 1.1 at 32, 6e-4 at 256).  Refuse with the error
		 * reached at the last solve. */
		double e = r->rms_rel_err;
		if (2 * nq > o->n_quad_max) {
			*cause = xasprintf("adding-doubling cannot meet the tolerance %g: estimated table error %.3g "
			    "at %d nodes per unit cosine (n_quad_max %d), %.2f times the error at %d", o->tol, e, nq,
			    o->n_quad_max, e_prev > 0.0 ? e / e_prev : NAN, nq / 2);
			goto fail;
		}
		e_prev = e;
		series_free(lo2);
		lo2 = lo;
		lo = hi;
		hi = NULL;
		nq *= 2;
	}
	for (struct ad_series *x = lo; x; x = x == lo ? lo2 : NULL)
		r->doublings += x->lv.doublings;
	series_free(lo2);
	r->series = hi;
	r->series_lo = lo;
	r->seconds = util_now() - t0;
	return 0;
fail:
	series_free(hi);
	series_free(lo);
	series_free(lo2);
	ad_result_free(r);
	return -1;
}

double ad_brdf(const struct ad_result *r, int k, double theta_o, double dphi, double *err)
{
	if (err)
		*err = 0.0;
	if (!r->series || k < 0 || k >= r->n_beams)
		return 0.0;
	const struct ad_series *hi = r->series;
	double f = ad_series_point(hi, k, theta_o, dphi, 0);
	if (err) {
		double kept = ad_series_point(hi, k, theta_o, dphi, ad_err_kept_orders(hi));
		*err = ad_err_tail_factor(hi) * fabs(f - kept);
		if (r->series_lo) {
			/* The difference of two interpolants oscillates with the node
			 * spacing and can vanish at a point where neither is exact:
			 * take its largest size within a quarter spacing around. */
			double d = 0.0, h = 0.25 * M_PI / r->n_quad;
			for (int j = -2; j <= 2; j++) {
				double t = fmin(0.5 * M_PI, fmax(0.0, theta_o + j * h));
				d = fmax(d, fabs(ad_series_point(hi, k, t, dphi, 0) -
				    ad_series_point(r->series_lo, k, t, dphi, 0)));
			}
			*err += r->conv_factor * d;
		}
	}
	return f;
}

/* |f_hi - f_lo| at exit theta_o, the largest within a quarter node spacing
 * around (as ad_brdf), per dphi node, added to err[]; cosm[ip * M + m] =
 * cos(m phi[ip]). */
static void points_quad_err(const struct ad_result *r, int k, double theta_o, const double *cosm, int n_phi,
    double *c_hi, double *c_lo, int M, double *err)
{
	double h = 0.25 * M_PI / r->n_quad;
	double *d = xcalloc((size_t)n_phi, sizeof(double));
	for (int j = -2; j <= 2; j++) {
		double t = fmin(0.5 * M_PI, fmax(0.0, theta_o + j * h));
		int mh = ad_series_fourier(r->series, k, t, c_hi, M);
		int ml = ad_series_fourier(r->series_lo, k, t, c_lo, M);
		for (int ip = 0; ip < n_phi; ip++) {
			double v = 0.0;
			for (int m = 0; m < mh || m < ml; m++)
				v += ((m < mh ? c_hi[m] : 0.0) - (m < ml ? c_lo[m] : 0.0)) * cosm[(size_t)ip * M + m];
			d[ip] = fmax(d[ip], fabs(v));
		}
	}
	for (int ip = 0; ip < n_phi; ip++)
		err[ip] += r->conv_factor * d[ip];
	free(d);
}

void ad_brdf_points(const struct ad_result *r, int k, const double *theta_o, int n_to, const double *phi, int n_phi,
    double *f, double *err)
{
	memset(f, 0, sizeof(double) * (size_t)n_to * n_phi);
	memset(err, 0, sizeof(double) * (size_t)n_to * n_phi);
	if (!r->series || k < 0 || k >= r->n_beams)
		return;
	const struct ad_series *hi = r->series;
	int M = hi->lv.M + (r->series_lo ? r->series_lo->lv.M : 0) + 1;
	int mk = ad_err_kept_orders(hi);
	double tf = ad_err_tail_factor(hi);
	double *c = xcalloc((size_t)2 * M, sizeof(double)), *c2 = c + M;
	/* cos(m phi) once per call, not per exit angle and error probe (a
	 * profiled hot spot of family bakes). */
	double *cosm = xmalloc(sizeof(double) * (size_t)n_phi * (size_t)M);
	for (int ip = 0; ip < n_phi; ip++)
		for (int m = 0; m < M; m++)
			cosm[(size_t)ip * M + m] = cos(m * phi[ip]);
	for (int it = 0; it < n_to; it++) {
		double *fo = f + (size_t)it * n_phi, *eo = err + (size_t)it * n_phi;
		int mh = ad_series_fourier(hi, k, theta_o[it], c, M);
		for (int ip = 0; ip < n_phi; ip++) {
			double v = 0.0, tail = 0.0;
			for (int m = 0; m < mh; m++) {
				double x = c[m] * cosm[(size_t)ip * M + m];
				v += x;
				if (m >= mk)
					tail += x;
			}
			fo[ip] = v;
			eo[ip] = tf * fabs(tail);
		}
		/* At grazing exit under a smooth top the BRDF is 0 in every solve
		 * (no transmittance), not by coincidence: exact; under a rough top
		 * it is not 0 (ad_eval.c exit_weights) and has the solves' error. */
		if (r->series_lo && (theta_o[it] < 0.5 * M_PI || hi->md.brough[0]))
			points_quad_err(r, k, theta_o[it], cosm, n_phi, c, c2, M, eo);
	}
	free(cosm);
	free(c);
}

int ad_brdf_fourier(const struct ad_result *r, int k, double theta_o, double *coef, int max)
{
	if (!r->series || k < 0 || k >= r->n_beams || max < 1)
		return 0;
	return ad_series_fourier(r->series, k, theta_o, coef, max);
}

void ad_result_free(struct ad_result *r)
{
	for (int k = 0; k < r->n_beams; k++) {
		free(r->beam[k].fr);
		free(r->beam[k].fr_err);
		free(r->beam[k].fr_az);
		free(r->beam[k].fr_az_err);
	}
	free(r->beam);
	series_free(r->series);
	series_free(r->series_lo);
	memset(r, 0, sizeof *r);
}
