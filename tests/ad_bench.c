/* Benchmark of the adding-doubling solver on the presets' stacks at the
 * bake's default table (18 x 18 bins, 10 incidence nodes 0, 9, ..., 81 deg)
 * and tolerance 1e-3 (table RMS error estimate), three ways:
 *   wl-parallel: wavelengths over OpenMP threads, one thread per solve;
 *   orders:      wavelengths one after another, Fourier orders over threads;
 *   serial:      one thread (per-wavelength times).
 * With --check it also solves every wavelength at 64 nodes per unit cosine
 * and tolerance 1e-6 and prints the actual table RMS error of the 1e-3
 * solve against that (the estimate should be above it).
 *   usage: ad_bench [--check] [PRESET ...]   (default: paper fair-oily)
 * --slab A,TAU,G,N,Q,REPS times REPS solves of one slab (albedo A, optical
 * thickness TAU, anisotropy G, index N in air, normal incidence, the m = 0
 * order only, Q nodes per unit cosine, with and without the error estimate)
 * and prints R (specular included) and T (unscattered included), as Prahl's
 * `ad` reports UR1 and UT1 (scripts/bench-iad.sh compares the two).
 * Built by `make check` but not run by it: timings are not tests. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "engine/ad.h"
#include "skin/preset.h"
#include "skin/tissue.h"
#include "base/util.h"

#define NTI 10

static int solve(const struct slab *s, int threads, double tol, int nq, struct ad_result *r)
{
	struct ad_opts o;
	char *cause = NULL;
	double th[NTI];
	for (int k = 0; k < NTI; k++)
		th[k] = 0.5 * M_PI * k / NTI;
	ad_opts_default(&o);
	o.tol = tol;
	o.n_quad = nq;
	o.threads = threads;
	if (nq >= 64)
		o.dtau_frac = 1.0 / 128.0;	/* the reference: the thinnest start, whatever the default */
	else if (getenv("AD_DTAU_FRAC"))
		o.dtau_frac = atof(getenv("AD_DTAU_FRAC"));
	if (ad_solve(s, OPTICS_FRESNEL_EXACT, th, NTI, &o, r, &cause)) {
		fprintf(stderr, "ad_bench: %s\n", cause);
		free(cause);
		return -1;
	}
	return 0;
}

/* Solid-angle-weighted RMS relative difference of two tables. */
static double table_rms(const struct ad_result *a, const struct ad_result *b)
{
	double num = 0.0, den = 0.0;
	for (int k = 0; k < a->n_beams; k++)
		for (int i = 0; i < a->n_to * a->n_phi; i++) {
			int it = i / a->n_phi;
			double w = cos(it * 0.5 * M_PI / a->n_to) - cos((it + 1) * 0.5 * M_PI / a->n_to);
			double x = b->beam[k].fr[i], rel = x != 0.0 ? (a->beam[k].fr[i] - x) / x : 0.0;
			num += w * rel * rel;
			den += w;
		}
	return sqrt(num / den);
}

static int bench(const char *name, int check)
{
	char *cause = NULL;
	struct skin_params *p = preset_load_builtin(name, &cause);
	if (!p) {
		fprintf(stderr, "ad_bench: %s\n", cause);
		return -1;
	}
	double wl[SKIN_MAX_WL];
	int n = preset_default_wavelengths(p, wl, SKIN_MAX_WL);
	struct slab *s = xcalloc((size_t)n, sizeof *s);
	for (int i = 0; i < n; i++)
		if (tissue_slab(p, wl[i], &s[i], &cause) || slab_check(&s[i], &cause)) {
			fprintf(stderr, "ad_bench: %s\n", cause);
			return -1;
		}
	for (int i = 0; i < n; i++)
		slab_prepare(&s[i]);
	preset_free(p);
	int nt = 1;
#ifdef _OPENMP
	nt = omp_get_max_threads();
#endif
	struct ad_result *r = xcalloc((size_t)n, sizeof *r);
	int fail = 0;
	double t0 = util_now();
#pragma omp parallel for schedule(dynamic, 1) reduction(| : fail)
	for (int i = 0; i < n; i++) {
		fail |= solve(&s[i], 1, 1e-3, 0, &r[i]) != 0;
	}
	double t_wl = util_now() - t0;
	if (fail)
		return -1;
	for (int i = 0; i < n; i++)
		ad_result_free(&r[i]);
	t0 = util_now();
	for (int i = 0; i < n && !fail; i++) {
		fail |= solve(&s[i], nt, 1e-3, 0, &r[i]) != 0;
		if (!fail)
			ad_result_free(&r[i]);
	}
	double t_ord = util_now() - t0;
	printf("preset %s: %d wavelengths x %d angles, 18 x 18 bins, tol 1e-3\n", name, n, NTI);
	printf("  wall: %.3f s wavelengths over %d threads, %.3f s orders over %d threads\n", t_wl, nt, t_ord, nt);
	printf("  %-7s %-7s %-6s %-7s %-10s %-10s %s\n", "wl_nm", "n_quad", "nodes", "orders", "rms_est", "seconds",
	    check ? "rms_actual" : "");
	double t_ser = 0.0, worst = 0.0;
	for (int i = 0; i < n && !fail; i++) {
		struct ad_result ref;
		fail |= solve(&s[i], 1, 1e-3, 0, &r[i]) != 0;
		if (fail)
			break;
		t_ser += r[i].seconds;
		printf("  %-7g %-7d %-6d %-7d %-10.2e %-10.4f", wl[i], r[i].n_quad, r[i].n_nodes, r[i].n_orders,
		    r[i].rms_rel_err, r[i].seconds);
		if (check && solve(&s[i], nt, 1e-6, 64, &ref) == 0) {
			double a = table_rms(&r[i], &ref);
			worst = fmax(worst, a);
			printf(" %.2e", a);
			ad_result_free(&ref);
		}
		printf("\n");
		ad_result_free(&r[i]);
	}
	printf("  serial (1 thread): %.3f s in all, %.4f s per wavelength\n", t_ser, t_ser / n);
	if (check)
		printf("  largest actual table RMS error: %.2e\n", worst);
	free(r);
	free(s);
	return fail ? -1 : 0;
}

static double cpu_seconds(void)
{
	struct timespec t;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* One slab REPS times (see the top); prints R, T and CPU ms per solve. */
static int bench_slab(const char *spec)
{
	double a, tau, g, n;
	int q, reps;
	if (sscanf(spec, "%lf,%lf,%lf,%lf,%d,%d", &a, &tau, &g, &n, &q, &reps) != 6 || reps < 1) {
		fprintf(stderr, "ad_bench: --slab wants A,TAU,G,N,Q,REPS\n");
		return -1;
	}
	struct slab s;
	char *cause = NULL;
	struct layer l = { .d = 1.0, .n = n, .mu_a = tau * (1.0 - a), .mu_s = tau * a, .g = g };
	slab_init(&s, 1.0, 1.0);
	if (slab_add(&s, &l, &cause) || slab_check(&s, &cause)) {
		fprintf(stderr, "ad_bench: %s\n", cause);
		return -1;
	}
	slab_prepare(&s);
	for (int est = 1; est >= 0; est--) {
		struct ad_opts o;
		struct ad_result r;
		double th = 0.0;
		ad_opts_default(&o);
		o.n_quad = q;
		o.max_orders = 1;
		o.threads = 1;
		o.error_estimate = est;
		o.n_to = o.n_phi = 1;
		if (getenv("AD_DTAU_FRAC"))
			o.dtau_frac = atof(getenv("AD_DTAU_FRAC"));
		double c0 = cpu_seconds();
		for (int k = 0; k < reps; k++) {
			if (ad_solve(&s, OPTICS_FRESNEL_EXACT, &th, 1, &o, &r, &cause)) {
				fprintf(stderr, "ad_bench: %s\n", cause);
				return -1;
			}
			if (k + 1 < reps)
				ad_result_free(&r);
		}
		double ms = 1e3 * (cpu_seconds() - c0) / reps;
		printf("q %d estimate %d R %.8f T %.8f Rerr %.2e Terr %.2e nodes %d doublings %ld ms_per_solve %.4f\n",
		    q, est, r.beam[0].rsp + r.beam[0].rd.v, r.beam[0].tt.v, r.beam[0].rd.err, r.beam[0].tt.err, r.n_nodes,
		    r.doublings, ms);
		ad_result_free(&r);
	}
	return 0;
}

int main(int argc, char **argv)
{
	if (argc == 3 && strcmp(argv[1], "--slab") == 0)
		return bench_slab(argv[2]) ? 1 : 0;
	int check = 0, n = 0;
	const char *names[64];
	for (int i = 1; i < argc; i++) {
		if (strcmp(argv[i], "--check") == 0)
			check = 1;
		else if (n < 64)
			names[n++] = argv[i];
	}
	if (n == 0) {
		names[n++] = "paper";
		names[n++] = "fair-oily";
	}
	for (int i = 0; i < n; i++)
		if (bench(names[i], check))
			return 1;
	return 0;
}
