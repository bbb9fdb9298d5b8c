/* separable: the fallback for many lights or lights edited later, a BRDF
 * approximated by what POV-Ray's own finish can do: pigment A(theta_o)
 * through `aoi` and finish `diffuse 1 brilliance b`, fitted by weighted least
 * squares to pi f cos(theta_i) over the hemispheres.  A separable model
 * cannot hold the surface specular lobe; the fit error is reported. */
#ifndef SKINBAKE_SEPARABLE_H
#define SKINBAKE_SEPARABLE_H
#include <stdio.h>

#include "export/pov/littable.h"

#define SEPARABLE_NODES 33

struct pov_separable {
	double brilliance;		/* POV finish brilliance b [-] */
	double a[SEPARABLE_NODES][3];	/* pigment at theta_o = 90 deg * k/(N-1) [-] */
	double rms;			/* fit error: rms(model - target)/rms(target) [-] */
	double mean;			/* fit error: mean|model - target|/mean(target) [-] */
};

void separable_fit(const struct pov_brdf *f, struct pov_separable *out);
/* `#declare NAME = pigment { aoi color_map { ... } }` with the fit's error
 * in a comment. */
void separable_write(FILE *fp, const char *name, const struct pov_separable *sep);
#endif
