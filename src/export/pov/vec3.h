/* vec3: the few 3-vector operations the POV-Ray exporter needs (inline). */
#ifndef SKINBAKE_VEC3_H
#define SKINBAKE_VEC3_H
#include <math.h>

static inline double vec3_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Unit vector from `from` toward `to` (0 when they coincide). */
static inline void vec3_unit_toward(const double from[3], const double to[3], double out[3])
{
	double d[3] = { to[0] - from[0], to[1] - from[1], to[2] - from[2] };
	double n = sqrt(vec3_dot(d, d));
	for (int i = 0; i < 3; i++)
		out[i] = n > 0 ? d[i] / n : 0;
}

static inline void vec3_cross(const double a[3], const double b[3], double out[3])
{
	out[0] = a[1] * b[2] - a[2] * b[1];
	out[1] = a[2] * b[0] - a[0] * b[2];
	out[2] = a[0] * b[1] - a[1] * b[0];
}
#endif
