/* blender_sss: Cycles' subsurface node beside the remainder of the baked
 * table (translucent mode; see blender_sss.h). */
#include "config.h"
#include "export/blender/blender_sss.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/util.h"

/* The node's far field f [1/sr] from the calibration: G(0) / pi, since
 * the walk enters and leaves Lambertian (scripts/calibrate-translucency.py);
 * G(0) is about the colour, 10 % above it at colour 0.01. */
static double far_f(const struct blender_sss *w, int c, double ti, double to)
{
	return sss_far_pi_f(w->fit.table, c, w->fit.colour[c], ti, to) / M_PI;
}

static void sss_remainder(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	const struct blender_sss *w = ctx;
	w->f_rgb(w->ctx, ti, to, dphi, rgb);
	for (int c = 0; c < 3; c++)
		rgb[c] = fmax(rgb[c] - far_f(w, c, ti, to), 0.0);
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
				for (int c = 0; c < 3; c++)
					if (t[c] > 0 && far_f(w, c, ti, to) > t[c])
						worst = fmax(worst, (far_f(w, c, ti, to) - t[c]) / t[c]);
			}
	return worst;
}

int blender_sss_wrap(struct brdf_source *src, struct blender_sss *w, char **cause)
{
	if (src->bake == NULL) {
		*cause = xstrdup("translucent mode needs a bake (its radial profile Rd(r))");
		return -1;
	}
	if (sss_fit_bake(&sss_cycles_table, src->bake, 1.0, &w->fit, cause) != 0)
		return -1;
	w->f_rgb = src->f_rgb;
	w->ctx = src->ctx;
	w->clipped = clipped_share(w);
	src->f_rgb = sss_remainder;
	src->ctx = w;
	return 0;
}

static void jvec(char *buf, size_t n, const double v[3], double k)
{
	snprintf(buf, n, "[%.8g, %.8g, %.8g]", v[0] * k, v[1] * k, v[2] * k);
}

char *blender_sss_json(const struct blender_sss *w)
{
	const struct sss_fit *f = &w->fit;
	char col[96], rad[96], ib[96], ifit[96], mb[96], mf[96], rl[96], loc[96];
	jvec(col, sizeof col, f->colour, 1.0);
	jvec(rad, sizeof rad, f->length_mm, 1e-3);
	jvec(ib, sizeof ib, f->integral_bake, 1.0);
	jvec(ifit, sizeof ifit, f->integral_fit, 1.0);
	jvec(mb, sizeof mb, f->mean_bake_mm, 1e-3);
	jvec(mf, sizeof mf, f->mean_fit_mm, 1e-3);
	jvec(rl, sizeof rl, f->rms_log, 1.0);
	jvec(loc, sizeof loc, f->local, 1.0);
	return xasprintf("{\"renderer\": \"%s\", \"version\": \"%s\", \"closure\": \"%s\", "
	    "\"node\": \"ShaderNodeSubsurfaceScattering\", \"falloff\": \"RANDOM_WALK\", \"ior\": %g, \"colour\": %s, "
	    "\"radius_m\": %s, \"scale\": 1.0, \"r_max_m\": %.8g, \"power_bake\": %s, \"power_fit\": %s, \"power_local\": %s, "
	    "\"mean_radius_bake_m\": %s, \"mean_radius_fit_m\": %s, \"rms_ln_r_predicted\": %s, "
	    "\"remainder_clipped_max\": %.6g, \"split\": \"brdf_lut.exr holds pi * max(0, f_bake - f_node): the "
	    "baked BRDF (diffuse + surface specular) minus the node's far field from the calibration (Lambertian, G(0) / pi "
	    "with G(0) the node's measured albedo), so power_local of power_fit stays in it at the entry point; "
	    "the importer adds the node beside it\"}",
	    f->table->renderer, f->table->version, f->table->closure, f->table->ior, col, rad, f->r_max_mm * 1e-3, ib, ifit, loc, mb, mf,
	    rl, w->clipped);
}
