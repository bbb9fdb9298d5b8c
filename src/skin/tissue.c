/* tissue: skin parameters -> layer stack per wavelength.
 * Mixing rules (Jacques 1998/2013, Donner & Jensen 2006; skin-optics.md A2):
 *   epidermis mu_a = f_mel [b mu_eu + (1-b) mu_pheo] + (1 - f_mel) mu_base
 *   dermis    mu_a = B [S mu_oxy + (1-S) mu_deoxy] + (1 - B) mu_base
 *   subcutis  mu_a = B [S mu_oxy + (1-S) mu_deoxy] + (1 - B) mu_fat
 *   mu_s = mu_s' / (1 - g), mu_s' = a [f (wl/500)^-4 + (1-f) (wl/500)^-b]
 *   (Mie + Rayleigh form of Jacques 2013; f = 0 is a plain power law). */
#include "config.h"
#include "skin/tissue.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "skin/spectra.h"
#include "base/util.h"

static const char *layer_names[SKIN_N_LAYERS] = { "sebum", "epidermis", "dermis", "subcutis" };

const char *tissue_layer_name(enum skin_layer_id id)
{
	return id >= 0 && id < SKIN_N_LAYERS ? layer_names[id] : "?";
}

int tissue_layer_present(const struct skin_params *p, enum skin_layer_id id)
{
	if (id == SKIN_EPIDERMIS || id == SKIN_DERMIS)
		return 1;
	return p->layer[id].d > 0.0;
}

static const struct skin_override *find_override(const struct skin_params *p, double wl)
{
	for (int i = 0; i < p->n_override; i++)
		if (fabs(p->override[i].wl - wl) < 1e-6)
			return &p->override[i];
	return NULL;
}

/* "470, 550 and 656 nm" (caller frees). */
static char *override_list(const struct skin_params *p)
{
	char *s = xstrdup("");
	for (int i = 0; i < p->n_override; i++) {
		const char *sep = i == 0 ? "" : i == p->n_override - 1 ? " and " : ", ";
		char *t = xasprintf("%s%s%g", s, sep, p->override[i].wl);
		free(s);
		s = t;
	}
	return s;
}

int tissue_check(const struct skin_params *p, char **cause)
{
	const struct skin_layer_params *de = &p->layer[SKIN_DERMIS], *sc = &p->layer[SKIN_SUBCUTIS];
	if (isinf(de->d) && sc->d > 0.0) {
		*cause = xasprintf("dermis.thickness = inf but a subcutis (thickness = %g) lies below it; "
		    "only the deepest layer may be semi-infinite", sc->d);
		return -1;
	}
	if (p->n_wl < 1) {
		*cause = xasprintf("no wavelengths: set [skin] wavelengths");
		return -1;
	}
	/* A layer's top roughness needs a boundary under another layer. */
	if (p->layer[SKIN_EPIDERMIS].rough_top > 0.0 && !tissue_layer_present(p, SKIN_SEBUM)) {
		*cause = xasprintf("epidermis.top_roughness = %g but there is no sebum film above the epidermis "
		    "(sebum.thickness = 0): its top is the surface, set [surface] roughness", p->layer[SKIN_EPIDERMIS].rough_top);
		return -1;
	}
	if (p->facet_ms != 0.0 && p->facet_ms != 1.0) {
		*cause = xasprintf("surface.multiple_scattering = %g: must be 0 or 1", p->facet_ms);
		return -1;
	}
	if (p->layer[SKIN_SUBCUTIS].rough_top > 0.0 && !tissue_layer_present(p, SKIN_SUBCUTIS)) {
		*cause = xasprintf("subcutis.top_roughness = %g but the preset has no subcutis (subcutis.thickness = 0)",
		    p->layer[SKIN_SUBCUTIS].rough_top);
		return -1;
	}
	for (int i = 0; i < p->n_override; i++) {
		const struct skin_override *o = &p->override[i];
		for (int l = 0; l < SKIN_N_LAYERS; l++) {
			int set = !isnan(o->mu_a[l]) || !isnan(o->mu_s[l]) || !isnan(o->g[l]) || !isnan(o->n[l]);
			if (set && !tissue_layer_present(p, l)) {
				*cause = xasprintf("[override.%g] sets %s values but the preset has no %s "
				    "(%s.thickness = 0)", o->wl, layer_names[l], layer_names[l], layer_names[l]);
				return -1;
			}
		}
		if (p->model != SKIN_MODEL_TABLES)
			continue;
		/* A tables preset has no chromophores to fall back on; g and n
		 * always have a value (layer constant or published fit). */
		for (int l = SKIN_EPIDERMIS; l < SKIN_N_LAYERS; l++) {
			if (!tissue_layer_present(p, l))
				continue;
			const char *miss = isnan(o->mu_a[l]) ? "mua" : isnan(o->mu_s[l]) ? "mus" : NULL;
			if (miss) {
				*cause = xasprintf("[override.%g] lacks %s.%s, which model = tables requires for "
				    "every layer at every tabulated wavelength", o->wl, layer_names[l], miss);
				return -1;
			}
		}
	}
	if (p->model == SKIN_MODEL_TABLES) {
		for (int i = 0; i < p->n_wl; i++) {
			if (find_override(p, p->wl[i]) == NULL) {
				char *list = override_list(p);
				*cause = xasprintf("[skin] wavelengths includes %g nm, which model = tables does not "
				    "tabulate (tabulated: %s nm; add an [override.%g] section)", p->wl[i],
				    p->n_override ? list : "none", p->wl[i]);
				free(list);
				return -1;
			}
		}
	}
	return 0;
}

int tissue_layer_optics(const struct skin_params *p, enum skin_layer_id id, double wl, struct layer *out,
    char **cause)
{
	if (!(wl >= SPECTRA_WL_MIN && wl <= SPECTRA_WL_MAX)) {
		*cause = xasprintf("wavelength = %g nm is out of range [%g, %g] nm", wl, SPECTRA_WL_MIN,
		    SPECTRA_WL_MAX);
		return -1;
	}
	const struct skin_override *o = find_override(p, wl);
	if (p->model == SKIN_MODEL_TABLES && o == NULL) {
		char *list = override_list(p);
		*cause = xasprintf("preset '%s' tabulates only %s nm and has no chromophore model for "
		    "wavelength = %g nm", p->name, p->n_override ? list : "no wavelengths", wl);
		free(list);
		return -1;
	}
	const struct skin_layer_params *l = &p->layer[id];
	double g = isnan(l->g) ? spectra_g_vangemert(wl) : l->g;
	double n = l->n, mu_a = 0.0, mu_s;
	if (isnan(n))
		n = id == SKIN_EPIDERMIS ? spectra_n_epidermis(wl) : spectra_n_dermis(wl);
	switch (id) {
	case SKIN_SEBUM:
		mu_a = l->mu_a;
		break;
	case SKIN_EPIDERMIS: {
		double mel = l->eumelanin * spectra_mua_eumelanin(wl)
		    + (1.0 - l->eumelanin) * spectra_mua_pheomelanin(wl);
		mu_a = l->melanin * mel + (1.0 - l->melanin) * spectra_mua_baseline(wl);
		break;
	}
	case SKIN_DERMIS:
		mu_a = l->blood * spectra_mua_blood(wl, l->so2) + (1.0 - l->blood) * spectra_mua_baseline(wl);
		break;
	case SKIN_SUBCUTIS:
		mu_a = l->blood * spectra_mua_blood(wl, l->so2) + (1.0 - l->blood) * spectra_mua_fat(wl);
		break;
	default:
		*cause = xasprintf("no such layer %d", (int)id);
		return -1;
	}
	if (id == SKIN_SEBUM)
		mu_s = l->mu_s;
	else
		mu_s = (l->musp_rayleigh * spectra_musp_power(wl, l->musp_500, 4.0)
		    + (1.0 - l->musp_rayleigh) * spectra_musp_power(wl, l->musp_500, l->musp_power)) / (1.0 - g);
	if (o != NULL) {
		if (!isnan(o->mu_a[id]))
			mu_a = o->mu_a[id];
		if (!isnan(o->mu_s[id]))
			mu_s = o->mu_s[id];
		if (!isnan(o->g[id]))
			g = o->g[id];
		if (!isnan(o->n[id]))
			n = o->n[id];
	}
	*out = (struct layer){ .d = l->d, .n = n, .mu_a = mu_a, .mu_s = mu_s, .g = g };
	return 0;
}

int tissue_slab(const struct skin_params *p, double wl_nm, struct slab *out, char **cause)
{
	struct layer ls[SKIN_N_LAYERS];
	int nl = 0;
	for (int id = 0; id < SKIN_N_LAYERS; id++) {
		if (!tissue_layer_present(p, id))
			continue;
		if (tissue_layer_optics(p, id, wl_nm, &ls[nl], cause) != 0)
			return -1;
		ls[nl].rough = nl == 0 ? p->roughness_top : p->layer[id].rough_top;
		nl++;
	}
	slab_init(out, 1.0, ls[nl - 1].n);
	out->rough_ms = p->facet_ms == 1.0;
	for (int i = 0; i < nl; i++)
		if (slab_add(out, &ls[i], cause) != 0)
			return -1;
	if (slab_check(out, cause) != 0) {
		char *c = xasprintf("preset '%s' at %g nm: %s", p->name, wl_nm, *cause);
		free(*cause);
		*cause = c;
		return -1;
	}
	slab_prepare(out);
	return 0;
}
