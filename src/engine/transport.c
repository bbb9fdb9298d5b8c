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
#include <string.h>

#include "engine/microfacet.h"
#include "engine/phase.h"
#include "base/check.h"
#include "base/rng.h"

void transport_opts_default(struct transport_opts *o)
{
	o->fresnel = OPTICS_FRESNEL_EXACT;
	o->roulette_w = 0.2;
	o->roulette_chance = 0.3;
	o->max_steps = 1000000;
	o->far_cm = 0.0;
}

void transport_launch(const struct slab *s, double theta_in, enum optics_fresnel model, struct launch *ln)
{
	const struct layer *L = s->layer;
	if (s->rough_top) {
		/* The walk crosses the rough top itself, from just above it. */
		*ln = (struct launch){ .rsp = 0.0, .w0 = 1.0, .layer = 0, .z = 0.0, .ux = sin(theta_in),
			.uz = cos(theta_in) };
		return;
	}
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

/* White Monte Carlo (tally.h): the escape at radial bin ir (-1: beyond
 * the bins) for every absorption variant, its weight times
 * exp(-sum dmua L) over the path lengths path[] [cm] per layer. */
static void score_variants(const struct tally_grid *g, struct tally *t, double w,
    const double *path, long ir)
{
	enum { NS = SLAB_MAX_LAYERS + 2 };
	for (int v = 0; v < g->var->n; v++) {
		const double *d = g->var->dmua + (size_t)v * NS;
		double tau = 0.0;
		for (int l = 0; l < NS; l++)
			tau += d[l] * path[l];
		double wv = w * exp(-tau);
		t->var_total[v] += wv;
		if (ir >= 0)
			t->radial_var[(size_t)v * (size_t)g->n_r + (size_t)ir] += wv;
	}
}

/* Score a photon leaving the top with weight w, ambient direction cosines
 * (ux, uy, uz > 0 pointing up out of the skin) at lateral position (x, y). */
static inline void score_top(const struct tally_grid *g, struct tally *t, double w, int scattered, int bin,
    double ux, double uy, double cos_o, double x, double y, const double *path)
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
		if (t->radial_var)
			score_variants(g, t, w, path, ir < g->n_r ? ir : -1);
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

/* One photon between events.  Every step below is inlined into the walk, so
 * the state stays in registers as it did in one function. */
struct photon {
	double x, y, z;	/* position [cm] */
	double ux, uy, uz;	/* direction cosines [1] */
	double w;	/* weight [1] */
	double tau;	/* optical depth left of the current step [1] */
	int l;	/* current layer */
	int scattered;	/* scattered at least once */
	int direct;	/* flying straight on since the last scattering (what nee scores) */
	int entered;	/* has reached the first turbid layer (else a return is specular) */
	long steps;	/* interactions so far */
	int far;	/* far roulettes played (transport.h) */
	double ws;	/* 2^far: the weight roulette's threshold scale */
	double path[SLAB_MAX_LAYERS + 2];	/* path length per layer so far [cm] (wmc.h) */
};

/* Launch: the refracted direction and weight of struct launch, at the top
 * of the first turbid layer. */
static inline void launch(struct photon *ph, const struct launch *ln)
{
	ph->x = 0.0;
	ph->y = 0.0;
	ph->z = ln->z;
	ph->ux = ln->ux;
	ph->uy = 0.0;
	ph->uz = ln->uz;
	ph->w = ln->w0;
	ph->tau = 0.0;
	ph->l = ln->layer;
	ph->scattered = 0;
	ph->direct = 0;
	ph->entered = ln->layer > 0;
	ph->steps = 0;
	ph->far = 0;
	ph->ws = 1.0;
	memset(ph->path, 0, sizeof ph->path);
}

/* Hop: draw a step as optical depth, or finish the one carried across a
 * boundary, and move to the interaction site if it lies in this layer (1).
 * Otherwise (0) the photon stays, with *mu_t and *dz (the distance to the
 * boundary ahead along z) for cross(). */
static inline int hop(struct photon *ph, const struct slab *s, struct rng *r, double *mu_t, double *dz)
{
	if (ph->tau == 0.0)
		ph->tau = -log(rng_uniform(r));
	*mu_t = s->mu_t[ph->l];
	*dz = ph->uz > 0.0 ? s->z_bot[ph->l] - ph->z : ph->z - s->z_top[ph->l];
	/* Comparing optical depths as tau |uz| < mu_t dz avoids a division per
	 * step. */
	if (*mu_t > 0.0 && ph->tau * fabs(ph->uz) < *mu_t * *dz) {
		double step = ph->tau * s->inv_mu_t[ph->l];
		ph->path[ph->l] += step;
		ph->x += step * ph->ux;
		ph->y += step * ph->uy;
		ph->z += step * ph->uz;
		ph->tau = 0.0;
		return 1;
	}
	return 0;
}

/* The step guard: 1 (weight booked as lost) after max_steps interactions. */
static inline int guard(struct photon *ph, const struct transport_opts *o, struct tally *t)
{
	if (++ph->steps >= o->max_steps) {
		t->lost += ph->w;
		return 1;
	}
	return 0;
}

static double uniform_of(void *r)
{
	return rng_uniform(r);
}

/* Rough crossing from layer l into nb (microfacet.h): a facet normal from
 * the visible normals, reflection or refraction on it, the weight times
 * G1 of the new direction (what it shadows is booked as facet_loss); or,
 * with s->rough_ms, the walk over the facets until the light leaves.  The
 * frame has the incident side up: wi = -u with z toward the side the
 * photon comes from.  Sets the new direction; returns 1 when reflected. */
static int rough_cross(struct photon *ph, const struct slab *s, const struct transport_opts *o, int l, int nb,
    double alpha, struct rng *r, struct tally *t)
{
	const struct microfacet mf = { MICROFACET_GGX, alpha, o->fresnel };
	double wi[3] = { -ph->ux, -ph->uy, fabs(ph->uz) }, wo[3];
	double g;
	if (s->rough_ms)
		g = microfacet_sample_ms(&mf, s->layer[l].n, s->layer[nb].n, wi, uniform_of, r, wo, NULL);
	else {
		double u1 = rng_uniform(r), u2 = rng_uniform(r), u3 = rng_uniform(r);
		g = microfacet_sample(&mf, s->layer[l].n, s->layer[nb].n, wi, u1, u2, u3, wo);
	}
	double side = ph->uz > 0.0 ? 1.0 : -1.0;
	t->facet_loss += ph->w * (1.0 - g);
	ph->w *= g;
	ph->ux = wo[0];
	ph->uy = wo[1];
	ph->uz = -side * wo[2];
	return wo[2] > 0.0;
}

/* Boundary: move to the boundary ahead keeping the unused optical depth,
 * then reflect (total internal reflection or Fresnel) or refract (Snell in
 * cosines) into the next layer; leaving the top is scored, leaving the
 * bottom is transmission.  1 when the walk ends. */
static inline int boundary(struct photon *ph, const struct slab *s, const struct transport_opts *o,
    const struct tally_grid *grid, const struct nee *nee, double mu_t, double dz, struct rng *r,
    struct tally *t)
{
	double auz = fabs(ph->uz);
	if (auz == 0.0 || isinf(dz)) {
		/* Travelling parallel to the layers in a clear layer: it would
		 * never arrive anywhere. */
		t->lost += ph->w;
		return 1;
	}
	double db = dz / auz;
	ph->path[ph->l] += db;
	ph->x += db * ph->ux;
	ph->y += db * ph->uy;
	ph->tau -= mu_t * db;
	if (ph->tau < 0.0)
		ph->tau = 0.0;
	ph->z = ph->uz < 0.0 ? s->z_top[ph->l] : s->z_bot[ph->l];

	const struct layer *L = s->layer;
	int l = ph->l, up = ph->uz < 0.0;
	int nb = up ? l - 1 : l + 1;
	double ci = up ? -ph->uz : ph->uz;
	double crit = up ? s->cos_crit_up[l] : s->cos_crit_down[l];
	int reflect;
	double ct = ci, alpha = up ? L[l].rough : L[nb].rough;
	if (alpha > 0.0) {
		reflect = rough_cross(ph, s, o, l, nb, alpha, r, t);
		if (ph->w == 0.0)
			return 1;	/* shadowed: all of it is in facet_loss */
		ct = fabs(ph->uz);
		if (reflect && l == 0) {
			t->rsp += ph->w;	/* off the rough top from above */
			return 1;
		}
	} else if (ci <= crit)
		reflect = 1;	/* total internal reflection */
	else {
		double rf = optics_fresnel(o->fresnel, L[l].n, L[nb].n, ci, &ct);
		reflect = rf > 0.0 && rng_uniform(r) < rf;
	}
	if (reflect) {
		if (alpha == 0.0)
			ph->uz = -ph->uz;
		if (l >= s->first_turbid)
			ph->direct = 0;	/* back into the turbid layers: nee did not count this path */
		return guard(ph, o, t);
	}
	if (alpha == 0.0) {
		double eta = L[l].n / L[nb].n;
		ph->ux *= eta;
		ph->uy *= eta;
		ph->uz = up ? -ct : ct;
	}
	if (nb == 0) {
		if (!ph->entered)
			t->rsp += ph->w;	/* back out of clear layers on top: specular */
		else
			score_top(grid, t, ph->w, ph->scattered, !(nee && ph->direct), ph->ux, ph->uy, ct,
			    ph->x, ph->y, ph->path);
		return 1;
	}
	if (nb == s->n_layers + 1) {
		t->tt += ph->w;
		if (!ph->scattered)
			t->tt_unscat += ph->w;
		return 1;
	}
	ph->l = nb;
	if (nb >= s->first_turbid)
		ph->entered = 1;
	return 0;
}

/* Drop: implicit absorption of the fraction 1 - albedo.  1 when nothing is
 * left. */
static inline int drop(struct photon *ph, const struct slab *s, struct tally *t)
{
	double wa = ph->w * (1.0 - s->albedo[ph->l]);
	t->a[ph->l] += wa;
	ph->w -= wa;
	return ph->w <= 0.0;
}

/* Spin: a new direction from Henyey-Greenstein and a uniform azimuth. */
static inline void spin(struct photon *ph, const struct hg_const *hg, struct rng *r, struct tally *t)
{
	double ct = hg_sample_cos_c(hg, rng_uniform(r));
	double cp, sp;
	azimuth_sample(rng_uniform(r), &cp, &sp);
	spin_dir(&ph->ux, &ph->uy, &ph->uz, ct, cp, sp);
	ph->scattered = 1;
	t->events += 1.0;
}

/* Roulette below w_th: survive with probability chance at weight w /
 * chance, else die; the weight change is booked against A (see top).  1
 * when the photon dies. */
static inline int roulette(struct photon *ph, double w_th, double chance, double inv_chance, struct rng *r,
    struct tally *t)
{
	if (ph->w < w_th) {
		if (rng_uniform(r) < chance) {
			t->a[ph->l] -= ph->w * (inv_chance - 1.0);
			ph->w *= inv_chance;
		} else {
			t->a[ph->l] += ph->w;
			return 1;
		}
	}
	return 0;
}

enum { FAR_MAX = 64 };	/* far roulettes per photon at most */

/* Far roulette (transport.h) at an interaction, z0 the entry depth and
 * far2[k] the squared k-th distance: 1 when the photon dies. */
static inline int far_roulette(struct photon *ph, double z0, const double *far2, struct rng *r,
    struct tally *t)
{
	double dz = ph->z - z0, d2 = ph->x * ph->x + ph->y * ph->y + dz * dz;
	if (ph->far >= FAR_MAX || d2 <= far2[ph->far])
		return 0;
	ph->far++;
	if (rng_uniform(r) < 0.5) {
		t->a[ph->l] -= ph->w;
		ph->w *= 2.0;
		ph->ws *= 2.0;
		return 0;
	}
	t->a[ph->l] += ph->w;
	return 1;
}

#ifdef SKINBAKE_DEBUG
/* Debug builds: all the weight the tally has booked, and whether a
 * direction is a unit vector. */
static double booked(const struct slab *s, const struct tally *t)
{
	double sum = t->rd + t->tt + t->lost;
	for (int i = 0; i <= s->n_layers + 1; i++)
		sum += t->a[i];
	return sum;
}

static int unit(const struct photon *ph)
{
	return fabs(ph->ux * ph->ux + ph->uy * ph->uy + ph->uz * ph->uz - 1.0) < 1e-9;
}
#endif

void transport_run(const struct slab *s, const struct launch *ln, const struct transport_opts *o,
    const struct tally_grid *grid, struct nee *nee, uint64_t seed, uint32_t stream, uint64_t first,
    uint64_t count, struct tally *t)
{
	/* Copies, so that stores to the tally need not reload them. */
	const double w_th = o->roulette_w, chance = o->roulette_chance, inv_chance = 1.0 / o->roulette_chance;
	struct hg_const hg[SLAB_MAX_LAYERS + 2];
	for (int i = 0; i <= s->n_layers + 1; i++)
		hg_const_init(&hg[i], s->layer[i].g);

	if (ln->layer > s->n_layers) {
		/* All clear: what is not reflected goes straight through. */
		t->tt += ln->w0 * (double)count;
		t->tt_unscat += ln->w0 * (double)count;
		return;
	}
	/* Weights stay in [0, 1], or up to w_th / chance after roulette. */
	const double w_max = fmax(1.0, w_th * inv_chance);
	(void)w_max;
	const int far = nee == NULL && o->far_cm > 0.0;
	double far2[FAR_MAX];
	for (int k = 0; k < FAR_MAX; k++) {
		double d = o->far_cm * (1.0 + (double)k / TRANSPORT_FAR_LEVELS);
		far2[k] = d * d;
	}
	for (uint64_t p = first; p < first + count; p++) {
		struct rng r;
		rng_seed(&r, seed, stream, p);
		struct photon ph;
		launch(&ph, ln);
#ifdef SKINBAKE_DEBUG
		const double booked0 = booked(s, t);
#endif
		if (nee)
			nee_prepare(nee, s, o->fresnel, rng_uniform(&r));
		for (;;) {
			double mu_t, dz;
			if (!hop(&ph, s, &r, &mu_t, &dz)) {
				if (boundary(&ph, s, o, grid, nee, mu_t, dz, &r, t))
					break;
				DCHECK(unit(&ph));
				continue;
			}
			if (drop(&ph, s, t))
				break;
			if (nee) {
				nee_score(nee, s, ph.l, ph.z, ph.ux, ph.uy, ph.uz, ph.w, rng_uniform(&r),
				    rng_uniform(&r), t->exit);
				ph.direct = 1;
			}
			spin(&ph, &hg[ph.l], &r, t);
			DCHECK(unit(&ph));
			if (roulette(&ph, w_th * ph.ws, chance, inv_chance, &r, t))
				break;
			if (guard(&ph, o, t))
				break;
			if (far && far_roulette(&ph, ln->z, far2, &r, t))
				break;
			DCHECK(ph.w >= 0.0 && ph.w <= w_max * ph.ws);
		}
		/* Every photon's launch weight ends in a tally (energy booked). */
		DCHECK(fabs(booked(s, t) - booked0 - ln->w0) <= 1e-9 * (1.0 + fabs(booked0)));
	}
}
