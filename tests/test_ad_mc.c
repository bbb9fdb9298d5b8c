/* The adding-doubling solver against the Monte Carlo engine, the
 * independent method (same problem, same Fresnel, same clear-film launch):
 *   - the skin stack's azimuth-averaged BRDF per 5-degree band at normal
 *     incidence, against the transport kernel with next-event estimation
 *     (as the bake uses it) at 1e6 photons: every band within 3 standard
 *     errors (the MC error is 0.15-0.3% per band here; plain escape
 *     binning, sim_run's, would need about 1e8 photons for 0.2%); with
 *     AD_MC_LONG=1 in the environment 2e7 photons and 0.2% per band (a
 *     validation run, about 4 min of CPU, not in `make check`);
 *   - the whole 18 x 18 table at 34 and 60 degrees against 2e5 photons of
 *     next-event estimation (about 0.5% per bin): no bin beyond 4 sigma, at
 *     most 1% of the bins beyond 3 sigma (of 648 bins about 2 would be by
 *     chance even for a perfect solver), and chi^2 per bin below 2 (the bins
 *     share photons, so their z move together and chi^2 per bin scatters
 *     far more than for independent bins; only a high value means much);
 *   - Rd, Tt and the absorption per layer at 34 and 60 degrees against
 *     sim_run (escapes, no next-event estimation) within 3 sigma;
 *   - a stack of four indices under Schlick's Fresnel at 45 degrees: totals
 *     against sim_run and bands against next-event estimation.
 * Fixed seeds.  Cost: 33 s of CPU on the 2-core CI machine (the Monte Carlo;
 * the solver takes under 1 s of it). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/ad.h"
#include "engine/nee.h"
#include "engine/sim.h"
#include "engine/transport.h"
#include "base/util.h"

typedef double lrow[5];	/* d [cm], mu_a, mu_s [1/cm], g, n */

static void mkslab(struct slab *s, double na, double nb, int nl, const lrow *L)
{
	char *cause = NULL;
	slab_init(s, na, nb);
	for (int i = 0; i < nl; i++) {
		struct layer l = { L[i][0], L[i][4], L[i][1], L[i][2], L[i][3] };
		assert_int_equal(slab_add(s, &l, &cause), 0);
	}
	if (slab_check(s, &cause))
		fail_msg("%s", cause);
	slab_prepare(s);
}

static const lrow skin3[] = { { 0.001, 0, 0, 0, 1.5 }, { 0.01, 50, 370, 0.8, 1.4 }, { 0.25, 7, 370, 0.8, 1.4 } };
static const lrow four[] = { { 0.0005, 0, 0, 0, 1.5 }, { 0.006, 9.9, 330, 0.75, 1.45 }, { 0.2, 5.3, 223, 0.75, 1.39 },
	{ INFINITY, 10.6, 154, 0.75, 1.44 } };

static void ad_run(const struct slab *s, enum optics_fresnel fm, const double *th, int n, int n_phi, struct ad_result *r)
{
	struct ad_opts o;
	char *cause = NULL;
	ad_opts_default(&o);
	o.tol = 1e-5;
	o.n_phi = n_phi;
	if (ad_solve(s, fm, th, n, &o, r, &cause))
		fail_msg("ad_solve: %s", cause);
}

/* Monte Carlo table by next-event estimation: nb batches of `per` photons
 * in parallel (as bake.c), bin means and their standard errors from the
 * spread of the batch means. */
struct mc_table {
	int nt, np;
	double fr[18 * 18], err[18 * 18];
	double seconds;
};

static void mc_nee(const struct slab *s, enum optics_fresnel fm, double th, int nt, int np, long per, int nb,
    uint64_t seed, struct mc_table *m)
{
	struct transport_opts o;
	struct launch ln;
	transport_opts_default(&o);
	o.fresnel = fm;
	transport_launch(s, th, fm, &ln);
	struct tally_grid g = { .n_theta = nt, .n_phi = np, .n_r = 0, .dr = 0.01 };
	int ne = nt * np;
	double *v = xcalloc((size_t)nb * ne, sizeof(double)), t0 = util_now();
#pragma omp parallel
	{
		struct tally t;
		struct nee e;
		tally_alloc(&t, &g);
		nee_alloc(&e, nt, np, SLAB_MAX_LAYERS);
#pragma omp for schedule(dynamic, 1)
		for (int b = 0; b < nb; b++) {
			tally_zero(&t, &g);
			transport_run(s, &ln, &o, &g, &e, seed, 1, (uint64_t)b * per, per, &t);
			for (int i = 0; i < ne; i++)
				v[(size_t)b * ne + i] = t.exit[i] / per;
		}
		tally_free(&t);
		nee_free(&e);
	}
	m->seconds = util_now() - t0;
	m->nt = nt;
	m->np = np;
	for (int it = 0; it < nt; it++) {
		double co = sim_cos_solid_angle(it * M_PI / (2 * nt), (it + 1) * M_PI / (2 * nt), M_PI / np);
		for (int ip = 0; ip < np; ip++) {
			double s1 = 0.0, s2 = 0.0;
			for (int b = 0; b < nb; b++) {
				double x = v[(size_t)b * ne + it * np + ip];
				s1 += x;
				s2 += x * x;
			}
			double mean = s1 / nb;
			m->fr[it * np + ip] = mean / co;
			m->err[it * np + ip] = sqrt(fmax(0.0, s2 / nb - mean * mean) / (nb - 1)) / co;
		}
	}
	free(v);
}

/* Each azimuthal band within 3 sigma (the AD error added, it is tiny). */
static void check_bands(const char *name, const struct ad_beam *b, const struct mc_table *m)
{
	double worst_rel = 0.0, worst_z = 0.0, sig = 0.0;
	for (int it = 0; it < m->nt; it++) {
		double d = m->fr[it] - b->fr_az[it], s = sqrt(m->err[it] * m->err[it] + b->fr_az_err[it] * b->fr_az_err[it]);
		worst_rel = fmax(worst_rel, fabs(d) / b->fr_az[it]);
		worst_z = fmax(worst_z, fabs(d) / s);
		sig = fmax(sig, m->err[it] / m->fr[it]);
		if (!(fabs(d) <= 3.0 * s))
			fail_msg("%s band %d: AD %.6g MC %.6g +- %.2g (%.1f sigma)", name, it, b->fr_az[it], m->fr[it],
			    m->err[it], d / s);
	}
	print_message("# %s: 18 bands, MC sigma up to %.2f%%, |AD - MC| up to %.2f%% (%.1f sigma); MC %.1f s\n", name,
	    100 * sig, 100 * worst_rel, worst_z, m->seconds);
}

static void test_bands_normal(void **state)
{
	(void)state;
	struct slab s;
	mkslab(&s, 1.0, 1.4, 3, skin3);
	double th = 0.0;
	struct ad_result r;
	ad_run(&s, OPTICS_FRESNEL_EXACT, &th, 1, 18, &r);
	static struct mc_table m;
	/* AD_MC_LONG=1: 2e7 photons (MC error 0.03-0.07% per band, about 4 min of
	 * CPU, so not part of `make check`), and every band within 0.2% too. */
	int lng = getenv("AD_MC_LONG") && atoi(getenv("AD_MC_LONG")) > 0;
	mc_nee(&s, OPTICS_FRESNEL_EXACT, th, 18, 1, lng ? 200000 : 10000, 100, 21, &m);
	check_bands("skin3 0 deg", &r.beam[0], &m);
	if (lng)
		for (int it = 0; it < 18; it++)
			if (!(fabs(m.fr[it] - r.beam[0].fr_az[it]) <= 2e-3 * r.beam[0].fr_az[it]))
				fail_msg("band %d: AD %.6g MC %.6g +- %.2g: beyond 0.2%%", it, r.beam[0].fr_az[it], m.fr[it],
				    m.err[it]);
	ad_result_free(&r);
}

/* Every bin of the 18 x 18 table (see the top for the criterion). */
static void test_tables_oblique(void **state)
{
	(void)state;
	struct slab s;
	mkslab(&s, 1.0, 1.4, 3, skin3);
	double th[2] = { 34 * M_PI / 180, 60 * M_PI / 180 };
	struct ad_result r;
	ad_run(&s, OPTICS_FRESNEL_EXACT, th, 2, 18, &r);
	int n = 0, n3 = 0;
	double zmax = 0.0, chi2 = 0.0, sig = 0.0;
	for (int k = 0; k < 2; k++) {
		static struct mc_table m;
		mc_nee(&s, OPTICS_FRESNEL_EXACT, th[k], 18, 18, 2000, 100, 22 + (uint64_t)k, &m);
		double sk = 0.0;
		for (int i = 0; i < 18 * 18; i++) {
			double e = sqrt(m.err[i] * m.err[i] + r.beam[k].fr_err[i] * r.beam[k].fr_err[i]);
			double z = (m.fr[i] - r.beam[k].fr[i]) / e;
			zmax = fmax(zmax, fabs(z));
			chi2 += z * z;
			n3 += fabs(z) > 3.0;
			n++;
			sk += pow(m.err[i] / m.fr[i], 2);
		}
		sig = fmax(sig, sqrt(sk / (18 * 18)));
		print_message("# %g deg: MC %.1f s\n", th[k] * 180 / M_PI, m.seconds);
	}
	print_message("# %d bins: MC sigma RMS up to %.2f%%, |z| up to %.2f, %d beyond 3 sigma, chi2/bin %.2f\n", n,
	    100 * sig, zmax, n3, chi2 / n);
	assert_true(zmax < 4.0);
	assert_true(n3 <= n / 100);
	assert_true(chi2 / n < 2.0);
	ad_result_free(&r);
}

/* Totals against the escape-based tallies of sim_run. */
static void totals(const char *name, const struct slab *s, enum optics_fresnel fm, double th, long photons,
    uint32_t stream)
{
	struct ad_result r;
	ad_run(s, fm, &th, 1, 18, &r);
	struct sim_config c;
	struct sim_result m;
	sim_config_default(&c);
	c.slab = *s;
	c.theta_in = th;
	c.opts.fresnel = fm;
	c.photons = photons;
	c.grid.n_r = 0;
	c.seed = 5;
	c.stream = stream;
	sim_run(&c, &m, NULL, NULL);
	const struct ad_beam *b = &r.beam[0];
	assert_float_equal(b->rsp, m.rsp, 1e-15);
	double z = (m.rd.v - b->rd.v) / m.rd.err;
	print_message("# %s: Rd AD %.6f MC %.6f +- %.6f (%.1f sigma), Tt AD %.3g MC %.3g +- %.2g; MC %.1f s\n", name,
	    b->rd.v, m.rd.v, m.rd.err, z, b->tt.v, m.tt.v, m.tt.err, m.seconds);
	assert_true(fabs(z) <= 3.0);
	assert_true(fabs(m.tt.v - b->tt.v) <= 3.0 * m.tt.err + 1e-12);
	for (int l = 1; l <= s->n_layers; l++) {
		double d = m.a[l].v - b->a[l].v;
		if (!(fabs(d) <= 3.0 * m.a[l].err + 1e-12))
			fail_msg("%s layer %d: A AD %.6g MC %.6g +- %.2g", name, l, b->a[l].v, m.a[l].v, m.a[l].err);
	}
	sim_result_free(&m);
	ad_result_free(&r);
}

static void test_totals_oblique(void **state)
{
	(void)state;
	struct slab s;
	mkslab(&s, 1.0, 1.4, 3, skin3);
	totals("skin3 34 deg", &s, OPTICS_FRESNEL_EXACT, 34 * M_PI / 180, 400000, 1);
	totals("skin3 60 deg", &s, OPTICS_FRESNEL_EXACT, 60 * M_PI / 180, 400000, 2);
}

static void test_four_indices_schlick(void **state)
{
	(void)state;
	struct slab s;
	mkslab(&s, 1.0, 1.44, 4, four);
	double th = 45 * M_PI / 180;
	totals("four indices, Schlick, 45 deg", &s, OPTICS_FRESNEL_SCHLICK, th, 300000, 3);
	struct ad_result r;
	ad_run(&s, OPTICS_FRESNEL_SCHLICK, &th, 1, 18, &r);
	static struct mc_table m;
	mc_nee(&s, OPTICS_FRESNEL_SCHLICK, th, 18, 1, 5000, 100, 23, &m);
	check_bands("four indices, Schlick, 45 deg", &r.beam[0], &m);
	ad_result_free(&r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_bands_normal),
		cmocka_unit_test(test_tables_oblique),
		cmocka_unit_test(test_totals_oblique),
		cmocka_unit_test(test_four_indices_schlick),
	};
	return cmocka_run_group_tests_name("ad_mc", tests, NULL, NULL);
}
