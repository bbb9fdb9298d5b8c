/* relief_waves: the smooth fields of a relief drawn from plane waves with
 * whole cycles per tile (so they are periodic with it): the regional depth
 * factor of the furrows and the corneocyte-scale plateau texture
 * (relief_render.c draws the latter). */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "geom/relief_impl.h"
#include "base/rng.h"
#include "base/util.h"

/* The smooth depth factor exp(region_sd F(x, y)) at (x, y) [tiles]: F is
 * a sum of RELIEF_REGION_WAVES unit-variance plane waves of 1-3 cycles per
 * tile, so whole regions of the tile have deeper or shallower lines. */
double relief_region_at(const struct relief *r, double x, double y)
{
	double f = 0;
	for (int q = 0; q < RELIEF_REGION_WAVES; q++) {
		const struct wave *w = &r->region[q];
		f += w->amp * cos(2 * M_PI * (w->kx * x + w->ky * y) + w->phase);
	}
	return exp(r->p.region_sd * f);
}

void relief_region_place(struct relief *r, uint64_t seed, uint32_t stream)
{
	struct rng rg;
	rng_seed(&rg, seed, stream, 0);
	for (int q = 0; q < RELIEF_REGION_WAVES; q++) {
		struct wave *w = &r->region[q];
		do {
			w->kx = (int)(7 * rng_uniform(&rg)) - 3;
			w->ky = (int)(7 * rng_uniform(&rg)) - 3;
		} while (w->kx == 0 && w->ky == 0);
		w->amp = sqrt(2.0 / RELIEF_REGION_WAVES);
		w->phase = 2 * M_PI * rng_uniform(&rg);
	}
}

/* The plateau texture: RELIEF_WAVES plane waves of random direction and a
 * wavelength log-normal about plateau_scale (sigma 0.2), rounded to whole
 * cycles per tile, random phases; RMS plateau_roughness. */
void relief_waves_place(struct relief *r, uint64_t seed, uint32_t stream)
{
	const struct relief_params *p = &r->p;
	if (p->plateau_roughness <= 0)
		return;
	struct rng rg;
	rng_seed(&rg, seed, stream, 0);
	r->n_waves = RELIEF_WAVES;
	r->waves = xmalloc(sizeof *r->waves * RELIEF_WAVES);
	double k0 = p->tile / p->plateau_scale;
	for (int q = 0; q < RELIEF_WAVES; q++) {
		double ang = 2 * M_PI * rng_uniform(&rg), kk = k0 * exp(0.2 * relief_normal(&rg));
		struct wave *wv = &r->waves[q];
		wv->kx = (int)lround(kk * cos(ang));
		wv->ky = (int)lround(kk * sin(ang));
		if (wv->kx == 0 && wv->ky == 0)
			wv->kx = 1;
		wv->amp = p->plateau_roughness * sqrt(2.0 / RELIEF_WAVES);
		wv->phase = 2 * M_PI * rng_uniform(&rg);
	}
}

/* The meander: for bend > 0 and furrows, RELIEF_WARP_WAVES plane waves per
 * displacement component, random directions, wavelengths log-normal (sigma
 * 0.3) about half the primary cell rounded to whole cycles per tile, random
 * phases, RMS bend x furrow width per component. */
void relief_warp_place(struct relief *r, uint64_t seed, uint32_t stream)
{
	const struct relief_params *p = &r->p;
	r->n_warp = 0;
	if (p->levels == 0 || p->bend <= 0)
		return;
	struct rng rg;
	rng_seed(&rg, seed, stream, 0);
	double k0 = p->tile / (0.5 * p->furrow_cell);
	for (int c = 0; c < 2; c++)
		for (int q = 0; q < RELIEF_WARP_WAVES; q++) {
			double ang = 2 * M_PI * rng_uniform(&rg);
			double kk = k0 * exp(0.3 * relief_normal(&rg));
			struct wave *wv = &r->warp[c][q];
			wv->kx = (int)lround(kk * cos(ang));
			wv->ky = (int)lround(kk * sin(ang));
			if (wv->kx == 0 && wv->ky == 0)
				wv->kx = 1;
			wv->amp = p->bend * p->furrow_width * sqrt(2.0 / RELIEF_WARP_WAVES);
			wv->phase = 2 * M_PI * rng_uniform(&rg);
		}
	r->n_warp = RELIEF_WARP_WAVES;
}
