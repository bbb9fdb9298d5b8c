/* tissue: skin parameters (a sebum film over epidermis, dermis and an
 * optional subcutis) and their conversion to a layer stack at one wavelength.
 * Absorption mixes chromophores by volume fraction, scattering follows power
 * laws, g and n follow published fits (../shared/notes/skin-optics.md A2;
 * functions in spectra.h), and per-wavelength overrides replace any computed
 * value, e.g. with a paper's tabulated coefficients.  Lengths in cm,
 * coefficients in 1/cm, wavelengths in nm. */
#ifndef SKINBAKE_TISSUE_H
#define SKINBAKE_TISSUE_H
#include "engine/slab.h"

enum skin_layer_id {
	SKIN_SEBUM,		/* clear (or weakly turbid) surface lipid film */
	SKIN_EPIDERMIS,
	SKIN_DERMIS,
	SKIN_SUBCUTIS,
	SKIN_N_LAYERS
};

enum skin_model {
	SKIN_MODEL_CHROMOPHORES,	/* optics from chromophores at any wavelength, overrides on top */
	SKIN_MODEL_TABLES		/* optics only from overrides, at their wavelengths only */
};

#define SKIN_MAX_WL 401		/* 380..780 nm in 1 nm steps */

/* One layer.  Not every field applies to every layer (see docs/presets.md):
 * melanin only to the epidermis, blood to dermis and subcutis, mu_a and mu_s
 * only to the sebum; the others are ignored. */
struct skin_layer_params {
	double d;		/* thickness [cm]; 0 = absent (sebum, subcutis); INFINITY = semi-infinite (deepest layer) */
	double n;		/* refractive index [-]; NAN = Ding 2006 Cauchy fit (epidermis, dermis) */
	double g;		/* HG anisotropy [-]; NAN = van Gemert 1989 g(wl) */
	double musp_500;	/* reduced scattering mu_s' at 500 nm [1/cm] */
	double musp_power;	/* Mie exponent: mu_s'(wl) = musp_500 [f (wl/500)^-4 + (1-f) (wl/500)^-musp_power] [-] */
	double musp_rayleigh;	/* f above: Rayleigh share of mu_s' at 500 nm [-] */
	double mu_a;		/* sebum: absorption [1/cm] */
	double mu_s;		/* sebum: scattering [1/cm] */
	double melanin;		/* epidermis: melanosome volume fraction [-] */
	double eumelanin;	/* epidermis: eumelanin share of melanin, rest pheomelanin [-] */
	double blood;		/* dermis, subcutis: blood volume fraction [-] */
	double so2;		/* dermis, subcutis: blood oxygen saturation [-] */
	double rough_top;	/* epidermis, dermis, subcutis: GGX alpha of the boundary to the
				 * layer above [-]; 0 = smooth (the surface's is roughness_top) */
};

/* Values that replace the computed ones at one wavelength; NAN = keep. */
struct skin_override {
	double wl;			/* wavelength [nm] */
	double mu_a[SKIN_N_LAYERS];	/* [1/cm] */
	double mu_s[SKIN_N_LAYERS];	/* [1/cm] */
	double g[SKIN_N_LAYERS];	/* [-] */
	double n[SKIN_N_LAYERS];	/* [-] */
};

struct skin_params {
	char *name;		/* preset name */
	char *description;	/* one line */
	char *origin;		/* "built-in" or the file it was read from */
	enum skin_model model;
	int n_wl;		/* default wavelengths, 1..SKIN_MAX_WL */
	double wl[SKIN_MAX_WL];	/* default wavelengths [nm], ascending */
	struct skin_layer_params layer[SKIN_N_LAYERS];
	double roughness_skin;	/* GGX alpha of the bare skin surface [-] */
	double roughness_sebum;	/* GGX alpha of the sebum-covered surface [-] */
	double roughness_top;	/* GGX alpha of the top boundary in the subsurface transport [-];
				 * 0 = smooth; > 0 is also the specular lobe's alpha */
	double facet_ms;	/* 1 = light scatters on the rough boundaries' facets until it leaves
				 * (Heitz 2016), 0 = once (Walter 2007, the rest booked as lost) */
	double macro_slope;	/* RMS slope of the mm-scale relief (Beckmann m) over the
				 * baked BRDF, applied where it is evaluated (engine/macro.h)
				 * [-]; 0 = none */
	int n_override;
	struct skin_override *override;	/* [n_override], ascending wl */
};

/* Layer names as used in preset files: "sebum", "epidermis", ... */
const char *tissue_layer_name(enum skin_layer_id id);
/* Whether the layer is part of the stack (epidermis and dermis always are). */
int tissue_layer_present(const struct skin_params *p, enum skin_layer_id id);

/* Cross-field checks (layer order, semi-infinite layers, overrides of absent
 * layers, completeness of a tables-model preset); -1 with *cause. */
int tissue_check(const struct skin_params *p, char **cause);

/* Optical constants of layer id at wl [nm] (chromophores, then overrides).
 * -1 with *cause if wl is out of [380, 780] or, for a tables-model preset,
 * not one of its tabulated wavelengths. */
int tissue_layer_optics(const struct skin_params *p, enum skin_layer_id id, double wl, struct layer *out,
    char **cause);

/* Fill (slab_init + slab_add) the layer stack at wavelength wl_nm in
 * [380, 780], top first: sebum (if present), epidermis, dermis, subcutis (if
 * present).  n_above = 1 (air), n_below = index of the deepest layer (index
 * matched, so a finite deepest layer acts as if more of it followed, minus its
 * transmission).  Overrides apply at their wavelength; a tables-model preset
 * (the paper's) accepts only its tabulated wavelengths and the error names
 * them.  The slab is checked and prepared (slab_check, slab_prepare; preparing
 * it again is harmless).  -1 with *cause. */
int tissue_slab(const struct skin_params *p, double wl_nm, struct slab *out, char **cause);
#endif
