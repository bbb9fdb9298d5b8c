/* microfacet: the rough dielectric BSDF of Walter et al. 2007 (see
 * microfacet.h). */
#include "config.h"
#include "engine/microfacet.h"

#include <math.h>

static double dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(double v[3])
{
	double l = sqrt(dot3(v, v));
	v[0] /= l;
	v[1] /= l;
	v[2] /= l;
}

double microfacet_d(const struct microfacet *m, double cos_m)
{
	if (cos_m <= 0.0)
		return 0.0;
	double a2 = m->alpha * m->alpha, c2 = cos_m * cos_m;
	if (m->dist == MICROFACET_GGX) {
		double den = c2 * (a2 - 1.0) + 1.0;
		return a2 / (M_PI * den * den);
	}
	double t2 = (1.0 - c2) / c2;
	return exp(-t2 / a2) / (M_PI * a2 * c2 * c2);
}

double microfacet_lambda(const struct microfacet *m, double cos_v)
{
	double c2 = cos_v * cos_v;
	if (c2 >= 1.0)
		return 0.0;
	if (c2 <= 0.0)
		return INFINITY;
	double t2 = (1.0 - c2) / c2;
	if (m->dist == MICROFACET_GGX)
		return 0.5 * (sqrt(1.0 + m->alpha * m->alpha * t2) - 1.0);
	/* Beckmann: a = 1 / (alpha tan), exact form (Walter 2007 eq. 27). */
	double a = 1.0 / (m->alpha * sqrt(t2));
	return 0.5 * (erf(a) - 1.0) + exp(-a * a) / (2.0 * a * sqrt(M_PI));
}

double microfacet_g1(const struct microfacet *m, double cos_v)
{
	return 1.0 / (1.0 + microfacet_lambda(m, cos_v));
}

/* Fresnel reflectance of the facet with normal h for light from wi (index
 * n_i) into n_t; the refraction cosine (> 0) into *ct, 0 on total internal
 * reflection. */
static double facet_fresnel(const struct microfacet *m, double n_i, double n_t, double cos_ih,
    double *ct)
{
	return optics_fresnel(m->fresnel, n_i, n_t, cos_ih, ct);
}

double microfacet_bsdf(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    const double wo[3])
{
	if (wi[2] <= 0.0 || wo[2] == 0.0)
		return 0.0;
	double h[3], ct;
	if (wo[2] > 0.0) {
		h[0] = wi[0] + wo[0];
		h[1] = wi[1] + wo[1];
		h[2] = wi[2] + wo[2];
		normalize3(h);
		double ch = dot3(wi, h);
		double F = facet_fresnel(m, n_i, n_t, ch, &ct);
		double G = microfacet_g1(m, wi[2]) * microfacet_g1(m, wo[2]);
		return F * microfacet_d(m, h[2]) * G / (4.0 * wi[2] * wo[2]);
	}
	if (n_i == n_t)
		return 0.0;
	/* The generalised half vector, on the side of the macro normal
	 * (Walter eq. 16). */
	for (int k = 0; k < 3; k++)
		h[k] = -(n_i * wi[k] + n_t * wo[k]);
	normalize3(h);
	if (h[2] < 0.0)
		for (int k = 0; k < 3; k++)
			h[k] = -h[k];
	double ih = dot3(wi, h), oh = dot3(wo, h);
	if (ih <= 0.0 || oh >= 0.0)
		return 0.0;	/* the facet faces away from one of the two directions */
	double F = facet_fresnel(m, n_i, n_t, ih, &ct);
	if (F >= 1.0)
		return 0.0;
	double G = microfacet_g1(m, wi[2]) * microfacet_g1(m, wo[2]);
	double den = n_i * ih + n_t * oh;
	return ih * -oh * n_t * n_t * (1.0 - F) * microfacet_d(m, h[2]) * G
	    / (wi[2] * -wo[2] * den * den);
}

/* A GGX visible normal for wi (Heitz 2018): stretch wi to the unit-roughness
 * configuration, sample a point on the projected hemisphere, unstretch. */
static void ggx_visible_normal(double alpha, const double wi[3], double u1, double u2, double mo[3])
{
	double vh[3] = { alpha * wi[0], alpha * wi[1], wi[2] };
	normalize3(vh);
	double lensq = vh[0] * vh[0] + vh[1] * vh[1];
	double t1v[3] = { 1.0, 0.0, 0.0 };
	if (lensq > 0.0) {
		double il = 1.0 / sqrt(lensq);
		t1v[0] = -vh[1] * il;
		t1v[1] = vh[0] * il;
	}
	double t2v[3] = { vh[1] * t1v[2] - vh[2] * t1v[1], vh[2] * t1v[0] - vh[0] * t1v[2],
		vh[0] * t1v[1] - vh[1] * t1v[0] };
	double r = sqrt(u1), phi = 2.0 * M_PI * u2;
	double t1 = r * cos(phi), t2 = r * sin(phi);
	double s = 0.5 * (1.0 + vh[2]);
	t2 = (1.0 - s) * sqrt(1.0 - t1 * t1) + s * t2;
	double tz = sqrt(fmax(0.0, 1.0 - t1 * t1 - t2 * t2));
	double nh[3];
	for (int k = 0; k < 3; k++)
		nh[k] = t1 * t1v[k] + t2 * t2v[k] + tz * vh[k];
	mo[0] = alpha * nh[0];
	mo[1] = alpha * nh[1];
	mo[2] = fmax(1e-12, nh[2]);
	normalize3(mo);
}

/* A facet normal from D cos_m (either distribution), by inverting its
 * cumulative distribution in u1 (Walter 2007 eqs. 28, 35). */
static void normal_from_d(const struct microfacet *m, double u1, double u2, double mo[3])
{
	double a2 = m->alpha * m->alpha, c2;
	if (m->dist == MICROFACET_GGX)
		c2 = (1.0 - u1) / (1.0 + (a2 - 1.0) * u1);
	else
		c2 = 1.0 / (1.0 - a2 * log(1.0 - u1));
	double c = sqrt(c2), s = sqrt(fmax(0.0, 1.0 - c2)), phi = 2.0 * M_PI * u2;
	mo[0] = s * cos(phi);
	mo[1] = s * sin(phi);
	mo[2] = c;
}

double microfacet_sample(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    double u1, double u2, double u3, double wo[3])
{
	if (n_i == n_t) {
		wo[0] = -wi[0];
		wo[1] = -wi[1];
		wo[2] = -wi[2];
		return 1.0;
	}
	double h[3];
	if (m->dist == MICROFACET_GGX)
		ggx_visible_normal(m->alpha, wi, u1, u2, h);
	else
		normal_from_d(m, u1, u2, h);
	double ih = dot3(wi, h), ct;
	if (ih <= 0.0)
		return 0.0;	/* Beckmann only: a facet facing away */
	double F = facet_fresnel(m, n_i, n_t, ih, &ct);
	if (u3 < F) {
		for (int k = 0; k < 3; k++)
			wo[k] = 2.0 * ih * h[k] - wi[k];
		if (wo[2] <= 0.0)
			return 0.0;
	} else {
		double eta = n_i / n_t;
		for (int k = 0; k < 3; k++)
			wo[k] = (eta * ih - ct) * h[k] - eta * wi[k];
		if (wo[2] >= 0.0)
			return 0.0;
	}
	double g1o = microfacet_g1(m, wo[2]);
	if (m->dist == MICROFACET_GGX)
		return g1o;
	return ih * microfacet_g1(m, wi[2]) * g1o / (wi[2] * h[2]);
}

void microfacet_sample_split(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    double u1, double u2, double wr[3], double *w_r, double wt[3], double *w_t)
{
	*w_r = 0.0;
	*w_t = 0.0;
	if (n_i == n_t) {
		for (int k = 0; k < 3; k++)
			wt[k] = -wi[k];
		*w_t = 1.0;
		return;
	}
	double h[3];
	ggx_visible_normal(m->alpha, wi, u1, u2, h);
	double ih = dot3(wi, h), ct;
	if (ih <= 0.0)
		return;
	double F = facet_fresnel(m, n_i, n_t, ih, &ct);
	for (int k = 0; k < 3; k++)
		wr[k] = 2.0 * ih * h[k] - wi[k];
	if (wr[2] > 0.0)
		*w_r = F * microfacet_g1(m, wr[2]);
	if (F >= 1.0)
		return;
	double eta = n_i / n_t;
	for (int k = 0; k < 3; k++)
		wt[k] = (eta * ih - ct) * h[k] - eta * wi[k];
	normalize3(wt);
	if (wt[2] < 0.0)
		*w_t = (1.0 - F) * microfacet_g1(m, wt[2]);
}

void microfacet_albedo(const struct microfacet *m, double n_i, double n_t, double cos_i, int n_mu,
    int n_phi, double *R, double *T)
{
	double wi[3] = { sqrt(fmax(0.0, 1.0 - cos_i * cos_i)), 0.0, cos_i };
	double g1i = microfacet_g1(m, cos_i), r = 0.0, t = 0.0;
	if (n_i == n_t) {
		*R = 0.0;
		*T = 1.0;
		return;
	}
	/* E = int D(h) cos_h (wi.h / wi.z) G1(wi) [F G1(wo_r) + (1 - F) G1(wo_t)] d(omega_h).
	 * In the variable u of D cos_h's cumulative distribution and phi the
	 * measure D cos_h d(omega_h) is du dphi / (2 pi); the factor 1 / cos_h
	 * left over is an integrable 1 / sqrt(1 - u) singularity at the
	 * horizon, which u = 1 - s^2 (du = 2 s ds) removes. */
	for (int a = 0; a < n_mu; a++) {
		double sv = (a + 0.5) / n_mu;
		for (int b = 0; b < n_phi; b++) {
			double h[3];
			normal_from_d(m, 1.0 - sv * sv, (b + 0.5) / n_phi, h);
			double ih = dot3(wi, h), ct;
			if (ih <= 0.0)
				continue;
			double F = facet_fresnel(m, n_i, n_t, ih, &ct);
			double wr = 2.0 * sv * ih * g1i / (cos_i * h[2]), wo[3];
			for (int k = 0; k < 3; k++)
				wo[k] = 2.0 * ih * h[k] - wi[k];
			if (wo[2] > 0.0)
				r += wr * F * microfacet_g1(m, wo[2]);
			if (F < 1.0) {
				double eta = n_i / n_t;
				for (int k = 0; k < 3; k++)
					wo[k] = (eta * ih - ct) * h[k] - eta * wi[k];
				if (wo[2] < 0.0)
					t += wr * (1.0 - F) * microfacet_g1(m, wo[2]);
			}
		}
	}
	*R = r / ((double)n_mu * n_phi);
	*T = t / ((double)n_mu * n_phi);
}

/* The microsurface of the Smith model with uniformly distributed heights
 * in [-1, 1] (Heitz, Hanika, d'Eon & Dachsbacher, "Multiple-scattering
 * microfacet BSDFs with the Smith model", SIGGRAPH 2016, sections 3-5):
 * C1(h) is the height's cumulative distribution; a ray at height h going
 * up (w.z > 0) escapes with probability C1(h)^Lambda(w), the Smith G1 at
 * that height. */
static double c1(double h)
{
	return fmin(1.0, fmax(0.0, 0.5 * (h + 1.0)));
}

static double inv_c1(double u)
{
	return fmax(-1.0, fmin(1.0, 2.0 * u - 1.0));
}

/* The next height at which the ray (direction w, from height h) meets the
 * microsurface, or INFINITY when it leaves (Heitz 2016, eq. 9 inverted). */
static double next_height(const struct microfacet *m, const double w[3], double h, double u)
{
	if (w[2] > 0.9999)
		return INFINITY;
	if (w[2] < -0.9999)
		return inv_c1(u * c1(h));
	if (fabs(w[2]) < 1e-4)
		return h;
	double lam = microfacet_lambda(m, w[2]);
	if (w[2] > 0.0) {
		double g1 = pow(c1(h), lam);
		if (u > 1.0 - g1)
			return INFINITY;
		return inv_c1(c1(h) / pow(1.0 - u, 1.0 / lam));
	}
	/* Going down it always meets the surface: Lambda(-w) = -1 - Lambda(w). */
	return inv_c1(c1(h) * pow(1.0 - u, 1.0 / (1.0 + lam)));
}

/* A GGX visible normal for a direction v on either side of the surface:
 * in the unit-roughness configuration the visible normals are v + c
 * normalised, c uniform on the spherical cap c.z >= -v.z (Dupuy & Benyoub,
 * "Sound and complete visible normal sampling", 2023), then unstretched. */
static void ggx_visible_normal_any(double alpha, const double v[3], double u1, double u2,
    double mo[3])
{
	double vs[3] = { alpha * v[0], alpha * v[1], v[2] };
	normalize3(vs);
	double phi = 2.0 * M_PI * u1, z = (1.0 - u2) * (1.0 + vs[2]) - vs[2];
	double st = sqrt(fmax(0.0, 1.0 - z * z));
	double h[3] = { st * cos(phi) + vs[0], st * sin(phi) + vs[1], z + vs[2] };
	mo[0] = alpha * h[0];
	mo[1] = alpha * h[1];
	mo[2] = fmax(1e-12, h[2]);
	normalize3(mo);
}

double microfacet_sample_ms(const struct microfacet *m, double n_i, double n_t, const double wi[3],
    double (*uniform)(void *), void *rng, double wo[3], int *order)
{
	if (n_i == n_t) {
		for (int k = 0; k < 3; k++)
			wo[k] = -wi[k];
		return 1.0;
	}
	/* d: travel direction, h: height, both with z toward the side of
	 * incidence; inside the other medium the walk runs mirrored (cs). */
	double d[3] = { -wi[0], -wi[1], -wi[2] }, h = 2.0;
	int outside = 1;
	for (int k = 0; k < MICROFACET_MAX_BOUNCES; k++) {
		double sg = outside ? 1.0 : -1.0, dc[3] = { d[0], d[1], sg * d[2] };
		double hc = next_height(m, dc, sg * h, uniform(rng));
		if (isinf(hc)) {
			for (int j = 0; j < 3; j++)
				wo[j] = d[j];
			if (order)
				*order = k;
			return 1.0;
		}
		h = sg * hc;
		double v[3] = { -dc[0], -dc[1], -dc[2] }, mn[3], ct;
		double u1 = uniform(rng), u2 = uniform(rng), u3 = uniform(rng);
		ggx_visible_normal_any(m->alpha, v, u1, u2, mn);
		double vm = dot3(v, mn), n1 = outside ? n_i : n_t, n2 = outside ? n_t : n_i;
		if (vm <= 0.0)
			vm = 1e-12;	/* rounding at the cap's edge */
		double F = facet_fresnel(m, n1, n2, vm, &ct);
		if (u3 < F) {
			for (int j = 0; j < 3; j++)
				dc[j] = 2.0 * vm * mn[j] - v[j];
		} else {
			double eta = n1 / n2;
			for (int j = 0; j < 3; j++)
				dc[j] = (eta * vm - ct) * mn[j] - eta * v[j];
			normalize3(dc);
			outside = !outside;
		}
		d[0] = dc[0];
		d[1] = dc[1];
		d[2] = sg * dc[2];
	}
	if (order)
		*order = MICROFACET_MAX_BOUNCES;
	return 0.0;	/* stuck on the surface: vanishingly rare, booked as lost */
}
