/* brdf_model: a preset's BRDF at many geometries from the adding-doubling
 * solver (engine/ad.h), without a bake: the deterministic model evaluation of
 * the CUReT fit (scripts/fit-curet.py --solver ad) and of its checks.
 * Diffuse part: ad_brdf at the point (the Monte Carlo bake gives bin means);
 * specular part: the bake's analytic GGX lobe (specular_ggx on the clear top
 * stack, specular_stack_of_slab, roughness preset_surface_roughness or
 * --alpha).  Output columns as tests/brdf_points: total, diffuse, specular
 * [1/sr], each the mean over the wavelengths, and the solver's error estimate
 * of the diffuse mean.
 *
 *   brdf_model (--preset NAME | --preset-file F) [--wavelengths LIST]
 *              [--alpha A] [--tol T] [--nodes N] [--no-ms-lobe] < points
 *
 * Input lines: theta_i theta_o delta_phi [deg] (delta_phi 0 = back toward
 * the light, 180 = mirror side); '#' lines are skipped.  Default wavelengths
 * 470, 550, 656 nm (the camera's B, G, R stand-ins of docs/presets.md);
 * default tolerance 1e-3 (the solver's table RMS error estimate); --nodes N
 * solves once at N nodes per unit cosine instead, without error estimates
 * (the fit's fast path: scripts/fit-curet.py --nodes).
 *
 * With a mm-scale relief ([surface] macro_slope > 0, or --macro M) both
 * parts are integrated over the tilted facets (engine/macro.h, as
 * bake_eval_* do for a bake): the solver then runs at fixed incidence
 * angles (every 2 deg to 88, then 89 and 89.5) and the diffuse part is
 * interpolated linearly between them; the lobe is evaluated where needed. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/ad.h"
#include "engine/macro.h"
#include "engine/microfacet_ms.h"
#include "engine/specular.h"
#include "skin/preset.h"
#include "skin/tissue.h"
#include "base/util.h"

#define MAX_POINTS 100000

static int usage(void)
{
	fprintf(stderr, "usage: brdf_model (--preset NAME | --preset-file F) [--wavelengths LIST] [--alpha A] "
	    "[--tol T] [--nodes N] [--macro M] [--no-ms-lobe] < points (theta_i theta_o delta_phi in deg)\n");
	return 2;
}

/* The facet-scale BRDF at one wavelength for the macro integral: diffuse
 * (linear in theta_i between the solved angles), its error, the lobe. */
struct facet_ctx {
	const struct ad_result *r;
	const double *th;	/* [n_th] solved incidence angles [rad], ascending */
	int n_th;
	const struct specular_stack *st;
	double alpha;
	const struct microfacet_ms *ms;	/* the facets' later reflections, or NULL */
};

static void facet_at(void *ctx, double ti, double to, double ph, double *out)
{
	const struct facet_ctx *c = ctx;
	int k = 0;
	while (k + 2 < c->n_th && c->th[k + 1] < ti)
		k++;
	double t = (ti - c->th[k]) / (c->th[k + 1] - c->th[k]), e0, e1;
	t = fmin(fmax(t, 0.0), 1.0);
	double f0 = ad_brdf(c->r, k, to, ph, &e0), f1 = ad_brdf(c->r, k + 1, to, ph, &e1);
	out[0] = (1.0 - t) * f0 + t * f1;
	out[1] = (1.0 - t) * e0 + t * e1;
	out[2] = specular_ggx(c->st, c->alpha, ti, to, ph);
	if (c->ms)
		out[2] += microfacet_ms_eval(c->ms, cos(ti), cos(to));
}

/* Index of theta in the list of distinct incidence angles, added if new. */
static int angle_index(double *th, int *n, double t)
{
	for (int k = 0; k < *n; k++)
		if (fabs(th[k] - t) < 1e-12)
			return k;
	if (*n >= AD_MAX_BEAMS)
		return -1;
	th[*n] = t;
	return (*n)++;
}

int main(int argc, char **argv)
{
	const char *name = NULL, *file = NULL, *wls = "470,550,656";
	double alpha = -1.0, tol = 1e-3, macro = -1.0;
	int nodes = 0, ms_lobe = 1;
	for (int i = 1; i < argc; i++) {
		if (strcmp(argv[i], "--no-ms-lobe") == 0) {
			ms_lobe = 0;
			continue;
		}
		if (i + 1 >= argc)
			return usage();
		char *end = NULL;
		if (strcmp(argv[i], "--preset") == 0)
			name = argv[++i];
		else if (strcmp(argv[i], "--preset-file") == 0)
			file = argv[++i];
		else if (strcmp(argv[i], "--wavelengths") == 0)
			wls = argv[++i];
		else if (strcmp(argv[i], "--alpha") == 0) {
			alpha = strtod(argv[++i], &end);
			if (*end != '\0' || !(alpha >= 0.01 && alpha <= 1.0)) {
				fprintf(stderr, "brdf_model: --alpha %s: not a number in [0.01, 1]\n", argv[i]);
				return 2;
			}
		} else if (strcmp(argv[i], "--tol") == 0) {
			tol = strtod(argv[++i], &end);
			if (*end != '\0' || !(tol > 0.0 && tol <= 0.1)) {
				fprintf(stderr, "brdf_model: --tol %s: not a number in (0, 0.1]\n", argv[i]);
				return 2;
			}
		} else if (strcmp(argv[i], "--macro") == 0) {
			macro = strtod(argv[++i], &end);
			if (*end != '\0' || !(macro >= 0.0 && macro <= MACRO_SLOPE_MAX)) {
				fprintf(stderr, "brdf_model: --macro %s: not a number in [0, %g]\n", argv[i],
				    MACRO_SLOPE_MAX);
				return 2;
			}
		} else if (strcmp(argv[i], "--nodes") == 0) {
			nodes = (int)strtol(argv[++i], &end, 10);
			if (*end != '\0' || nodes < 4 || nodes > 1024) {
				fprintf(stderr, "brdf_model: --nodes %s: not an integer in [4, 1024]\n", argv[i]);
				return 2;
			}
		} else
			return usage();
	}
	if ((name == NULL) == (file == NULL))
		return usage();
	char *cause = NULL;
	struct skin_params *p = name ? preset_load_builtin(name, &cause) : preset_load_file(file, &cause);
	double wl[SKIN_MAX_WL];
	int n_wl = p ? preset_parse_wavelengths(wls, wl, &cause) : -1;
	if (p == NULL || n_wl < 0) {
		fprintf(stderr, "brdf_model: %s\n", cause);
		free(cause);
		preset_free(p);
		return 2;
	}
	if (alpha < 0.0)
		alpha = preset_surface_roughness(p);
	if (macro < 0.0)
		macro = p->macro_slope;
	static struct macro_rule rule;
	macro_rule_init(&rule, macro, MACRO_NQ);

	/* The points, and their distinct incidence angles. */
	double (*pt)[3] = xcalloc(MAX_POINTS, sizeof *pt);
	int *beam = xcalloc(MAX_POINTS, sizeof *beam);
	double th[AD_MAX_BEAMS];
	int n_th = 0, n = 0, rc = 0;
	char line[512];
	const double rad = M_PI / 180.0;
	while (fgets(line, sizeof line, stdin)) {
		if (line[0] == '#' || line[0] == '\n')
			continue;
		double *q = pt[n];
		if (n >= MAX_POINTS || sscanf(line, "%lf %lf %lf", &q[0], &q[1], &q[2]) != 3 || !(q[0] >= 0 && q[0] < 90)
		    || !(q[1] >= 0 && q[1] <= 90) || !(q[2] >= 0 && q[2] <= 360)) {
			fprintf(stderr, "brdf_model: point %d: expected theta_i theta_o delta_phi in degrees (theta_i in "
			    "[0, 90), theta_o in [0, 90], delta_phi in [0, 360]; at most %d points)\n", n + 1, MAX_POINTS);
			rc = 2;
			goto out;
		}
		if ((beam[n] = angle_index(th, &n_th, q[0] * rad)) < 0) {
			fprintf(stderr, "brdf_model: more than %d incidence angles\n", AD_MAX_BEAMS);
			rc = 2;
			goto out;
		}
		n++;
	}
	if (rule.n > 0) {	/* the relief: fixed incidence angles, not the points' own */
		n_th = 0;
		for (int d = 0; d <= 88; d += 2)
			th[n_th++] = d * rad;
		th[n_th++] = 89.0 * rad;
		th[n_th++] = 89.5 * rad;
	}
	double *fd = xcalloc((size_t)n * 3, sizeof *fd), *fs = fd + n, *ve = fs + n;
	struct ad_opts o;
	ad_opts_default(&o);
	o.tol = tol;
	if (nodes > 0) {
		o.n_quad = nodes;
		o.error_estimate = 0;
	}
	struct microfacet_ms ms = { .alpha = -1.0 };
	for (int w = 0; w < n_wl && rc == 0; w++) {
		struct slab s;
		struct ad_result r;
		struct specular_stack st;
		if (tissue_slab(p, wl[w], &s, &cause) != 0 || ad_solve(&s, OPTICS_FRESNEL_EXACT, th, n_th, &o, &r, &cause) != 0) {
			fprintf(stderr, "brdf_model: %s at %g nm: %s\n", preset_get_name(p), wl[w], cause);
			free(cause);
			rc = 1;
			break;
		}
		specular_stack_of_slab(&s, OPTICS_FRESNEL_EXACT, &st);
		/* Multiple scattering on a rough top: the lobe of its later
		 * reflections (engine/microfacet_ms.h), as eval adds it to a bake's. */
		const struct microfacet_ms *msp = NULL;
		if (ms_lobe && s.rough_ms && s.rough_top && alpha > 0.0) {
			if (!(ms.alpha == alpha && ms.n_i == st.n_list[0] && ms.n_t == st.n_list[1]))
				microfacet_ms_init(&ms, alpha, st.n_list[0], st.n_list[1], OPTICS_FRESNEL_EXACT, 0);
			msp = &ms;
		}
		struct facet_ctx fc = { &r, th, n_th, &st, alpha, msp };
		for (int i = 0; i < n && rule.n > 0; i++) {
			double v[3], ph = pt[i][2] > 180.0 ? 360.0 - pt[i][2] : pt[i][2];
			macro_eval(&rule, facet_at, &fc, 3, pt[i][0] * rad, pt[i][1] * rad, ph * rad,
			    v);
			fd[i] += v[0] / n_wl;
			ve[i] += v[1] * v[1];
			fs[i] += v[2] / n_wl;
		}
		for (int i = 0; i < n && rule.n == 0; i++) {
			double e, ph = pt[i][2] > 180.0 ? 360.0 - pt[i][2] : pt[i][2];
			fd[i] += ad_brdf(&r, beam[i], pt[i][1] * rad, ph * rad, &e) / n_wl;
			fs[i] += specular_ggx(&st, alpha, pt[i][0] * rad, pt[i][1] * rad, ph * rad) / n_wl;
			if (msp)
				fs[i] += microfacet_ms_eval(msp, cos(pt[i][0] * rad), cos(pt[i][1] * rad)) / n_wl;
			ve[i] += e * e;
		}
		ad_result_free(&r);
	}
	for (int i = 0; i < n && rc == 0; i++)
		printf("%.6g\t%.6g\t%.6g\t%.3g\n", fd[i] + fs[i], fd[i], fs[i], sqrt(ve[i]) / n_wl);
	free(fd);
out:
	free(pt);
	free(beam);
	preset_free(p);
	return rc;
}
