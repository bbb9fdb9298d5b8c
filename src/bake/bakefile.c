/* bakefile: the bake directory (layout in bakefile.h): the tables written
 * through a staging directory swapped in as a whole (base/outdir.h), read back,
 * and the BRDF interpolated from them.  The manifest is manifest.c. */
#include "config.h"
#include "bake/bakefile.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bake/bake.h"
#include "bake/bakeinterp.h"
#include "bake/checkpoint.h"
#include "bake/manifest.h"
#include "bake/manifest_check.h"
#include "base/check.h"
#include "base/checksum.h"
#include "base/srgb.h"
#include "base/util.h"
#include "engine/macro.h"
#include "io/exrio.h"
#include "io/pngio.h"
#include "skin/preset.h"

/* ---- writer ---- */

static const char *const bake_names[] = { "manifest.json", "brdf.exr", "brdf_rgb.exr", "albedo.exr", "albedo.png",
	".staging.*", NULL };	/* .staging.PID: left inside by a killed bake before outdir */
const struct outdir_kind bake_outdir_kind = { "bake directory", "manifest.json", "format", "skinbake-bake",
	bake_names };

/* What every table file carries. */
struct stage {
	const char *dir;		/* the staging directory */
	const struct bake_spec *s;
	const struct bake_result *r;
	const struct bake_meta *m;
	struct exr_attr_kv attrs[5];	/* EXR string attributes */
	char *axes;			/* owned by attrs[1] */
	int nch;			/* brdf.exr channels: value and error per wavelength */
	char **names;			/* [nch] */
	float **planes;			/* [nch][n_phi * n_ti * n_to] */
};

static void stage_init(struct stage *st, const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m)
{
	int nti = s->n_ti, nto = s->n_to, np = s->n_phi, nw = s->n_wl;
	size_t npx = (size_t)np * (size_t)nti * (size_t)nto;
	*st = (struct stage){ .dir = dir, .s = s, .r = r, .m = m, .nch = 2 * nw };
	st->axes = xasprintf("rows: theta_i index * %d + theta_o index; columns: delta_phi bin; see manifest.json", nto);
	struct exr_attr_kv attrs[] = {
		{ "skinbake:format", "skinbake-bake 1" }, { "skinbake:axes", st->axes },
		{ "skinbake:units", "1/sr (diffuse BRDF, bin means)" }, { "skinbake:preset", m->preset ? m->preset : "" },
		{ "skinbake:version", PACKAGE_VERSION },
	};
	memcpy(st->attrs, attrs, sizeof attrs);
	st->names = xcalloc((size_t)st->nch, sizeof(char *));
	st->planes = xcalloc((size_t)st->nch, sizeof(float *));
	for (int w = 0; w < nw; w++) {
		st->names[2 * w] = xasprintf("fr.%.0fnm", s->wl_nm[w]);
		st->names[2 * w + 1] = xasprintf("fr_err.%.0fnm", s->wl_nm[w]);
		st->planes[2 * w] = xmalloc(npx * sizeof(float));
		st->planes[2 * w + 1] = xmalloc(npx * sizeof(float));
		for (int ti = 0; ti < nti; ti++) {
			const struct brdf_entry *jb = &r->table.entry[w * nti + ti];
			for (int k = 0; k < nto * np; k++) {
				st->planes[2 * w][(size_t)ti * nto * np + k] = (float)jb->fr[k];
				st->planes[2 * w + 1][(size_t)ti * nto * np + k] = (float)jb->fr_err[k];
			}
		}
	}
}

static void stage_free(struct stage *st)
{
	free(st->axes);
	for (int i = 0; i < st->nch; i++) {
		free(st->names[i]);
		free(st->planes[i]);
	}
	free(st->names);
	free(st->planes);
}

/* brdf.exr (value and error per wavelength) and brdf_rgb.exr (linear sRGB
 * from the float values). */
static int write_brdf(const struct stage *st, char **cause)
{
	const struct bake_spec *s = st->s;
	int W = s->n_phi, H = s->n_ti * s->n_to, nw = s->n_wl;
	size_t npx = (size_t)W * (size_t)H;
	char *path = xasprintf("%s/brdf.exr", st->dir);
	int e = exrio_write(path, W, H, st->nch, (const char *const *)st->names, (const float *const *)st->planes, 5,
	    st->attrs, cause);
	free(path);
	if (e)
		return -1;
	float *rgbp[3];
	const char *rn[3] = { "R", "G", "B" };
	for (int c = 0; c < 3; c++) {
		rgbp[c] = xcalloc(npx, sizeof(float));
		for (size_t k = 0; k < npx; k++) {
			double v = 0.0;
			for (int w = 0; w < nw; w++)
				v += st->m->rgb_from_wl[c * nw + w] * st->planes[2 * w][k];
			rgbp[c][k] = (float)v;
		}
	}
	path = xasprintf("%s/brdf_rgb.exr", st->dir);
	e = exrio_write(path, W, H, 3, rn, (const float *const *)rgbp, 5, st->attrs, cause);
	free(path);
	for (int c = 0; c < 3; c++)
		free(rgbp[c]);
	return e ? -1 : 0;
}

/* albedo.exr (per wavelength and RGB, one column per theta_i node) and its
 * 8-bit sRGB preview albedo.png. */
static int write_albedo(const struct stage *st, char **cause)
{
	const struct bake_spec *s = st->s;
	int nti = s->n_ti, nw = s->n_wl, na = nw + 3;
	char **an = xcalloc((size_t)na, sizeof(char *));
	float **ap = xcalloc((size_t)na, sizeof(float *));
	for (int w = 0; w < nw; w++) {
		an[w] = xasprintf("albedo.%.0fnm", s->wl_nm[w]);
		ap[w] = xmalloc(sizeof(float) * (size_t)nti);
		for (int ti = 0; ti < nti; ti++)
			ap[w][ti] = (float)st->r->table.entry[w * nti + ti].albedo.v;
	}
	uint16_t *px = xmalloc(sizeof(uint16_t) * 3 * (size_t)nti);
	for (int c = 0; c < 3; c++) {
		an[nw + c] = xasprintf("%c", "RGB"[c]);
		ap[nw + c] = xmalloc(sizeof(float) * (size_t)nti);
		for (int ti = 0; ti < nti; ti++) {
			double v = 0.0;
			for (int w = 0; w < nw; w++)
				v += st->m->rgb_from_wl[c * nw + w] * ap[w][ti];
			ap[nw + c][ti] = (float)v;
			px[3 * ti + c] = (uint16_t)lround(255.0 * srgb_encode(v));
		}
	}
	char *path = xasprintf("%s/albedo.exr", st->dir);
	int e = exrio_write(path, nti, 1, na, (const char *const *)an, (const float *const *)ap, 5, st->attrs, cause);
	free(path);
	if (!e) {
		path = xasprintf("%s/albedo.png", st->dir);
		struct png_text_kv tx[] = { { "Software", PACKAGE_STRING },
			{ "Comment", "diffuse albedo per theta_i node (columns), sRGB preview" } };
		e = pngio_write(path, nti, 1, 3, 8, px, 1, 2, tx, cause);
		free(path);
	}
	for (int i = 0; i < na; i++) {
		free(an[i]);
		free(ap[i]);
	}
	free(an);
	free(ap);
	free(px);
	return e ? -1 : 0;
}

static int write_manifest(const struct stage *st, char **cause)
{
	char *text = bake_manifest_text(st->s, st->r, st->m);
	int rc = checksum_write_manifest(st->dir, "manifest.json", text, cause);
	free(text);
	return rc;
}

int bake_write_files(const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m, char **cause)
{
	CHECK(r->table.n_wl == s->n_wl && r->table.n_ti == s->n_ti && r->stack && r->mean_radius_cm);
	struct stage st;
	stage_init(&st, dir, s, r, m);
	int rc = write_brdf(&st, cause) || write_albedo(&st, cause) || write_manifest(&st, cause) ? -1 : 0;
	stage_free(&st);
	return rc;
}

int bake_write(const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m, char **cause)
{
	struct outdir od;
	if (outdir_begin(&od, dir, &bake_outdir_kind, cause) != 0)
		return -1;
	if (bake_write_files(outdir_path(&od), s, r, m, cause) != 0) {
		outdir_fail(&od, cause);
		return -1;
	}
	return outdir_commit(&od, cause);
}

/* ---- reader ---- */

/* brdf.exr: value and error planes per wavelength, sized as the manifest says. */
static int read_brdf(const char *dir, struct bake *b, char **cause)
{
	int W = b->n_phi, H = b->n_ti * b->n_to, ew, eh, rc = -1;
	size_t npx = (size_t)W * (size_t)H;
	char *p = xasprintf("%s/brdf.exr", dir);
	if (exrio_size(p, &ew, &eh, cause) || ew != W || eh != H) {
		if (*cause == NULL)
			*cause = xasprintf("%s: size %d x %d does not match the manifest (%d x %d)", p, ew, eh, W, H);
		goto out;
	}
	b->fr = xmalloc(sizeof(float) * npx * (size_t)b->n_wl);
	b->fr_err = xmalloc(sizeof(float) * npx * (size_t)b->n_wl);
	for (int w = 0; w < b->n_wl; w++) {
		char *cn = xasprintf("fr.%.0fnm", b->wl_nm[w]), *ce = xasprintf("fr_err.%.0fnm", b->wl_nm[w]);
		int e = exrio_read_channel(p, cn, W, H, b->fr + (size_t)w * npx, cause) ||
		    exrio_read_channel(p, ce, W, H, b->fr_err + (size_t)w * npx, cause);
		free(cn);
		free(ce);
		if (e)
			goto out;
	}
	free(p);
	p = xasprintf("%s/brdf_rgb.exr", dir);
	b->fr_rgb = xmalloc(sizeof(float) * npx * 3);
	for (int c = 0; c < 3; c++) {
		char cn[2] = { "RGB"[c], 0 };
		if (exrio_read_channel(p, cn, W, H, b->fr_rgb + (size_t)c * npx, cause))
			goto out;
	}
	rc = 0;
out:
	free(p);
	return rc;
}

/* albedo.exr: one row, a column per theta_i node, per wavelength and RGB. */
static int read_albedo(const char *dir, struct bake *b, char **cause)
{
	char *p = xasprintf("%s/albedo.exr", dir);
	b->albedo = xcalloc((size_t)b->n_wl * (size_t)b->n_ti, sizeof(double));
	b->albedo_rgb = xcalloc(3 * (size_t)b->n_ti, sizeof(double));
	float *row = xmalloc(sizeof(float) * (size_t)b->n_ti);
	int rc = 0;
	for (int w = 0; w < b->n_wl + 3 && rc == 0; w++) {
		char *cn = w < b->n_wl ? xasprintf("albedo.%.0fnm", b->wl_nm[w]) : xasprintf("%c", "RGB"[w - b->n_wl]);
		rc = exrio_read_channel(p, cn, b->n_ti, 1, row, cause) ? -1 : 0;
		free(cn);
		for (int i = 0; i < b->n_ti && rc == 0; i++) {
			if (w < b->n_wl)
				b->albedo[w * b->n_ti + i] = row[i];
			else
				b->albedo_rgb[(w - b->n_wl) * b->n_ti + i] = row[i];
		}
	}
	free(row);
	free(p);
	return rc;
}

struct bake *bake_load(const char *dir, char **cause)
{
	struct bake *b = xcalloc(1, sizeof *b);
	b->dir = xstrdup(dir);
	if (manifest_check_bake(dir, cause) || bake_manifest_read(dir, b, cause) || read_brdf(dir, b, cause) ||
	    read_albedo(dir, b, cause) || manifest_check_values(b, cause)) {
		bake_free(b);
		return NULL;
	}
	bake_prepare(b);
	return b;
}

void bake_prepare(struct bake *b)
{
	bake_interp_free(b);
	bake_interp_build(b);
}

static double fold_phi(double dphi)
{
	dphi = fmod(fabs(dphi), 2.0 * M_PI);
	return dphi > M_PI ? 2.0 * M_PI - dphi : dphi;
}

static double clamp_theta(double t)
{
	return fmin(0.5 * M_PI, fmax(0.0, t));
}

/* The facet-scale BRDF: the table and the lobe as baked. */
static void raw_diffuse(const struct bake *b, double theta_i, double theta_o, double dphi, double *f,
    double *err)
{
	double ph = fold_phi(dphi), ti = clamp_theta(theta_i), to = clamp_theta(theta_o);
	for (int w = 0; w < b->n_wl; w++)
		f[w] = bake_interp_eval(b, w, ti, to, ph, err ? &err[w] : NULL);
}

static void raw_specular(const struct bake *b, double theta_i, double theta_o, double dphi,
    double *f)
{
	for (int w = 0; w < b->n_wl; w++) {
		f[w] = specular_ggx(&b->stack[w], b->roughness, theta_i, theta_o, fold_phi(dphi));
		if (b->ms)	/* multiple scattering on the facets: their later reflections */
			f[w] += microfacet_ms_eval(&b->ms[w], cos(theta_i), cos(theta_o));
	}
}

/* The diffuse table's part of raw_rgb. */
static void raw_diffuse_rgb(const struct bake *b, double theta_i, double theta_o, double dphi,
    double rgb[3])
{
	double ph = fold_phi(dphi), ti = clamp_theta(theta_i), to = clamp_theta(theta_o);
	double fd[BAKE_MAX_WL];
	CHECK(b->n_wl <= BAKE_MAX_WL);	/* bake_load guarantees it */
	int mixed = 0;
	for (int c = 0; c < 3; c++)
		mixed |= bake_interp_rgb(b, c, ti, to, ph, &rgb[c]) != 0;
	if (mixed) {	/* point values and bin means: wavelength by wavelength */
		raw_diffuse(b, ti, to, ph, fd, NULL);
		for (int c = 0; c < 3; c++) {
			rgb[c] = 0.0;
			for (int w = 0; w < b->n_wl; w++)
				rgb[c] += b->rgb_from_wl[c * b->n_wl + w] * fd[w];
		}
	}
}

static void raw_rgb(const struct bake *b, double theta_i, double theta_o, double dphi,
    double rgb[3])
{
	double sp[BAKE_MAX_WL];
	CHECK(b->n_wl <= BAKE_MAX_WL);	/* bake_load guarantees it */
	raw_specular(b, theta_i, theta_o, fold_phi(dphi), sp);
	raw_diffuse_rgb(b, theta_i, theta_o, dphi, rgb);
	for (int c = 0; c < 3; c++)
		for (int w = 0; w < b->n_wl; w++)
			rgb[c] += b->rgb_from_wl[c * b->n_wl + w] * sp[w];
}

/* The macro-scale roughness (engine/macro.h): the facet BRDF above
 * integrated over the mm-scale facets, part by part (the sum of the parts'
 * integrals is the total's: the integral is linear). */
enum part { PART_DIFFUSE, PART_DIFFUSE_ERR, PART_SPECULAR, PART_RGB, PART_DIFFUSE_RGB };
struct part_ctx {
	const struct bake *b;
	enum part part;
};

static void part_at(void *ctx, double ti, double to, double ph, double *out)
{
	const struct part_ctx *c = ctx;
	switch (c->part) {
	case PART_DIFFUSE:
		raw_diffuse(c->b, ti, to, ph, out, NULL);
		break;
	case PART_DIFFUSE_ERR:	/* values, then errors */
		raw_diffuse(c->b, ti, to, ph, out, out + c->b->n_wl);
		break;
	case PART_SPECULAR:
		raw_specular(c->b, ti, to, ph, out);
		break;
	case PART_RGB:
		raw_rgb(c->b, ti, to, ph, out);
		break;
	case PART_DIFFUSE_RGB:
		raw_diffuse_rgb(c->b, ti, to, ph, out);
		break;
	}
}

void bake_eval_diffuse(const struct bake *b, double theta_i, double theta_o, double dphi, double *f,
    double *err)
{
	if (b->macro == NULL) {
		raw_diffuse(b, theta_i, theta_o, dphi, f, err);
		return;
	}
	/* The error: the facets' errors summed with the integral's weights, as
	 * if fully correlated (an upper bound). */
	double v[2 * BAKE_MAX_WL];
	struct part_ctx c = { b, err ? PART_DIFFUSE_ERR : PART_DIFFUSE };
	macro_eval(b->macro, part_at, &c, (err ? 2 : 1) * b->n_wl, clamp_theta(theta_i),
	    clamp_theta(theta_o), fold_phi(dphi), v);
	for (int w = 0; w < b->n_wl; w++) {
		f[w] = v[w];
		if (err)
			err[w] = v[b->n_wl + w];
	}
}

void bake_eval_specular(const struct bake *b, double theta_i, double theta_o, double dphi,
    double *f)
{
	if (b->macro == NULL) {
		raw_specular(b, theta_i, theta_o, dphi, f);
		return;
	}
	struct part_ctx c = { b, PART_SPECULAR };
	macro_eval(b->macro, part_at, &c, b->n_wl, clamp_theta(theta_i), clamp_theta(theta_o),
	    fold_phi(dphi), f);
}

void bake_eval_rgb(const struct bake *b, double theta_i, double theta_o, double dphi, double rgb[3])
{
	if (b->macro == NULL) {
		raw_rgb(b, theta_i, theta_o, dphi, rgb);
		return;
	}
	struct part_ctx c = { b, PART_RGB };
	macro_eval(b->macro, part_at, &c, 3, clamp_theta(theta_i), clamp_theta(theta_o),
	    fold_phi(dphi), rgb);
}

void bake_eval_specular_rgb(const struct bake *b, double theta_i, double theta_o, double dphi,
    double rgb[3])
{
	double sp[BAKE_MAX_WL];
	CHECK(b->n_wl <= BAKE_MAX_WL);
	bake_eval_specular(b, theta_i, theta_o, dphi, sp);
	for (int c = 0; c < 3; c++) {
		rgb[c] = 0.0;
		for (int w = 0; w < b->n_wl; w++)
			rgb[c] += b->rgb_from_wl[c * b->n_wl + w] * sp[w];
	}
}

void bake_eval_diffuse_rgb(const struct bake *b, double theta_i, double theta_o, double dphi,
    double rgb[3])
{
	if (b->macro == NULL) {
		raw_diffuse_rgb(b, theta_i, theta_o, dphi, rgb);
		return;
	}
	struct part_ctx c = { b, PART_DIFFUSE_RGB };
	macro_eval(b->macro, part_at, &c, 3, clamp_theta(theta_i), clamp_theta(theta_o),
	    fold_phi(dphi), rgb);
}

int bake_preset_to_dir(struct bake_spec *s, const struct skin_params *p, const char *label, const char *out,
    const char *command, struct bake_result *r, char **cause)
{
	s->checkpoint_out = out;
	memset(r, 0, sizeof *r);
	if (bake_budget(s, 1, out, cause) != 0)
		return -1;
	/* Rank 0 takes the output (and its lock) before the work: a target that
	 * is not a bake, or one another bake is writing, fails now. */
	struct outdir od;
	if (s->rank == 0 && outdir_begin(&od, out, &bake_outdir_kind, cause) != 0)
		return -1;
	if (bake_run(s, r, cause) != 0) {
		if (s->rank == 0)
			outdir_fail(&od, cause);
		return -1;
	}
	if (s->rank != 0)
		return 0;	/* every rank holds the whole result; rank 0 writes it */
	double *m = xmalloc(sizeof(double) * 3 * (size_t)s->n_wl);
	struct bake_meta meta = { .preset = label, .ior = preset_surface_ior(p), .roughness = preset_surface_roughness(p),
		.macro_slope = p->macro_slope, .rgb_from_wl = m, .rgb_note = bake_rgb_weights(s, m),
		.command = command };
	int rc = bake_write_files(outdir_path(&od), s, r, &meta, cause) != 0 ? -2 : 0;
	if (rc != 0)
		outdir_fail(&od, cause);
	else if (outdir_commit(&od, cause) != 0 || checkpoint_remove(out, cause) != 0)
		rc = -2;
	free(m);
	return rc;
}
