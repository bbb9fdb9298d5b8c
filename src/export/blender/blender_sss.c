/* blender_sss: Cycles' subsurface node beside the remainder of the baked
 * table (translucent mode; see blender_sss.h). */
#include "config.h"
#include "export/blender/blender_sss.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/util.h"
#include "export/blender/blender_sss_albedo.h"

void blender_sss_series(const struct sss_table *t, char *buf, size_t n)
{
	int major = 0, minor = 0;
	if (sscanf(t->version, "%d.%d", &major, &minor) != 2)
		major = minor = 0;
	snprintf(buf, n, "%d.%d", major, minor);
}

/* The same major.minor?  (Digits compared up to the second dot: this runs
 * at every far-field lookup, where sscanf had cost 2 s of a translucent
 * export.) */
static int same_series(const char *a, const char *b)
{
	int dots = 0;
	for (;; a++, b++) {
		if (*a == '.' && *b == '.') {
			if (++dots == 2)
				return 1;
			continue;
		}
		int da = *a >= '0' && *a <= '9', db = *b >= '0' && *b <= '9';
		if (!da || !db)
			return !da && !db && dots == 1;	/* both numbers end here */
		if (*a != *b)
			return 0;
	}
}

/* The node below V in the ascending X[n] and the weight of the one above (clamped). */
static int cell(const double *x, int n, double v, double *u)
{
	int i = 0;
	while (i < n - 2 && v > x[i + 1])
		i++;
	*u = fmin(fmax((v - x[i]) / (x[i + 1] - x[i]), 0.0), 1.0);
	return i;
}

double blender_sss_albedo_factor(const struct sss_table *t, int c, double colour)
{
	const struct sss_albedo_table *a = NULL;
	for (int k = 0; blender_sss_albedo_tables[k] != NULL; k++)
		if (same_series(t->version, blender_sss_albedo_tables[k]->version))
			a = blender_sss_albedo_tables[k];
	if (a == NULL || a->n_colour < 2 || t->n_colour < 2)
		return 1.0;
	double u, v;
	int i = cell(a->colour, a->n_colour, colour, &u);
	int k = cell(t->colour, t->n_colour, colour, &v);
	const double *g = t->g + ((size_t)c * (size_t)t->n_colour + (size_t)k) * (size_t)t->n_edge;
	double tab = (1 - v) * g[0] + v * g[t->n_edge];
	return tab > 0 ? ((1 - u) * a->g0[i] + u * a->g0[i + 1]) / tab : 1.0;
}

/* The far field pi f [-] of version v's node, channel c: the table's, at the
 * measured albedo (blender_sss_albedo.h). */
static double far_v(const struct blender_sss *w, int v, int c, double ti, double to)
{
	const struct sss_fit *f = &w->fit[v];
	return sss_far_pi_f(f->table, c, f->colour[c], ti, to) *
	    blender_sss_albedo_factor(f->table, c, f->colour[c]);
}

/* The far field the remainder takes off: the largest of the versions'. */
static double far_max(const struct blender_sss *w, int c, double ti, double to)
{
	double m = 0.0;
	for (int v = 0; v < w->n; v++)
		m = fmax(m, far_v(w, v, c, ti, to));
	return m;
}

static void sss_remainder(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	const struct blender_sss *w = ctx;
	w->f_rgb(w->ctx, ti, to, dphi, rgb);
	for (int c = 0; c < 3; c++)
		rgb[c] = fmax(rgb[c] - far_max(w, c, ti, to) / M_PI, 0.0);
}

/* The largest share of the table the remainder clips, over a grid to 85 deg. */
static double clipped_share(const struct blender_sss *w)
{
	double worst = 0.0;
	for (int i = 0; i <= 17; i++)
		for (int j = 0; j <= 17; j++)
			for (int k = 0; k <= 4; k++) {
				double t[3], ti = i * 5.0 * M_PI / 180, to = j * 5.0 * M_PI / 180;
				w->f_rgb(w->ctx, ti, to, k * M_PI / 4, t);
				for (int c = 0; c < 3; c++) {
					double far = far_max(w, c, ti, to) / M_PI;
					if (t[c] > 0 && far > t[c])
						worst = fmax(worst, (far - t[c]) / t[c]);
				}
			}
	return worst;
}

int blender_sss_fit(const struct bake *b, struct blender_sss *w, char **cause)
{
	*w = (struct blender_sss){ 0 };
	for (int v = 0; blender_sss_tables[v] != NULL; v++) {
		CHECK(v < BLENDER_SSS_MAX);
		if (sss_fit_bake(blender_sss_tables[v], b, 1.0, &w->fit[v], cause) != 0)
			return -1;
		w->n = v + 1;
	}
	return 0;
}

void blender_sss_wrap_fitted(struct brdf_source *src, struct blender_sss *w)
{
	w->f_rgb = src->f_rgb;
	w->ctx = src->ctx;
	w->clipped = clipped_share(w);
	src->f_rgb = sss_remainder;
	src->ctx = w;
}

int blender_sss_wrap(struct brdf_source *src, struct blender_sss *w, char **cause)
{
	if (src->bake == NULL) {
		*cause = xstrdup("translucent mode needs a bake (its radial profile Rd(r))");
		return -1;
	}
	if (blender_sss_fit(src->bake, w, cause) != 0)
		return -1;
	double tt[BLENDER_THICK_N][3];
	if (blender_thick_stack(src->bake, tt, cause) != 0)
		return -1;
	for (int v = 0; v < w->n; v++)
		blender_thick_weights(&w->fit[v], tt, &w->thick[v]);
	blender_sss_wrap_fitted(src, w);
	return 0;
}

int blender_sss_auto(struct brdf_source *src, int textures, struct blender_sss *w, char **note)
{
	char *err = NULL;
	if (textures || blender_sss_wrap(src, w, &err) != 0) {
		const char *why = textures ?
		    "--textures: the fitted node carries no detail normal map" : err;
		*note = xasprintf("exact (--mode auto: %s)", why);
		free(err);
		return 0;
	}
	char vers[128] = "";
	for (int v = 0; v < w->n; v++) {
		char ser[32];
		blender_sss_series(w->fit[v].table, ser, sizeof ser);
		size_t at = strlen(vers);
		snprintf(vers + at, sizeof vers - at, "%s%s", v ? ", " : "", ser);
	}
	*note = xasprintf("translucent (--mode auto: a bake with Rd(r), Cycles' node fitted for "
	    "Blender %s; --mode exact for the exact set)", vers);
	return 1;
}

void blender_sss_extra(const struct blender_sss *w, int v, double theta_o, double rgb[3])
{
	for (int c = 0; c < 3; c++)
		rgb[c] = far_max(w, c, 0.0, theta_o) - far_v(w, v, c, 0.0, theta_o);
}

/* The theta_o nodes [deg] of the far fields in the manifest (the tables' FAR_ANGLES). */
const double blender_sss_view_deg[BLENDER_SSS_N_VIEW] = { 0, 20, 40, 60, 75, 85 };

/* A list over blender_sss_view_deg of [R, G, B]: version v's far field (v >= 0), or the
 * largest less version v's (diff), or the largest (v < 0); at theta_i = 0,
 * on which none of them depends. */
static char *by_view(const struct blender_sss *w, int v, int diff)
{
	char *s = xstrdup("[");
	for (int k = 0; k < BLENDER_SSS_N_VIEW; k++) {
		double x[3], to = blender_sss_view_deg[k] * M_PI / 180;
		for (int c = 0; c < 3; c++) {
			double m = far_max(w, c, 0.0, to);
			double f = v < 0 ? m : far_v(w, v, c, 0.0, to);
			x[c] = diff ? m - f : f;
		}
		char *t = xasprintf("%s%s[%.8g, %.8g, %.8g]", s, k ? ", " : "", x[0], x[1], x[2]);
		free(s);
		s = t;
	}
	char *t = xasprintf("%s]", s);
	free(s);
	return t;
}

static void jvec(char *buf, size_t n, const double v[3], double k)
{
	snprintf(buf, n, "[%.8g, %.8g, %.8g]", v[0] * k, v[1] * k, v[2] * k);
}

/* Blender's falloff identifier from the table's closure ("... falloff random_walk_skin"). */
static void falloff(const struct sss_table *t, char *buf, size_t n)
{
	const char *p = strstr(t->closure, "falloff ");
	p = p ? p + 8 : "random_walk";
	size_t i = 0;
	for (; p[i] && i + 1 < n; i++)
		buf[i] = (char)toupper((unsigned char)p[i]);
	buf[i] = '\0';
}

/* One version's entry of "versions". */
static char *version_json(const struct blender_sss *w, int v, const char *maps)
{
	const struct sss_fit *f = &w->fit[v];
	char ser[32], fo[48], col[96], rad[96], ifit[96], mf[96], rl[96], loc[96];
	char *far = by_view(w, v, 0), *extra = by_view(w, v, 1);
	char *th = blender_thick_json(&w->thick[v]);
	blender_sss_series(f->table, ser, sizeof ser);
	falloff(f->table, fo, sizeof fo);
	jvec(col, sizeof col, f->colour, 1.0);
	jvec(rad, sizeof rad, f->length_mm, 1e-3);
	jvec(ifit, sizeof ifit, f->integral_fit, 1.0);
	jvec(mf, sizeof mf, f->mean_fit_mm, 1e-3);
	jvec(rl, sizeof rl, f->rms_log, 1.0);
	jvec(loc, sizeof loc, f->local, 1.0);
	char *j = xasprintf("{\"blender\": \"%s\", \"version\": \"%s\", \"closure\": \"%s\", "
	    "\"falloff\": \"%s\", \"ior\": %g, \"colour\": %s, \"radius_m\": %s, \"scale\": 1.0, "
	    "\"power_fit\": %s, \"power_local\": %s, \"mean_radius_fit_m\": %s, "
	    "\"rms_ln_r_predicted\": %s, \"far_pi_f\": %s, \"lambert_extra\": %s%s%s%s}", ser,
	    f->table->version, f->table->closure, fo, f->table->ior, col, rad, ifit, loc, mf, rl,
	    far, extra, th, maps ? ", \"maps\": " : "", maps ? maps : "");
	free(th);
	free(far);
	free(extra);
	return j;
}

char *blender_sss_json(const struct blender_sss *w, const char *const *maps)
{
	const struct sss_fit *f = &w->fit[0];
	char ib[96], mb[96], *rem = by_view(w, -1, 0);
	jvec(ib, sizeof ib, f->integral_bake, 1.0);
	jvec(mb, sizeof mb, f->mean_bake_mm, 1e-3);
	char *list = xstrdup("");
	for (int v = 0; v < w->n; v++) {
		char *e = version_json(w, v, maps ? maps[v] : NULL);
		char *l = xasprintf("%s%s%s", list, v ? ", " : "", e);
		free(e);
		free(list);
		list = l;
	}
	char *j = xasprintf("{\"renderer\": \"cycles\", "
	    "\"node\": \"ShaderNodeSubsurfaceScattering\", "
	    "\"r_max_m\": %.8g, \"power_bake\": %s, \"mean_radius_bake_m\": %s, "
	    "\"theta_o_deg\": [0, 20, 40, 60, 75, 85], \"far_pi_f_removed\": %s, "
	    "\"remainder_clipped_max\": %.6g, \"split\": \"brdf_lut.exr "
	    "holds pi * max(0, f_bake - far_pi_f_removed / pi): the baked BRDF (diffuse + surface "
	    "specular) minus the largest far field of the versions' nodes at each angle "
	    "(measured; none depends on theta_i; listed per theta_o_deg), so each version's "
	    "power_local stays in it at the entry point; the importer adds the node of its own "
	    "Blender (versions[].blender = major.minor) beside it with a Diffuse BSDF whose colour "
	    "is lambert_extra (far_pi_f_removed - that node's far_pi_f) at the view angle, and "
	    "refuses a Blender that has no entry\", \"versions\": [%s]}", f->r_max_mm * 1e-3, ib,
	    mb, rem, w->clipped, list);
	free(list);
	free(rem);
	return j;
}
