/* specular: the analytic GGX surface reflection of the clear top stack
 * (see specular.h). */
#include "config.h"
#include "engine/specular.h"

#include <math.h>

void specular_stack_of_slab(const struct slab *s, enum optics_fresnel model, struct specular_stack *out)
{
	out->model = model;
	out->n = 0;
	int last = s->first_turbid <= s->n_layers ? s->first_turbid : s->n_layers + 1;
	for (int i = 0; i <= last && out->n < SPECULAR_MAX_IFACES; i++)
		out->n_list[out->n++] = s->layer[i].n;
}

double specular_stack_reflectance(const struct specular_stack *s, double cos_i)
{
	double ct;
	return optics_stack_reflectance(s->model, s->n_list, s->n, cos_i, &ct);
}

/* Smith's masking for GGX. */
static double g1(double alpha, double cos_v)
{
	if (cos_v <= 0.0)
		return 0.0;
	double t2 = (1.0 - cos_v * cos_v) / (cos_v * cos_v);
	return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * t2));
}

double specular_ggx(const struct specular_stack *s, double alpha, double theta_i, double theta_o, double dphi)
{
	double ci = cos(theta_i), co = cos(theta_o);
	if (ci <= 1e-9 || co <= 1e-9)
		return 0.0;
	/* wi points toward the light at azimuth 0 and wo at azimuth dphi, so
	 * dphi = 0 is back toward the light and dphi = pi the mirror side. */
	double si = sin(theta_i), so = sin(theta_o);
	double wi[3] = { si, 0.0, ci };
	double wo[3] = { so * cos(dphi), so * sin(dphi), co };
	double h[3] = { wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2] };
	double hn = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
	if (hn <= 0.0)
		return 0.0;
	double ch = h[2] / hn, cd = (wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]) / hn;
	double a2 = alpha * alpha, c2 = ch * ch;
	double den = c2 * (a2 - 1.0) + 1.0;
	double D = a2 / (M_PI * den * den);
	double F = specular_stack_reflectance(s, cd > 1.0 ? 1.0 : cd);
	return F * D * g1(alpha, ci) * g1(alpha, co) / (4.0 * ci * co);
}
