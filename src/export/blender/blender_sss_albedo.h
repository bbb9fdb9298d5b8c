/* blender_sss_albedo: the albedo G(0) of Cycles' walk, measured densely in
 * the colour at many samples, for the node's far field that the translucent
 * remainder takes off the table (blender_sss.h).  The profile calibration
 * (blender_sss_tables) has 15 colours and G is linear in the colour between
 * them, but G(0) / colour bends at small colours (1.10 at 0.01, 1.07 at
 * 0.02, 1.02 at 0.04, 1.00 from 0.06), and 3.4.1's table was rendered at 64
 * samples, 0.6 % low: at 3.4.1 blue 0.029 (`paper`) the table interpolated
 * G(0) = 0.03007 where the walk returns 0.03054 (1024 and 4096 samples), and
 * the flat box came out +1.2 % in blue.  The node's far field is therefore
 * the table's times g0(colour) / the table's G(0) at that colour (its shape
 * over the view angle, 4.x, stays the table's). */
#ifndef SKINBAKE_BLENDER_SSS_ALBEDO_H
#define SKINBAKE_BLENDER_SSS_ALBEDO_H
#include "export/sss_fit.h"

struct sss_albedo_table {
	const char *version;		/* the Blender measured */
	int samples;			/* per pixel */
	int n_colour;
	const double *colour;		/* [n_colour] ascending [-] */
	const double *g0;		/* [n_colour] the walk's G(0), every channel [-] */
};

/* The measured versions, NULL-terminated (generated: blender_sss_albedo.c,
 * scripts/calibrate-transmission.py --albedo). */
extern const struct sss_albedo_table *const blender_sss_albedo_tables[];

/* The factor on fit table T's far field at COLOUR, channel c: the measured
 * albedo (linear between its dense nodes) over T's G(0) there; 1 when T's
 * Blender has no albedo table. */
double blender_sss_albedo_factor(const struct sss_table *t, int c, double colour);
#endif
