/* blender: write the image set for exporters/blender/import_skin.py (layout
 * and axes in blender.h).  The exact-mode atlas tabulates pi * f_r so that a
 * Diffuse BSDF of that colour under a sun of irradiance E returns
 * E cos_l f_r, the BRDF's own radiance (Cycles' diffuse closure is
 * colour * cos_l / pi; measured in docs/blender.md). */
#include "config.h"

#include "export/blender/blender.h"
#include "export/blender/blender_detail.h"
#include "export/blender/blender_fit.h"
#include "export/blender/blender_manifest.h"

#include <errno.h>
#include <json-c/json.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"
#include "io/exrio.h"
#include "io/pngio.h"
#include "geom/texdir.h"
#include "base/check.h"
#include "base/checksum.h"
#include "base/util.h"
#include "io/json.h"

void blender_options_default(struct blender_options *o)
{
	*o = (struct blender_options){
		.lut_cos = 64,
		.lut_phi = 37,
		.sun_elevation = 45.0 * M_PI / 180.0,
		.sun_azimuth = -45.0 * M_PI / 180.0,
		.sun_strength = 3.0,
		.view_elevation = 60.0 * M_PI / 180.0,
		.view_azimuth = -90.0 * M_PI / 180.0,
		.map_size = 16,
		.generator = PACKAGE_NAME " " PACKAGE_VERSION,
	};
}

void blender_direction(double elevation, double azimuth, double v[3])
{
	v[0] = cos(elevation) * cos(azimuth);
	v[1] = cos(elevation) * sin(azimuth);
	v[2] = sin(elevation);
}

static double clamp(double x, double lo, double hi)
{
	return x < lo ? lo : x > hi ? hi : x;
}

float *blender_lut(const struct brdf_source *m, int n_cos, int n_phi)
{
	CHECK(n_cos >= 2 && n_phi >= 2);
	size_t w = (size_t)n_phi * (size_t)n_cos, h = (size_t)n_cos, plane = w * h;
	float *lut = xmalloc(3 * plane * sizeof *lut);
	for (int k = 0; k < n_phi; k++) {
		double dphi = M_PI * k / (n_phi - 1);
		for (int r = 0; r < n_cos; r++) {
			/* acos of the clamped cosine keeps theta inside [0, pi/2]. */
			double ti = acos(clamp(1.0 - (double)r / (n_cos - 1), 0.0, 1.0));
			for (int j = 0; j < n_cos; j++) {
				double to = acos(clamp((double)j / (n_cos - 1), 0.0, 1.0)), rgb[3];
				m->f_rgb(m->ctx, ti, to, dphi, rgb);
				size_t at = (size_t)r * w + (size_t)k * (size_t)n_cos + (size_t)j;
				for (int c = 0; c < 3; c++)
					lut[(size_t)c * plane + at] = (float)(M_PI * rgb[c]);
			}
		}
	}
	return lut;
}

/* a(90 deg) per channel: 0 for a smooth top (nothing enters at grazing); for
 * a rough top (the bake's rough_top) the diffuse table's own value there,
 * 2 int f(90, o) cos(theta_o) domega over the exits, from bake_eval_diffuse_rgb's
 * grazing completion (f(90, theta_o) = f(theta_o, 90) by reciprocity,
 * bakeinterp.h), so the curve goes to what the table holds instead of to 0. */
static void albedo_grazing(const struct brdf_source *m, double a90[3])
{
	enum { NU = 64, NP = 48 };
	for (int c = 0; c < 3; c++)
		a90[c] = 0.0;
	if (m->bake == NULL || !m->bake->rough_top)
		return;
	for (int u = 0; u < NU; u++) {
		double co = (u + 0.5) / NU, to = acos(co);
		for (int p = 0; p < NP; p++) {
			double rgb[3];
			bake_eval_diffuse_rgb(m->bake, M_PI / 2, to, M_PI * (p + 0.5) / NP, rgb);
			for (int c = 0; c < 3; c++)
				a90[c] += rgb[c] * co;
		}
	}
	/* d omega = d(cos) d(phi), phi over [0, 2 pi): twice [0, pi]. */
	for (int c = 0; c < 3; c++)
		a90[c] *= (1.0 / NU) * (2 * M_PI / NP);
}

/* a(theta) of channel c, linear between nodes, held below the first, and
 * past the last linear to a90 at 90 deg (albedo_grazing: 0 for a smooth top,
 * nothing enters a smooth surface at grazing; a bake's albedo curve was held
 * there before issue 26). */
static double albedo_at(const struct brdf_source *m, int c, double theta, double a90)
{
	const double *t = m->theta_albedo, *a = m->albedo_rgb + (size_t)c * (size_t)m->n_albedo;
	int n = m->n_albedo;
	if (theta <= t[0] && (n > 1 || t[0] >= M_PI / 2))
		return a[0];
	if (theta >= t[n - 1]) {
		if (t[n - 1] >= M_PI / 2)
			return a[n - 1];
		double f = fmin(1.0, (theta - t[n - 1]) / (M_PI / 2 - t[n - 1]));
		return (1 - f) * a[n - 1] + f * a90;
	}
	int i = 0;
	while (i < n - 2 && theta > t[i + 1])
		i++;
	double f = (theta - t[i]) / (t[i + 1] - t[i]);
	return (1 - f) * a[i] + f * a[i + 1];
}

void blender_albedo_mean(const struct brdf_source *m, double rgb[3])
{
	/* Midpoint rule in mu = cos(theta): 2 int_0^1 a(mu) mu dmu. */
	enum { STEPS = 4096 };
	double a90[3];
	albedo_grazing(m, a90);
	for (int c = 0; c < 3; c++) {
		double s = 0.0;
		for (int i = 0; i < STEPS; i++) {
			double mu = (i + 0.5) / STEPS;
			s += albedo_at(m, c, acos(mu), a90[c]) * mu;
		}
		rgb[c] = 2.0 * s / STEPS;
	}
}

static void detail_free(struct blender_maps *d)
{
	free(d->own_height);
	free(d->own_normal);
	free(d->far);
	free(d->cavity);
}

static void detail_use(const struct texdir *t, struct blender_maps *d)
{
	d->w = t->w;
	d->h = t->h;
	d->height = t->height;
	d->normal = t->normal;
	d->tile_mm = t->tile_mm_text;
	d->hmin_um = t->h_min_text;
	d->hmax_um = t->h_max_text;
	/* roughness_far.png, when the texture directory has it (older ones do
	 * not): a square 16-bit gray map, else left out. */
	char *fp = xasprintf("%s/roughness_far.png", t->dir), *why = NULL;
	FILE *f = fopen(fp, "rb");
	if (f != NULL) {
		int w, h, ch, bits;
		fclose(f);
		d->far = pngio_read(fp, &w, &h, &ch, &bits, &why);
		if (d->far != NULL && (w != h || ch != 1 || bits != 16)) {
			free(d->far);
			d->far = NULL;
		}
		d->far_n = d->far != NULL ? w : 0;
	}
	free(why);
	free(fp);
	/* cavity.png likewise (texture directories before issue 24's relief7
	 * round have none). */
	fp = xasprintf("%s/cavity.png", t->dir);
	why = NULL;
	f = fopen(fp, "rb");
	if (f != NULL) {
		int w, h, ch, bits;
		fclose(f);
		d->cavity = pngio_read(fp, &w, &h, &ch, &bits, &why);
		if (d->cavity != NULL && (w != h || ch != 1 || bits != 16)) {
			free(d->cavity);
			d->cavity = NULL;
		}
		d->cavity_n = d->cavity != NULL ? w : 0;
	}
	free(why);
	free(fp);
}

static void detail_flat(int size, struct blender_maps *d)
{
	size_t n = (size_t)size * (size_t)size;
	d->w = d->h = size;
	d->flat = 1;
	d->own_height = xcalloc(n, sizeof *d->own_height);
	d->own_normal = xmalloc(3 * n * sizeof *d->own_normal);
	for (size_t i = 0; i < n; i++) {
		d->own_normal[3 * i] = d->own_normal[3 * i + 1] = 32768;	/* 0.5: no tilt */
		d->own_normal[3 * i + 2] = 65535;
	}
	d->height = d->own_height;
	d->normal = d->own_normal;
}

static int check_options(const struct blender_options *o, char **cause)
{
	if (o->lut_cos < BLENDER_LUT_COS_MIN || o->lut_cos > BLENDER_LUT_COS_MAX) {
		*cause = xasprintf("lut_cos = %d is out of range [%d, %d]", o->lut_cos,
		    BLENDER_LUT_COS_MIN, BLENDER_LUT_COS_MAX);
		return -1;
	}
	if (o->lut_phi < BLENDER_LUT_PHI_MIN || o->lut_phi > BLENDER_LUT_PHI_MAX) {
		*cause = xasprintf("lut_phi = %d is out of range [%d, %d]", o->lut_phi,
		    BLENDER_LUT_PHI_MIN, BLENDER_LUT_PHI_MAX);
		return -1;
	}
	if ((size_t)o->lut_cos * (size_t)o->lut_phi > 65536) {
		*cause = xasprintf("lut_cos * lut_phi = %d is wider than 65536 px",
		    o->lut_cos * o->lut_phi);
		return -1;
	}
	if (!(o->sun_elevation > 0 && o->sun_elevation <= M_PI / 2) ||
	    !(o->view_elevation > 0 && o->view_elevation <= M_PI / 2)) {
		*cause = xasprintf("sun/view elevation %g/%g deg is out of range (0, 90]",
		    o->sun_elevation * 180 / M_PI, o->view_elevation * 180 / M_PI);
		return -1;
	}
	if (!(o->sun_strength > 0) || !isfinite(o->sun_strength)) {
		*cause = xasprintf("sun_strength = %g W/m^2 must be > 0", o->sun_strength);
		return -1;
	}
	if (o->map_size < BLENDER_MAP_MIN || o->map_size > BLENDER_MAP_MAX) {
		*cause = xasprintf("map_size = %d is out of range [%d, %d]", o->map_size,
		    BLENDER_MAP_MIN, BLENDER_MAP_MAX);
		return -1;
	}
	return 0;
}

static int check_model(const struct brdf_source *m, char **cause)
{
	if (m->n_albedo < 1) {
		*cause = xasprintf("the model has no albedo nodes");
		return -1;
	}
	if (!(m->ior >= 1.0 && m->ior <= 10.0) || !(m->roughness >= 0.0 && m->roughness <= 1.0)) {
		*cause = xasprintf("ior %g / roughness %g out of range [1, 10] / [0, 1]", m->ior,
		    m->roughness);
		return -1;
	}
	if (m->detail != NULL && m->detail->normal == NULL) {
		*cause = xasprintf("%s: the detail maps were read without normal.png",
		    m->detail->dir);
		return -1;
	}
	for (int c = 0; c < 3; c++)
		if (!(m->sss_radius_cm[c] > 0) || !isfinite(m->sss_radius_cm[c])) {
			*cause = xasprintf("subsurface radius[%d] = %g cm must be > 0", c,
			    m->sss_radius_cm[c]);
			return -1;
		}
	return 0;
}

int blender_check(const struct brdf_source *m, const struct blender_options *o, char **cause)
{
	return check_options(o, cause) != 0 || check_model(m, cause) != 0 ? -1 : 0;
}

static void reference_compute(const struct brdf_source *m, const struct blender_options *o,
    const float *lut, struct blender_reference *r)
{
	blender_direction(o->sun_elevation, o->sun_azimuth, r->sun);
	blender_direction(o->view_elevation, o->view_azimuth, r->view);
	r->cos_l = r->sun[2];
	r->cos_v = r->view[2];
	double d = fabs(remainder(o->sun_azimuth - o->view_azimuth, 2 * M_PI)), f[3];
	r->dphi = d;
	m->f_rgb(m->ctx, acos(r->cos_l), acos(r->cos_v), d, f);
	blender_lut_sample(lut, o->lut_cos, o->lut_phi, r->cos_l, r->cos_v, d, r->pi_fr_lut);
	for (int c = 0; c < 3; c++) {
		r->pi_fr[c] = M_PI * f[c];
		r->radiance[c] = o->sun_strength * r->cos_l * f[c];
	}
}

static int write_manifest(const char *dir, json_object *j, char **cause)
{
	char *s = json_text(j, JSON_PRETTY);
	int rc = checksum_write_manifest(dir, "manifest.json", s, cause);
	free(s);
	return rc;
}

static int write_rgb_exr(const char *path, int w, int h, const float *rgb, int nattr,
    const struct exr_attr_kv *attrs, char **cause)
{
	static const char *const names[3] = { "R", "G", "B" };
	size_t plane = (size_t)w * (size_t)h;
	const float *planes[3] = { rgb, rgb + plane, rgb + 2 * plane };
	return exrio_write(path, w, h, 3, names, planes, nattr, attrs, cause);
}

static uint16_t quantise16(double x)
{
	return (uint16_t)lround(clamp(x, 0.0, 1.0) * 65535.0);
}

/* Everything blender_write puts on disk, computed and validated up front. */
struct blender_set {
	struct blender_options o;	/* copy; o.generator is borrowed */
	struct blender_maps d;		/* height and normal maps */
	float *lut;			/* pi f_r atlas, 3 planes */
	float *albedo;			/* map_size^2 x 3 planes */
	uint16_t *roughness;		/* map_size^2 */
	json_object *manifest;
};

void blender_set_free(struct blender_set *s)
{
	if (s == NULL)
		return;
	detail_free(&s->d);
	free(s->lut);
	free(s->albedo);
	free(s->roughness);
	if (s->manifest)
		json_object_put(s->manifest);
	free(s);
}

struct blender_set *blender_prepare(const struct brdf_source *m, const struct blender_options *o,
    char **cause)
{
	if (blender_check(m, o, cause) != 0)
		return NULL;
	struct blender_set *s = xcalloc(1, sizeof *s);
	s->o = *o;
	if (m->detail != NULL)
		detail_use(m->detail, &s->d);
	else
		detail_flat(o->map_size, &s->d);

	double albedo[3];
	struct blender_reference ref;
	blender_albedo_mean(m, albedo);
	s->lut = blender_lut(m, o->lut_cos, o->lut_phi);
	reference_compute(m, o, s->lut, &ref);
	for (int c = 0; c < 3; c++)
		if (!isfinite(albedo[c]) || !isfinite(ref.pi_fr[c])) {
			*cause = xasprintf("the BRDF gives a non-finite value "
			    "(albedo %g, pi f_r %g)", albedo[c], ref.pi_fr[c]);
			blender_set_free(s);
			return NULL;
		}
	size_t mp = (size_t)o->map_size * (size_t)o->map_size;
	s->albedo = xmalloc(3 * mp * sizeof *s->albedo);
	s->roughness = xmalloc(mp * sizeof *s->roughness);
	for (size_t i = 0; i < mp; i++) {
		for (int c = 0; c < 3; c++)
			s->albedo[(size_t)c * mp + i] = (float)albedo[c];
		s->roughness[i] = quantise16(sqrt(m->roughness));
	}
	s->manifest = blender_manifest_build(m, o, &s->d, albedo, &ref);
	double sun[3], view[3];
	blender_direction(o->sun_elevation, o->sun_azimuth, sun);
	blender_direction(o->view_elevation, o->view_azimuth, view);
	blender_fit_manifest(s->manifest, m, sun, view, o->sun_strength, s->lut, o->lut_cos,
	    o->lut_phi, s->d.normal, s->d.w, s->d.h);
	return s;
}

int blender_write(const struct blender_set *s, const char *dir, char **cause)
{
	struct outdir od;
	if (outdir_begin(&od, dir, &blender_outdir_kind, cause) != 0)
		return -1;
	if (blender_write_files(s, outdir_path(&od), cause) != 0) {
		outdir_fail(&od, cause);
		return -2;
	}
	return outdir_commit(&od, cause) != 0 ? -2 : 0;
}

int blender_write_files(const struct blender_set *s, const char *dir, char **cause)
{
	const struct blender_options *o = &s->o;
	const struct blender_maps *d = &s->d;
	char *path = NULL, *np_s = xasprintf("%d", o->lut_phi), *nc_s = xasprintf("%d", o->lut_cos);
	int rc = -1;

	struct exr_attr_kv aattr[] = {
		{ "skinbake:quantity", "bihemispherical diffuse albedo, linear Rec.709" },
		{ "skinbake:generator", o->generator },
	};
	path = xasprintf("%s/albedo.exr", dir);
	if (write_rgb_exr(path, o->map_size, o->map_size, s->albedo, 2, aattr, cause) != 0)
		goto out;
	free(path);
	struct exr_attr_kv lattr[] = {
		{ "skinbake:quantity", "pi * f_r (total BRDF), linear Rec.709" },
		{ "skinbake:layout",
		    "tiles k = delta_phi k*180/(phi_nodes-1) deg side by side; in a tile column "
		    "j = cos_view j/(cos_nodes-1), row r from the top = cos_light "
		    "1 - r/(cos_nodes-1)" },
		{ "skinbake:phi_nodes", np_s },
		{ "skinbake:cos_nodes", nc_s },
		{ "skinbake:generator", o->generator },
	};
	path = xasprintf("%s/brdf_lut.exr", dir);
	if (write_rgb_exr(path, o->lut_cos * o->lut_phi, o->lut_cos, s->lut, 5, lattr, cause) != 0)
		goto out;
	free(path);
	struct png_text_kv rtext[] = {
		{ "skinbake:quantity", "Blender roughness = sqrt(GGX alpha)" },
	};
	path = xasprintf("%s/roughness.png", dir);
	if (pngio_write(path, o->map_size, o->map_size, 1, 16, s->roughness, 0, 1, rtext,
	    cause) != 0)
		goto out;
	free(path);
	struct png_text_kv htext[3];
	int nh = 0;
	if (d->tile_mm)
		htext[nh++] = (struct png_text_kv){ "skinbake:tile_mm", d->tile_mm };
	if (d->hmin_um)
		htext[nh++] = (struct png_text_kv){ "skinbake:height_min_um", d->hmin_um };
	if (d->hmax_um)
		htext[nh++] = (struct png_text_kv){ "skinbake:height_max_um", d->hmax_um };
	path = xasprintf("%s/height.png", dir);
	if (pngio_write(path, d->w, d->h, 1, 16, d->height, 0, nh, htext, cause) != 0)
		goto out;
	free(path);
	path = xasprintf("%s/normal.png", dir);
	if (pngio_write(path, d->w, d->h, 3, 16, d->normal, 0, d->tile_mm ? 1 : 0, htext,
	    cause) != 0)
		goto out;
	free(path);
	path = d->far != NULL ? xasprintf("%s/roughness_far.png", dir) : NULL;
	if (path != NULL && pngio_write(path, d->far_n, d->far_n, 1, 16, d->far, 0, 0, NULL,
	    cause) != 0)
		goto out;
	free(path);
	path = d->cavity != NULL ? xasprintf("%s/cavity.png", dir) : NULL;
	if (path != NULL && pngio_write(path, d->cavity_n, d->cavity_n, 1, 16, d->cavity, 0, 0,
	    NULL, cause) != 0)
		goto out;
	free(path);
	/* The manifest goes last: its presence marks a complete image set. */
	path = NULL;
	if (write_manifest(dir, s->manifest, cause) != 0)
		goto out;
	rc = 0;
out:
	free(path);
	free(np_s);
	free(nc_s);
	return rc;
}

void blender_set_add_section(struct blender_set *s, const char *key, const char *json)
{
	json_object *o = json_tokener_parse(json);
	CHECK(o != NULL);
	json_object_object_add(s->manifest, key, o);
}

int blender_export(const struct brdf_source *m, const struct blender_options *o, const char *dir,
    char **cause)
{
	struct blender_set *s = blender_prepare(m, o, cause);
	if (s == NULL)
		return -1;
	int rc = blender_write(s, dir, cause) != 0 ? -1 : 0;
	blender_set_free(s);
	return rc;
}
