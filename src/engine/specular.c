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

double specular_schlick(double cos_i, double n)
{
	double r0 = (n - 1) / (n + 1);
	r0 *= r0;
	return r0 + (1 - r0) * pow(1 - cos_i, 5);
}

double specular_ggx_d(double cos_h, double alpha2)
{
	double den = cos_h * cos_h * (alpha2 - 1.0) + 1.0;
	return alpha2 / (M_PI * den * den);
}

double specular_smith_g1(double cos_v, double alpha2)
{
	return 2 * cos_v / (cos_v + sqrt(alpha2 + (1 - alpha2) * cos_v * cos_v));
}

/* Smith's masking for GGX in its tangent form: the same function as
 * specular_smith_g1, but half of its values differ in the last bit, and
 * these are the ones every bake's eval and exports were made with.  One
 * form should replace the other in a commit that may change outputs. */
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
	double D = specular_ggx_d(ch, alpha * alpha);
	double F = specular_stack_reflectance(s, cd > 1.0 ? 1.0 : cd);
	return F * D * g1(alpha, ci) * g1(alpha, co) / (4.0 * ci * co);
}
