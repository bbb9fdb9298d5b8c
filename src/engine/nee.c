/* nee: the per-slab constants of next-event estimation toward the exit
 * bins; the scoring itself is inline in nee.h. */
#include "config.h"
#include "engine/nee.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine/optics.h"
#include "base/util.h"

void nee_alloc(struct nee *e, int n_to, int n_phi, int n_layers)
{
	memset(e, 0, sizeof *e);
	e->n_to = n_to;
	e->n_phi = n_phi;
	e->n_slots = n_layers + 2;
	e->eps = 0.1;	/* tuned on the paper preset (BENCHMARKS.md): best error x time */
	size_t kl = (size_t)n_to * (size_t)e->n_slots;
	e->inv_mu = xcalloc(kl, sizeof(double));
	e->c = xcalloc(kl, sizeof(double));
	e->sz = xcalloc(kl, sizeof(double));
	e->sxy = xcalloc(kl, sizeof(double));
	e->cphi = xcalloc((size_t)n_phi, sizeof(double));
	e->sphi = xcalloc((size_t)n_phi, sizeof(double));
	for (int p = 0; p < n_phi; p++) {
		e->cphi[p] = cos(p * M_PI / n_phi);
		e->sphi[p] = sin(p * M_PI / n_phi);
	}
}

void nee_free(struct nee *e)
{
	free(e->inv_mu);
	free(e->c);
	free(e->sz);
	free(e->sxy);
	free(e->cphi);
	free(e->sphi);
	memset(e, 0, sizeof *e);
}

void nee_prepare(struct nee *e, const struct slab *s, enum optics_fresnel model, double xi_t)
{
	const int ns = e->n_slots, nl = s->n_layers, ft = s->first_turbid;
	const double dth = 0.5 * M_PI / e->n_to, dph = M_PI / e->n_phi, n0 = s->layer[0].n;
	for (int i = 0; i <= nl + 1; i++) {
		double g = s->layer[i].g;
		e->g2p1[i] = 1.0 + g * g;
		e->two_g[i] = 2.0 * g;
	}
	for (int k = 0; k < e->n_to; k++) {
		double th = (k + xi_t) * dth, c0 = cos(th), s0 = sin(th);
		double *C = e->c + k * ns;
		memset(C, 0, sizeof(double) * (size_t)ns);
		if (c0 <= 0.0 || ft > nl)
			continue;
		/* The internal ray in every layer: n sin is conserved. */
		int tir = 0;
		for (int l = 1; l <= nl; l++) {
			double sl = n0 * s0 / s->layer[l].n;
			if (sl >= 1.0) {
				tir = 1;
				break;
			}
			double cl = sqrt(1.0 - sl * sl);
			e->inv_mu[k * ns + l] = 1.0 / cl;
			e->sz[k * ns + l] = -cl;
			e->sxy[k * ns + l] = sl;
		}
		if (tir)
			continue;
		/* Walk down from the first turbid layer, accumulating the
		 * transmission and attenuation of the path above each layer. */
		double n_list[SLAB_MAX_LAYERS + 2], c_ft;
		for (int j = 0; j <= ft; j++)
			n_list[j] = s->layer[j].n;
		double T = 1.0 - optics_stack_reflectance(model, n_list, ft + 1, c0, &c_ft);
		for (int l = ft; l <= nl && T > 0.0; l++) {
			if (l > ft) {
				double ct;
				double cu = 1.0 / e->inv_mu[k * ns + l];
				double r = optics_fresnel(model, s->layer[l].n, s->layer[l - 1].n, cu, &ct);
				T *= (1.0 - r) * exp(-s->mu_t[l - 1] * s->layer[l - 1].d * e->inv_mu[k * ns + l - 1]);
			}
			if (slab_layer_clear(s, l))
				continue;	/* no events happen there */
			double nl0 = n0 / s->layer[l].n;
			double jac = nl0 * nl0 * c0 * e->inv_mu[k * ns + l];
			double g = s->layer[l].g;
			/* HG per steradian = (1-g^2) / (4 pi s^1.5); bin measure
			 * sin(theta) dtheta dphi per side; both sides are summed. */
			C[l] = T * jac * (1.0 - g * g) / (4.0 * M_PI) * s0 * dth * dph;
		}
	}
}
