/* nee: next-event (point) estimation of the exit tallies.  At every
 * scattering event the expected weight that leaves the top in each
 * (theta_o, delta_phi) bin straight after that event is scored: the phase
 * function toward the bin's direction, attenuation along the straight path
 * up, Fresnel transmission of every interface on the way (the clear top
 * stack with its multiple reflections), and the change of solid angle
 * across the interfaces (n^2 cos d(omega) is invariant).  Real escapes
 * straight after a scattering are then not binned (they are what this
 * estimates); escapes after a reflection inside the turbid layers still are.
 *
 * Unbiased for the bin means: the direction used in each bin is the bin's
 * lower corner plus a uniform random offset, drawn per photon in theta_o and
 * per event in delta_phi (so the forward peak of the phase function is
 * sampled at many points inside each bin), and each bin is evaluated on both
 * sides of the incidence plane.  References:
 * Kalos & Whitlock, Monte Carlo Methods (2008), point estimators; Wang &
 * Jacques' MCML manual for the layer geometry. */
#ifndef SKINBAKE_NEE_H
#define SKINBAKE_NEE_H
#include <math.h>
#include "engine/optics.h"
#include "engine/slab.h"

struct nee {
	int n_to, n_phi;	/* bins over theta_o [0, 90] and delta_phi [0, 180] deg */
	int n_slots;		/* layers + 2 */
	double *inv_mu;		/* [n_to][n_slots] 1 / cos of the internal ray in layer l */
	double *c;		/* [n_to][n_slots] transmission x Jacobian x bin measure x phase norm */
	double *sx, *sy;	/* [n_to][n_phi] internal direction's x, y in layer l's index... see nee.c */
	double *sz;		/* [n_to][n_slots] internal direction's z (negative: upward) per layer */
	double *sxy;		/* [n_to][n_slots] sin of the internal angle per layer */
	double *cphi, *sphi;	/* [n_phi] cos, sin of the lower bin edges in delta_phi */
	double g2p1[SLAB_MAX_LAYERS + 2], two_g[SLAB_MAX_LAYERS + 2];	/* 1 + g^2, 2 g per layer */
	double eps;		/* roulette scale: a band is scored with probability
				 * min(1, w exp(-tau) / eps), weighted by its inverse */
};

/* Allocate for a grid (caller frees with nee_free). */
void nee_alloc(struct nee *e, int n_to, int n_phi, int n_layers);
void nee_free(struct nee *e);
/* Fill for slab s (prepared) with the bin offset xi_t in [0, 1) in theta_o. */
void nee_prepare(struct nee *e, const struct slab *s, enum optics_fresnel model, double xi_t);

/* Add to bins[n_to * n_phi] the expected direct escape of a photon of weight
 * w scattering at depth z in turbid layer l, arriving with direction u.
 * Bands whose attenuated weight is small are scored only with probability
 * q = min(1, w exp(-tau) / eps) and then divided by q (roulette, unbiased);
 * rnd in (0, 1) is one uniform per event, shared by the bands; xi_p in
 * [0, 1) is the event's offset inside the delta_phi bins. */
static inline void nee_score(const struct nee *e, const struct slab *s, int l, double z, double ux, double uy,
    double uz, double w, double rnd, double xi_p, double *bins)
{
	const int ns = e->n_slots, np = e->n_phi;
	const double dd = xi_p * M_PI / np, cd = cos(dd), sd = sin(dd);
	const double depth = (z - s->z_top[l]) * s->mu_t[l];
	const double a = e->g2p1[l], b = e->two_g[l];
	/* The bins are symmetric in the sign of the exit's y; so is this sum. */
	for (int k = 0; k < e->n_to; k++) {
		double ck = e->c[k * ns + l];
		if (ck == 0.0)
			continue;
		double ex = w * exp(-depth * e->inv_mu[k * ns + l]);
		double att = ck * ex;
		if (ex < e->eps) {
			double q = ex / e->eps;
			if (rnd >= q)
				continue;
			att /= q;
		}
		double st = e->sxy[k * ns + l], zz = uz * e->sz[k * ns + l];
		double *row = bins + k * np;
		for (int p = 0; p < np; p++) {
			/* Exit azimuth measured from the source side: x = -sin cos(dphi). */
			double cp = e->cphi[p] * cd - e->sphi[p] * sd, sp = e->sphi[p] * cd + e->cphi[p] * sd;
			double dx = -st * cp * ux, dy = st * sp * uy;
			double c1 = zz + dx + dy, c2 = zz + dx - dy;
			double s1 = a - b * c1, s2 = a - b * c2;
			row[p] += att * (1.0 / (s1 * sqrt(s1)) + 1.0 / (s2 * sqrt(s2)));
		}
	}
}
#endif
