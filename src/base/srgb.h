/* srgb: the sRGB transfer function (IEC 61966-2-1) that turns a linear
 * value into the encoded one of 8-bit previews.  Header only. */
#ifndef SKINBAKE_SRGB_H
#define SKINBAKE_SRGB_H
#include <math.h>

/* Encoded value in [0, 1] of a linear value, clamped to [0, 1] first
 * (NaN encodes as 1). */
static inline double srgb_encode(double linear)
{
	double v = fmax(0.0, fmin(1.0, linear));
	return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}
#endif
