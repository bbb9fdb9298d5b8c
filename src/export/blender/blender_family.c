/* blender_family: a family with parameter maps as a Blender image set
 * (see blender_family.h): the sub-grid of tables, the per-texel albedo,
 * radius and sub-grid position, the manifest's family section. */
#include "config.h"
#include "export/blender/blender_family.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "export/blender/blender_sss.h"
#include "export/sss_family.h"
#include "io/exrio.h"
#include "io/json.h"

/* The sub-grid: per axis K points uniform in the axis coordinate over the
 * maps' range. */
struct subgrid {
	int k;				/* axes */
	int n[FAMILY_MAX_AXES];		/* points per axis (1 for a constant map) */
	double c0[FAMILY_MAX_AXES], c1[FAMILY_MAX_AXES];	/* coordinate range */
	int slices;			/* product of n */
};

static void subgrid_make(const struct brdf_family *f, const struct mapset *m, int sub,
    struct subgrid *g)
{
	size_t n = (size_t)m->w * m->h;
	g->k = f->n_axes;
	g->slices = 1;
	for (int a = 0; a < FAMILY_MAX_AXES; a++) {
		g->n[a] = 1;
		if (a >= g->k)
			continue;
		const struct family_axis *ax = &f->axis[a];
		double lo = INFINITY, hi = -INFINITY;
		for (size_t i = 0; i < n; i++) {
			double v = fmin(fmax(m->p[a].v[i], ax->node[0]), ax->node[ax->n - 1]);
			lo = fmin(lo, v);
			hi = fmax(hi, v);
		}
		g->c0[a] = family_axis_coord(ax, lo);
		g->c1[a] = family_axis_coord(ax, hi);
		/* A map that varies by less than 0.1 % is constant here. */
		if (fabs(hi - lo) > 1e-3 * fmax(fabs(hi), fabs(lo)))
			g->n[a] = sub;
		g->slices *= g->n[a];
	}
}

/* Parameters of sub-grid point s. */
static void subgrid_point(const struct brdf_family *f, const struct subgrid *g, int s,
    double *x)
{
	for (int a = 0; a < g->k; a++) {
		int i = s % g->n[a];
		s /= g->n[a];
		double t = g->n[a] > 1 ? (double)i / (g->n[a] - 1) : 0.5;
		x[a] = family_axis_value(&f->axis[a], g->c0[a] + t * (g->c1[a] - g->c0[a]));
	}
}

/* Translucent mode (blender_sss.h): the fits of the members the maps reach,
 * per calibrated Blender; a point between members gets them interpolated
 * (export/sss_family.h), as POV-Ray's maps export does. */
struct family_sss {
	struct blender_sss *member;	/* [n_members]: n > 0 where fitted */
	int n;				/* versions fitted */
};

/* Fit every version to each member the maps reach (about 8 s of CPU per
 * member and version: the members in parallel).  -1 and *cause. */
static int family_sss_fit(const struct brdf_family *f, const struct mapset *m,
    struct family_sss *fs, char **cause)
{
	size_t n = (size_t)m->w * m->h;
	int lo[FAMILY_MAX_AXES], hi[FAMILY_MAX_AXES];
	for (int a = 0; a < f->n_axes; a++)
		sss_family_reach(f, a, m->p[a].v, n, &lo[a], &hi[a]);
	fs->member = xcalloc((size_t)f->n_members, sizeof *fs->member);
	fs->n = 0;
	char **err = xcalloc((size_t)f->n_members, sizeof *err);
#pragma omp parallel for schedule(dynamic)
	for (int k = 0; k < f->n_members; k++) {
		int idx[FAMILY_MAX_AXES], in = 1;
		brdf_family_member_index(f, k, idx);
		for (int a = 0; a < f->n_axes; a++)
			in &= idx[a] >= lo[a] && idx[a] <= hi[a];
		const struct bake *b = brdf_family_member_bake(f, k);
		if (in && blender_sss_fit(b, &fs->member[k], &err[k]) != 0)
			fs->member[k].n = 0;
	}
	int rc = 0;
	for (int k = 0; k < f->n_members; k++) {
		if (err[k] != NULL && rc == 0)
			*cause = xasprintf("translucent: family member %d: %s", k, err[k]);
		rc = err[k] != NULL ? -1 : rc;
		fs->n = fs->member[k].n > fs->n ? fs->member[k].n : fs->n;
		free(err[k]);
	}
	free(err);
	return rc;
}

/* Every version's fit at parameters x into *w (not wrapped); scratch holds
 * n_members pointers. */
static void family_sss_at(const struct brdf_family *f, const struct family_sss *fs, const double *x,
    const struct sss_fit **scratch, struct blender_sss *w)
{
	*w = (struct blender_sss){ 0 };
	for (int v = 0; v < fs->n; v++) {
		for (int k = 0; k < f->n_members; k++)
			scratch[k] = fs->member[k].n > v ? &fs->member[k].fit[v] : NULL;
		sss_fit_family_at(f, scratch, x, &w->fit[v]);
	}
	w->n = fs->n;
}

/* The stacked atlases: slice s in file rows [H - (s + 1) nc, H - s nc).
 * Translucent (fs not NULL): each the remainder of its point's table, and
 * extra[v] (3 planes of BLENDER_SSS_N_VIEW x slices, slice s in file row
 * slices - 1 - s) version v's lambert_extra there per view node. */
static float *family_lut(const struct brdf_family *f, const struct subgrid *g, int nc,
    int nphi, const struct family_sss *fs, float **extra)
{
	size_t w = (size_t)nc * nphi, h = (size_t)nc * g->slices, plane = w * h, sp = w * nc;
	size_t eplane = (size_t)BLENDER_SSS_N_VIEW * g->slices;
	float *lut = xmalloc(sizeof(float) * 3 * plane);
	const struct sss_fit **scratch = fs ? xcalloc((size_t)f->n_members, sizeof *scratch) : NULL;
	for (int v = 0; fs && v < fs->n; v++)
		extra[v] = xmalloc(sizeof(float) * 3 * eplane);
	for (int s = 0; s < g->slices; s++) {
		double x[FAMILY_MAX_AXES];
		subgrid_point(f, g, s, x);
		struct brdf_source *src = brdf_family_at(f, x);
		struct blender_sss ws;
		if (fs) {
			family_sss_at(f, fs, x, scratch, &ws);
			blender_sss_wrap_fitted(src, &ws);
			size_t row = (size_t)(g->slices - 1 - s) * BLENDER_SSS_N_VIEW;
			for (int v = 0; v < fs->n; v++)
				for (int k = 0; k < BLENDER_SSS_N_VIEW; k++) {
					double e[3], to = blender_sss_view_deg[k] * M_PI / 180;
					blender_sss_extra(&ws, v, to, e);
					for (int c = 0; c < 3; c++)
						extra[v][(size_t)c * eplane + row + k] = (float)e[c];
				}
		}
		float *one = blender_lut(src, nc, nphi);
		size_t row0 = h - (size_t)(s + 1) * nc;
		for (int c = 0; c < 3; c++)
			memcpy(lut + (size_t)c * plane + row0 * w, one + (size_t)c * sp, sizeof(float) * sp);
		free(one);
		brdf_source_free(src);
	}
	free(scratch);
	return lut;
}

/* Per texel, version v's node colour [-] and radius [m] (3 planes each). */
static void texel_sss(const struct brdf_family *f, const struct mapset *m,
    const struct family_sss *fs, int v, float *col, float *rad)
{
	long n = (long)m->w * m->h;
#pragma omp parallel
	{
		const struct sss_fit **scratch = xcalloc((size_t)f->n_members, sizeof *scratch);
#pragma omp for schedule(static)
		for (long i = 0; i < n; i++) {
			double x[FAMILY_MAX_AXES];
			struct blender_sss w;
			for (int a = 0; a < f->n_axes; a++)
				x[a] = m->p[a].v[i];
			family_sss_at(f, fs, x, scratch, &w);
			for (int c = 0; c < 3; c++) {
				col[(size_t)c * n + i] = (float)w.fit[v].colour[c];
				rad[(size_t)c * n + i] = (float)(1e-3 * w.fit[v].length_mm[c]);
			}
		}
		free(scratch);
	}
}

static int write_rgb(const char *dir, const char *name, int w, int h, const float *v, const char *what, char **cause)
{
	static const char *const names[3] = { "R", "G", "B" };
	size_t plane = (size_t)w * h;
	const float *planes[3] = { v, v + plane, v + 2 * plane };
	struct exr_attr_kv at[] = { { "skinbake:quantity", what } };
	char *path = xasprintf("%s/%s", dir, name);
	int rc = exrio_write(path, w, h, 3, names, planes, 1, at, cause);
	free(path);
	return rc;
}

static json_object *file_entry(const char *name, int w, int h, const char *what)
{
	json_object *o = json_object_new_object();
	json_object_object_add(o, "file", json_object_new_string(name));
	json_object_object_add(o, "width", json_object_new_int(w));
	json_object_object_add(o, "height", json_object_new_int(h));
	json_object_object_add(o, "content", json_object_new_string(what));
	return o;
}

static char *section(const struct brdf_family *f, const struct mapset *m, const struct subgrid *g, int nc, int nphi)
{
	json_object *o = json_object_new_object(), *axes = json_object_new_array(), *files = json_object_new_object();
	json_object_object_add(o, "family_dir", json_object_new_string(f->dir ? f->dir : ""));
	json_object_object_add(o, "preset", json_object_new_string(f->preset ? f->preset : ""));
	for (int a = 0; a < g->k; a++) {
		json_object *x = json_object_new_object(), *nodes = json_object_new_array();
		json_object_object_add(x, "key", json_object_new_string(f->axis[a].key));
		json_object_object_add(x, "log_coordinate", json_object_new_boolean(f->axis[a].log_coord));
		for (int i = 0; i < g->n[a]; i++) {
			double t = g->n[a] > 1 ? (double)i / (g->n[a] - 1) : 0.5;
			double c = g->c0[a] + t * (g->c1[a] - g->c0[a]);
			json_object_array_add(nodes, json_num(family_axis_value(&f->axis[a], c)));
		}
		json_object_object_add(x, "sub_nodes", nodes);
		json_object_array_add(axes, x);
	}
	json_object_object_add(o, "axes", axes);
	json_object *cnt = json_object_new_array();
	for (int a = 0; a < FAMILY_MAX_AXES; a++)
		json_object_array_add(cnt, json_object_new_int(g->n[a]));
	json_object_object_add(o, "sub_counts", cnt);
	json_object_object_add(o, "slices", json_object_new_int(g->slices));
	json_object_object_add(o, "slice_order", json_object_new_string("s = i0 + n0 * (i1 + n1 * i2); slice s is rows "
	    "s * cos_nodes .. (s + 1) * cos_nodes - 1 counted from the bottom (Blender v), each laid out as brdf_lut.exr"));
	json_object_object_add(o, "interpolation", json_object_new_string("multilinear between the atlases of the "
	    "texel's neighbouring sub-grid points (family_coord: the position per axis); each atlas is the family "
	    "interpolated at its point (cubic in log between members)"));
	json_object_object_add(files, "family_lut", file_entry("family_lut.exr", nc * nphi, nc * g->slices,
	    "pi * f_r atlases of the sub-grid points, stacked"));
	json_object_object_add(files, "family_coord", file_entry("family_coord.exr", m->w, m->h,
	    "position of the texel in the sub-grid, per axis (R, G, B)"));
	json_object_object_add(files, "albedo_map", file_entry("albedo_map.exr", m->w, m->h,
	    "bihemispherical diffuse albedo per texel, linear Rec.709"));
	json_object_object_add(files, "sss_radius_map", file_entry("sss_radius_map.exr", m->w, m->h,
	    "mean exit radius per R, G, B per texel [m]"));
	json_object_object_add(o, "files", files);
	char *t = json_text(o, JSON_PLAIN);
	json_object_put(o);
	return t;
}

/* Per texel: albedo (members' bihemispherical albedos blended), radius,
 * sub-grid position; three planes each. */
static void texel_maps(const struct brdf_family *f, const struct mapset *m, const struct subgrid *g, float *alb, float *rad,
    float *pos)
{
	double *bm = xmalloc(sizeof(double) * 3 * (size_t)f->n_members);
	for (int k = 0; k < f->n_members; k++) {
		struct brdf_source *src = brdf_family_source(f, k);
		blender_albedo_mean(src, bm + 3 * k);
		brdf_source_free(src);
	}
	long n = (long)m->w * m->h;
#pragma omp parallel for schedule(static)
	for (long i = 0; i < n; i++) {
		double x[FAMILY_MAX_AXES], a3[3], r[3];
		for (int a = 0; a < g->k; a++)
			x[a] = m->p[a].v[i];
		brdf_family_blend(f, x, bm, 3, a3);
		brdf_family_radius(f, x, r);
		for (int c = 0; c < 3; c++) {
			alb[(size_t)c * n + i] = (float)a3[c];
			rad[(size_t)c * n + i] = (float)(0.01 * r[c]);
			double p = 0.0;
			if (c < g->k && g->n[c] > 1) {
				double v = fmin(fmax(x[c], f->axis[c].node[0]), f->axis[c].node[f->axis[c].n - 1]);
				double cv = family_axis_coord(&f->axis[c], v);
				p = (cv - g->c0[c]) / (g->c1[c] - g->c0[c]) * (g->n[c] - 1);
				p = fmin(fmax(p, 0.0), g->n[c] - 1.0);
			}
			pos[(size_t)c * n + i] = (float)p;
		}
	}
	free(bm);
}

/* Version v's per-texel files in the manifest's translucent section ("maps"). */
static char *sss_maps_json(const char *ser, const struct mapset *m, int slices)
{
	return xasprintf("{\"colour\": {\"file\": \"sss_colour_%s.exr\", \"width\": %d, "
	    "\"height\": %d, \"content\": \"the node's Color per texel [-] (R, G, B)\"}, "
	    "\"radius_m\": {\"file\": \"sss_radius_%s.exr\", \"width\": %d, \"height\": %d, "
	    "\"content\": \"the node's Radius per texel [m] (R, G, B)\"}, \"extra\": {\"file\": "
	    "\"sss_extra_%s.exr\", \"width\": %d, \"height\": %d, \"content\": \"lambert_extra "
	    "per family sub-grid point: column k at theta_o_deg[k], row s (from the bottom) at "
	    "slice s; blended at family_coord as family_lut is\"}, \"interpolation\": \"colour, "
	    "radius: the members' fits (each to its own Rd(r)) per axis linear in the axis "
	    "coordinate between neighbouring members, the colour linearly, the radius as its log; "
	    "family_lut.exr holds each sub-grid point's remainder (its table less the largest far "
	    "field of the versions' nodes at that point's fits)\"}", ser, m->w, m->h, ser, m->w,
	    m->h, ser, BLENDER_SSS_N_VIEW, slices);
}

int blender_family_export(struct brdf_family *f, const struct mapset *m,
    const struct blender_options *o, int sub, const char *detail_dir, int translucent,
    const char *out_dir, char **cause)
{
	if (sub < BLENDER_FAMILY_SUB_MIN || sub > BLENDER_FAMILY_SUB_MAX) {
		*cause = xasprintf("%d sub-grid points per axis is out of range [%d, %d]", sub, BLENDER_FAMILY_SUB_MIN,
		    BLENDER_FAMILY_SUB_MAX);
		return -1;
	}
	if (mapset_check_family(m, m->family_dir ? m->family_dir : "maps", f->family, cause) != 0 ||
	    brdf_family_load_tables(f, cause) != 0)
		return -1;
	struct subgrid g;
	subgrid_make(f, m, sub, &g);
	struct family_sss fs = { NULL, 0 };
	if (translucent && family_sss_fit(f, m, &fs, cause) != 0) {
		free(fs.member);
		return -1;
	}
	double mid[FAMILY_MAX_AXES];
	for (int a = 0; a < g.k; a++)
		mid[a] = family_axis_value(&f->axis[a], 0.5 * (g.c0[a] + g.c1[a]));
	struct brdf_source *ref = brdf_family_at(f, mid);
	struct blender_set *set = NULL;
	struct blender_sss wref;
	if (translucent) {
		const struct sss_fit **scratch = xcalloc((size_t)f->n_members, sizeof *scratch);
		family_sss_at(f, &fs, mid, scratch, &wref);
		free(scratch);
		blender_sss_wrap_fitted(ref, &wref);
	}
	if ((detail_dir && brdf_source_add_textures(ref, detail_dir, cause) != 0) ||
	    (set = blender_prepare(ref, o, cause)) == NULL) {
		brdf_source_free(ref);
		free(fs.member);
		return -1;
	}
	char *sec = section(f, m, &g, o->lut_cos, o->lut_phi);
	blender_set_add_section(set, "family", sec);
	free(sec);
	size_t n = (size_t)m->w * m->h;
	float *extra[BLENDER_SSS_MAX] = { NULL };
	float *lut = family_lut(f, &g, o->lut_cos, o->lut_phi, translucent ? &fs : NULL, extra);
	float *alb = xmalloc(sizeof(float) * 3 * n);
	float *rad = xmalloc(sizeof(float) * 3 * n), *pos = xmalloc(sizeof(float) * 3 * n);
	texel_maps(f, m, &g, alb, rad, pos);
	char *maps[BLENDER_SSS_MAX] = { NULL }, ser[BLENDER_SSS_MAX][32];
	for (int v = 0; v < fs.n; v++) {
		blender_sss_series(wref.fit[v].table, ser[v], sizeof ser[v]);
		maps[v] = sss_maps_json(ser[v], m, g.slices);
	}
	if (translucent) {
		char *j = blender_sss_json(&wref, (const char *const *)maps);
		blender_set_add_section(set, "translucent", j);
		free(j);
	}
	/* The family's files first: blender_write_files puts the manifest last. */
	struct outdir od;
	int rc = outdir_begin(&od, out_dir, &blender_outdir_kind, cause) != 0 ? -1 : 0;
	const char *dir = rc == 0 ? outdir_path(&od) : NULL;
	const char *lut_what = translucent ? "pi * f_r atlases of the family's sub-grid, stacked, less "
	    "the subsurface node's far field (manifest translucent)" :
	    "pi * f_r atlases of the family's sub-grid, stacked (manifest family)";
	rc = rc != 0 ? -1 : write_rgb(dir, "family_lut.exr", o->lut_cos * o->lut_phi, o->lut_cos * g.slices, lut,
	    lut_what, cause) ||
	    write_rgb(dir, "family_coord.exr", m->w, m->h, pos, "sub-grid position per axis", cause) ||
	    write_rgb(dir, "albedo_map.exr", m->w, m->h, alb, "bihemispherical diffuse albedo, linear Rec.709", cause) ||
	    write_rgb(dir, "sss_radius_map.exr", m->w, m->h, rad, "mean exit radius per R, G, B [m]", cause) ? -2 : 0;
	for (int v = 0; rc == 0 && v < fs.n; v++) {
		float *col = xmalloc(sizeof(float) * 3 * n), *len = xmalloc(sizeof(float) * 3 * n);
		texel_sss(f, m, &fs, v, col, len);
		char *nc = xasprintf("sss_colour_%s.exr", ser[v]);
		char *nr = xasprintf("sss_radius_%s.exr", ser[v]);
		char *ne = xasprintf("sss_extra_%s.exr", ser[v]);
		rc = write_rgb(dir, nc, m->w, m->h, col,
		    "Cycles subsurface node Color per texel (manifest translucent)", cause) ||
		    write_rgb(dir, nr, m->w, m->h, len,
		    "Cycles subsurface node Radius per texel [m]", cause) ||
		    write_rgb(dir, ne, BLENDER_SSS_N_VIEW, g.slices, extra[v],
		    "lambert_extra per sub-grid point and view node (manifest translucent)", cause) ? -2 : 0;
		free(nc);
		free(nr);
		free(ne);
		free(col);
		free(len);
	}
	rc = rc != 0 ? rc : blender_write_files(set, dir, cause) ? -2 : 0;
	if (rc == -2)
		outdir_fail(&od, cause);
	else if (rc == 0 && outdir_commit(&od, cause) != 0)
		rc = -2;
	for (int v = 0; v < BLENDER_SSS_MAX; v++) {
		free(extra[v]);
		free(maps[v]);
	}
	free(fs.member);
	free(lut);
	free(alb);
	free(rad);
	free(pos);
	blender_set_free(set);
	brdf_source_free(ref);
	return rc;
}
