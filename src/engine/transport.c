/* The photon walk, in MCML's order and vocabulary: launch, hop (move with a
 * step drawn as optical depth), cross or reflect at boundaries (Fresnel, total
 * internal reflection, Snell in cosines), drop (implicit absorption), spin
 * (Henyey-Greenstein) and roulette.
 *
 * Energy is booked exactly: every change of a photon's weight goes to a
 * tally.  Roulette changes weight too (a loss when the photon dies, a gain
 * when it survives with w/chance); that change is booked against the
 * absorption of the layer where it happens.  Its expectation is zero, so A
 * stays unbiased, and Rsp + Rd + Tt + sum(A) + lost = 1 in every run up to
 * floating-point rounding.
 *
 * How the walk ends: each photon ends by leaving the stack, by absorption to
 * zero weight, by roulette, or by the guard after max_steps interactions
 * (weight booked as `lost`).  Without absorption (mu_a = 0) roulette never
 * plays, so in a semi-infinite non-absorbing layer the guard is what ends the
 * rare photons that wander deep; their weight shows in `lost`. */
#include "config.h"
#include "engine/transport.h"

#include <math.h>

#include "engine/phase.h"
#include "base/rng.h"

void transport_opts_default(struct transport_opts *o)
{
	o->fresnel = OPTICS_FRESNEL_EXACT;
	o->roulette_w = 0.2;
	o->roulette_chance = 0.3;
	o->max_steps = 1000000;
}

void transport_launch(const struct slab *s, double theta_in, enum optics_fresnel model, struct launch *ln)
{
	const struct layer *L = s->layer;
	int k = s->first_turbid;	/* n_layers + 1 when all clear: then down to the ambient below */
	double n_list[SLAB_MAX_LAYERS + 2], ct;
	for (int j = 0; j <= k; j++)
		n_list[j] = L[j].n;
	ln->rsp = optics_stack_reflectance(model, n_list, k + 1, cos(theta_in), &ct);
	ln->w0 = 1.0 - ln->rsp;
	ln->layer = k;
	ln->z = s->z_top[k];
	/* n sin(theta) is conserved through parallel interfaces. */
	double st = L[0].n * sin(theta_in) / L[k].n;
	ln->ux = st;
	ln->uz = sqrt(fmax(0.0, 1.0 - st * st));
}

/* Score a photon leaving the top with weight w, ambient direction cosines
 * (ux, uy, uz > 0 pointing up out of the skin) at lateral position (x, y). */
static inline void score_top(const struct tally_grid *g, struct tally *t, double w, int scattered, int bin,
    double ux, double uy, double cos_o, double x, double y)
{
	t->rd += w;
	if (!scattered) {
		t->rd_unscat += w;
		return;
	}
	if (g->n_r > 0) {
		double r = sqrt(x * x + y * y);
		long ir = (long)(r / g->dr);
		if (ir < g->n_r)
			t->radial[ir] += w;
	}
	if (!bin)
		return;
	/* Incident light travels along +x, so the direction toward the source has
	 * azimuth pi; delta_phi = 0 is back toward the source, pi the mirror side. */
	double theta = acos(cos_o > 1.0 ? 1.0 : cos_o);
	int it = (int)(theta * (2.0 / M_PI) * g->n_theta);
	if (it >= g->n_theta)
		it = g->n_theta - 1;
	double sp = sqrt(ux * ux + uy * uy);
	double cp = sp > 0.0 ? -ux / sp : 1.0;
	double phi = acos(cp > 1.0 ? 1.0 : (cp < -1.0 ? -1.0 : cp));
	int ip = (int)(phi * (1.0 / M_PI) * g->n_phi);
	if (ip >= g->n_phi)
		ip = g->n_phi - 1;
	t->exit[it * g->n_phi + ip] += w;
}

void transport_run(const struct slab *s, const struct launch *ln, const struct transport_opts *o,
    const struct tally_grid *grid, struct nee *nee, uint64_t seed, uint32_t stream, uint64_t first,
    uint64_t count, struct tally *t)
{
	const int ft = s->first_turbid;
	const int nl = s->n_layers;
	const struct layer *L = s->layer;
	const double w_th = o->roulette_w, chance = o->roulette_chance, inv_chance = 1.0 / o->roulette_chance;

	struct hg_const hg[SLAB_MAX_LAYERS + 2];
	for (int i = 0; i <= nl + 1; i++)
		hg_const_init(&hg[i], L[i].g);

	if (ln->layer > nl) {
		/* All clear: what is not reflected goes straight through. */
		t->tt += ln->w0 * (double)count;
		t->tt_unscat += ln->w0 * (double)count;
		return;
	}
	for (uint64_t p = first; p < first + count; p++) {
		struct rng r;
		rng_seed(&r, seed, stream, p);
		double x = 0.0, y = 0.0, z = ln->z;
		double ux = ln->ux, uy = 0.0, uz = ln->uz;
		double w = ln->w0;
		double tau = 0.0;	/* optical depth left of the current step */
		int l = ln->layer, scattered = 0;
		int direct = 0;	/* flying straight on since the last scattering (what nee scores) */
		if (nee)
			nee_prepare(nee, s, o->fresnel, rng_uniform(&r));
		long steps = 0;

		for (;;) {
			/* Hop: draw a step as optical depth, or finish the one carried
			 * across a boundary. */
			if (tau == 0.0)
				tau = -log(rng_uniform(&r));
			double mu_t = s->mu_t[l];
			/* Distance to the boundary ahead along z; comparing optical
			 * depths as tau |uz| < mu_t dz avoids a division per step. */
			double auz = fabs(uz);
			double dz = uz > 0.0 ? s->z_bot[l] - z : z - s->z_top[l];

			if (mu_t > 0.0 && tau * auz < mu_t * dz) {
				double step = tau * s->inv_mu_t[l];
				x += step * ux;
				y += step * uy;
				z += step * uz;
				tau = 0.0;
				/* Drop: implicit absorption. */
				double wa = w * (1.0 - s->albedo[l]);
				t->a[l] += wa;
				w -= wa;
				if (w <= 0.0)
					break;
				if (nee) {
					nee_score(nee, s, l, z, ux, uy, uz, w, rng_uniform(&r), rng_uniform(&r), t->exit);
					direct = 1;
				}
				/* Spin. */
				double ct = hg_sample_cos_c(&hg[l], rng_uniform(&r));
				double cp, sp;
				azimuth_sample(rng_uniform(&r), &cp, &sp);
				spin_dir(&ux, &uy, &uz, ct, cp, sp);
				scattered = 1;
				t->events += 1.0;
				/* Roulette; its weight change is booked against A (see top). */
				if (w < w_th) {
					if (rng_uniform(&r) < chance) {
						t->a[l] -= w * (inv_chance - 1.0);
						w *= inv_chance;
					} else {
						t->a[l] += w;
						break;
					}
				}
				if (++steps >= o->max_steps) {
					t->lost += w;
					break;
				}
				continue;
			}
			if (auz == 0.0 || isinf(dz)) {
				/* Travelling parallel to the layers in a clear layer: it
				 * would never arrive anywhere. */
				t->lost += w;
				break;
			}
			double db = dz / auz;
			/* Move to the boundary and keep the unused optical depth. */
			x += db * ux;
			y += db * uy;
			tau -= mu_t * db;
			if (tau < 0.0)
				tau = 0.0;
			int up = uz < 0.0;
			int nb = up ? l - 1 : l + 1;
			z = up ? s->z_top[l] : s->z_bot[l];
			double ci = up ? -uz : uz;
			double crit = up ? s->cos_crit_up[l] : s->cos_crit_down[l];
			int reflect;
			double ct = ci;
			if (ci <= crit)
				reflect = 1;	/* total internal reflection */
			else {
				double rf = optics_fresnel(o->fresnel, L[l].n, L[nb].n, ci, &ct);
				reflect = rf > 0.0 && rng_uniform(&r) < rf;
			}
			if (reflect) {
				uz = -uz;
				if (l >= ft)
					direct = 0;	/* back into the turbid layers: nee did not count this path */
				if (++steps >= o->max_steps) {
					t->lost += w;
					break;
				}
				continue;
			}
			double eta = L[l].n / L[nb].n;
			ux *= eta;
			uy *= eta;
			uz = up ? -ct : ct;
			if (nb == 0) {
				score_top(grid, t, w, scattered, !(nee && direct), ux, uy, ct, x, y);
				break;
			}
			if (nb == nl + 1) {
				t->tt += w;
				if (!scattered)
					t->tt_unscat += w;
				break;
			}
			l = nb;
		}
	}
}
