/* radial: Rd(r) by Monte Carlo with adding-doubling control variates
 * (radial.h). */
#include "config.h"
#include "bake/radial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "engine/ad.h"
#include "engine/tally.h"
#include "engine/wmc.h"

enum { NS = SLAB_MAX_LAYERS + 2, KMAX = 2 };
/* The absorption shifts of the controls [1/cm]: 0 is the diffuse
 * reflectance itself, 2 weighs paths by exp(-L / 5 mm).  (Measured on the
 * paper stack: these two take the variance of the mean radius down 2.5-3.9x,
 * shifts 0, 0.5, 2, 8 together 2.6-4.1x.) */
static const double cv_shift[KMAX] = { 0.0, 2.0 };

/* The controls' means: the scattered diffuse reflectance with mu_a + s_k in
 * the turbid layers, by adding-doubling, into mu[] with error estimates
 * err[]; the number of controls (0 when a solve fails). */
static int control_means(const struct radial_spec *sp, double *mu, double *err)
{
	struct ad_opts o;
	ad_opts_default(&o);
	o.tol = RADIAL_CV_TOL;
	o.n_to = o.n_phi = 1;
	o.max_orders = 1;
	o.threads = 1;
	for (int k = 0; k < KMAX; k++) {
		if (cv_shift[k] == 0.0 && sp->rd0 >= 0.0) {
			mu[k] = sp->rd0;
			err[k] = sp->rd0_err;
			continue;
		}
		struct slab s = *sp->slab;
		for (int l = 1; l <= s.n_layers; l++)
			if (!slab_layer_clear(sp->slab, l))
				s.layer[l].mu_a += cv_shift[k];
		slab_prepare(&s);
		struct ad_result r;
		char *cause = NULL;
		if (ad_solve(&s, sp->opts->fresnel, &sp->theta_in, 1, &o, &r, &cause) != 0) {
			free(cause);
			return 0;
		}
		mu[k] = r.beam[0].rd.v - r.beam[0].rd_unscat;
		err[k] = r.beam[0].rd.err;
		ad_result_free(&r);
	}
	return KMAX;
}

/* Solve the k x k system g x = b in place (Cholesky; g symmetric positive
 * definite); 0, or -1 when g is not. */
static int chol_solve(int k, double *g, double *b, int nrhs)
{
	for (int j = 0; j < k; j++) {
		double d = g[j * k + j];
		for (int m = 0; m < j; m++)
			d -= g[j * k + m] * g[j * k + m];
		if (!(d > 1e-13 * fabs(g[j * k + j])) || d <= 0.0)
			return -1;
		g[j * k + j] = sqrt(d);
		for (int i = j + 1; i < k; i++) {
			double v = g[i * k + j];
			for (int m = 0; m < j; m++)
				v -= g[i * k + m] * g[j * k + m];
			g[i * k + j] = v / g[j * k + j];
		}
	}
	for (int c = 0; c < nrhs; c++) {
		double *x = b + (size_t)c * k;
		for (int i = 0; i < k; i++) {
			for (int m = 0; m < i; m++)
				x[i] -= g[i * k + m] * x[m];
			x[i] /= g[i * k + i];
		}
		for (int i = k - 1; i >= 0; i--) {
			for (int m = i + 1; m < k; m++)
				x[i] -= g[m * k + i] * x[m];
			x[i] /= g[i * k + i];
		}
	}
	return 0;
}

/* Raw sums over the batches: per column c (the n_r bins, then N = sum r_i
 * y_i and D = sum y_i) of y, y^2 and y times each control; of the controls
 * and their products; and of N D. */
struct moments {
	long nb;
	double *sy, *syy, *syc;	/* [nc], [nc], [nc * KMAX] */
	double sc[KMAX], scc[KMAX * KMAX], snd;
};

/* Add batches prof[nb * n_r], tot[nb * KMAX] to m. */
static void moments_add(struct moments *m, int n_r, double dr, const double *prof,
    const double *tot, int nb)
{
	for (int b = 0; b < nb; b++) {
		const double *yb = prof + (size_t)b * n_r, *cb = tot + (size_t)b * KMAX;
		double nn = 0.0, dd = 0.0;
		for (int i = 0; i < n_r + 2; i++) {
			double v;
			if (i < n_r) {
				v = yb[i];
				if (v == 0.0)
					continue;
				nn += (i + 0.5) * dr * v;
				dd += v;
			} else
				v = i == n_r ? nn : dd;
			m->sy[i] += v;
			m->syy[i] += v * v;
			for (int j = 0; j < KMAX; j++)
				m->syc[(size_t)i * KMAX + j] += v * cb[j];
		}
		m->snd += nn * dd;
		for (int j = 0; j < KMAX; j++) {
			m->sc[j] += cb[j];
			for (int l = 0; l < KMAX; l++)
				m->scc[j * KMAX + l] += cb[j] * cb[l];
		}
	}
	m->nb += nb;
}

/* The regression estimate from m with k controls (fewer when they are
 * collinear): out's profile, mean radius and errors. */
static void estimate(const struct radial_spec *sp, const struct moments *mo, int k,
    const double *mu, const double *mu_err, struct radial_out *out)
{
	const int n_r = sp->n_r, nc = n_r + 2;
	const double nb = (double)mo->nb;
	double cm[KMAX], g[KMAX * KMAX], gk[KMAX * KMAX];
	for (int j = 0; j < KMAX; j++)
		cm[j] = mo->sc[j] / nb;
	for (int j = 0; j < KMAX; j++)
		for (int l = 0; l < KMAX; l++)
			g[j * KMAX + l] = mo->scc[j * KMAX + l] - nb * cm[j] * cm[l];
	/* cov[c * KMAX + j] = sum over batches of (y_c - mean)(c_j - mean). */
	double *cov = xmalloc(sizeof(double) * (size_t)nc * KMAX);
	double *beta = xmalloc(sizeof(double) * (size_t)nc * KMAX);
	for (int c = 0; c < nc; c++)
		for (int j = 0; j < KMAX; j++) {
			size_t i = (size_t)c * KMAX + (size_t)j;
			cov[i] = mo->syc[i] - mo->sy[c] * cm[j];
		}
	for (; k > 0; k--) {
		for (int j = 0; j < k; j++)
			for (int l = 0; l < k; l++)
				gk[j * k + l] = g[j * KMAX + l];
		for (int c = 0; c < nc; c++)
			for (int j = 0; j < k; j++)
				beta[(size_t)c * k + j] = cov[(size_t)c * KMAX + j];
		if (mo->nb - k - 1 >= 8 && chol_solve(k, gk, beta, nc) == 0)
			break;
	}
	double dof = (double)(mo->nb - k - 1) * nb, adj_n = 0.0, adj_d = 0.0;
	for (int c = 0; c < nc; c++) {
		double a = mo->sy[c] / nb, ss = mo->syy[c] - mo->sy[c] * a;
		for (int j = 0; j < k; j++) {
			a -= beta[(size_t)c * k + j] * (cm[j] - mu[j]);
			ss -= beta[(size_t)c * k + j] * cov[(size_t)c * KMAX + j];
		}
		if (c < n_r) {
			double area = tally_annulus_area(sp->dr, c);
			out->rd_r[c] = a / area;
			out->rd_r_err[c] = sqrt(fmax(ss, 0.0) / dof) / area;
		} else if (c == n_r)
			adj_n = a;
		else
			adj_d = a;
	}
	/* The mean radius m = N / D: the residual of N - m D, and the effect of
	 * the controls' means' errors (adding-doubling's estimates). */
	double m = adj_d > 0.0 ? adj_n / adj_d : 0.0;
	const double *bn = beta + (size_t)n_r * k, *bd = beta + (size_t)(n_r + 1) * k;
	double sn = mo->sy[n_r], sd = mo->sy[n_r + 1];
	double vz = (mo->syy[n_r] - sn * sn / nb) - 2.0 * m * (mo->snd - sn * sd / nb) +
	    m * m * (mo->syy[n_r + 1] - sd * sd / nb), bias = 0.0;
	for (int j = 0; j < k; j++) {
		double bz = bn[j] - m * bd[j];
		vz -= bz * (cov[(size_t)n_r * KMAX + j] - m * cov[(size_t)(n_r + 1) * KMAX + j]);
		bias += bz * mu_err[j] * bz * mu_err[j];
	}
	out->mean_radius_cm = m;
	out->mean_radius_err_cm = adj_d > 0.0 ? sqrt(fmax(vz, 0.0) / dof + bias) / adj_d : 0.0;
	out->controls = k;
	free(cov);
	free(beta);
}

void radial_solve(const struct radial_spec *sp, struct radial_out *out)
{
	double t0 = util_now(), mu[KMAX], mu_err[KMAX], dmua[KMAX * NS];
	int k = control_means(sp, mu, mu_err);
	memset(dmua, 0, sizeof dmua);
	for (int j = 0; j < KMAX; j++)
		for (int l = 1; l <= sp->slab->n_layers; l++)
			if (!slab_layer_clear(sp->slab, l))
				dmua[j * NS + l] = cv_shift[j];
	/* Far roulette beyond the bins, never nearer than TRANSPORT_FAR_MIN_CM
	 * (engine/transport.h): the profile and the mean radius count nothing
	 * that leaves beyond the bins. */
	struct transport_opts o = *sp->opts;
	o.far_cm = fmax(sp->n_r * sp->dr, TRANSPORT_FAR_MIN_CM);
	const long bp = RADIAL_BATCH;
	const int nc = sp->n_r + 2, chunk = 1024;
	/* Whole batches, at least 2 (the photon cap rounded up); the pilot at
	 * least 32 batches where the cap allows (for the regression). */
	long cap_b = (sp->cap + bp - 1) / bp > 2 ? (sp->cap + bp - 1) / bp : 2;
	long nb = (sp->pilot + bp - 1) / bp, have = 0;
	if (nb < 32)
		nb = 32;
	if (nb > cap_b)
		nb = cap_b;
	struct moments mo = { 0 };
	mo.sy = xcalloc((size_t)nc, sizeof(double));
	mo.syy = xcalloc((size_t)nc, sizeof(double));
	mo.syc = xcalloc((size_t)nc * KMAX, sizeof(double));
	double *prof = xmalloc(sizeof(double) * (size_t)chunk * (size_t)sp->n_r);
	double *tot = xmalloc(sizeof(double) * (size_t)chunk * KMAX);
	for (int round = 0;; round++) {
		for (long done = 0; done < nb; done += chunk) {
			int c = nb - done < chunk ? (int)(nb - done) : chunk;
			int b0 = (int)(have + done);
			wmc_batches(sp->slab, dmua, KMAX, sp->theta_in, &o, sp->n_r, sp->dr,
			    bp, b0, c, sp->seed, sp->stream, sp->threads, prof, tot);
			moments_add(&mo, sp->n_r, sp->dr, prof, tot, c);
		}
		have += nb;
		estimate(sp, &mo, k, mu, mu_err, out);
		/* No spread although light comes back (rd0 > 0, or not known):
		 * none or one bin scored so far, which is no convergence, so the
		 * run goes on. */
		double m = out->mean_radius_cm, e = out->mean_radius_err_cm;
		double rel = sp->rd0 != 0.0 ? INFINITY : 0.0;
		if (m > 0.0 && e > 0.0)
			rel = e / m;
		if (rel <= sp->target || have >= cap_b || round >= sp->rounds)
			break;
		double q = rel / sp->target, want = (double)have * (q * q * sp->margin - 1.0);
		/* At most 4x the batches so far per round: a small pilot's error
		 * estimate can be far off. */
		nb = want > have / 4.0 ? (long)fmin(ceil(want), 3.0 * (double)have) : have / 4;
		if (nb > cap_b - have)
			nb = cap_b - have;
	}
	out->photons = have * bp;
	/* Still no spread at the cap (nothing in the bins, or all of it in one):
	 * where so few photons come back (photons x rd0 under
	 * RADIAL_ZERO_PLAUSIBLE) that this is likely, the run only says that
	 * the mean radius lies within the bins, and states their extent as its
	 * error.  Beyond that a 0 stays 0 (an estimator failure the bake
	 * refuses, bake.c). */
	double expect = (double)out->photons * sp->rd0;
	if (!(out->mean_radius_err_cm > 0.0) && sp->rd0 > 0.0 && expect < RADIAL_ZERO_PLAUSIBLE)
		out->mean_radius_err_cm = sp->n_r * sp->dr;
	out->seconds = util_now() - t0;
	free(prof);
	free(tot);
	free(mo.sy);
	free(mo.syy);
	free(mo.syc);
}
