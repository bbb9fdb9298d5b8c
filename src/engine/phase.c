/* phase: Henyey-Greenstein sampling and the direction update (see phase.h). */
#include "config.h"
#include <math.h>
#include "engine/phase.h"

double hg_pdf_cos(double g, double cos_theta)
{
	double d = 1.0 + g * g - 2.0 * g * cos_theta;
	return 0.5 * (1.0 - g * g) / (d * sqrt(d));
}
