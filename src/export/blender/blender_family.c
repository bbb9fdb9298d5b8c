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
#include "io/exrio.h"

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

/* The stacked atlases: slice s in file rows [H - (s + 1) nc, H - s nc). */
static float *family_lut(const struct brdf_family *f, const struct subgrid *g, int nc,
    int nphi)
{
	size_t w = (size_t)nc * nphi, h = (size_t)nc * g->slices, plane = w * h, sp = w * nc;
	float *lut = xmalloc(sizeof(float) * 3 * plane);
	for (int s = 0; s < g->slices; s++) {
		double x[FAMILY_MAX_AXES];
		subgrid_point(f, g, s, x);
		struct brdf_source *src = brdf_family_at(f, x);
		float *one = blender_lut(src, nc, nphi);
		size_t row0 = h - (size_t)(s + 1) * nc;
		for (int c = 0; c < 3; c++)
			memcpy(lut + (size_t)c * plane + row0 * w, one + (size_t)c * sp, sizeof(float) * sp);
		free(one);
		brdf_source_free(src);
	}
	return lut;
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
			json_object_array_add(nodes, json_object_new_double(family_axis_value(&f->axis[a], g->c0[a] + t * (g->c1[a] - g->c0[a]))));
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
	char *t = xstrdup(json_object_to_json_string_ext(o, JSON_C_TO_STRING_PLAIN | JSON_C_TO_STRING_NOSLASHESCAPE));
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

int blender_family_export(struct brdf_family *f, const struct mapset *m, const struct blender_options *o, int sub,
    const char *detail_dir, const char *out_dir, char **cause)
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
	double mid[FAMILY_MAX_AXES];
	for (int a = 0; a < g.k; a++)
		mid[a] = family_axis_value(&f->axis[a], 0.5 * (g.c0[a] + g.c1[a]));
	struct brdf_source *ref = brdf_family_at(f, mid);
	struct blender_set *set = NULL;
	if ((detail_dir && brdf_source_add_textures(ref, detail_dir, cause) != 0) ||
	    (set = blender_prepare(ref, o, cause)) == NULL) {
		brdf_source_free(ref);
		return -1;
	}
	char *sec = section(f, m, &g, o->lut_cos, o->lut_phi);
	blender_set_add_section(set, "family", sec);
	free(sec);
	size_t n = (size_t)m->w * m->h;
	float *lut = family_lut(f, &g, o->lut_cos, o->lut_phi), *alb = xmalloc(sizeof(float) * 3 * n);
	float *rad = xmalloc(sizeof(float) * 3 * n), *pos = xmalloc(sizeof(float) * 3 * n);
	texel_maps(f, m, &g, alb, rad, pos);
	/* The family's files first: blender_write_files puts the manifest last. */
	struct outdir od;
	int rc = outdir_begin(&od, out_dir, &blender_outdir_kind, cause) != 0 ? -1 : 0;
	const char *dir = rc == 0 ? outdir_path(&od) : NULL;
	rc = rc != 0 ? -1 : write_rgb(dir, "family_lut.exr", o->lut_cos * o->lut_phi, o->lut_cos * g.slices, lut,
	    "pi * f_r atlases of the family's sub-grid, stacked (manifest family)", cause) ||
	    write_rgb(dir, "family_coord.exr", m->w, m->h, pos, "sub-grid position per axis", cause) ||
	    write_rgb(dir, "albedo_map.exr", m->w, m->h, alb, "bihemispherical diffuse albedo, linear Rec.709", cause) ||
	    write_rgb(dir, "sss_radius_map.exr", m->w, m->h, rad, "mean exit radius per R, G, B [m]", cause) ||
	    blender_write_files(set, dir, cause) ? -2 : 0;
	if (rc == -2)
		outdir_fail(&od, cause);
	else if (rc == 0 && outdir_commit(&od, cause) != 0)
		rc = -2;
	free(lut);
	free(alb);
	free(rad);
	free(pos);
	blender_set_free(set);
	brdf_source_free(ref);
	return rc;
}
