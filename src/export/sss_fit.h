/* sss_fit: a renderer's own subsurface closure fitted to a bake's radial
 * profile Rd(r), from a calibration table measured once in the real
 * renderer (scripts/calibrate-translucency.py, `make calibrate`; the table
 * is sss_table.c), so that exporting needs no render.
 *
 * The closures (POV-Ray 3.7 `subsurface { translucency }`, Cycles' random
 * walk) have two parameters per channel: a colour, which sets how much
 * light comes back and the shape of the profile, and a length (POV-Ray's
 * translucency, Cycles' radius), which scales every distance.  The table
 * holds, per channel and colour at unit length, G(r): the fraction of the incident
 * power leaving beyond r (normal incidence, all exit directions), and the
 * far-field BRDF of the lit slab, pi f(theta_i, theta_o), which does not
 * depend on the length.  The fit matches the power and the mean radius
 * within the bake's profile (r_max), per channel, where it helps the shape
 * with a share of the power left to the table at the entry point (local). */
#ifndef SKINBAKE_SSS_FIT_H
#define SKINBAKE_SSS_FIT_H
#include "bake/bakefile.h"

struct sss_table {
	const char *renderer;		/* "povray" or "cycles" */
	const char *version;		/* the renderer version measured */
	const char *closure;		/* what was measured */
	double ior;			/* the closure's refractive index in the measurement [-]: POV-Ray's
					 * dipole and Cycles' walk depend on it, so the material uses it */
	int n_colour, n_edge, n_far;
	const double *colour;		/* [n_colour] the closure's colour [-], ascending */
	const double *edge_mm;		/* [n_edge] ring edges at unit length [mm], from 0 */
	const double *g;		/* [3][n_colour][n_edge] power leaving beyond the edge per R, G, B [-] */
	const double *far_deg;		/* [n_far] theta nodes of far_pi_f [deg] */
	const double *far_pi_f;		/* [3][n_colour][n_far (theta_i)][n_far (theta_o)] pi f [-] */
};

extern const struct sss_table sss_pov_table;
extern const struct sss_table sss_cycles_table;

struct sss_fit {
	const struct sss_table *table;
	double scale;			/* the closure's weight in the material [-] */
	double colour[3];		/* fitted colour per R, G, B [-] */
	double length_mm[3];		/* fitted translucency / radius [mm] */
	double r_max_mm;		/* how far the bake's profile reaches [mm] */
	double integral_bake[3];	/* the bake's power within r_max [-] */
	double local[3];		/* power left to the table's remainder at the entry point (r = 0) [-] */
	double integral_fit[3];		/* the closure's (times scale) plus local [-] */
	double mean_bake_mm[3];		/* first moments within r_max [mm] */
	double mean_fit_mm[3];
	double rms_log[3];		/* RMS of ln(R_fit / R_bake) over the rings that hold 95 % of the bake's power [-] */
	int clamped[3];			/* 1 when the colour hit the table's range */
};

/* Ring edges [mm] the residuals and the tests compare on (-1 terminated). */
extern const double sss_ring_edges_mm[];

/* Fit T's closure, weighted by SCALE, to bake B's profile.  -1 and *cause
 * when B has no radial profile. */
int sss_fit_bake(const struct sss_table *t, const struct bake *b, double scale, struct sss_fit *f, char **cause);

/* The fitted material's power on the ring [r1, r2] mm, channel c: the
 * closure's times scale, plus local on the ring holding r = 0. */
double sss_fit_ring(const struct sss_fit *f, int c, double r1_mm, double r2_mm);
/* The bake's power on the ring [r1, r2] mm (bins by their centres), channel c. */
double sss_bake_ring(const struct bake *b, int c, double r1_mm, double r2_mm);

/* The closure's far-field pi f in channel c at colour COLOUR [-], angles in
 * radians (not times any scale). */
double sss_far_pi_f(const struct sss_table *t, int c, double colour, double theta_i,
    double theta_o);
#endif
