/* skinbake texture: grow the micro-relief of a skin site (pores and
 * Delaunay furrows) as seamless maps: a 16-bit height PNG with its physical
 * range in tEXt chunks, the components, a tangent-space normal map (16-bit
 * PNG and float EXR, OpenGL +Y), a float height EXR, an 8-bit preview and
 * manifest.json.  Everything is validated before any file is written. */
#include "config.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "io/exrio.h"
#include "io/pngio.h"
#include "geom/relief.h"
#include "geom/sites.h"
#include "base/util.h"

static const char *CMD = "texture";

static const char *NORMAL_CONVENTION = "OpenGL +Y";
static const char *NORMAL_CONVENTION_LONG =
    "tangent space, OpenGL +Y: +X right, +Y up (toward row 0), +Z out of the skin; "
    "PNG value = (n + 1) / 2 * 65535";

static void list_sites(void)
{
	for (int i = 0; i < sites_count(); i++)
		printf("%-10s %s\n", sites_name(i), sites_summary(i));
}

static void dump_config(const struct texture_config *cfg)
{
	int n;
	const struct texture_param *p = sites_params(&n);
	printf("[texture]\nsite = %s\n", cfg->site);
	for (int i = 0; i < n; i++) {
		char key[64];
		snprintf(key, sizeof key, "%s", p[i].key);
		for (char *c = key; *c; c++)
			if (*c == '-')
				*c = '_';
		printf("%s = %.17g\n", key, sites_get(cfg, &p[i]));
	}
}

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
		{ "skinbake:encoding", "height = min + value / 65535 * (max - min); y up = toward row 0" },
	};
	char *path = path_in(o, name);
	int rc = pngio_write(path, (int)n, (int)n, 1, 16, q, 0, (int)(sizeof text / sizeof text[0]), text,
	    cause);
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
	int rc = pngio_write(path, (int)n, (int)n, 3, 16, q, 0, (int)(sizeof text / sizeof text[0]), text,
	    cause);
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
		{ "skinbake:encoding", "R, G, B = unit normal x, y, z in [-1, 1]; x right, y up, z out" },
	};
	path = path_in(o, "normal.exr");
	rc = exrio_write(path, (int)n, (int)n, 3, names, planes, (int)(sizeof attrs / sizeof attrs[0]),
	    attrs, cause);
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
		{ "skinbake:units", "um, relative to the undisturbed skin surface (0); y up = toward row 0" },
	};
	char *path = path_in(o, "height.exr");
	int rc = exrio_write(path, o->cfg->size, o->cfg->size, 1, names, planes,
	    (int)(sizeof attrs / sizeof attrs[0]), attrs, cause);
	free(path);
	free(um);
	return rc;
}

static double srgb_encode(double v)
{
	v = fmax(0, fmin(1, v));
	return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

/* Lambert shading under a light from the upper left at 45 degrees, on a
 * light skin tone: for people, not for rendering. */
static int write_preview(const struct outputs *o, const float *nx, const float *ny, const float *nz,
    char **cause)
{
	size_t np = (size_t)o->cfg->size * (size_t)o->cfg->size;
	const double tint[3] = { 0.80, 0.56, 0.45 };	/* linear albedo, light skin; illustrative */
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
		{ "skinbake:preview", "Lambert shading of normal.png, light from the upper left at 45 deg" },
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
	json_object_object_add(c, "height_min_um", json_object_new_double(s.lo * 1e4));
	json_object_object_add(c, "height_max_um", json_object_new_double(s.hi * 1e4));
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
	json_object_object_add(m, "seed", json_object_new_int64((int64_t)cfg->seed));
	json_object_object_add(m, "size_px", json_object_new_int64(cfg->size));
	json_object_object_add(m, "tile_mm", json_object_new_double(tile_mm));
	json_object_object_add(m, "pixel_um", json_object_new_double(tile_mm * 1000 / (double)cfg->size));
	json_object_object_add(m, "height_min_um", json_object_new_double(sh.lo * 1e4));
	json_object_object_add(m, "height_max_um", json_object_new_double(sh.hi * 1e4));
	json_object_object_add(m, "height_encoding", json_object_new_string(
	    "height.png: 16-bit gray, 0 = height_min_um, 65535 = height_max_um, linear; "
	    "heights relative to the undisturbed surface"));
	/* POV-Ray bump_map scale (docs pov.md section 4): range * pixels / tile. */
	json_object_object_add(m, "pov_bump_size",
	    json_object_new_double((sh.hi - sh.lo) * 10 * (double)cfg->size / tile_mm));
	json_object_object_add(m, "normal_convention", json_object_new_string(NORMAL_CONVENTION));
	json_object_object_add(m, "normal_encoding", json_object_new_string(NORMAL_CONVENTION_LONG));
	json_object_object_add(m, "row0", json_object_new_string("top of the image = +y end of the tile"));
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
		json_object_object_add(par, key, p[i].type == SITES_REAL ? json_object_new_double(v)
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
		json_object_object_add(l, "furrows", json_object_new_int(3 * li.points));
		json_object_object_add(l, "cell_mm", json_object_new_double(li.cell * 10));
		json_object_object_add(l, "width_um", json_object_new_double(li.width * 1e4));
		json_object_object_add(l, "depth_um", json_object_new_double(li.depth * 1e4));
		json_object_object_add(l, "ridge_um", json_object_new_double(li.ridge * 1e4));
		json_object_array_add(lv, l);
	}
	json_object_object_add(m, "furrow_levels", lv);
	json_object_object_add(m, "pores", json_object_new_int(relief_n_pores(r)));
	json_object *comp = json_object_new_object();
	json_object_object_add(comp, "combined", jrange("height.png", sh));
	json_object_object_add(comp, "pores", jrange("pores_height.png", sp));
	json_object_object_add(comp, "furrows", jrange("furrows_height.png", sf));
	json_object_object_add(m, "components", comp);

	static const char *files[] = { "height.png", "normal.png", "normal.exr", "height.exr",
		"preview.png", "pores_height.png", "furrows_height.png", "manifest.json" };
	json_object *fl = json_object_new_array();
	for (size_t i = 0; i < sizeof files / sizeof files[0]; i++)
		json_object_array_add(fl, json_object_new_string(files[i]));
	json_object_object_add(m, "files", fl);

	char *path = path_in(o, "manifest.json");
	struct outfile of;
	int rc = outfile_open(&of, path, cause);
	if (rc == 0) {
		fprintf(of.fp, "%s\n", json_object_to_json_string_ext(m,
		    JSON_C_TO_STRING_PRETTY | JSON_C_TO_STRING_NOSLASHESCAPE));
		rc = outfile_commit(&of, cause);
	}
	free(path);
	json_object_put(m);
	return rc;
}

/* Furrows narrower than two pixels alias in the normal map. */
static void warn_resolution(const struct texture_config *cfg, const struct relief *r)
{
	double pitch = cfg->relief.tile / (double)cfg->size;
	for (int k = 0; k < cfg->relief.levels; k++) {
		struct relief_level_info li = relief_level(r, k);
		if (li.width < 2 * pitch && li.depth > 0)
			fprintf(stderr, "skinbake texture: note: furrow level %d is %.3g um wide, less than "
			    "2 pixels (%.3g um); raise --size or lower --levels\n", k + 1, li.width * 1e4,
			    2 * pitch * 1e4);
	}
	if (cfg->relief.pore_density > 0 && cfg->relief.pore_radius < 1.5 * pitch)
		fprintf(stderr, "skinbake texture: note: pore radius %.3g um is under 1.5 pixels (%.3g um)\n",
		    cfg->relief.pore_radius * 1e4, 1.5 * pitch * 1e4);
}

int cmd_texture(int argc, char **argv)
{
	int np;
	const struct texture_param *params = sites_params(&np);
	const char *site = "face", *preset = NULL, *out = NULL;
	int quiet = 0, dump = 0, list = 0, rc = CLI_EXIT_USAGE;
	struct opt opts[OPT_MAX] = {
		{ "site", OPT_STRING, &site, "NAME", "face", .help = "start from a body site (see --list-sites)" },
		{ "preset-file", OPT_PATH_IN, &preset, "FILE", .flags = OPT_FILE, .help = "start from the [texture] "
		  "section of an INI file (keys as below with '_' for '-'; 'site = NAME' first resets to that site); "
		  "applied after --site" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .help = "output directory (created if missing), required unless "
		  "--list-sites or --dump-config" },
		{ "list-sites", OPT_FLAG, &list, .help = "list the sites and exit" },
		{ "dump-config", OPT_FLAG, &dump, .help = "print the resolved [texture] section and exit" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stderr" },
	};
	/* One option per texture parameter, from the table in geom/sites.c. */
	enum { N_FIXED = 6 };
	char defs[OPT_MAX][32];
	struct texture_config cfg;
	char *cause = NULL;
	sites_load("face", &cfg, &cause);
	for (int i = 0; i < np && N_FIXED + i < OPT_MAX - 1; i++) {
		const struct texture_param *p = &params[i];
		snprintf(defs[i], sizeof defs[i], "%.10g", sites_get(&cfg, p));
		opts[N_FIXED + i] = (struct opt){ p->key, p->type == SITES_REAL ? OPT_DOUBLE : OPT_LONG, NULL,
			p->type == SITES_REAL ? "X" : "N", .def_note = defs[i], .lo = p->lo, .hi = p->hi,
			.unit = strcmp(p->unit, "1") ? p->unit : NULL, .help = p->help };
	}
	const struct opt_cmd cmd = { "texture", "[--site NAME | --preset-file FILE] [options] --out DIR",
		"Grow the micro-relief of skin (pores and a net of triangular furrows) as\n"
		"seamless, tileable maps: DIR/height.png (16-bit, physical range in its tEXt\n"
		"chunks), pores_height.png, furrows_height.png, normal.png (16-bit RGB) and\n"
		"normal.exr (float) in tangent space with the OpenGL +Y convention,\n"
		"height.exr (float, um), preview.png (8-bit) and manifest.json.  The\n"
		"parameters after --quiet override the site; the defaults shown are site 'face'.", opts,
		"Finer furrow level k (k = 0 primary) has cell furrow-cell * level-scale^k,\n"
		"depth furrow-depth * level-gain^k, dome ridge-height * level-gain^k and\n"
		"width furrow-width * level-scale^(k/2) (at most half its cell).\n\n"
		"Heights are relative to the undisturbed surface; 0 in height.png is the\n"
		"lowest point of the map and 65535 the highest (skinbake:height_min_um and\n"
		"skinbake:height_max_um).  POV-Ray: bump_size = (max - min) * size / tile.\n"
		"Sources and details: docs/texture.md.", 0, 0 };
	struct opt_ctx x;
	struct relief *r = NULL;
	float *pores = NULL, *furrows = NULL, *h = NULL, *nx = NULL, *ny = NULL, *nz = NULL;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (list) {
		list_sites();
		return CLI_EXIT_OK;
	}

	/* Site, then preset file, then the options in command-line order. */
	if (sites_load(site, &cfg, &cause) != 0) {
		cli_usage_error(CMD, "--site: %s", cause);
		goto done;
	}
	if (preset && sites_read_ini(preset, &cfg, &cause) != 0) {
		cli_usage_error(CMD, "--preset-file: %s", cause);
		goto done;
	}
	for (int i = 0; i < np; i++) {
		char label[64];
		snprintf(label, sizeof label, "--%s", params[i].key);
		if (opt_given(&x, params[i].key) && sites_set(&cfg, &params[i], label, opt_text(&x, params[i].key), &cause) != 0) {
			cli_usage_error(CMD, "%s", cause);
			goto done;
		}
	}
	if (relief_params_check(&cfg.relief, &cause) != 0) {
		cli_usage_error(CMD, "%s", cause);
		goto done;
	}
	if (dump) {
		dump_config(&cfg);
		rc = CLI_EXIT_OK;
		goto done;
	}
	if (out == NULL) {
		cli_usage_error(CMD, "--out DIR is required");
		goto done;
	}

	/* Grow the relief: nothing is written before this has succeeded. */
	double t0 = util_now();
	r = relief_new(&cfg.relief, cfg.seed, &cause);
	if (r == NULL) {
		rc = cli_fail(CMD, "%s", cause);
		goto done;
	}
	if (!quiet)
		warn_resolution(&cfg, r);
	double t1 = util_now();
	size_t n = (size_t)cfg.size, npx = n * n;
	pores = xmalloc(sizeof *pores * npx);
	furrows = xmalloc(sizeof *furrows * npx);
	h = xmalloc(sizeof *h * npx);
	relief_render(r, (int)n, 0, 0, pores, furrows);
	for (size_t i = 0; i < npx; i++)
		h[i] = pores[i] + furrows[i];
	nx = xmalloc(sizeof *nx * npx);
	ny = xmalloc(sizeof *ny * npx);
	nz = xmalloc(sizeof *nz * npx);
	relief_normals((int)n, cfg.relief.tile / (double)n, h, nx, ny, nz);
	struct stats sh = minmax(h, npx), sp = minmax(pores, npx), sf = minmax(furrows, npx);
	double t2 = util_now();

	struct outputs o = { .cfg = &cfg, .dir = out };
	snprintf(o.software, sizeof o.software, "skinbake %s", PACKAGE_VERSION);
	snprintf(o.tile, sizeof o.tile, "%.10g", cfg.relief.tile * 10);
	snprintf(o.seed, sizeof o.seed, "%llu", (unsigned long long)cfg.seed);
	snprintf(o.size, sizeof o.size, "%ld", cfg.size);
	rc = CLI_EXIT_FAIL;
	if (util_mkdirs(out, &cause) != 0) {
		cli_fail(CMD, "%s", cause);
		goto done;
	}
	/* The writers are independent (own libpng / OpenEXR contexts), and
	 * compression dominates, so they run in parallel; the manifest, which
	 * lists them, comes last. */
	char *why[7] = { NULL };
	int failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(|:failed)
	for (int t = 0; t < 7; t++) {
		int e = 0;
		switch (t) {
		case 0: e = write_normals(&o, nx, ny, nz, &why[t]); break;
		case 1: e = write_height_exr(&o, h, &why[t]); break;
		case 2: e = write_height_png(&o, "height.png", "combined", h, sh, &why[t]); break;
		case 3: e = write_preview(&o, nx, ny, nz, &why[t]); break;
		case 4: e = write_height_png(&o, "pores_height.png", "pores", pores, sp, &why[t]); break;
		case 5: e = write_height_png(&o, "furrows_height.png", "furrows", furrows, sf, &why[t]); break;
		default: break;
		}
		failed |= e != 0;
	}
	for (int t = 0; t < 7; t++) {
		if (why[t] && cause == NULL)
			cause = why[t];
		else
			free(why[t]);
	}
	if (failed || write_manifest(&o, r, sh, sp, sf, &cause) != 0) {
		cli_fail(CMD, "%s", cause);
		goto done;
	}
	double t3 = util_now();
	if (!quiet)
		fprintf(stderr, "skinbake texture: %s, %ld px over %.4g mm, seed %llu: %d pores, "
		    "relief %.4g to %.4g um; place %.2f s, render %.2f s, write %.2f s -> %s\n",
		    cfg.site, cfg.size, cfg.relief.tile * 10, (unsigned long long)cfg.seed,
		    relief_n_pores(r), sh.lo * 1e4, sh.hi * 1e4, t1 - t0, t2 - t1, t3 - t2, out);
	rc = CLI_EXIT_OK;
done:
	free(cause);
	relief_free(r);
	free(pores);
	free(furrows);
	free(h);
	free(nx);
	free(ny);
	free(nz);
	return rc;
}
