/* pov_maps: a family of bakes blended per texel by parameter maps, as a
 * POV-Ray pigment of member lit tables under image_pattern blend maps. */
#include "config.h"

#include "export/pov/pov_maps.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
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
	mapset_free(pm->maps);
	brdf_family_free(pm->fam);
	free(pm);
}

struct pov_brdf pov_maps_brdf(const struct pov_maps *pm, int m)
{
	const struct brdf_source *b = pm->src[m];
	return (struct pov_brdf){ b->f_rgb, b->ctx, b->n_ti, b->n_to, b->theta_i, b->theta_o };
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
	return 0;
}

/* The blend over axis a at the node indices idx[a + 1 ..] given: nested
 * image_pattern pigments down to the member tables. */
static void write_blend(FILE *fp, const char *name, const struct pov_maps *pm, int a, int *idx,
    int depth, int top, const char *mapping)
{
	const struct family_axis *ax = &pm->fam->axis[a];
	/* A blend-map entry holds a pigment body, not `pigment { }` (pov.md). */
	fprintf(fp, "%*s%s%simage_pattern { png \"%s\" gamma 1.0 map_type 0 interpolate 2 }\n", depth, "",
	    top ? "pigment { " : "", top ? mapping : "", pm->png[a]);
	fprintf(fp, "%*s  pigment_map {\n", depth, "");
	for (int j = pm->lo_idx[a]; j <= pm->hi_idx[a]; j++) {
		idx[a] = j;
		double t = family_axis_t(ax, ax->node[j]);
		if (a == 0)
			fprintf(fp, "%*s    [%.7f %s_M%04d]  // %s = %g\n", depth, "", t, name,
			    brdf_family_member(pm->fam, idx), ax->key, ax->node[j]);
		else {
			fprintf(fp, "%*s    [%.7f  // %s = %g\n", depth, "", t, ax->key,
			    ax->node[j]);
			write_blend(fp, name, pm, a - 1, idx, depth + 6, 0, mapping);
			fprintf(fp, "%*s    ]\n", depth, "");
		}
	}
	fprintf(fp, "%*s  }\n", depth, "");
}

int pov_maps_write_key(FILE *fp, const char *name, const struct pov_maps *pm,
    const struct pov_light *l, const struct pov_view *v, const double lo[3], const double hi[3],
    int n_theta, int n_gamma, int uv)
{
	const struct brdf_family *f = pm->fam;
	int g = 1;
	fprintf(fp, "// Family %s blended by maps (%d x %d texels): one lit table per member the maps reach.\n",
	    f->dir, pm->maps->w, pm->maps->h);
	for (int m = 0; m < f->n_members; m++) {
		if (pm->src[m] == NULL)
			continue;
		char *nm = xasprintf("%s_M%04d", name, m);
		struct pov_brdf b = pov_maps_brdf(pm, m);
		int gm = littable_write_key(fp, nm, &b, l, v, lo, hi, n_theta, n_gamma);
		g = gm > g ? gm : g;
		free(nm);
	}
	int idx[FAMILY_MAX_AXES] = { 0 };
	fprintf(fp, "#declare %s =\n", name);
	write_blend(fp, name, pm, f->n_axes - 1, idx, 0, 1, uv ? "uv_mapping " : "");
	if (!uv) {
		double s[3] = { hi[0] - lo[0], hi[1] - lo[1], 1 }, t[3] = { lo[0], lo[1], 0 };
		fputs("  scale ", fp);
		sdl_vec(fp, s);
		fputs(" translate ", fp);
		sdl_vec(fp, t);
		fputs("\n", fp);
	}
	fputs("}\n", fp);
	return g;
}
