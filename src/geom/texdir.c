/* texdir: write the maps of a skin-relief tile with their metadata, and
 * read back what exporters need (layout in texdir.h).
 * Over 600 lines because the writer and the reader of one directory format
 * are kept together, so that a change to one is seen next to the other. */
#include "config.h"
#include "geom/texdir.h"

#include <json-c/json.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/check.h"
#include "base/checksum.h"
#include "base/outdir.h"
#include "base/srgb.h"
#include "base/util.h"
#include "geom/relief_cavity.h"
#include "geom/relief_far.h"
#include "io/exrio.h"
#include "io/json.h"
#include "io/pngio.h"

static const char *NORMAL_CONVENTION = "OpenGL +Y";
static const char *NORMAL_CONVENTION_LONG =
    "tangent space, OpenGL +Y: +X right, +Y up (toward row 0), +Z out of the skin; "
    "PNG value = (n + 1) / 2 * 65535";

/* ---- writer ---- */

void texdir_maps_render(struct texdir_maps *m, const struct relief *r,
    const struct texture_config *cfg)
{
	size_t n = (size_t)cfg->size, npx = n * n;
	m->n = (int)n;
	m->pores = xmalloc(sizeof *m->pores * npx);
	m->furrows = xmalloc(sizeof *m->furrows * npx);
	m->height = xmalloc(sizeof *m->height * npx);
	relief_render(r, (int)n, 0, 0, m->pores, m->furrows);
	for (size_t i = 0; i < npx; i++)
		m->height[i] = m->pores[i] + m->furrows[i];
	m->nx = xmalloc(sizeof *m->nx * npx);
	m->ny = xmalloc(sizeof *m->ny * npx);
	m->nz = xmalloc(sizeof *m->nz * npx);
	relief_normals((int)n, cfg->relief.tile / (double)n, m->height, m->nx, m->ny, m->nz);
}

void texdir_maps_free(struct texdir_maps *m)
{
	free(m->pores);
	free(m->furrows);
	free(m->height);
	free(m->nx);
	free(m->ny);
	free(m->nz);
	memset(m, 0, sizeof *m);
}

char *texdir_resolution_notes(const struct texture_config *cfg, const struct relief *r)
{
	/* Furrows narrower than two pixels alias in the normal map. */
	double pitch = cfg->relief.tile / (double)cfg->size;
	char *s = NULL;
	for (int k = 0; k < cfg->relief.levels; k++) {
		struct relief_level_info li = relief_level(r, k);
		if (li.width < 2 * pitch && li.depth > 0) {
			char *t = xasprintf(
			    "%s%sfurrow level %d is %.3g um wide, less than 2 pixels (%.3g um); "
			    "raise --size or lower --levels", s ? s : "", s ? "\n" : "", k + 1,
			    li.width * 1e4, 2 * pitch * 1e4);
			free(s);
			s = t;
		}
	}
	if (cfg->relief.pore_density > 0 && cfg->relief.pore_radius < 1.5 * pitch) {
		char *t = xasprintf("%s%spore radius %.3g um is under 1.5 pixels (%.3g um)",
		    s ? s : "", s ? "\n" : "", cfg->relief.pore_radius * 1e4, 1.5 * pitch * 1e4);
		free(s);
		s = t;
	}
	return s;
}

/* Range of a height map [cm]. */
struct stats {
	double lo, hi;	/* [cm] */
};

static struct stats minmax(const float *h, size_t n)
{
	struct stats s = { INFINITY, -INFINITY };
	for (size_t i = 0; i < n; i++) {
		s.lo = fmin(s.lo, h[i]);
		s.hi = fmax(s.hi, h[i]);
	}
	return s;
}

void texdir_height_range(const struct texdir_maps *m, double *lo, double *hi)
{
	struct stats s = minmax(m->height, (size_t)m->n * (size_t)m->n);
	*lo = s.lo;
	*hi = s.hi;
}

/* 16-bit gray: lowest point 0, highest 65535 (a flat map is all 0). */
static uint16_t *quantise(const float *h, size_t n, struct stats s)
{
	uint16_t *q = xmalloc(sizeof *q * n);
	double range = s.hi - s.lo, k = range > 0 ? 65535.0 / range : 0;
	for (size_t i = 0; i < n; i++)
		q[i] = (uint16_t)fmin(65535.0, nearbyint((h[i] - s.lo) * k));
	return q;
}

struct outputs {
	const struct texture_config *cfg;
	const char *dir;
	char software[64];
	char tile[32], seed[32], size[32];
	const struct relief_stats *stats;	/* or NULL: no "stats" in the manifest */
	int far_m;	/* roughness_far.png edge [px] */
	float *far_alpha;	/* its alpha_relief values [1] */
	double far_block_um;	/* its texel on the skin [um] */
	float *cavity;		/* cavity.png's values [1], n x n */
	double cavity_um;	/* its look-around radius [um] */
};

static char *path_in(const struct outputs *o, const char *name)
{
	return xasprintf("%s/%s", o->dir, name);
}

static int write_height_png(const struct outputs *o, const char *name, const char *component,
    const float *h, struct stats s, char **cause)
{
	size_t n = (size_t)o->cfg->size;
	uint16_t *q = quantise(h, n * n, s);
	char lo[32], hi[32];
	snprintf(lo, sizeof lo, "%.6f", s.lo * 1e4);
	snprintf(hi, sizeof hi, "%.6f", s.hi * 1e4);
	struct png_text_kv text[] = {
		{ "Software", o->software },
		{ "skinbake:tile_mm", o->tile },
		{ "skinbake:height_min_um", lo },
		{ "skinbake:height_max_um", hi },
		{ "skinbake:site", o->cfg->site },
		{ "skinbake:seed", o->seed },
		{ "skinbake:size_px", o->size },
		{ "skinbake:component", component },
		{ "skinbake:encoding",
		  "height = min + value / 65535 * (max - min); y up = toward row 0" },
	};
	char *path = path_in(o, name);
	int rc = pngio_write(path, (int)n, (int)n, 1, 16, q, 0, (int)(sizeof text / sizeof text[0]),
	    text, cause);
	free(path);
	free(q);
	return rc;
}

static int write_normals(const struct outputs *o, const float *nx, const float *ny, const float *nz,
    char **cause)
{
	size_t n = (size_t)o->cfg->size, np = n * n;
	uint16_t *q = xmalloc(sizeof *q * 3 * np);
	for (size_t i = 0; i < np; i++) {
		q[3 * i] = (uint16_t)nearbyint((nx[i] + 1) * 0.5 * 65535);
		q[3 * i + 1] = (uint16_t)nearbyint((ny[i] + 1) * 0.5 * 65535);
		q[3 * i + 2] = (uint16_t)nearbyint((nz[i] + 1) * 0.5 * 65535);
	}
	struct png_text_kv text[] = {
		{ "Software", o->software },
		{ "skinbake:tile_mm", o->tile },
		{ "skinbake:site", o->cfg->site },
		{ "skinbake:seed", o->seed },
		{ "skinbake:size_px", o->size },
		{ "skinbake:normal_convention", NORMAL_CONVENTION },
		{ "skinbake:encoding", NORMAL_CONVENTION_LONG },
	};
	char *path = path_in(o, "normal.png");
	int rc = pngio_write(path, (int)n, (int)n, 3, 16, q, 0, (int)(sizeof text / sizeof text[0]),
	    text, cause);
	free(path);
	free(q);
	if (rc != 0)
		return rc;
	const char *names[] = { "R", "G", "B" };
	const float *planes[] = { nx, ny, nz };
	struct exr_attr_kv attrs[] = {
		{ "skinbake:software", o->software },
		{ "skinbake:tile_mm", o->tile },
		{ "skinbake:site", o->cfg->site },
		{ "skinbake:seed", o->seed },
		{ "skinbake:normal_convention", NORMAL_CONVENTION },
		{ "skinbake:encoding",
		  "R, G, B = unit normal x, y, z in [-1, 1]; x right, y up, z out" },
	};
	path = path_in(o, "normal.exr");
	rc = exrio_write(path, (int)n, (int)n, 3, names, planes,
	    (int)(sizeof attrs / sizeof attrs[0]), attrs, cause);
	free(path);
	return rc;
}

static int write_height_exr(const struct outputs *o, float *h, char **cause)
{
	size_t np = (size_t)o->cfg->size * (size_t)o->cfg->size;
	float *um = xmalloc(sizeof *um * np);
	for (size_t i = 0; i < np; i++)
		um[i] = h[i] * 1e4f;
	const char *names[] = { "Y" };
	const float *planes[] = { um };
	struct exr_attr_kv attrs[] = {
		{ "skinbake:software", o->software },
		{ "skinbake:tile_mm", o->tile },
		{ "skinbake:site", o->cfg->site },
		{ "skinbake:seed", o->seed },
		{ "skinbake:units",
		  "um, relative to the undisturbed skin surface (0); y up = toward row 0" },
	};
	char *path = path_in(o, "height.exr");
	int rc = exrio_write(path, o->cfg->size, o->cfg->size, 1, names, planes,
	    (int)(sizeof attrs / sizeof attrs[0]), attrs, cause);
	free(path);
	free(um);
	return rc;
}

/* Lambert shading under a light from the upper left at 45 degrees, on a
 * light skin tone: for people, not for rendering. */
static int write_preview(const struct outputs *o, const float *nx, const float *ny, const float *nz,
    char **cause)
{
	size_t np = (size_t)o->cfg->size * (size_t)o->cfg->size;
	const double tint[3] = { 0.80, 0.56, 0.45 };	/* linear albedo, light
							 * skin; illustrative */
	double lx = -0.5, ly = 0.5, lz = sqrt(0.5);
	uint16_t *q = xmalloc(sizeof *q * 3 * np);
	for (size_t i = 0; i < np; i++) {
		double s = fmax(0, nx[i] * lx + ny[i] * ly + nz[i] * lz) / lz;
		for (int c = 0; c < 3; c++)
			q[3 * i + c] = (uint16_t)nearbyint(255 * srgb_encode(0.85 * tint[c] * s));
	}
	struct png_text_kv text[] = {
		{ "Software", o->software },
		{ "skinbake:tile_mm", o->tile },
		{ "skinbake:site", o->cfg->site },
		{ "skinbake:seed", o->seed },
		{ "skinbake:preview",
		  "Lambert shading of normal.png, light from the upper left at 45 deg" },
	};
	char *path = path_in(o, "preview.png");
	int rc = pngio_write(path, o->cfg->size, o->cfg->size, 3, 8, q, 1,
	    (int)(sizeof text / sizeof text[0]), text, cause);
	free(path);
	free(q);
	return rc;
}

static json_object *jrange(const char *file, struct stats s)
{
	json_object *c = json_object_new_object();
	json_object_object_add(c, "file", json_object_new_string(file));
	json_object_object_add(c, "height_min_um", json_num(s.lo * 1e4));
	json_object_object_add(c, "height_max_um", json_num(s.hi * 1e4));
	return c;
}

static int write_manifest(const struct outputs *o, const struct relief *r, struct stats sh,
    struct stats sp, struct stats sf, char **cause)
{
	const struct texture_config *cfg = o->cfg;
	double tile_mm = cfg->relief.tile * 10;
	json_object *m = json_object_new_object();
	json_object_object_add(m, "kind", json_object_new_string("skinbake texture"));
	json_object_object_add(m, "skinbake_version", json_object_new_string(PACKAGE_VERSION));
	json_object_object_add(m, "site", json_object_new_string(cfg->site));
	const char *dmap = cfg->direction_map;
	json_object_object_add(m, "direction_map", dmap ? json_object_new_string(dmap) : NULL);
	json_object_object_add(m, "seed", json_object_new_uint64(cfg->seed));
	json_object_object_add(m, "size_px", json_object_new_int64(cfg->size));
	json_object_object_add(m, "tile_mm", json_num(tile_mm));
	json_object_object_add(m, "pixel_um", json_num(tile_mm * 1000 / (double)cfg->size));
	json_object_object_add(m, "height_min_um", json_num(sh.lo * 1e4));
	json_object_object_add(m, "height_max_um", json_num(sh.hi * 1e4));
	json_object_object_add(m, "height_encoding", json_object_new_string(
	    "height.png: 16-bit gray, 0 = height_min_um, 65535 = height_max_um, linear; "
	    "heights relative to the undisturbed surface"));
	/* POV-Ray bump_map scale (docs pov.md section 4): range * pixels / tile. */
	json_object_object_add(m, "pov_bump_size",
	    json_num((sh.hi - sh.lo) * 10 * (double)cfg->size / tile_mm));
	json_object_object_add(m, "normal_convention", json_object_new_string(NORMAL_CONVENTION));
	json_object_object_add(m, "normal_encoding",
	    json_object_new_string(NORMAL_CONVENTION_LONG));
	json_object_object_add(m, "row0",
	    json_object_new_string("top of the image = +y end of the tile"));
	json_object_object_add(m, "tileable", json_object_new_boolean(1));

	int n;
	const struct texture_param *p = sites_params(&n);
	json_object *par = json_object_new_object(), *units = json_object_new_object();
	for (int i = 0; i < n; i++) {
		char key[64];
		snprintf(key, sizeof key, "%s", p[i].key);
		for (char *c = key; *c; c++)
			if (*c == '-')
				*c = '_';
		double v = sites_get(cfg, &p[i]);
		json_object_object_add(par, key, p[i].type == SITES_REAL ? json_num(v)
		    : p[i].type == SITES_SEED ? json_object_new_uint64(cfg->seed)
		    : json_object_new_int64((int64_t)v));
		json_object_object_add(units, key, json_object_new_string(p[i].unit));
	}
	json_object_object_add(m, "parameters", par);
	json_object_object_add(m, "parameter_units", units);

	json_object *lv = json_object_new_array();
	for (int k = 0; k < cfg->relief.levels; k++) {
		struct relief_level_info li = relief_level(r, k);
		json_object *l = json_object_new_object();
		json_object_object_add(l, "level", json_object_new_int(k + 1));
		json_object_object_add(l, "junctions", json_object_new_int(li.points));
		json_object_object_add(l, "furrows", json_object_new_int(li.furrows));
		json_object_object_add(l, "cell_mm", json_num(li.cell * 10));
		json_object_object_add(l, "width_um", json_num(li.width * 1e4));
		json_object_object_add(l, "depth_um", json_num(li.depth * 1e4));
		json_object_object_add(l, "ridge_um", json_num(li.ridge * 1e4));
		json_object_array_add(lv, l);
	}
	json_object_object_add(m, "furrow_levels", lv);
	json_object_object_add(m, "pores", json_object_new_int(relief_n_pores(r)));
	json_object *comp = json_object_new_object();
	json_object_object_add(comp, "combined", jrange("height.png", sh));
	json_object_object_add(comp, "pores", jrange("pores_height.png", sp));
	json_object_object_add(comp, "furrows", jrange("furrows_height.png", sf));
	json_object_object_add(m, "components", comp);
	if (o->stats)
		json_object_object_add(m, "stats", relief_stats_json(o->stats));

	json_object *far = json_object_new_object();
	double amean = 0, amax = 0;
	for (int i = 0; i < o->far_m * o->far_m; i++) {
		amean += o->far_alpha[i] / ((double)o->far_m * o->far_m);
		amax = fmax(amax, o->far_alpha[i]);
	}
	json_object_object_add(far, "file", json_object_new_string("roughness_far.png"));
	json_object_object_add(far, "size_px", json_object_new_int(o->far_m));
	json_object_object_add(far, "block_um", json_num(o->far_block_um));
	json_object_object_add(far, "alpha_mean", json_num(amean));
	json_object_object_add(far, "alpha_max", json_num(amax));
	json_object_object_add(m, "far_roughness", far);
	json_object *cv = json_object_new_object();
	double cmean = 0, cmin = 1;
	size_t ncv = (size_t)o->cfg->size * (size_t)o->cfg->size;
	for (size_t i = 0; i < ncv; i++) {
		cmean += o->cavity[i] / (double)ncv;
		cmin = fmin(cmin, o->cavity[i]);
	}
	json_object_object_add(cv, "file", json_object_new_string("cavity.png"));
	json_object_object_add(cv, "radius_um", json_num(o->cavity_um));
	json_object_object_add(cv, "furrow_weight", json_num(RELIEF_CAVITY_FURROW_WEIGHT));
	json_object_object_add(cv, "mean", json_num(cmean));
	json_object_object_add(cv, "min", json_num(cmin));
	json_object_object_add(cv, "encoding", json_object_new_string(
	    "16-bit gray, cavity = value / 65535 = AO(pores) * AO(furrows)^furrow_weight, "
	    "horizon-based ambient occlusion of each relief (1 = open sky); multiply into "
	    "the skin's shading (docs/relief.md)"));
	json_object_object_add(m, "cavity", cv);
	static const char *files[] = { "height.png", "normal.png", "normal.exr", "height.exr",
		"preview.png", "pores_height.png", "furrows_height.png", "roughness_far.png",
		"cavity.png", "manifest.json" };
	json_object *fl = json_object_new_array();
	for (size_t i = 0; i < sizeof files / sizeof files[0]; i++)
		json_object_array_add(fl, json_object_new_string(files[i]));
	json_object_object_add(m, "files", fl);

	char *text = json_text(m, JSON_PRETTY);
	int rc = checksum_write_manifest(o->dir, "manifest.json", text, cause);
	free(text);
	json_object_put(m);
	return rc;
}

static const char *const texdir_names[] = {
	"height.png", "normal.png", "normal.exr", "height.exr", "preview.png",
	"pores_height.png", "furrows_height.png", "roughness_far.png", "cavity.png", NULL
};
const struct outdir_kind texdir_outdir_kind = {
	"texture directory", "manifest.json", "kind", "skinbake texture", texdir_names
};

/* Every file into the existing directory DIR, manifest.json last. */
static int write_files(const char *dir, const struct texture_config *cfg, const struct relief *r,
    const struct texdir_maps *m, const struct relief_stats *st, char **cause)
{
	CHECK(m->n == (int)cfg->size);
	size_t npx = (size_t)m->n * (size_t)m->n;
	struct stats sh = minmax(m->height, npx), sp = minmax(m->pores, npx),
	    sf = minmax(m->furrows, npx);
	struct outputs o = { .cfg = cfg, .dir = dir, .stats = st };
	snprintf(o.software, sizeof o.software, "skinbake %s", PACKAGE_VERSION);
	snprintf(o.tile, sizeof o.tile, "%.10g", cfg->relief.tile * 10);
	snprintf(o.seed, sizeof o.seed, "%llu", (unsigned long long)cfg->seed);
	snprintf(o.size, sizeof o.size, "%ld", cfg->size);
	double pitch = cfg->relief.tile / (double)m->n;
	double cell = cfg->relief.levels > 0 ? cfg->relief.furrow_cell : cfg->relief.tile;
	o.far_m = relief_far_size(m->n, pitch, cell);
	o.far_alpha = xmalloc(sizeof *o.far_alpha * (size_t)o.far_m * (size_t)o.far_m);
	o.far_block_um = cfg->relief.tile / o.far_m * 1e4;
	relief_far_alpha(m->n, m->nx, m->ny, m->nz, o.far_m, o.far_alpha);
	char *far_path = path_in(&o, "roughness_far.png");
	double cav_r = relief_cavity_radius(cell, cfg->relief.tile);
	o.cavity = xmalloc(sizeof *o.cavity * npx);
	o.cavity_um = cav_r * 1e4;
	relief_cavity_combined(m->n, pitch, m->pores, m->furrows, cav_r, o.cavity);
	char *cav_path = path_in(&o, "cavity.png");
	/* The writers are independent (own libpng / OpenEXR contexts), and
	 * compression dominates, so they run in parallel; the manifest, which
	 * lists them, comes last. */
	char *why[8] = { NULL };
	int failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(|:failed)
	for (int t = 0; t < 8; t++) {
		int e = 0;
		switch (t) {
		case 0:
			e = write_normals(&o, m->nx, m->ny, m->nz, &why[t]);
			break;
		case 1:
			e = write_height_exr(&o, m->height, &why[t]);
			break;
		case 2:
			e = write_height_png(&o, "height.png", "combined", m->height, sh, &why[t]);
			break;
		case 3:
			e = write_preview(&o, m->nx, m->ny, m->nz, &why[t]);
			break;
		case 4:
			e = write_height_png(&o, "pores_height.png", "pores", m->pores, sp,
			    &why[t]);
			break;
		case 5:
			e = write_height_png(&o, "furrows_height.png", "furrows", m->furrows, sf,
			    &why[t]);
			break;
		case 6:
			e = relief_cavity_write(cav_path, m->n, o.cavity, o.cavity_um, cfg->site,
			    o.software, &why[t]);
			break;
		default:
			e = relief_far_write(far_path, o.far_m, o.far_alpha, o.far_block_um,
			    cfg->site, o.software, &why[t]);
			break;
		}
		failed |= e != 0;
	}
	for (int t = 0; t < 8; t++) {
		if (why[t] && *cause == NULL)
			*cause = why[t];
		else
			free(why[t]);
	}
	free(far_path);
	free(cav_path);
	int rc = failed ? -1 : write_manifest(&o, r, sh, sp, sf, cause);
	free(o.far_alpha);
	free(o.cavity);
	return rc;
}

/* The steps in the order the command reports them; the output (and its
 * lock) is taken first, nothing is written before the relief has been
 * placed. */
int texdir_make(const char *dir, const struct texture_config *cfg, struct texdir_made *made,
    char **cause)
{
	memset(made, 0, sizeof *made);
	/* Measured: peak memory about 40 bytes per pixel (the six float maps
	 * and the writers' buffers), files about 27 bytes per pixel. */
	double npx = (double)cfg->size * (double)cfg->size;
	char *what = xasprintf("texture --size %ld", cfg->size);
	int e = budget_check(what, TEXDIR_MEM_PER_PX * npx + 16e6, TEXDIR_DISK_PER_PX * npx, dir,
	    "lower --size (a quarter of the pixels at half the size)", cause);
	free(what);
	if (e != 0) {
		made->refused = 1;
		return -1;
	}
	struct outdir od;
	if (outdir_begin(&od, dir, &texdir_outdir_kind, cause) != 0) {
		made->refused = 1;
		return -1;
	}
	double t0 = util_now();
	struct relief *r = relief_new(&cfg->relief, cfg->seed, cause);
	if (r == NULL) {
		outdir_fail(&od, cause);
		return -1;
	}
	made->n_pores = relief_n_pores(r);
	made->notes = texdir_resolution_notes(cfg, r);
	double t1 = util_now();
	struct texdir_maps m;
	texdir_maps_render(&m, r, cfg);
	texdir_height_range(&m, &made->h_min, &made->h_max);
	made->have_stats = cfg->with_stats
	    && relief_stats_for(&cfg->relief, m.n, m.height, m.furrows, m.pores, &made->stats) == 0;
	double t2 = util_now();
	int rc = write_files(outdir_path(&od), cfg, r, &m, made->have_stats ? &made->stats : NULL,
	    cause);
	if (rc != 0)
		outdir_fail(&od, cause);
	else
		rc = outdir_commit(&od, cause);
	made->t_place = t1 - t0;
	made->t_render = t2 - t1;
	made->t_write = util_now() - t2;
	texdir_maps_free(&m);
	relief_free(r);
	return rc;
}

/* ---- reader ---- */

void texdir_free(struct texdir *t)
{
	if (t == NULL)
		return;
	free(t->dir);
	free(t->height);
	free(t->normal);
	free(t->tile_mm_text);
	free(t->h_min_text);
	free(t->h_max_text);
	free(t);
}

static int finite_number(const char *s, double *v)
{
	return s != NULL && util_parse_double(s, v) == 0 && isfinite(*v);
}

/* height.png's pixels. */
static int read_height(const char *hp, struct texdir *t, char **cause)
{
	int hc, hb;
	t->height = pngio_read(hp, &t->w, &t->h, &hc, &hb, cause);
	if (t->height == NULL)
		return -1;
	if (hc != 1 || hb != 16) {
		*cause = xasprintf("%s: %d channel(s) at %d bits; expected 16-bit gray", hp, hc,
		    hb);
		return -1;
	}
	/* Maps made elsewhere may be small or not square; the largest is that of
	 * `texture --size`. */
	const struct texture_param *sp = sites_param_find("size");
	if (t->w < 2 || t->h < 2 || t->w > sp->hi || t->h > sp->hi) {
		*cause = xasprintf("%s: %dx%d pixels; expected each side in [2, %g]", hp, t->w,
		    t->h, sp->hi);
		return -1;
	}
	return 0;
}

/* The physical size and range in height.png's tEXt chunks: tile_mm in
 * the range of the texture parameter tile-mm, the heights both absent or
 * both finite with min <= max. */
static int read_numbers(const char *hp, struct texdir *t, char **cause)
{
	const struct texture_param *tp = sites_param_find("tile-mm");
	t->tile_mm_text = pngio_read_text(hp, "skinbake:tile_mm");
	if (t->tile_mm_text == NULL || util_parse_double(t->tile_mm_text, &t->tile_mm) != 0 ||
	    !(t->tile_mm >= tp->lo && t->tile_mm <= tp->hi)) {
		*cause = xasprintf(
		    "%s: tEXt skinbake:tile_mm is %s; expected a length in [%g, %g] mm", hp,
		    t->tile_mm_text ? t->tile_mm_text : "missing", tp->lo, tp->hi);
		return -1;
	}
	t->h_min_text = pngio_read_text(hp, "skinbake:height_min_um");
	t->h_max_text = pngio_read_text(hp, "skinbake:height_max_um");
	if (t->h_min_text == NULL && t->h_max_text == NULL)
		return 0;
	const char *bad = !finite_number(t->h_min_text, &t->h_min_um) ? "skinbake:height_min_um"
	    : !finite_number(t->h_max_text, &t->h_max_um) ? "skinbake:height_max_um" : NULL;
	if (bad) {
		const char *v = strstr(bad, "min") ? t->h_min_text : t->h_max_text;
		*cause = xasprintf("%s: tEXt %s is %s; expected a finite height [um] (with the "
		    "other of skinbake:height_min_um, skinbake:height_max_um)", hp, bad,
		    v ? v : "missing");
		return -1;
	}
	if (!(t->h_min_um <= t->h_max_um)) {
		*cause = xasprintf("%s: tEXt skinbake:height_min_um = %s is above "
		    "skinbake:height_max_um = %s; expected min <= max", hp, t->h_min_text,
		    t->h_max_text);
		return -1;
	}
	t->have_range = 1;
	return 0;
}

/* One number of manifest.json: present, a number, and (when text is not
 * NULL) equal to that tEXt value of height.png to rel (relative). */
static int manifest_number(const char *mp, json_object *m, const char *key, double want,
    const char *text, double rel, char **cause)
{
	json_object *v;
	if (!json_object_object_get_ex(m, key, &v) || !(json_object_is_type(v, json_type_double) ||
	    json_object_is_type(v, json_type_int))) {
		*cause = xasprintf("%s: key %s is %s; expected a number", mp, key,
		    v ? json_object_to_json_string(v) : "missing");
		return -1;
	}
	double x = json_object_get_double(v);
	if (!(fabs(x - want) <= rel * fmax(fabs(want), 1e-3))) {
		*cause = xasprintf("%s: key %s = %s disagrees with height.png (%s); expected %s",
		    mp, key, json_object_to_json_string(v), text, text);
		return -1;
	}
	return 0;
}

/* manifest.json, when there is one (maps made elsewhere may come without):
 * a skinbake texture whose size and physical numbers are those of height.png. */
static int check_manifest(const char *dir, const struct texdir *t, char **cause)
{
	char *mp = xasprintf("%s/manifest.json", dir);
	FILE *f = fopen(mp, "r");
	if (f == NULL) {
		free(mp);
		return 0;
	}
	fclose(f);
	json_object *m = json_load(mp), *v;
	int rc = -1;
	char px[32];
	snprintf(px, sizeof px, "%d px", t->w);
	if (m == NULL || !json_object_is_type(m, json_type_object))
		*cause = xasprintf("%s: not a JSON object (%s)", mp, json_util_get_last_err());
	else if (!json_object_object_get_ex(m, "kind", &v) ||
	    !json_object_is_type(v, json_type_string) ||
	    strcmp(json_object_get_string(v), "skinbake texture") != 0)
		*cause = xasprintf("%s: key kind is %s; expected \"skinbake texture\"", mp,
		    v ? json_object_to_json_string(v) : "missing");
	else if (!json_object_object_get_ex(m, "size_px", &v) ||
	    !json_object_is_type(v, json_type_int) ||
	    json_object_get_int64(v) != t->w || t->w != t->h)
		*cause = xasprintf("%s: key size_px is %s but height.png is %dx%d; expected %d", mp,
		    v ? json_object_to_json_string(v) : "missing", t->w, t->h, t->w);
	else if (manifest_number(mp, m, "tile_mm", t->tile_mm, t->tile_mm_text, 1e-9, cause) == 0 &&
	    (!t->have_range || (
	    manifest_number(mp, m, "height_min_um", t->h_min_um, t->h_min_text, 1e-5, cause) == 0 &&
	    manifest_number(mp, m, "height_max_um", t->h_max_um, t->h_max_text, 1e-5, cause) == 0)))
		rc = 0;
	json_object_put(m);
	free(mp);
	return rc;
}

static int read_normal(const char *np, const char *hp, struct texdir *t, char **cause)
{
	int nw, nh, nc, nb;
	t->normal = pngio_read(np, &nw, &nh, &nc, &nb, cause);
	if (t->normal == NULL)
		return -1;
	if (nc != 3 || nb != 16) {
		*cause = xasprintf("%s: %d channel(s) at %d bits; expected 16-bit RGB", np, nc, nb);
		return -1;
	}
	if (nw != t->w || nh != t->h) {
		*cause = xasprintf("%s is %dx%d but %s is %dx%d; they must match", np, nw, nh, hp,
		    t->w, t->h);
		return -1;
	}
	return 0;
}

struct texdir *texdir_load(const char *dir, int with_normal, char **cause)
{
	struct texdir *t = xcalloc(1, sizeof *t);
	t->dir = xstrdup(dir);
	char *hp = xasprintf("%s/height.png", dir), *np = xasprintf("%s/normal.png", dir);
	int rc = checksum_verify_dir(dir, "manifest.json", cause);
	if (rc == 0)
		rc = read_height(hp, t, cause);
	if (rc == 0 && with_normal)
		rc = read_normal(np, hp, t, cause);
	if (rc == 0)
		rc = read_numbers(hp, t, cause);
	if (rc == 0)
		rc = check_manifest(dir, t, cause);
	free(hp);
	free(np);
	if (rc != 0) {
		texdir_free(t);
		return NULL;
	}
	return t;
}
