/* blender_sss_thick: the translucent node weighted by the local thickness
 * (issue 27's back-light test; docs/translucency.md, Back light).  Cycles'
 * walk fitted to the bake's Rd(r) is one homogeneous medium: lit from
 * behind, it lets through up to twice what the layered slab does (`paper`,
 * red, 1 mm: 0.397 against Tt 0.193).  The importer weights the node per
 * channel by f_c(d) = Tt_c(d) / T_walk,c(d), at most 1, where d is the local
 * thickness (Cycles' Ambient Occlusion node with Inside within
 * D = BLENDER_THICK_AO_MM, and within BLENDER_THICK_NEAR_MM for thin parts:
 * AO = (d / D)^2), and adds (1 - f_c) times the node's
 * far field as a Lambertian, so that a flat surface under uniform light
 * keeps its exactness.  Tt_c(d) is the bake's stack cut to d (the deeper
 * layers shortened, the last extended, light entering the deepest layer;
 * adding-doubling per wavelength, weighted into linear sRGB as the bake's
 * colours are), T_walk from the transmission table of the Blender version,
 * measured in the real renderer (scripts/calibrate-transmission.py; generated
 * blender_sss_trans.c). */
#ifndef SKINBAKE_BLENDER_SSS_THICK_H
#define SKINBAKE_BLENDER_SSS_THICK_H
#include "export/sss_fit.h"

/* The transmittance of the walk through a slab lit from behind (all exit
 * directions), at radius 1 mm, per colour and thickness. */
struct sss_trans_table {
	const char *version;		/* the Blender measured */
	const char *falloff;		/* its node's falloff (lower case, as sss_profile.py) */
	int n_colour, n_x;
	const double *colour;		/* [n_colour] ascending [-] */
	const double *x_mm;		/* [n_x] slab thickness at radius 1 mm, ascending [mm] */
	const double *t;		/* [n_colour][n_x] transmittance [-] */
};

/* The measured versions, NULL-terminated (generated: blender_sss_trans.c). */
extern const struct sss_trans_table *const blender_sss_trans_tables[];

#define BLENDER_THICK_N 10
#define BLENDER_THICK_AO_MM 8.0		/* the AO distance: thicker counts as BLENDER_THICK_AO_MM */
/* A second AO within this resolves thin parts: one AO within 8 mm over a
 * 1 mm slab is unoccluded for (1/8)^2 of its rays, so 16 rays see 0 or 1 of
 * them and the weight, not linear in that count, came out biased. */
#define BLENDER_THICK_NEAR_MM 2.0
/* The thickness nodes [mm], ascending, the last the AO distance. */
extern const double blender_thick_d_mm[BLENDER_THICK_N];

struct blender_thick {
	int has;			/* 1 when the version has a transmission table */
	double tt[BLENDER_THICK_N][3];	/* the stack's Tt per thickness and R, G, B [-] */
	double walk[BLENDER_THICK_N][3];	/* the fitted walk's [-] */
	/* f = min(1, tt / walk) (1 at the last node; the previous node's where
	 * the walk passes < 1e-4) [-] */
	double weight[BLENDER_THICK_N][3];
};

/* The table of the Blender series of fit table T ("3.4"), or NULL. */
const struct sss_trans_table *blender_thick_table(const struct sss_table *t);

/* The walk's transmittance at colour COLOUR through X_MM at radius 1 mm
 * (colour linear, ln T linear in x between the nodes, ln T extrapolated
 * beyond them; at most 1). */
double blender_thick_walk(const struct sss_trans_table *t, double colour, double x_mm);

/* Tt per blender_thick_d_mm and R, G, B of bake B's stack (its manifest's
 * layers per wavelength, weighted by its rgb_from_wl).  -1 and *cause when
 * the manifest's layers are missing or the solver fails. */
int blender_thick_stack(const struct bake *b, double tt[BLENDER_THICK_N][3], char **cause);

/* The weights of fit F from TT (blender_thick_stack's) into *OUT; OUT->has
 * is 0 when F's Blender has no transmission table. */
void blender_thick_weights(const struct sss_fit *f, const double tt[BLENDER_THICK_N][3],
    struct blender_thick *out);

/* A version entry's "thickness" member: `"thickness": {...}` (caller
 * frees), or an empty string when T->has is 0. */
char *blender_thick_json(const struct blender_thick *t);
#endif
