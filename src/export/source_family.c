/* source_family: a family of bakes for the exporters (see
 * source_family.h), a thin view of family/family.h. */
#include "config.h"
#include "export/source_family.h"

#include <stdlib.h>

#include "base/util.h"

struct brdf_family *brdf_family_open(const char *dir, char **cause)
{
	struct family *fam = family_load(dir, cause);
	if (fam == NULL)
		return NULL;
	struct brdf_family *f = xcalloc(1, sizeof *f);
	*f = (struct brdf_family){
		.dir = fam->dir,
		.preset = fam->preset,
		.n_axes = fam->n_axes,
		.axis = fam->axis,
		.n_members = fam->n_members,
		.family = fam,
		.own = fam,
	};
	return f;
}

int brdf_family_load_tables(struct brdf_family *f, char **cause)
{
	if (family_load_tables(f->own, cause) != 0)
		return -1;
	/* The members' log albedos for brdf_family_radius, which may run in parallel. */
	family_albedo_prepare(f->own);
	return 0;
}

void brdf_family_free(struct brdf_family *f)
{
	if (f == NULL)
		return;
	family_free(f->own);
	free(f);
}

int brdf_family_member(const struct brdf_family *f, const int *idx)
{
	int m = 0;
	for (int a = f->n_axes - 1; a >= 0; a--)
		m = m * f->axis[a].n + idx[a];
	return m;
}

void brdf_family_member_index(const struct brdf_family *f, int m, int idx[FAMILY_MAX_AXES])
{
	family_member_index(f->family, m, idx);
}

const struct bake *brdf_family_member_bake(const struct brdf_family *f, int m)
{
	return f->family->bake[m];
}

struct brdf_source *brdf_family_source(const struct brdf_family *f, int m)
{
	return brdf_source_of_bake(f->family->bake[m], 0);
}

struct brdf_source *brdf_family_at(const struct brdf_family *f, const double *x)
{
	return brdf_source_of_bake(family_bake_at(f->family, x), 1);
}

void brdf_family_blend(const struct brdf_family *f, const double *x, const double *v, int nv,
    double *out)
{
	struct family_stencil st;
	family_stencil(f->family, x, &st);
	for (int c = 0; c < nv; c++)
		out[c] = family_blend(&st, v + c, (size_t)nv);
}

void brdf_family_radius(const struct brdf_family *f, const double *x, double radius_rgb_cm[3])
{
	double rgb[3];
	family_albedo(f->family, x, NULL, rgb, radius_rgb_cm);
}
