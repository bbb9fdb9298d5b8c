/* An analytic test BRDF for the Blender exporter: Lambert with a reciprocal
 * retro/forward term, f = rho/pi (1 + B sin(ti) sin(to) cos(dphi)).  The
 * extra term integrates to zero over the exit hemisphere, so the
 * directional-hemispherical albedo is rho at every incidence. */
#ifndef SKINBAKE_TESTS_BLENDER_ANALYTIC_H
#define SKINBAKE_TESTS_BLENDER_ANALYTIC_H
#include <math.h>

#include "export/blender/blender.h"

#define ANALYTIC_B 0.3	/* strength of the delta_phi term [-] */
static const double analytic_rho[3] = { 0.6, 0.4, 0.3 };
static const double analytic_theta[2] = { 0.0, M_PI / 2 };
static const double analytic_albedo[6] = { 0.6, 0.6, 0.4, 0.4, 0.3, 0.3 };

static void analytic_f(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	(void)ctx;
	double k = 1.0 + ANALYTIC_B * sin(ti) * sin(to) * cos(dphi);
	for (int c = 0; c < 3; c++)
		rgb[c] = analytic_rho[c] / M_PI * k;
}

static void analytic_model(struct brdf_source *m)
{
	*m = (struct brdf_source){
		.f_rgb = analytic_f,
		.n_albedo = 2,
		.theta_albedo = analytic_theta,
		.albedo_rgb = analytic_albedo,
		.ior = 1.44,
		.roughness = 0.35,
		.sss_radius_cm = { 0.12, 0.045, 0.025 },
		.source = "analytic test model (tests/blender_analytic.h)",
		.preset = NULL,
	};
}
#endif
