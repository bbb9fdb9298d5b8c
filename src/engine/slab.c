/* slab: build, check and prepare a layer stack (see slab.h). */
#include "config.h"
#include "engine/slab.h"

#include <math.h>
#include <string.h>

#include "engine/optics.h"
#include "base/util.h"

void slab_init(struct slab *s, double n_above, double n_below)
{
	memset(s, 0, sizeof *s);
	s->n_above = n_above;
	s->n_below = n_below;
}

int slab_add(struct slab *s, const struct layer *l, char **cause)
{
	if (s->n_layers >= SLAB_MAX_LAYERS) {
		*cause = xasprintf("too many layers: at most %d are allowed", SLAB_MAX_LAYERS);
		return -1;
	}
	s->layer[++s->n_layers] = *l;
	return 0;
}

int slab_layer_clear(const struct slab *s, int i)
{
	return s->layer[i].mu_a == 0.0 && s->layer[i].mu_s == 0.0;
}

int slab_check(const struct slab *s, char **cause)
{
	if (s->n_layers < 1 || s->n_layers > SLAB_MAX_LAYERS) {
		*cause = xasprintf("number of layers = %d is out of range [1, %d]", s->n_layers, SLAB_MAX_LAYERS);
		return -1;
	}
	if (!(s->n_above >= 1.0 && s->n_above <= 10.0)) {
		*cause = xasprintf("n-above = %g is out of range [1, 10]", s->n_above);
		return -1;
	}
	if (!(s->n_below >= 1.0 && s->n_below <= 10.0)) {
		*cause = xasprintf("n-below = %g is out of range [1, 10]", s->n_below);
		return -1;
	}
	for (int i = 1; i <= s->n_layers; i++) {
		const struct layer *l = &s->layer[i];
		int last = i == s->n_layers;
		if (isnan(l->d) || l->d <= 0.0 || (isinf(l->d) && !last)) {
			*cause = xasprintf("layer %d: d = %g is out of range (0, inf) cm%s", i, l->d,
			    last ? " (inf allowed)" : "; inf is allowed only for the last layer");
			return -1;
		}
		if (!(l->n >= 1.0 && l->n <= 10.0)) {
			*cause = xasprintf("layer %d: n = %g is out of range [1, 10]", i, l->n);
			return -1;
		}
		if (!(l->mu_a >= 0.0 && l->mu_a <= 1e8)) {
			*cause = xasprintf("layer %d: mua = %g is out of range [0, 1e8] 1/cm", i, l->mu_a);
			return -1;
		}
		if (!(l->mu_s >= 0.0 && l->mu_s <= 1e8)) {
			*cause = xasprintf("layer %d: mus = %g is out of range [0, 1e8] 1/cm", i, l->mu_s);
			return -1;
		}
		if (!(l->g > -1.0 && l->g < 1.0)) {
			*cause = xasprintf("layer %d: g = %g is out of range (-1, 1)", i, l->g);
			return -1;
		}
		if (!(l->rough >= 0.0 && l->rough <= 1.0)) {
			*cause = xasprintf("layer %d: rough = %g is out of range [0, 1] (GGX alpha of its top boundary)", i,
			    l->rough);
			return -1;
		}
		if (isinf(l->d) && l->mu_a == 0.0 && l->mu_s == 0.0) {
			*cause = xasprintf("layer %d: a semi-infinite layer must absorb or scatter (mua = mus = 0)", i);
			return -1;
		}
	}
	return 0;
}

void slab_prepare(struct slab *s)
{
	int n = s->n_layers;
	struct layer *L = s->layer;
	L[0] = (struct layer){ .d = INFINITY, .n = s->n_above };
	L[n + 1] = (struct layer){ .d = INFINITY, .n = s->n_below };
	double z = 0.0;
	s->z_top[0] = -INFINITY;
	s->z_bot[0] = 0.0;
	s->first_turbid = n + 1;
	for (int i = 1; i <= n; i++) {
		s->z_top[i] = z;
		z += L[i].d;
		s->z_bot[i] = z;
		if (s->first_turbid == n + 1 && !slab_layer_clear(s, i))
			s->first_turbid = i;
	}
	s->z_top[n + 1] = z;
	s->rough_top = 0;
	s->rough_any = 0;
	for (int i = 1; i <= n; i++) {
		if (L[i].rough > 0.0)
			s->rough_any = 1;
		if (L[i].rough > 0.0 && i <= s->first_turbid)
			s->rough_top = 1;
	}
	s->z_bot[n + 1] = INFINITY;
	for (int i = 0; i <= n + 1; i++) {
		s->mu_t[i] = L[i].mu_a + L[i].mu_s;
		s->albedo[i] = s->mu_t[i] > 0.0 ? L[i].mu_s / s->mu_t[i] : 0.0;
		s->inv_mu_t[i] = s->mu_t[i] > 0.0 ? 1.0 / s->mu_t[i] : 0.0;
		s->cos_crit_up[i] = i > 0 ? optics_cos_critical(L[i].n, L[i - 1].n) : 0.0;
		s->cos_crit_down[i] = i <= n ? optics_cos_critical(L[i].n, L[i + 1].n) : 0.0;
	}
}
