/* Bake directory: writer (manifest.json, brdf.exr, brdf_rgb.exr,
 * albedo.exr, albedo.png) and reader with interpolation. */
#include "config.h"
#include "bake/bakefile.h"

#include <errno.h>
#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <dirent.h>

#include "bake/bake.h"
#include "io/exrio.h"
#include "io/pngio.h"
#include "base/util.h"

#define BAKE_FORMAT_VERSION 1

static json_object *jarr(const double *v, int n)
{
	json_object *a = json_object_new_array_ext(n);
	for (int i = 0; i < n; i++)
		json_object_array_add(a, json_object_new_double(v[i]));
	return a;
}

static json_object *jarr_deg(const double *v, int n)
{
	json_object *a = json_object_new_array_ext(n);
	for (int i = 0; i < n; i++)
		json_object_array_add(a, json_object_new_double(v[i] * 180.0 / M_PI));
	return a;
}

static double srgb_encode(double v)
{
	v = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
	return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* Remove a staging directory and what it holds. */
static void rm_staging(const char *dir)
{
	DIR *d = opendir(dir);
	if (d) {
		struct dirent *e;
		while ((e = readdir(d)) != NULL) {
			if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
				continue;
			char *p = xasprintf("%s/%s", dir, e->d_name);
			unlink(p);
			free(p);
		}
		closedir(d);
	}
	rmdir(dir);
}

static char *manifest_text(const struct bake_spec *s, const struct bake_result *r, const struct bake_meta *m)
{
	int nti = s->n_ti, nto = s->n_to, np = s->n_phi;
	json_object *o = json_object_new_object();
	json_object_object_add(o, "format", json_object_new_string("skinbake-bake"));
	json_object_object_add(o, "format_version", json_object_new_int(BAKE_FORMAT_VERSION));
	json_object_object_add(o, "skinbake_version", json_object_new_string(PACKAGE_VERSION));
	json_object_object_add(o, "preset", json_object_new_string(m->preset ? m->preset : ""));
	if (m->command)
		json_object_object_add(o, "command", json_object_new_string(m->command));
	json_object_object_add(o, "wavelengths_nm", jarr(s->wl_nm, s->n_wl));
	json_object_object_add(o, "theta_i_deg", jarr_deg(s->theta_i, nti));
	double *e = xmalloc(sizeof(double) * (size_t)(nto + np + 2));
	for (int i = 0; i <= nto; i++)
		e[i] = 90.0 * i / nto;
	json_object_object_add(o, "theta_o_edges_deg", jarr(e, nto + 1));
	for (int i = 0; i < nto; i++)
		e[i] = 90.0 * (i + 0.5) / nto;
	json_object_object_add(o, "theta_o_centres_deg", jarr(e, nto));
	for (int i = 0; i <= np; i++)
		e[i] = 180.0 * i / np;
	json_object_object_add(o, "delta_phi_edges_deg", jarr(e, np + 1));
	for (int i = 0; i < np; i++)
		e[i] = 180.0 * (i + 0.5) / np;
	json_object_object_add(o, "delta_phi_centres_deg", jarr(e, np));
	free(e);
	json_object *t = json_object_new_object();
	json_object_object_add(t, "file", json_object_new_string("brdf.exr"));
	json_object_object_add(t, "width", json_object_new_int(np));
	json_object_object_add(t, "height", json_object_new_int(nti * nto));
	json_object_object_add(t, "row", json_object_new_string("theta_i_index * n_theta_o + theta_o_index, row 0 at the top"));
	json_object_object_add(t, "column", json_object_new_string("delta_phi bin index"));
	json_object_object_add(t, "value", json_object_new_string(
	    "diffuse (subsurface) BRDF [1/sr]: mean over the (theta_o, delta_phi) bin at the theta_i node; "
	    "delta_phi = 0 back toward the light, 180 the mirror side"));
	json_object_object_add(t, "channels", json_object_new_string("fr.<WL>nm and fr_err.<WL>nm (standard error)"));
	json_object_object_add(o, "table", t);
	json_object *rgb = json_object_new_object();
	json_object_object_add(rgb, "file", json_object_new_string("brdf_rgb.exr"));
	json_object_object_add(rgb, "colour_space", json_object_new_string("linear sRGB (Rec. 709 primaries), D65 white, CIE 1931 2-degree observer"));
	json_object *mm = json_object_new_array();
	for (int c = 0; c < 3; c++)
		json_object_array_add(mm, jarr(m->rgb_from_wl + c * s->n_wl, s->n_wl));
	json_object_object_add(rgb, "rgb_from_wl", mm);
	if (m->rgb_note)
		json_object_object_add(rgb, "note", json_object_new_string(m->rgb_note));
	json_object_object_add(o, "rgb", rgb);

	json_object *sp = json_object_new_object();
	json_object_object_add(sp, "model", json_object_new_string("GGX microfacet (Walter et al. 2007), Smith masking, facet reflectance of the clear top stack"));
	json_object_object_add(sp, "alpha", json_object_new_double(m->roughness));
	json_object_object_add(sp, "ior", json_object_new_double(m->ior));
	json_object_object_add(sp, "fresnel", json_object_new_string(s->opts.fresnel == OPTICS_FRESNEL_SCHLICK ? "schlick" : "exact"));
	json_object *stacks = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++) {
		struct specular_stack st;
		bake_specular_stack(&s->slab[w], s->opts.fresnel, &st);
		json_object_array_add(stacks, jarr(st.n_list, st.n));
	}
	json_object_object_add(sp, "stack_n", stacks);
	json_object_object_add(o, "specular", sp);

	json_object *layers = json_object_new_array();
	for (int w = 0; w < s->n_wl; w++) {
		json_object *lw = json_object_new_object();
		json_object_object_add(lw, "wavelength_nm", json_object_new_double(s->wl_nm[w]));
		json_object_object_add(lw, "n_above", json_object_new_double(s->slab[w].n_above));
		json_object_object_add(lw, "n_below", json_object_new_double(s->slab[w].n_below));
		json_object *ls = json_object_new_array();
		for (int i = 1; i <= s->slab[w].n_layers; i++) {
			const struct layer *l = &s->slab[w].layer[i];
			json_object *lo = json_object_new_object();
			json_object_object_add(lo, "d_cm", isinf(l->d) ? json_object_new_string("inf") : json_object_new_double(l->d));
			json_object_object_add(lo, "n", json_object_new_double(l->n));
			json_object_object_add(lo, "mua_per_cm", json_object_new_double(l->mu_a));
			json_object_object_add(lo, "mus_per_cm", json_object_new_double(l->mu_s));
			json_object_object_add(lo, "g", json_object_new_double(l->g));
			json_object_array_add(ls, lo);
		}
		json_object_object_add(lw, "layers", ls);
		json_object_array_add(layers, lw);
	}
	json_object_object_add(o, "layers", layers);

	/* Radial profile and subsurface radius at the node nearest normal incidence. */
	json_object *rad = json_object_new_object();
	json_object_object_add(rad, "dr_cm", json_object_new_double(s->dr));
	json_object_object_add(rad, "n_r", json_object_new_int(s->n_r));
	json_object_object_add(rad, "theta_i_deg", json_object_new_double(s->theta_i[0] * 180.0 / M_PI));
	json_object_object_add(rad, "units", json_object_new_string("Rd(r) [1/cm^2]; radius [cm]"));
	json_object *prof = json_object_new_array(), *prof_e = json_object_new_array();
	double *rad_w = xmalloc(sizeof(double) * (size_t)s->n_wl);
	for (int w = 0; w < s->n_wl; w++) {
		const struct bake_job *jb = &r->job[w * nti];
		json_object_array_add(prof, jarr(jb->rd_r, s->n_r));
		json_object_array_add(prof_e, jarr(jb->rd_r_err, s->n_r));
		rad_w[w] = bake_mean_radius(jb->rd_r, s->n_r, s->dr);
	}
	json_object_object_add(rad, "rd_r", prof);
	json_object_object_add(rad, "rd_r_err", prof_e);
	json_object_object_add(rad, "mean_radius_cm", jarr(rad_w, s->n_wl));
	double rr[3];
	for (int c = 0; c < 3; c++) {
		double num = 0.0, den = 0.0;
		for (int w = 0; w < s->n_wl; w++) {
			double k = fabs(m->rgb_from_wl[c * s->n_wl + w]);
			num += k * rad_w[w];
			den += k;
		}
		rr[c] = den > 0 ? num / den : 0.0;
	}
	json_object_object_add(rad, "mean_radius_rgb_cm", jarr(rr, 3));
	json_object_object_add(rad, "definition", json_object_new_string(
	    "mean lateral distance between entry and exit of the diffusely reflected light (first moment of Rd(r) r dr), "
	    "from the profile's bins (light beyond the last bin is not counted)"));
	free(rad_w);
	json_object_object_add(o, "radial", rad);

	json_object *st = json_object_new_object();
	json_object_object_add(st, "seed", json_object_new_int64((int64_t)s->seed));
	json_object_object_add(st, "batch_photons", json_object_new_int64(s->batch_photons));
	json_object_object_add(st, "min_batches", json_object_new_int(s->min_batches));
	json_object_object_add(st, "target_error", json_object_new_double(s->target_error));
	json_object_object_add(st, "max_photons", json_object_new_int64(s->max_photons));
	json_object_object_add(st, "roulette_w", json_object_new_double(s->opts.roulette_w));
	json_object_object_add(st, "roulette_chance", json_object_new_double(s->opts.roulette_chance));
	json_object_object_add(st, "max_steps", json_object_new_int64(s->opts.max_steps));
	json_object_object_add(o, "settings", st);

	json_object *res = json_object_new_object();
	json_object_object_add(res, "photons", json_object_new_int64(r->photons));
	json_object_object_add(res, "seconds", json_object_new_double(r->seconds));
	json_object_object_add(res, "rms_rel_err", json_object_new_double(r->rms_rel_err));
	json_object_object_add(res, "target_met", json_object_new_boolean(r->target_met));
	json_object_object_add(o, "result", res);

	json_object *jobs = json_object_new_array();
	for (int j = 0; j < r->n_jobs; j++) {
		const struct bake_job *b = &r->job[j];
		json_object *jo = json_object_new_object();
		json_object_object_add(jo, "wavelength_nm", json_object_new_double(b->wl_nm));
		json_object_object_add(jo, "theta_i_deg", json_object_new_double(b->theta_i * 180.0 / M_PI));
		json_object_object_add(jo, "photons", json_object_new_int64(b->photons));
		json_object_object_add(jo, "Rsp", json_object_new_double(b->rsp));
		json_object_object_add(jo, "albedo", json_object_new_double(b->albedo));
		json_object_object_add(jo, "albedo_err", json_object_new_double(b->albedo_err));
		json_object_object_add(jo, "Rd_unscattered", json_object_new_double(b->rd_unscat));
		json_object_object_add(jo, "Tt", json_object_new_double(b->tt));
		json_object_object_add(jo, "A", json_object_new_double(b->a_total));
		json_object_object_add(jo, "lost", json_object_new_double(b->lost));
		json_object_object_add(jo, "rms_rel_err", json_object_new_double(b->rms_rel_err));
		json_object_array_add(jobs, jo);
	}
	json_object_object_add(o, "jobs", jobs);
	char *text = xstrdup(json_object_to_json_string_ext(o, JSON_C_TO_STRING_PRETTY | JSON_C_TO_STRING_NOSLASHESCAPE));
	json_object_put(o);
	return text;
}

int bake_write(const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m, char **cause)
{
	if (util_mkdirs(dir, cause) != 0)
		return -1;
	char *stage = xasprintf("%s/.staging.%ld", dir, (long)getpid());
	if (mkdir(stage, 0777) != 0) {
		*cause = xasprintf("%s: cannot create: %s", stage, strerror(errno));
		free(stage);
		return -1;
	}
	int nti = s->n_ti, nto = s->n_to, np = s->n_phi, nw = s->n_wl;
	int W = np, H = nti * nto;
	size_t npx = (size_t)W * (size_t)H;
	int rc = -1;
	char *path = NULL;
	/* brdf.exr: per wavelength value and error. */
	int nch = 2 * nw;
	char **names = xcalloc((size_t)nch, sizeof(char *));
	float **planes = xcalloc((size_t)nch, sizeof(float *));
	for (int w = 0; w < nw; w++) {
		names[2 * w] = xasprintf("fr.%.0fnm", s->wl_nm[w]);
		names[2 * w + 1] = xasprintf("fr_err.%.0fnm", s->wl_nm[w]);
		planes[2 * w] = xmalloc(npx * sizeof(float));
		planes[2 * w + 1] = xmalloc(npx * sizeof(float));
		for (int ti = 0; ti < nti; ti++) {
			const struct bake_job *jb = &r->job[w * nti + ti];
			for (int k = 0; k < nto * np; k++) {
				planes[2 * w][(size_t)ti * nto * np + k] = (float)jb->fr[k];
				planes[2 * w + 1][(size_t)ti * nto * np + k] = (float)jb->fr_err[k];
			}
		}
	}
	char *axes = xasprintf("rows: theta_i index * %d + theta_o index; columns: delta_phi bin; see manifest.json", nto);
	struct exr_attr_kv attrs[] = {
		{ "skinbake:format", "skinbake-bake 1" }, { "skinbake:axes", axes },
		{ "skinbake:units", "1/sr (diffuse BRDF, bin means)" }, { "skinbake:preset", m->preset ? m->preset : "" },
		{ "skinbake:version", PACKAGE_VERSION },
	};
	path = xasprintf("%s/brdf.exr", stage);
	if (exrio_write(path, W, H, nch, (const char *const *)names, (const float *const *)planes, 5, attrs, cause))
		goto out;
	free(path);
	/* brdf_rgb.exr */
	{
		float *rgbp[3];
		const char *rn[3] = { "R", "G", "B" };
		for (int c = 0; c < 3; c++) {
			rgbp[c] = xcalloc(npx, sizeof(float));
			for (size_t k = 0; k < npx; k++) {
				double v = 0.0;
				for (int w = 0; w < nw; w++)
					v += m->rgb_from_wl[c * nw + w] * planes[2 * w][k];
				rgbp[c][k] = (float)v;
			}
		}
		path = xasprintf("%s/brdf_rgb.exr", stage);
		int e = exrio_write(path, W, H, 3, rn, (const float *const *)rgbp, 5, attrs, cause);
		for (int c = 0; c < 3; c++)
			free(rgbp[c]);
		if (e)
			goto out;
		free(path);
	}
	/* albedo.exr and albedo.png */
	{
		int na = nw + 3;
		char **an = xcalloc((size_t)na, sizeof(char *));
		float **ap = xcalloc((size_t)na, sizeof(float *));
		for (int w = 0; w < nw; w++) {
			an[w] = xasprintf("albedo.%.0fnm", s->wl_nm[w]);
			ap[w] = xmalloc(sizeof(float) * (size_t)nti);
			for (int ti = 0; ti < nti; ti++)
				ap[w][ti] = (float)r->job[w * nti + ti].albedo;
		}
		uint16_t *px = xmalloc(sizeof(uint16_t) * 3 * (size_t)nti);
		for (int c = 0; c < 3; c++) {
			an[nw + c] = xasprintf("%c", "RGB"[c]);
			ap[nw + c] = xmalloc(sizeof(float) * (size_t)nti);
			for (int ti = 0; ti < nti; ti++) {
				double v = 0.0;
				for (int w = 0; w < nw; w++)
					v += m->rgb_from_wl[c * nw + w] * ap[w][ti];
				ap[nw + c][ti] = (float)v;
				px[3 * ti + c] = (uint16_t)lround(255.0 * srgb_encode(v));
			}
		}
		path = xasprintf("%s/albedo.exr", stage);
		int e = exrio_write(path, nti, 1, na, (const char *const *)an, (const float *const *)ap, 5, attrs, cause);
		free(path);
		path = NULL;
		if (!e) {
			path = xasprintf("%s/albedo.png", stage);
			struct png_text_kv tx[] = { { "Software", PACKAGE_STRING }, { "Comment", "diffuse albedo per theta_i node (columns), sRGB preview" } };
			e = pngio_write(path, nti, 1, 3, 8, px, 1, 2, tx, cause);
		}
		for (int i = 0; i < na; i++) {
			free(an[i]);
			free(ap[i]);
		}
		free(an);
		free(ap);
		free(px);
		if (e)
			goto out;
		free(path);
	}
	/* manifest.json */
	{
		path = xasprintf("%s/manifest.json", stage);
		struct outfile of;
		char *text = manifest_text(s, r, m);
		if (outfile_open(&of, path, cause)) {
			free(text);
			goto out;
		}
		fputs(text, of.fp);
		fputc('\n', of.fp);
		free(text);
		if (outfile_commit(&of, cause))
			goto out;
		free(path);
	}
	path = NULL;
	/* Everything is written: move it into place. */
	{
		static const char *files[] = { "brdf.exr", "brdf_rgb.exr", "albedo.exr", "albedo.png", "manifest.json" };
		for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
			char *from = xasprintf("%s/%s", stage, files[i]), *to = xasprintf("%s/%s", dir, files[i]);
			int e = rename(from, to);
			if (e != 0)
				*cause = xasprintf("%s: cannot rename into place: %s", to, strerror(errno));
			free(from);
			free(to);
			if (e != 0)
				goto out;
		}
	}
	rc = 0;
out:
	free(path);
	free(axes);
	for (int i = 0; i < nch; i++) {
		free(names[i]);
		free(planes[i]);
	}
	free(names);
	free(planes);
	rm_staging(stage);
	free(stage);
	return rc;
}

/* ---- reader ---- */

static int jnum_array(json_object *o, const char *key, double **out, int *n, char **cause, const char *path)
{
	json_object *a;
	if (!json_object_object_get_ex(o, key, &a) || !json_object_is_type(a, json_type_array)) {
		*cause = xasprintf("%s: missing array '%s'", path, key);
		return -1;
	}
	*n = (int)json_object_array_length(a);
	*out = xcalloc((size_t)(*n > 0 ? *n : 1), sizeof(double));
	for (int i = 0; i < *n; i++)
		(*out)[i] = json_object_get_double(json_object_array_get_idx(a, (size_t)i));
	return 0;
}

static double jnum(json_object *o, const char *key, double dflt)
{
	json_object *v;
	return json_object_object_get_ex(o, key, &v) ? json_object_get_double(v) : dflt;
}

void bake_free(struct bake *b)
{
	if (b == NULL)
		return;
	free(b->dir);
	free(b->preset);
	free(b->wl_nm);
	free(b->theta_i);
	free(b->theta_o);
	free(b->phi);
	free(b->fr);
	free(b->fr_err);
	free(b->fr_rgb);
	free(b->albedo);
	free(b->albedo_rgb);
	free(b->rgb_from_wl);
	free(b->stack);
	free(b->sss_radius_cm);
	free(b);
}

struct bake *bake_load(const char *dir, char **cause)
{
	char *mpath = xasprintf("%s/manifest.json", dir);
	struct bake *b = xcalloc(1, sizeof *b);
	json_object *o = NULL;
	b->dir = xstrdup(dir);
	if (access(mpath, R_OK) != 0) {
		*cause = xasprintf("%s: not a bake directory (%s: %s)", dir, mpath, strerror(errno));
		goto fail;
	}
	o = json_object_from_file(mpath);
	json_object *v;
	if (o == NULL || !json_object_object_get_ex(o, "format", &v) || !json_object_is_type(v, json_type_string) ||
	    strcmp(json_object_get_string(v), "skinbake-bake") != 0) {
		*cause = xasprintf("%s: not a skinbake bake manifest (corrupt JSON or wrong format)", mpath);
		goto fail;
	}
	if (jnum(o, "format_version", 0) != BAKE_FORMAT_VERSION) {	/* a double: (int)1e999 is undefined */
		*cause = xasprintf("%s: format_version %g is not %d", mpath, jnum(o, "format_version", 0), BAKE_FORMAT_VERSION);
		goto fail;
	}
	if (json_object_object_get_ex(o, "preset", &v) && json_object_is_type(v, json_type_string))
		b->preset = xstrdup(json_object_get_string(v));
	double *tmp;
	int n;
	if (jnum_array(o, "wavelengths_nm", &b->wl_nm, &b->n_wl, cause, mpath) ||
	    jnum_array(o, "theta_i_deg", &b->theta_i, &b->n_ti, cause, mpath) ||
	    jnum_array(o, "theta_o_centres_deg", &b->theta_o, &b->n_to, cause, mpath) ||
	    jnum_array(o, "delta_phi_centres_deg", &b->phi, &b->n_phi, cause, mpath))
		goto fail;
	if (b->n_wl < 1 || b->n_ti < 1 || b->n_to < 1 || b->n_phi < 1) {
		*cause = xasprintf("%s: empty table axes", mpath);
		goto fail;
	}
	if (b->n_wl > BAKE_MAX_WL) {
		*cause = xasprintf("%s: %d wavelengths, more than a bake holds (%d)", mpath, b->n_wl, BAKE_MAX_WL);
		goto fail;
	}
	for (int i = 0; i < b->n_ti; i++)
		b->theta_i[i] *= M_PI / 180.0;
	for (int i = 0; i < b->n_to; i++)
		b->theta_o[i] *= M_PI / 180.0;
	for (int i = 0; i < b->n_phi; i++)
		b->phi[i] *= M_PI / 180.0;
	json_object *rgb, *sp, *rad;
	if (!json_object_object_get_ex(o, "rgb", &rgb) || !json_object_object_get_ex(rgb, "rgb_from_wl", &v) ||
	    json_object_array_length(v) != 3) {
		*cause = xasprintf("%s: missing rgb.rgb_from_wl", mpath);
		goto fail;
	}
	b->rgb_from_wl = xcalloc(3 * (size_t)b->n_wl, sizeof(double));
	for (int c = 0; c < 3; c++) {
		json_object *row = json_object_array_get_idx(v, (size_t)c);
		if ((int)json_object_array_length(row) != b->n_wl) {
			*cause = xasprintf("%s: rgb_from_wl row %d has the wrong length", mpath, c);
			goto fail;
		}
		for (int w = 0; w < b->n_wl; w++)
			b->rgb_from_wl[c * b->n_wl + w] = json_object_get_double(json_object_array_get_idx(row, (size_t)w));
	}
	if (!json_object_object_get_ex(o, "specular", &sp)) {
		*cause = xasprintf("%s: missing specular", mpath);
		goto fail;
	}
	b->ior = jnum(sp, "ior", 1.5);
	b->roughness = jnum(sp, "alpha", 0.3);
	b->stack = xcalloc((size_t)b->n_wl, sizeof *b->stack);
	json_object *fr;
	enum optics_fresnel model = OPTICS_FRESNEL_EXACT;
	if (json_object_object_get_ex(sp, "fresnel", &fr) && json_object_is_type(fr, json_type_string) &&
	    strcmp(json_object_get_string(fr), "schlick") == 0)
		model = OPTICS_FRESNEL_SCHLICK;
	if (!json_object_object_get_ex(sp, "stack_n", &v) || (int)json_object_array_length(v) != b->n_wl) {
		*cause = xasprintf("%s: missing specular.stack_n", mpath);
		goto fail;
	}
	for (int w = 0; w < b->n_wl; w++) {
		json_object *row = json_object_array_get_idx(v, (size_t)w);
		int k = (int)json_object_array_length(row);
		if (k < 2 || k > SPECULAR_MAX_IFACES) {
			*cause = xasprintf("%s: specular.stack_n[%d] has %d entries", mpath, w, k);
			goto fail;
		}
		b->stack[w].n = k;
		b->stack[w].model = model;
		for (int i = 0; i < k; i++)
			b->stack[w].n_list[i] = json_object_get_double(json_object_array_get_idx(row, (size_t)i));
	}
	b->sss_radius_cm = xcalloc((size_t)b->n_wl, sizeof(double));
	if (json_object_object_get_ex(o, "radial", &rad)) {
		/* Optional: a missing array leaves the radii 0 (each message is dropped). */
		if (jnum_array(rad, "mean_radius_cm", &tmp, &n, cause, mpath) == 0) {
			for (int w = 0; w < b->n_wl && w < n; w++)
				b->sss_radius_cm[w] = tmp[w];
			free(tmp);
		} else {
			free(*cause);
			*cause = NULL;
		}
		if (jnum_array(rad, "mean_radius_rgb_cm", &tmp, &n, cause, mpath) == 0) {
			for (int c = 0; c < 3 && c < n; c++)
				b->sss_radius_rgb_cm[c] = tmp[c];
			free(tmp);
		} else {
			free(*cause);
			*cause = NULL;
		}
	}

	/* Tables. */
	int W = b->n_phi, H = b->n_ti * b->n_to, ew, eh;
	size_t npx = (size_t)W * (size_t)H;
	char *p = xasprintf("%s/brdf.exr", dir);
	if (exrio_size(p, &ew, &eh, cause) || ew != W || eh != H) {
		if (*cause == NULL)
			*cause = xasprintf("%s: size %d x %d does not match the manifest (%d x %d)", p, ew, eh, W, H);
		free(p);
		goto fail;
	}
	b->fr = xmalloc(sizeof(float) * npx * (size_t)b->n_wl);
	b->fr_err = xmalloc(sizeof(float) * npx * (size_t)b->n_wl);
	for (int w = 0; w < b->n_wl; w++) {
		char *cn = xasprintf("fr.%.0fnm", b->wl_nm[w]), *ce = xasprintf("fr_err.%.0fnm", b->wl_nm[w]);
		int e = exrio_read_channel(p, cn, W, H, b->fr + (size_t)w * npx, cause) ||
		    exrio_read_channel(p, ce, W, H, b->fr_err + (size_t)w * npx, cause);
		free(cn);
		free(ce);
		if (e) {
			free(p);
			goto fail;
		}
	}
	free(p);
	p = xasprintf("%s/brdf_rgb.exr", dir);
	b->fr_rgb = xmalloc(sizeof(float) * npx * 3);
	for (int c = 0; c < 3; c++) {
		char cn[2] = { "RGB"[c], 0 };
		if (exrio_read_channel(p, cn, W, H, b->fr_rgb + (size_t)c * npx, cause)) {
			free(p);
			goto fail;
		}
	}
	free(p);
	p = xasprintf("%s/albedo.exr", dir);
	b->albedo = xcalloc((size_t)b->n_wl * (size_t)b->n_ti, sizeof(double));
	b->albedo_rgb = xcalloc(3 * (size_t)b->n_ti, sizeof(double));
	float *row = xmalloc(sizeof(float) * (size_t)b->n_ti);
	for (int w = 0; w < b->n_wl + 3; w++) {
		char *cn = w < b->n_wl ? xasprintf("albedo.%.0fnm", b->wl_nm[w]) : xasprintf("%c", "RGB"[w - b->n_wl]);
		int e = exrio_read_channel(p, cn, b->n_ti, 1, row, cause);
		free(cn);
		if (e) {
			free(row);
			free(p);
			goto fail;
		}
		for (int i = 0; i < b->n_ti; i++) {
			if (w < b->n_wl)
				b->albedo[w * b->n_ti + i] = row[i];
			else
				b->albedo_rgb[(w - b->n_wl) * b->n_ti + i] = row[i];
		}
	}
	free(row);
	free(p);
	json_object_put(o);
	free(mpath);
	return b;
fail:
	if (o)
		json_object_put(o);
	free(mpath);
	bake_free(b);
	return NULL;
}

/* Linear interpolation weights on an ascending axis, clamped at the ends. */
static void axis_weights(const double *ax, int n, double x, int *i0, double *t)
{
	if (n == 1 || x <= ax[0]) {
		*i0 = 0;
		*t = 0.0;
		return;
	}
	if (x >= ax[n - 1]) {
		*i0 = n - 2;
		*t = 1.0;
		return;
	}
	int lo = 0, hi = n - 1;
	while (hi - lo > 1) {
		int mid = (lo + hi) / 2;
		if (ax[mid] <= x)
			lo = mid;
		else
			hi = mid;
	}
	*i0 = lo;
	*t = (x - ax[lo]) / (ax[lo + 1] - ax[lo]);
}

static double fold_phi(double dphi)
{
	dphi = fmod(fabs(dphi), 2.0 * M_PI);
	return dphi > M_PI ? 2.0 * M_PI - dphi : dphi;
}

/* Trilinear interpolation of one plane [n_ti][n_to][n_phi]. */
static double interp(const struct bake *b, const float *plane, double ti, double to, double ph)
{
	int a0, b0, c0;
	double ta, tb, tc;
	axis_weights(b->theta_i, b->n_ti, ti, &a0, &ta);
	axis_weights(b->theta_o, b->n_to, to, &b0, &tb);
	axis_weights(b->phi, b->n_phi, ph, &c0, &tc);
	int a1 = b->n_ti > 1 ? a0 + 1 : a0, b1 = b->n_to > 1 ? b0 + 1 : b0, c1 = b->n_phi > 1 ? c0 + 1 : c0;
#define AT(i, o, p) ((double)plane[((size_t)(i) * b->n_to + (size_t)(o)) * b->n_phi + (size_t)(p)])
	double v = 0.0;
	v += (1 - ta) * (1 - tb) * (1 - tc) * AT(a0, b0, c0) + (1 - ta) * (1 - tb) * tc * AT(a0, b0, c1);
	v += (1 - ta) * tb * (1 - tc) * AT(a0, b1, c0) + (1 - ta) * tb * tc * AT(a0, b1, c1);
	v += ta * (1 - tb) * (1 - tc) * AT(a1, b0, c0) + ta * (1 - tb) * tc * AT(a1, b0, c1);
	v += ta * tb * (1 - tc) * AT(a1, b1, c0) + ta * tb * tc * AT(a1, b1, c1);
#undef AT
	return v;
}

void bake_eval_diffuse(const struct bake *b, double theta_i, double theta_o, double dphi, double *f, double *err)
{
	size_t npx = (size_t)b->n_ti * b->n_to * b->n_phi;
	double ph = fold_phi(dphi);
	for (int w = 0; w < b->n_wl; w++) {
		f[w] = interp(b, b->fr + w * npx, theta_i, theta_o, ph);
		if (err)
			err[w] = interp(b, b->fr_err + w * npx, theta_i, theta_o, ph);
	}
}

void bake_eval_specular(const struct bake *b, double theta_i, double theta_o, double dphi, double *f)
{
	for (int w = 0; w < b->n_wl; w++)
		f[w] = specular_ggx(&b->stack[w], b->roughness, theta_i, theta_o, fold_phi(dphi));
}

void bake_eval_rgb(const struct bake *b, double theta_i, double theta_o, double dphi, double rgb[3])
{
	size_t npx = (size_t)b->n_ti * b->n_to * b->n_phi;
	double ph = fold_phi(dphi);
	double sp[BAKE_MAX_WL];	/* bake_load guarantees n_wl <= BAKE_MAX_WL */
	bake_eval_specular(b, theta_i, theta_o, ph, sp);
	for (int c = 0; c < 3; c++) {
		rgb[c] = interp(b, b->fr_rgb + c * npx, theta_i, theta_o, ph);
		for (int w = 0; w < b->n_wl; w++)
			rgb[c] += b->rgb_from_wl[c * b->n_wl + w] * sp[w];
	}
}
