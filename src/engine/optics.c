/* optics: Fresnel reflectance and refraction in cosines (see optics.h). */
#include "config.h"
#include "engine/optics.h"

#include <math.h>

double optics_cos_t(double n1, double n2, double cos_i)
{
	double r = n1 / n2;
	double c2 = 1.0 - r * r * (1.0 - cos_i * cos_i);
	return c2 < 0.0 ? -1.0 : sqrt(c2);
}

double optics_cos_critical(double n1, double n2)
{
	if (n1 <= n2)
		return 0.0;
	double r = n2 / n1;
	return sqrt(1.0 - r * r);
}

double optics_fresnel(enum optics_fresnel model, double n1, double n2, double cos_i, double *cos_t)
{
	if (n1 == n2) {
		*cos_t = cos_i;
		return 0.0;
	}
	double ct = optics_cos_t(n1, n2, cos_i);
	if (ct < 0.0) {
		*cos_t = 0.0;
		return 1.0;
	}
	*cos_t = ct;
	if (model == OPTICS_FRESNEL_SCHLICK) {
		double r0 = (n1 - n2) / (n1 + n2);
		r0 *= r0;
		/* Schlick's cosine is the one in the thinner medium, so that the
		 * approximation respects reciprocity and goes to 1 at the critical angle. */
		double c = n1 <= n2 ? cos_i : ct;
		double m = 1.0 - c, m2 = m * m;
		return r0 + (1.0 - r0) * m2 * m2 * m;
	}
	double rs = (n1 * cos_i - n2 * ct) / (n1 * cos_i + n2 * ct);
	double rp = (n1 * ct - n2 * cos_i) / (n1 * ct + n2 * cos_i);
	return 0.5 * (rs * rs + rp * rp);
}

double optics_stack_reflectance(enum optics_fresnel model, const double *n, int count, double cos_i, double *cos_t)
{
	double R = 0.0, c = cos_i;
	for (int j = 1; j < count; j++) {
		double ct, r = optics_fresnel(model, n[j - 1], n[j], c, &ct);
		if (r >= 1.0) {
			*cos_t = 0.0;
			return 1.0;
		}
		R = R + (1.0 - R) * (1.0 - R) * r / (1.0 - R * r);
		c = ct;
	}
	*cos_t = c;
	return R;
}
