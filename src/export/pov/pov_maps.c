/* pov_maps: a family of bakes blended per texel by parameter maps, as a
 * POV-Ray pigment of member lit tables under image_pattern blend maps. */
#include "config.h"

#include "export/pov/pov_maps.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "export/pov/povsplit.h"
#include "export/pov/sdl.h"
#include "maps/image.h"

/* The node interval [*i0, *i1] that covers the values of map p. */
static void reach(const struct family_axis *a, const struct maps_param *p, size_t n, int *i0,
    int *i1)
{
	float vmin = p->v[0], vmax = p->v[0];
	for (size_t i = 1; i < n; i++) {
		vmin = p->v[i] < vmin ? p->v[i] : vmin;
		vmax = p->v[i] > vmax ? p->v[i] : vmax;
	}
	*i0 = 0;
	while (*i0 < a->n - 1 && a->node[*i0 + 1] <= vmin)
		(*i0)++;
	*i1 = a->n - 1;
	while (*i1 > 0 && a->node[*i1 - 1] >= vmax)
		(*i1)--;
	if (*i1 < *i0)
		*i1 = *i0;
}

struct pov_maps *pov_maps_open(const char *family_dir, const char *maps_dir, const char *base,
    const char *skin, char **cause)
{
	struct pov_maps *pm = xcalloc(1, sizeof *pm);
	char *err = NULL;
	if ((pm->fam = brdf_family_open(family_dir, &err)) == NULL ||
	    brdf_family_load_tables(pm->fam, &err) != 0 ||
	    (pm->maps = mapset_read(maps_dir, &err)) == NULL ||
	    mapset_check_family(pm->maps, maps_dir, pm->fam->family, &err) != 0) {
		*cause = xasprintf("--family %s --maps %s: %s", family_dir, maps_dir, err);
		free(err);
		pov_maps_free(pm);
		return NULL;
	}
	const struct brdf_family *f = pm->fam;
	size_t n = (size_t)pm->maps->w * pm->maps->h;
	int mid[FAMILY_MAX_AXES];
	for (int a = 0; a < f->n_axes; a++) {
		reach(&f->axis[a], &pm->maps->p[a], n, &pm->lo_idx[a], &pm->hi_idx[a]);
		float *s = xmalloc(sizeof(float) * n);
		memcpy(s, pm->maps->p[a].v, sizeof(float) * n);
		double med = s[n / 2];	/* a rough median: the member of the stand-ins */
		free(s);
		mid[a] = pm->lo_idx[a];
		for (int j = pm->lo_idx[a]; j <= pm->hi_idx[a]; j++)
			if (fabs(f->axis[a].node[j] - med) < fabs(f->axis[a].node[mid[a]] - med))
				mid[a] = j;
		pm->png[a] = xasprintf("%s_%s_%s.png", base, skin, f->axis[a].key);
	}
	pm->ref = brdf_family_member(f, mid);
	pm->sss_exr = xasprintf("%s_%s_sss.exr", base, skin);
	pm->src = xcalloc((size_t)f->n_members, sizeof *pm->src);
	for (int m = 0; m < f->n_members; m++) {
		int idx[FAMILY_MAX_AXES], in = 1;
		brdf_family_member_index(f, m, idx);
		for (int a = 0; a < f->n_axes; a++)
			in &= idx[a] >= pm->lo_idx[a] && idx[a] <= pm->hi_idx[a];
		if (in)
			pm->src[m] = brdf_family_source(f, m);
	}
	return pm;
}

void pov_maps_free(struct pov_maps *pm)
{
	if (pm == NULL)
		return;
	for (int m = 0; pm->src && m < pm->fam->n_members; m++)
		brdf_source_free(pm->src[m]);
	free(pm->src);
	for (int a = 0; a < FAMILY_MAX_AXES; a++)
		free(pm->png[a]);
	free(pm->sss);
	free(pm->sss_exr);
	mapset_free(pm->maps);
	brdf_family_free(pm->fam);
	free(pm);
}

struct pov_brdf pov_maps_brdf(const struct pov_maps *pm, int m)
{
	const struct brdf_source *b = pm->src[m];
	if (pm->sss && pm->sss[m].on)
		return (struct pov_brdf){ povsss_remainder, &pm->sss[m], b->n_ti, b->n_to,
			b->theta_i, b->theta_o };
	return (struct pov_brdf){ b->f_rgb, b->ctx, b->n_ti, b->n_to, b->theta_i, b->theta_o };
}

int pov_maps_sss_setup(struct pov_maps *pm, double *ior, char **cause)
{
	const struct brdf_family *f = pm->fam;
	pm->sss = xcalloc((size_t)f->n_members, sizeof *pm->sss);
	char **err = xcalloc((size_t)f->n_members, sizeof *err);
	double *ior_m = xcalloc((size_t)f->n_members, sizeof *ior_m);
	/* About 4 s of CPU per member (export/sss_fit.c): the members in parallel. */
#pragma omp parallel for schedule(dynamic)
	for (int m = 0; m < f->n_members; m++) {
		if (pm->src[m] == NULL)
			continue;
		const struct brdf_source *b = pm->src[m];
		struct pov_brdf t = { b->f_rgb, b->ctx, b->n_ti, b->n_to, b->theta_i, b->theta_o };
		povsss_setup(&pm->sss[m], &t, &ior_m[m], brdf_family_member_bake(f, m), &err[m]);
	}
	int rc = 0;
	for (int m = 0; m < f->n_members; m++) {
		if (err[m] != NULL && rc == 0)
			*cause = xasprintf("family member %d: %s", m, err[m]);
		rc = err[m] != NULL ? -1 : rc;
		if (pm->src[m] != NULL)
			*ior = ior_m[m];	/* the calibration's, the same for every member */
		free(err[m]);
	}
	free(err);
	free(ior_m);
	return rc;
}

/* Axis a's bracket at v among the nodes the maps reach: node j and the
 * weight w of node j + 1, in t (clamped, as a blend map is). */
static int bracket(const struct pov_maps *pm, int a, double v, double *w)
{
	const struct family_axis *ax = &pm->fam->axis[a];
	int j = pm->lo_idx[a];
	*w = 0.0;
	if (pm->hi_idx[a] == j)
		return j;
	double t = family_axis_t(ax, v);
	while (j + 1 < pm->hi_idx[a] && t > family_axis_t(ax, ax->node[j + 1]))
		j++;
	double t0 = family_axis_t(ax, ax->node[j]), t1 = family_axis_t(ax, ax->node[j + 1]);
	*w = fmin(fmax((t - t0) / (t1 - t0), 0.0), 1.0);
	return j;
}

void pov_maps_sss_at(const struct pov_maps *pm, const double *v, double colour[3],
    double length_mm[3])
{
	const struct brdf_family *f = pm->fam;
	int j[FAMILY_MAX_AXES];
	double w[FAMILY_MAX_AXES], lnl[3] = { 0, 0, 0 };
	for (int a = 0; a < f->n_axes; a++)
		j[a] = bracket(pm, a, v[a], &w[a]);
	for (int c = 0; c < 3; c++)
		colour[c] = 0.0;
	for (int corner = 0; corner < (1 << f->n_axes); corner++) {
		int idx[FAMILY_MAX_AXES];
		double wt = 1.0;
		for (int a = 0; a < f->n_axes; a++) {
			int up = (corner >> a) & 1;
			idx[a] = j[a] + (up && w[a] > 0 ? 1 : 0);
			wt *= up ? w[a] : 1.0 - w[a];
		}
		if (wt <= 0)
			continue;
		const struct sss_fit *fit = &pm->sss[brdf_family_member(f, idx)].fit;
		for (int c = 0; c < 3; c++) {
			colour[c] += wt * fit->colour[c];
			lnl[c] += wt * log(fit->length_mm[c]);
		}
	}
	for (int c = 0; c < 3; c++)
		length_mm[c] = exp(lnl[c]);
}

/* The per-texel closure parameters (pov_maps_sss_at) as float OpenEXR. */
static int write_sss_exr(const struct pov_maps *pm, const char *outdir, char **cause)
{
	static const char *const names[] = { "colour.R", "colour.G", "colour.B", "length_mm.R",
		"length_mm.G", "length_mm.B" };
	static const char *const attr[] = { "skinbake", "POV-Ray subsurface closure per texel, "
		"interpolated between the family members as the maps blend them (docs/maps.md)" };
	const struct mapset *m = pm->maps;
	size_t n = (size_t)m->w * m->h;
	struct image *im = image_new(m->w, m->h, 6, 32);
	for (size_t i = 0; i < n; i++) {
		double v[FAMILY_MAX_AXES], col[3], len[3];
		for (int a = 0; a < pm->fam->n_axes; a++)
			v[a] = m->p[a].v[i];
		pov_maps_sss_at(pm, v, col, len);
		for (int c = 0; c < 3; c++) {
			im->v[i * 6 + c] = (float)col[c];
			im->v[i * 6 + 3 + c] = (float)len[c];
		}
	}
	char *path = xasprintf("%s/%s", outdir, pm->sss_exr);
	int rc = image_write_exr(path, im, names, 1, attr, cause);
	free(path);
	image_free(im);
	return rc;
}

int pov_maps_write_images(const struct pov_maps *pm, const char *outdir, char **cause)
{
	const struct mapset *m = pm->maps;
	size_t n = (size_t)m->w * m->h;
	for (int a = 0; a < pm->fam->n_axes; a++) {
		struct image *im = image_new(m->w, m->h, 1, 16);
		for (size_t i = 0; i < n; i++)
			im->v[i] = (float)family_axis_t(&pm->fam->axis[a], m->p[a].v[i]);
		char *path = xasprintf("%s/%s", outdir, pm->png[a]);
		int rc = image_write_png(path, im, 16, 0, 0, NULL, cause);
		free(path);
		image_free(im);
		if (rc != 0)
			return -1;
	}
	return pm->sss ? write_sss_exr(pm, outdir, cause) : 0;
}

static void write_planar(FILE *fp, const double lo[3], const double hi[3], int uv);

/* The blend over axis a at the node indices idx[a + 1 ..] given: nested
 * image_pattern pigments down to the member tables. */
static void write_blend(FILE *fp, const char *name, const char *kind, const char *post,
    const struct pov_maps *pm, int a, int *idx, int depth, int top, const char *mapping)
{
	const struct family_axis *ax = &pm->fam->axis[a];
	/* A blend-map entry holds a pigment (texture) body, not `pigment { }` (pov.md). */
	fprintf(fp, "%*s%s%s%simage_pattern { png \"%s\" gamma 1.0 map_type 0 interpolate 2 }\n",
	    depth, "", top ? kind : "", top ? " { " : "", top ? mapping : "", pm->png[a]);
	fprintf(fp, "%*s  %s_map {\n", depth, "", kind);
	for (int j = pm->lo_idx[a]; j <= pm->hi_idx[a]; j++) {
		idx[a] = j;
		double t = family_axis_t(ax, ax->node[j]);
		if (a == 0)
			fprintf(fp, "%*s    [%.7f %s_M%04d%s]  // %s = %g\n", depth, "", t, name,
			    brdf_family_member(pm->fam, idx), post, ax->key, ax->node[j]);
		else {
			fprintf(fp, "%*s    [%.7f  // %s = %g\n", depth, "", t, ax->key,
			    ax->node[j]);
			write_blend(fp, name, kind, post, pm, a - 1, idx, depth + 6, 0, mapping);
			fprintf(fp, "%*s    ]\n", depth, "");
		}
	}
	fprintf(fp, "%*s  }\n", depth, "");
}

int pov_maps_write_key(FILE *fp, const char *name, const struct pov_maps *pm,
    const struct pov_light *l, const struct pov_view *v, const double lo[3], const double hi[3],
    int n_theta, int n_gamma, int uv)
{
	return pov_maps_write_part(fp, name, pm, 0, 0, l, v, lo, hi, n_theta, n_gamma, uv);
}

/* Whether every member reached has member ref's specular (ior, alpha and
 * top stack), checked on a few angles. */
static int one_specular(const struct pov_maps *pm, double alpha)
{
	static const double ang[4][3] = { { 0, 0, 0 }, { 0.5, 0.6, 3.0 }, { 1.2, 1.3, 2.5 },
		{ 1.5, 0.2, 1.0 } };
	const struct brdf_family *f = pm->fam;
	struct povsplit_spec r = { brdf_family_member_bake(f, pm->ref), alpha };
	for (int m = 0; m < f->n_members; m++) {
		if (pm->src[m] == NULL)
			continue;
		struct povsplit_spec q = { brdf_family_member_bake(f, m), alpha };
		for (int i = 0; i < 4; i++) {
			double a[3], b[3];
			povsplit_specular(&r, ang[i][0], ang[i][1], ang[i][2], a);
			povsplit_specular(&q, ang[i][0], ang[i][1], ang[i][2], b);
			for (int c = 0; c < 3; c++)
				if (fabs(a[c] - b[c]) > 1e-12 * (1 + fabs(a[c])))
					return 0;
		}
	}
	return 1;
}

void pov_maps_write_fill(FILE *fp, const char *name, const struct pov_maps *pm, int bounce,
    const double lo[3], const double hi[3], int uv)
{
	const struct brdf_family *f = pm->fam;
	for (int m = 0; m < f->n_members; m++) {
		if (pm->src[m] == NULL)
			continue;
		const struct brdf_source *b = pm->src[m];
		const struct bake *mb = brdf_family_member_bake(f, m);
		double *a = povsplit_fill_curve(mb, b->n_albedo, b->theta_albedo, b->albedo_rgb);
		if (bounce) {
			double *ab = povsplit_bounce_curve(b->n_albedo, b->theta_albedo, a, NULL);
			free(a);
			a = ab;
		}
		fprintf(fp, "#declare %s_M%04d = ", name, m);
		sdl_albedo_pigment(fp, b->n_albedo, b->theta_albedo, a);
		free(a);
	}
	int idx[FAMILY_MAX_AXES] = { 0 };
	fprintf(fp, "#declare %s =\n", name);
	write_blend(fp, name, "pigment", "", pm, f->n_axes - 1, idx, 0, 1, uv ? "uv_mapping " : "");
	write_planar(fp, lo, hi, uv);
}

int pov_maps_write_part(FILE *fp, const char *name, const struct pov_maps *pm, int part,
    double spec_alpha, const struct pov_light *l, const struct pov_view *v, const double lo[3],
    const double hi[3], int n_theta, int n_gamma, int uv)
{
	const struct brdf_family *f = pm->fam;
	int g = 1;
	if (part == 2 && one_specular(pm, spec_alpha)) {
		struct povsplit_spec sp = { brdf_family_member_bake(f, pm->ref), spec_alpha };
		const struct brdf_source *b = pm->src[pm->ref];
		struct pov_brdf t = { povsplit_specular, &sp, b->n_ti, b->n_to, b->theta_i,
			b->theta_o };
		fprintf(fp, "// The members' surface specular is the same (GGX alpha %.4g): one "
		    "table.\n", spec_alpha);
		return littable_write_key(fp, name, &t, l, v, lo, hi, n_theta, n_gamma);
	}
	fprintf(fp, "// Family %s blended by maps (%d x %d texels): one lit table per member the maps reach.\n",
	    f->dir, pm->maps->w, pm->maps->h);
	for (int m = 0; m < f->n_members; m++) {
		if (pm->src[m] == NULL)
			continue;
		char *nm = xasprintf("%s_M%04d", name, m);
		struct pov_brdf b = pov_maps_brdf(pm, m);
		struct povsplit_spec sp = { brdf_family_member_bake(f, m), spec_alpha };
		if (part != 0) {
			b.f_rgb = part == 1 ? povsplit_diffuse : povsplit_specular;
			b.ctx = part == 1 ? (void *)sp.b : (void *)&sp;
		}
		int gm = littable_write_key(fp, nm, &b, l, v, lo, hi, n_theta, n_gamma);
		g = gm > g ? gm : g;
		free(nm);
	}
	int idx[FAMILY_MAX_AXES] = { 0 };
	fprintf(fp, "#declare %s =\n", name);
	write_blend(fp, name, "pigment", "", pm, f->n_axes - 1, idx, 0, 1, uv ? "uv_mapping " : "");
	write_planar(fp, lo, hi, uv);
	return g;
}

void pov_maps_write_sss(FILE *fp, const char *skin, const struct pov_maps *pm, int reflection,
    const double lo[3], const double hi[3], int uv)
{
	const struct brdf_family *f = pm->fam;
	for (int m = 0; m < f->n_members; m++) {
		if (pm->src[m] == NULL)
			continue;
		char *nm = xasprintf("%s_M%04d", skin, m);
		fprintf(fp, "// family member %d\n", m);
		povsss_write(fp, nm, &pm->sss[m], reflection);
		free(nm);
	}
	for (int m = 0; m < f->n_members; m++) {
		if (pm->src[m] == NULL)
			continue;
		fprintf(fp, "#declare SKIN_%s_M%04d_Layered =\n", skin, m);
		fprintf(fp, "  texture { SKIN_%s_M%04d_Subsurface }\n", skin, m);
		fprintf(fp, "  texture { pigment { average pigment_map {\n"
		    "    [1 SKIN_%s_Remainder_M%04d] [%d rgbt <0, 0, 0, 1>] } }\n", skin, m,
		    POVSSS_CLEAR);
		fprintf(fp, "    finish { SKIN_%s_Finish } }\n", skin);
	}
	char *name = xasprintf("SKIN_%s", skin);
	int idx[FAMILY_MAX_AXES] = { 0 };
	/* POV-Ray cannot layer over a patterned texture: each member's layers go into the map. */
	fprintf(fp, "// Each member's closure under its remainder, blended by the maps as the lit\n"
	    "// tables are; the closure's parameters per texel: %s.\n"
	    "#declare SKIN_%s_Translucent =\n", pm->sss_exr, skin);
	write_blend(fp, name, "texture", "_Layered", pm, f->n_axes - 1, idx, 0, 1,
	    uv ? "uv_mapping " : "");
	write_planar(fp, lo, hi, uv);
	free(name);
}

/* The planar projection of the maps over the box's x-y extent, and the
 * closing brace of the outer pigment or texture. */
static void write_planar(FILE *fp, const double lo[3], const double hi[3], int uv)
{
	if (!uv) {
		double s[3] = { hi[0] - lo[0], hi[1] - lo[1], 1 }, t[3] = { lo[0], lo[1], 0 };
		fputs("  scale ", fp);
		sdl_vec(fp, s);
		fputs(" translate ", fp);
		sdl_vec(fp, t);
		fputs("\n", fp);
	}
	fputs("}\n", fp);
}
