/* source_family: a family of bakes (`skinbake bake --vary`, family/family.h)
 * as an exporter sees it, next to struct brdf_source for one bake: the
 * parameter axes with their nodes, a struct brdf_source per member and at
 * any point between members (the family interpolated there), and values
 * per member blended as the family blends its members.  Exporters reach
 * families only through this (and the inline axis transform of
 * family/family.h), as they reach bakes only through struct brdf_source. */
#ifndef SKINBAKE_SOURCE_FAMILY_H
#define SKINBAKE_SOURCE_FAMILY_H
#include "export/source.h"
#include "family/family.h"

struct brdf_family {
	const char *dir;		/* the family directory */
	const char *preset;		/* its base preset (name or file), or NULL */
	int n_axes;			/* 1..FAMILY_MAX_AXES */
	const struct family_axis *axis;	/* [n_axes]: key, nodes, interpolation coordinate */
	int n_members;			/* product of the node counts;
					 * member m = i0 + n0 (i1 + n1 i2) */
	const struct family *family;	/* the family itself, for mapset_check_family only */
	struct family *own;		/* owned */
};

/* The family of DIR (family.json; the member tables come with
 * brdf_family_load_tables).  NULL and *cause (caller frees). */
struct brdf_family *brdf_family_open(const char *dir, char **cause);
/* Read the member tables (before brdf_family_source and brdf_family_at);
 * -1 and *cause. */
int brdf_family_load_tables(struct brdf_family *f, char **cause);
void brdf_family_free(struct brdf_family *f);	/* NULL is a no-op */
/* The member at node indices idx[n_axes], and the indices of member m. */
int brdf_family_member(const struct brdf_family *f, const int *idx);
void brdf_family_member_index(const struct brdf_family *f, int m, int idx[FAMILY_MAX_AXES]);
/* Member m's BRDF; brdf_source_free it (the table stays the family's). */
struct brdf_source *brdf_family_source(const struct brdf_family *f, int m);
/* Member m's bake as read (its radial profile, for the translucent fit). */
const struct bake *brdf_family_member_bake(const struct brdf_family *f, int m);
/* The BRDF at parameters x[n_axes] (each clamped to its axis), the member
 * tables interpolated there (family_bake_at); brdf_source_free frees it. */
struct brdf_source *brdf_family_at(const struct brdf_family *f, const double *x);
/* out[c] for c < nv: the values v[m * nv + c] of the members blended at x
 * as the family blends its tables (family_stencil, family_blend). */
void brdf_family_blend(const struct brdf_family *f, const double *x, const double *v, int nv,
    double *out);
/* Mean exit radius of the diffuse light per R, G, B at x [cm] (the
 * members' blended). */
void brdf_family_radius(const struct brdf_family *f, const double *x, double radius_rgb_cm[3]);
#endif
