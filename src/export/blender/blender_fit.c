/* blender_fit: least-squares fit of the general mode's closure mixture (see
 * blender_fit.h) to a BRDF, and its error on a grid off the fit nodes. */
#include "config.h"

#include "export/blender/blender_fit.h"

#include <json-c/json.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export/blender/blender_detail.h"
#include "engine/specular.h"
#include "base/util.h"
#include "io/json.h"

enum {
	FIT_N_COSL = 24,	/* light cosines per view node */
	FIT_N_PHI = 19,		/* azimuths over [0, pi] */
	CHECK_N_COSV = 30,	/* view cosines of the error grid, between the fit nodes */
	N_EXPONENTS = 7
};
static const double exponents[N_EXPONENTS] = { 2, 3, 4, 6, 8, 12, 16 };

static double clamp01(double x)
{
	return x < 0 ? 0 : x > 1 ? 1 : x;
}

/* pi f / base of Cycles 3.x's Principled BSDF with random-walk subsurface:
 * the exit's Disney light falloff 1 - F_L / 2 plus the diffuse
 * retro-reflection term of roughness r, RR (F_L + F_V + F_L F_V (RR - 1)),
 * RR = r (1 + l.v), F = (1 - cos)^5.  Cycles 4.x and 5.x: 1 (the view and
 * base dependence is the importer's, see blender_fit.h). */
static double sss_basis(enum blender_fit_model model, double cl, double cv, double dphi)
{
	if (model == BLENDER_FIT_LAMBERT)
		return 1.0;
	double fl = pow(1.0 - cl, 5), fv = pow(1.0 - cv, 5);
	double rr = BLENDER_FIT_SSS_ROUGHNESS * (1.0 + cl * cv + sqrt((1 - cl * cl) * (1 - cv * cv)) * cos(dphi));
	return 1.0 - 0.5 * fl + rr * (fl + fv + fl * fv * (rr - 1.0));
}

/* pi f of Cycles' Ashikhmin-Shirley glossy lobe (isotropic, exponent e). */
static double as_pi_f(double e, double cl, double cv, double dphi)
{
	double sl = sqrt(1.0 - cl * cl), sv = sqrt(1.0 - cv * cv);
	double h[3] = { sl + sv * cos(dphi), sv * sin(dphi), cl + cv };
	double hn = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
	if (hn <= 0)
		return 0.0;
	double hz = h[2] / hn, hl = (sl * h[0] + cl * h[2]) / hn;
	if (hl < 1e-6)
		hl = 1e-6;
	return (e + 1.0) / 8.0 * pow(hz, e) / (hl * (cl > cv ? cl : cv));
}

static double spec_pi_f(const struct specular_stack *st, double alpha, double cl, double cv,
    double dphi)
{
	return M_PI * specular_ggx(st, alpha, acos(cl), acos(cv), dphi);
}

/* Weights at view cosine cv: weighted non-negative least squares of
 * s SSS(l, v) + g AS(l, v) against pi f - spec, relative error, weight cl cv. */
static void fit_node(enum blender_fit_model model, const double *pf, const double *spec,
    const double *as, double cmin, double cv, double s[3], double g[3])
{
	for (int c = 0; c < 3; c++) {
		double xx = 0, xy = 0, yy = 0, xr = 0, yr = 0;
		for (int i = 0; i < FIT_N_COSL; i++) {
			double cl = cmin + (1.0 - cmin) * i / (FIT_N_COSL - 1);
			for (int k = 0; k < FIT_N_PHI; k++) {
				size_t at = (size_t)i * FIT_N_PHI + (size_t)k;
				double t = pf[3 * at + (size_t)c];
				if (!(t > 0))
					continue;
				double x = sss_basis(model, cl, cv, M_PI * k / (FIT_N_PHI - 1));
				double w = cl * cv / (t * t), y = as[at], r = t - spec[at];
				xx += w * x * x;
				xy += w * x * y;
				yy += w * y * y;
				xr += w * x * r;
				yr += w * y * r;
			}
		}
		double det = xx * yy - xy * xy, a = -1, b = -1;
		if (det > 1e-12 * xx * yy) {
			a = (xr * yy - yr * xy) / det;
			b = (yr * xx - xr * xy) / det;
		}
		if (!(a >= 0 && b >= 0)) {
			/* One term only: the better of the two (objective up to a constant). */
			double a1 = xx > 0 && xr > 0 ? xr / xx : 0, b1 = yy > 0 && yr > 0 ? yr / yy : 0;
			double ga = a1 * a1 * xx - 2 * a1 * xr, gb = b1 * b1 * yy - 2 * b1 * yr;
			a = ga <= gb ? a1 : 0;
			b = ga <= gb ? 0 : b1;
		}
		s[c] = a;
		g[c] = b;
	}
}

void blender_fit_eval(const struct blender_fit *fit, double cos_l, double cos_v, double dphi,
    double pi_f[3])
{
	struct specular_stack st = { .n = 2, .n_list = { 1.0, fit->spec_ior }, .model = OPTICS_FRESNEL_EXACT };
	double cl = clamp01(cos_l), cv = clamp01(cos_v);
	double x = cv * (fit->n_view - 1);
	int j = (int)floor(x);
	if (j > fit->n_view - 2)
		j = fit->n_view - 2;
	double t = x - j, d = sss_basis(fit->model, cl, cv, dphi), a = as_pi_f(fit->glossy_exponent, cl, cv, dphi);
	double sp = fit->specular ? spec_pi_f(&st, fit->spec_alpha, cl, cv, dphi) : 0.0;
	for (int c = 0; c < 3; c++) {
		double s = (1 - t) * fit->sss_rgb[j][c] + t * fit->sss_rgb[j + 1][c];
		double g = (1 - t) * fit->glossy_rgb[j][c] + t * fit->glossy_rgb[j + 1][c];
		pi_f[c] = s * d + g * a + sp;
	}
}

/* Fill fit's weights for exponent e from the tabulated BRDF (pf at the fit
 * nodes, NULL rows below cos_min) and its specular. */
static void fit_all(struct blender_fit *fit, double e, double *const *pf, const double *spec,
    double *as)
{
	int first = -1;
	for (int j = 0; j < fit->n_view; j++) {
		if (pf[j] == NULL)
			continue;
		double cv = (double)j / (fit->n_view - 1);
		for (int i = 0; i < FIT_N_COSL; i++) {
			double cl = fit->cos_min + (1.0 - fit->cos_min) * i / (FIT_N_COSL - 1);
			for (int k = 0; k < FIT_N_PHI; k++)
				as[(size_t)i * FIT_N_PHI + (size_t)k] = as_pi_f(e, cl, cv, M_PI * k / (FIT_N_PHI - 1));
		}
		fit_node(fit->model, pf[j], spec + (size_t)j * FIT_N_COSL * FIT_N_PHI, as, fit->cos_min, cv, fit->sss_rgb[j],
		    fit->glossy_rgb[j]);
		if (first < 0)
			first = j;
	}
	/* Grazing views below the fitted range keep the first fitted node's weights. */
	for (int j = 0; j < first; j++) {
		memcpy(fit->sss_rgb[j], fit->sss_rgb[first], sizeof fit->sss_rgb[j]);
		memcpy(fit->glossy_rgb[j], fit->glossy_rgb[first], sizeof fit->glossy_rgb[j]);
	}
	fit->glossy_exponent = e;
	fit->glossy_roughness = sqrt(sqrt(2.0 / (e + 2.0)));
}

/* Errors of the current weights on the check grid (tabulated in chk). */
static void fit_errors(struct blender_fit *fit, const double *chk)
{
	double sw[3] = { 0 }, su[3] = { 0 }, wsum = 0;
	int n = 0;
	memset(fit->max_rel, 0, sizeof fit->max_rel);
	for (int jv = 0; jv < CHECK_N_COSV; jv++) {
		double cv = fit->cos_min + (1.0 - fit->cos_min) * (jv + 0.5) / CHECK_N_COSV;
		for (int i = 0; i < FIT_N_COSL; i++) {
			double cl = fit->cos_min + (1.0 - fit->cos_min) * i / (FIT_N_COSL - 1);
			for (int k = 0; k < FIT_N_PHI; k++) {
				const double *t = chk + 3 * (((size_t)jv * FIT_N_COSL + (size_t)i) * FIT_N_PHI + (size_t)k);
				double pm[3];
				if (!(t[0] > 0 && t[1] > 0 && t[2] > 0))
					continue;
				blender_fit_eval(fit, cl, cv, M_PI * k / (FIT_N_PHI - 1), pm);
				for (int c = 0; c < 3; c++) {
					double r = pm[c] / t[c] - 1.0;
					sw[c] += cl * cv * r * r;
					su[c] += r * r;
					if (fabs(r) > fit->max_rel[c])
						fit->max_rel[c] = fabs(r);
				}
				wsum += cl * cv;
				n++;
			}
		}
	}
	for (int c = 0; c < 3; c++) {
		fit->rms_weighted[c] = n ? sqrt(sw[c] / wsum) : INFINITY;
		fit->rms_uniform[c] = n ? sqrt(su[c] / n) : INFINITY;
	}
	fit->n_checked = n;
}

static double score(const struct blender_fit *f)
{
	return (f->rms_weighted[0] + f->rms_weighted[1] + f->rms_weighted[2]) / 3.0;
}

int blender_fit_general(const struct brdf_source *m, struct blender_fit *fit, char **cause)
{
	return blender_fit_general_model(m, BLENDER_FIT_CYCLES3, fit, cause);
}

int blender_fit_general_model(const struct brdf_source *m, enum blender_fit_model model,
    struct blender_fit *fit, char **cause)
{
	memset(fit, 0, sizeof *fit);
	fit->model = model;
	fit->n_view = BLENDER_FIT_VIEW_NODES;
	fit->spec_ior = m->ior;
	fit->spec_alpha = m->roughness > 1e-4 ? m->roughness : 1e-4;
	double cmin = cos(m->theta_albedo[m->n_albedo - 1]);
	fit->cos_min = cmin > 0.1 ? cmin : 0.1;
	struct specular_stack st = { .n = 2, .n_list = { 1.0, fit->spec_ior }, .model = OPTICS_FRESNEL_EXACT };
	size_t per = (size_t)FIT_N_COSL * FIT_N_PHI;
	double *pf[BLENDER_FIT_VIEW_NODES] = { NULL };
	double *spec = xcalloc((size_t)fit->n_view * per, sizeof *spec);
	double *as = xmalloc(per * sizeof *as);
	double *chk = xmalloc((size_t)CHECK_N_COSV * per * 3 * sizeof *chk);
	double rgb[3];
	for (int j = 0; j < fit->n_view; j++) {
		double cv = (double)j / (fit->n_view - 1);
		if (cv < fit->cos_min - 1e-12)
			continue;
		pf[j] = xmalloc(per * 3 * sizeof *pf[j]);
		for (int i = 0; i < FIT_N_COSL; i++) {
			double cl = fit->cos_min + (1.0 - fit->cos_min) * i / (FIT_N_COSL - 1);
			for (int k = 0; k < FIT_N_PHI; k++) {
				double ph = M_PI * k / (FIT_N_PHI - 1);
				size_t at = (size_t)i * FIT_N_PHI + (size_t)k;
				m->f_rgb(m->ctx, acos(cl), acos(cv), ph, rgb);
				for (int c = 0; c < 3; c++)
					pf[j][3 * at + (size_t)c] = M_PI * rgb[c];
				spec[(size_t)j * per + at] = spec_pi_f(&st, fit->spec_alpha, cl, cv, ph);
			}
		}
	}
	for (int jv = 0; jv < CHECK_N_COSV; jv++) {
		double cv = fit->cos_min + (1.0 - fit->cos_min) * (jv + 0.5) / CHECK_N_COSV;
		for (int i = 0; i < FIT_N_COSL; i++) {
			double cl = fit->cos_min + (1.0 - fit->cos_min) * i / (FIT_N_COSL - 1);
			for (int k = 0; k < FIT_N_PHI; k++) {
				m->f_rgb(m->ctx, acos(cl), acos(cv), M_PI * k / (FIT_N_PHI - 1), rgb);
				for (int c = 0; c < 3; c++)
					chk[3 * (((size_t)jv * FIT_N_COSL + (size_t)i) * FIT_N_PHI + (size_t)k) + (size_t)c] =
					    M_PI * rgb[c];
			}
		}
	}
	/* Every exponent, with the model's specular lobe and without it (a BRDF
	 * that has none, such as the tests' analytic one). */
	struct blender_fit best = *fit, trial;
	double best_score = INFINITY;
	double *nospec = xcalloc((size_t)fit->n_view * per, sizeof *nospec);
	for (int sp = 1; sp >= 0; sp--)
		for (int x = 0; x < N_EXPONENTS; x++) {
			trial = *fit;
			trial.specular = sp;
			fit_all(&trial, exponents[x], pf, sp ? spec : nospec, as);
			fit_errors(&trial, chk);
			if (score(&trial) < best_score) {
				best_score = score(&trial);
				best = trial;
			}
		}
	free(nospec);
	for (int j = 0; j < fit->n_view; j++)
		free(pf[j]);
	free(spec);
	free(as);
	free(chk);
	if (!isfinite(best_score) || best.n_checked == 0) {
		*cause = xasprintf("general-mode fit: the BRDF has no positive values over cos >= %.3g", fit->cos_min);
		return -1;
	}
	*fit = best;
	return 0;
}

static json_object *jd(double v)
{
	return json_num_g(v, 9);
}

static json_object *jvec(const double *v, int n)
{
	return json_num_g_array(v, n, 9);
}

static const char *const fit_model_name[] = { "skinbake-cycles3-mix-1", "skinbake-cycles4-mix-1" };
static const char *const fit_sss_description[] = {
	"pi f = s(v) (1 - F_L / 2 + RR (F_L + F_V + F_L F_V (RR - 1))) with F = (1 - cos)^5, RR = "
	"subsurface_roughness (1 + l.v) [Principled BSDF: subsurface 1 random walk, roughness "
	"subsurface_roughness, specular 0, Base = Subsurface Color = s(v)]",
	"pi f = s(v) [Principled BSDF of Blender 4.x/5.x: subsurface weight 1 random walk, roughness "
	"subsurface_roughness, specular IOR level 0, Base Color b(v) such that Blender's measured response "
	"R(b, cos_view) is s(v) (skinbake_import/calibration.py)]"
};

static json_object *fit_json(const struct blender_fit *f)
{
	json_object *x = json_object_new_object(), *a, *b, *c;
	char *desc = xasprintf("%s + g(v) pi f_AS [Glossy BSDF, Ashikhmin-Shirley, glossy_roughness] + pi f_GGX "
	    "[Principled BSDF: black base, specular_ior, roughness sqrt(specular_alpha)]; s(v), g(v) RGB at "
	    "cos_view_nodes (cos_view = N.I), linear between them", fit_sss_description[f->model]);
	json_object_object_add(x, "model", json_object_new_string(fit_model_name[f->model]));
	json_object_object_add(x, "description", json_object_new_string(desc));
	free(desc);
	json_object_object_add(x, "subsurface_roughness", jd(BLENDER_FIT_SSS_ROUGHNESS));
	a = json_object_new_array_ext(f->n_view);
	b = json_object_new_array_ext(f->n_view);
	c = json_object_new_array_ext(f->n_view);
	for (int j = 0; j < f->n_view; j++) {
		json_object_array_add(a, jd((double)j / (f->n_view - 1)));
		json_object_array_add(b, jvec(f->sss_rgb[j], 3));
		json_object_array_add(c, jvec(f->glossy_rgb[j], 3));
	}
	json_object_object_add(x, "cos_view_nodes", a);
	json_object_object_add(x, "subsurface_rgb", b);
	json_object_object_add(x, "glossy_rgb", c);
	json_object_object_add(x, "glossy_distribution", json_object_new_string("ASHIKHMIN_SHIRLEY"));
	json_object_object_add(x, "glossy_exponent", jd(f->glossy_exponent));
	json_object_object_add(x, "glossy_roughness", jd(f->glossy_roughness));
	json_object_object_add(x, "specular", json_object_new_boolean(f->specular));
	json_object_object_add(x, "specular_ior", jd(f->spec_ior));
	json_object_object_add(x, "specular_alpha", jd(f->spec_alpha));
	json_object_object_add(x, "cos_min", jd(f->cos_min));
	json_object_object_add(x, "rms_error", jd((f->rms_weighted[0] + f->rms_weighted[1] + f->rms_weighted[2]) / 3));
	json_object_object_add(x, "rms_error_rgb", jvec(f->rms_weighted, 3));
	json_object_object_add(x, "rms_error_uniform_rgb", jvec(f->rms_uniform, 3));
	json_object_object_add(x, "max_error_rgb", jvec(f->max_rel, 3));
	json_object_object_add(x, "checked_directions", json_object_new_int(f->n_checked));
	json_object_object_add(x, "error_definition", json_object_new_string(
	    "relative error of the mixture against the exported BRDF at cos_light, cos_view >= cos_min (24 x 30 "
	    "cosines, the view cosines between the fit nodes) and 19 azimuths over [0, 180] deg; rms_error_rgb "
	    "weights each pair of directions by cos_light cos_view (projected solid angle), "
	    "rms_error_uniform_rgb does not; rms_error is the mean of rms_error_rgb"));
	return x;
}

/* Directional albedo at normal view, integral of f cos_l over the light
 * hemisphere: what a white furnace renders looking along the normal. */
static void albedo_normal_view(const struct brdf_source *m, const struct blender_fit *fit, double rgb[3])
{
	enum { NL = 256, NP = 32 };
	double acc[3] = { 0 }, f[3];
	for (int i = 0; i < NL; i++) {
		double cl = (i + 0.5) / NL;
		for (int k = 0; k < NP; k++) {
			double ph = M_PI * (k + 0.5) / NP;
			if (fit != NULL) {
				blender_fit_eval(fit, cl, 1.0, ph, f);
			} else {
				m->f_rgb(m->ctx, acos(cl), 0.0, ph, f);
				for (int c = 0; c < 3; c++)
					f[c] *= M_PI;
			}
			for (int c = 0; c < 3; c++)
				acc[c] += f[c] * cl;
		}
	}
	/* A = 2 int_0^1 int_0^pi f cl dphi dcl, f = pi f / pi. */
	for (int c = 0; c < 3; c++)
		rgb[c] = 2.0 * acc[c] / M_PI * (1.0 / NL) * (M_PI / NP);
}

/* KEY: the fit of MODEL with its furnace values, or null and KEY_error. */
static void add_fit(json_object *j, const struct brdf_source *m, enum blender_fit_model model, const char *key)
{
	struct blender_fit fit;
	char *cause = NULL;
	if (blender_fit_general_model(m, model, &fit, &cause) == 0) {
		double a[3];
		json_object *x = fit_json(&fit);
		albedo_normal_view(m, &fit, a);
		json_object_object_add(x, "furnace_rgb", jvec(a, 3));
		albedo_normal_view(m, NULL, a);
		json_object_object_add(x, "furnace_bake_rgb", jvec(a, 3));
		json_object_object_add(x, "furnace_definition", json_object_new_string(
		    "directional albedo at normal view (integral of f cos_l over the light hemisphere, "
		    "specular included) of the mixture (furnace_rgb) and of the exported BRDF "
		    "(furnace_bake_rgb): a white furnace seen along the normal"));
		json_object_object_add(j, key, x);
	} else {
		char *ek = xasprintf("%s_error", key);
		json_object_object_add(j, key, NULL);
		json_object_object_add(j, ek, json_object_new_string(cause));
		free(ek);
		free(cause);
	}
}

void blender_fit_manifest(json_object *j, const struct brdf_source *m, const double sun[3],
    const double view[3], double sun_strength, const float *lut, int lut_cos, int lut_phi,
    const uint16_t *normal, int w, int h)
{
	json_object *x, *ref;
	add_fit(j, m, BLENDER_FIT_CYCLES3, "general_fit");
	add_fit(j, m, BLENDER_FIT_LAMBERT, "general_fit_v4");
	if (json_object_object_get_ex(j, "detail", &x))
		json_object_object_add(x, "mean_normal_z", jd(blender_detail_mean_nz(normal, (size_t)w * (size_t)h)));
	if (json_object_object_get_ex(j, "exact", &x) && json_object_object_get_ex(x, "reference", &ref)) {
		double rgb[3];
		blender_detail_radiance(normal, w, h, sun, view, sun_strength, lut, lut_cos, lut_phi, rgb);
		json_object_object_add(ref, "radiance_detail_rgb", jvec(rgb, 3));
		json_object_object_add(ref, "radiance_detail_definition", json_object_new_string(
		    "the same plane with the detail normal map, as the exact material renders it: the mean over "
		    "normal.png's texels of E cos_l f_r / max(n_z, 0.2) at each texel normal (1 / n_z is a "
		    "facet's area per unit of plane); equals radiance_rgb up to the table interpolation for "
		    "flat maps"));
	}
}
