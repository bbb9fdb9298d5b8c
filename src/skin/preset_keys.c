/* preset_keys: the table of preset keys and the setters that turn a key's
 * text into struct skin_params fields (see preset_keys.h). */
#include "config.h"
#include "skin/preset_keys.h"

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "skin/spectra.h"
#define NONE (-1)
#define LOFF(f) offsetof(struct skin_layer_params, f)
#define POFF(f) offsetof(struct skin_params, f)

const struct preset_key preset_key_table[] = {
	{ "skin", "base", K_BASE, NONE, 0, 0, 0, "", "",
	  "start from this built-in preset (must be the first key of the file)" },
	{ "skin", "name", K_TEXT, NONE, POFF(name), 1, 64, "", "",
	  "preset name, letters, digits, '.', '_', '-' (default: file name without .ini)" },
	{ "skin", "description", K_TEXT, NONE, POFF(description), 0, 160, "", "",
	  "one-line description" },
	{ "skin", "model", K_MODEL, NONE, POFF(model), 0, 0, "", "chromophores",
	  "chromophores: optics from the chromophore model at any wavelength, overrides on top; "
	  "tables: only the [override.WL] values, at those wavelengths only" },
	{ "skin", "wavelengths", K_WL, NONE, POFF(wl), 380, 780, "nm", "400:700:20",
	  "default wavelengths: a comma list of values and START:STOP:STEP ranges, ascending, "
	  "at most 401 (model = tables: default all override wavelengths)" },

	{ "sebum", "thickness", K_NUM, SKIN_SEBUM, LOFF(d), 0, 0.01, "cm", "0.0005",
	  "surface lipid film thickness; 0 = no sebum" },
	{ "sebum", "n", K_NUM, SKIN_SEBUM, LOFF(n), 1, 2, "", "1.5", "refractive index" },
	{ "sebum", "mua", K_NUM, SKIN_SEBUM, LOFF(mu_a), 0, 1000, "1/cm", "0", "absorption coefficient" },
	{ "sebum", "mus", K_NUM, SKIN_SEBUM, LOFF(mu_s), 0, 10000, "1/cm", "0", "scattering coefficient" },
	{ "sebum", "g", K_NUM, SKIN_SEBUM, LOFF(g), -0.99, 0.99, "", "0", "HG anisotropy" },

	{ "epidermis", "thickness", K_NUM, SKIN_EPIDERMIS, LOFF(d), 0.001, 0.05, "cm", "0.006", "thickness" },
	{ "epidermis", "n", K_IOR, SKIN_EPIDERMIS, LOFF(n), 1, 2, "", "ding2006",
	  "refractive index, or ding2006 = 1.4134 + 7907.96/wl^2" },
	{ "epidermis", "g", K_ANISO, SKIN_EPIDERMIS, LOFF(g), -0.99, 0.99, "", "vangemert1989",
	  "HG anisotropy, or vangemert1989 = 0.62 + 0.29e-3 wl" },
	{ "epidermis", "melanin", K_NUM, SKIN_EPIDERMIS, LOFF(melanin), 0, 0.5, "", "0.025",
	  "melanosome volume fraction" },
	{ "epidermis", "eumelanin", K_NUM, SKIN_EPIDERMIS, LOFF(eumelanin), 0, 1, "", "0.7",
	  "eumelanin share of the melanin (rest pheomelanin)" },
	{ "epidermis", "musp500", K_NUM, SKIN_EPIDERMIS, LOFF(musp_500), 0, 1000, "1/cm", "69.0",
	  "reduced scattering mu_s' at 500 nm" },
	{ "epidermis", "musp_power", K_NUM, SKIN_EPIDERMIS, LOFF(musp_power), 0, 4, "", "0.58",
	  "mu_s' exponent (Mie part when musp_rayleigh > 0)" },
	{ "epidermis", "musp_rayleigh", K_NUM, SKIN_EPIDERMIS, LOFF(musp_rayleigh), 0, 1, "", "0.37",
	  "Rayleigh share f of mu_s' at 500 nm (mu_s' = musp500 [f (wl/500)^-4 + (1-f) (wl/500)^-musp_power])" },

	{ "dermis", "thickness", K_LEN, SKIN_DERMIS, LOFF(d), 0.005, 2, "cm", "0.2",
	  "thickness, or inf (semi-infinite)" },
	{ "dermis", "n", K_IOR, SKIN_DERMIS, LOFF(n), 1, 2, "", "ding2006",
	  "refractive index, or ding2006 = 1.3696 + 3916.80/wl^2" },
	{ "dermis", "g", K_ANISO, SKIN_DERMIS, LOFF(g), -0.99, 0.99, "", "vangemert1989",
	  "HG anisotropy, or vangemert1989" },
	{ "dermis", "blood", K_NUM, SKIN_DERMIS, LOFF(blood), 0, 0.2, "", "0.02", "blood volume fraction" },
	{ "dermis", "so2", K_NUM, SKIN_DERMIS, LOFF(so2), 0, 1, "", "0.75", "blood oxygen saturation" },
	{ "dermis", "musp500", K_NUM, SKIN_DERMIS, LOFF(musp_500), 0, 1000, "1/cm", "45.6",
	  "reduced scattering mu_s' at 500 nm" },
	{ "dermis", "musp_power", K_NUM, SKIN_DERMIS, LOFF(musp_power), 0, 4, "", "0.52",
	  "mu_s' exponent (Mie part when musp_rayleigh > 0)" },
	{ "dermis", "musp_rayleigh", K_NUM, SKIN_DERMIS, LOFF(musp_rayleigh), 0, 1, "", "0.46",
	  "Rayleigh share f of mu_s' at 500 nm (mu_s' = musp500 [f (wl/500)^-4 + (1-f) (wl/500)^-musp_power])" },

	{ "subcutis", "thickness", K_LEN, SKIN_SUBCUTIS, LOFF(d), 0, 10, "cm", "0",
	  "thickness, or inf (semi-infinite); 0 = no subcutis" },
	{ "subcutis", "n", K_IOR, SKIN_SUBCUTIS, LOFF(n), 1, 2, "", "1.44", "refractive index" },
	{ "subcutis", "g", K_ANISO, SKIN_SUBCUTIS, LOFF(g), -0.99, 0.99, "", "0.75", "HG anisotropy" },
	{ "subcutis", "blood", K_NUM, SKIN_SUBCUTIS, LOFF(blood), 0, 0.2, "", "0.05", "blood volume fraction" },
	{ "subcutis", "so2", K_NUM, SKIN_SUBCUTIS, LOFF(so2), 0, 1, "", "0.75", "blood oxygen saturation" },
	{ "subcutis", "musp500", K_NUM, SKIN_SUBCUTIS, LOFF(musp_500), 0, 1000, "1/cm", "35.0",
	  "reduced scattering mu_s' at 500 nm" },
	{ "subcutis", "musp_power", K_NUM, SKIN_SUBCUTIS, LOFF(musp_power), 0, 4, "", "1.136",
	  "mu_s' exponent (Mie part when musp_rayleigh > 0)" },
	{ "subcutis", "musp_rayleigh", K_NUM, SKIN_SUBCUTIS, LOFF(musp_rayleigh), 0, 1, "", "0",
	  "Rayleigh share f of mu_s' at 500 nm (mu_s' = musp500 [f (wl/500)^-4 + (1-f) (wl/500)^-musp_power])" },

	{ "surface", "roughness_skin", K_NUM, NONE, POFF(roughness_skin), 0.01, 1, "", "0.35",
	  "GGX alpha of bare skin" },
	{ "surface", "roughness_sebum", K_NUM, NONE, POFF(roughness_sebum), 0.01, 1, "", "0.25",
	  "GGX alpha of the sebum-covered surface" },
	{ "surface", "roughness", K_ROUGH, NONE, POFF(roughness_top), 0, 1, "", "0",
	  "GGX alpha of the top boundary in the subsurface transport: light enters and leaves through "
	  "microfacets (Walter 2007, Smith G); 0 = smooth; > 0 is also the specular lobe's alpha" },
	{ "surface", "multiple_scattering", K_ROUGH, NONE, POFF(facet_ms), 0, 1, "", "0",
	  "1: light meets the rough boundaries' microfacets as often as it hits them (Heitz 2016 random "
	  "walk, energy conserving); 0: once (Walter 2007; what shadowing and masking stop is lost)" },
	{ "surface", "macro_slope", K_ROUGH, NONE, POFF(macro_slope), 0, 0.8, "", "0",
	  "RMS slope (Beckmann m) of the mm-scale relief, furrows and tilted patches, over "
	  "the whole BRDF: facets with the baked BRDF, height-correlated Smith shadowing "
	  "(engine/macro.h); 0 = flat" },
	{ "epidermis", "top_roughness", K_ROUGH, SKIN_EPIDERMIS, LOFF(rough_top), 0, 1, "", "0",
	  "GGX alpha of the boundary under the sebum film (needs a film); 0 = smooth" },
	{ "dermis", "top_roughness", K_ROUGH, SKIN_DERMIS, LOFF(rough_top), 0, 1, "", "0",
	  "GGX alpha of the epidermis-dermis boundary; 0 = smooth" },
	{ "subcutis", "top_roughness", K_ROUGH, SKIN_SUBCUTIS, LOFF(rough_top), 0, 1, "", "0",
	  "GGX alpha of the dermis-subcutis boundary (needs a subcutis); 0 = smooth" },
};
#define N_KEYS ((int)(sizeof preset_key_table / sizeof preset_key_table[0]))
_Static_assert(sizeof preset_key_table / sizeof preset_key_table[0] <= PRESET_MAX_KEYS, "struct preset_ctx.seen is too small");

/* Keys of [override.WL] sections: LAYER.PROP. */
const struct preset_ov_prop preset_ov_props[OV_N_PROPS] = {
	{ "mua", 0, 1e5, "1/cm", "absorption coefficient" },
	{ "mus", 0, 1e6, "1/cm", "scattering coefficient (not reduced)" },
	{ "g", -0.99, 0.99, "", "HG anisotropy" },
	{ "n", 1, 2, "", "refractive index" },
};

void preset_ctx_err(struct preset_ctx *c, const char *fmt, ...)
{
	if (c->err)
		return;
	va_list ap;
	va_start(ap, fmt);
	c->err = inifile_vmsg(c->origin, c->in.line, fmt, ap);
	va_end(ap);
	c->err_line = c->in.line;
}

int preset_key_find(const char *section, const char *name)
{
	int known_section = 0;
	for (int i = 0; i < N_KEYS; i++) {
		if (strcmp(preset_key_table[i].section, section) != 0)
			continue;
		known_section = 1;
		if (strcmp(preset_key_table[i].name, name) == 0)
			return i;
	}
	return known_section ? -1 : -2;
}

char *preset_key_names(const char *section)
{
	char *list = xstrdup("");
	for (int i = 0; i < N_KEYS; i++) {
		if (strcmp(preset_key_table[i].section, section) != 0)
			continue;
		char *t = xasprintf("%s%s%s", list, *list ? ", " : "", preset_key_table[i].name);
		free(list);
		list = t;
	}
	return list;
}

static int parse_number(const char *v, double *x)
{
	return util_parse_decimal(v, x);
}

/* "400:700:10, 720, 750" -> ascending list; -1 with a message on error. */
int preset_wavelengths_parse(const char *v, double *wl, int *n, char **why)
{
	char *s = xstrdup(v), *save = NULL;
	int k = 0, rc = -1;
	for (char *tok = strtok_r(s, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
		while (*tok == ' ' || *tok == '\t')
			tok++;
		char *end = tok + strlen(tok);
		while (end > tok && (end[-1] == ' ' || end[-1] == '\t'))
			*--end = '\0';
		double a, b, st;
		char *c1 = strchr(tok, ':');
		if (c1) {
			char *c2 = strchr(c1 + 1, ':');
			if (!c2) {
				*why = xasprintf("'%s' is not START:STOP:STEP", tok);
				goto out;
			}
			*c1 = *c2 = '\0';
			if (parse_number(tok, &a) || parse_number(c1 + 1, &b) || parse_number(c2 + 1, &st)) {
				*why = xasprintf("'%s:%s:%s' is not START:STOP:STEP with numbers", tok, c1 + 1, c2 + 1);
				goto out;
			}
			if (!(st > 0.0) || b < a) {
				*why = xasprintf("range %g:%g:%g needs STOP >= START and STEP > 0", a, b, st);
				goto out;
			}
			long cnt = (long)floor((b - a) / st + 1e-9) + 1;
			if (cnt > SKIN_MAX_WL - k) {
				*why = xasprintf("more than %d wavelengths", SKIN_MAX_WL);
				goto out;
			}
			for (long i = 0; i < cnt; i++)
				wl[k++] = a + st * (double)i;
		} else {
			if (parse_number(tok, &a)) {
				*why = xasprintf("'%s' is not a number", tok);
				goto out;
			}
			if (k >= SKIN_MAX_WL) {
				*why = xasprintf("more than %d wavelengths", SKIN_MAX_WL);
				goto out;
			}
			wl[k++] = a;
		}
	}
	if (k == 0) {
		*why = xasprintf("no wavelengths given");
		goto out;
	}
	for (int i = 0; i < k; i++) {
		if (!(wl[i] >= SPECTRA_WL_MIN && wl[i] <= SPECTRA_WL_MAX)) {
			*why = xasprintf("%g nm is out of range [%g, %g] nm", wl[i], SPECTRA_WL_MIN, SPECTRA_WL_MAX);
			goto out;
		}
		if (i > 0 && !(wl[i] > wl[i - 1])) {
			*why = xasprintf("%g nm after %g nm: wavelengths must be strictly ascending", wl[i], wl[i - 1]);
			goto out;
		}
	}
	*n = k;
	rc = 0;
out:
	free(s);
	return rc;
}

static int valid_name(const char *s)
{
	if (*s == '\0')
		return 0;
	for (; *s; s++)
		if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9')
		    || *s == '.' || *s == '_' || *s == '-'))
			return 0;
	return 1;
}

static void range_text(char *buf, size_t sz, double lo, double hi, const char *unit)
{
	snprintf(buf, sz, "[%g, %g]%s%s", lo, hi, *unit ? " " : "", unit);
}

void preset_free_contents(struct skin_params *p)
{
	free(p->name);
	free(p->description);
	free(p->origin);
	free(p->override);
	memset(p, 0, sizeof *p);
}

/* Set one key of the table; 0 or -1 (message in c). */
int preset_key_set(struct preset_ctx *c, int ki, const char *v)
{
	const struct preset_key *k = &preset_key_table[ki];
	struct skin_params *p = c->p;
	char *base = k->layer == NONE ? (char *)p : (char *)&p->layer[k->layer];
	double *dp = (double *)(base + k->off), x;
	char rng[96];
	range_text(rng, sizeof rng, k->lo, k->hi, k->unit);

	switch (k->kind) {
	case K_NUM:
	case K_ROUGH:
	case K_LEN:
	case K_IOR:
	case K_ANISO:
		if (k->kind == K_LEN && strcmp(v, "inf") == 0) {
			*dp = INFINITY;
			return 0;
		}
		if (k->kind == K_IOR && strcmp(v, "ding2006") == 0) {
			if (k->layer != SKIN_EPIDERMIS && k->layer != SKIN_DERMIS) {
				preset_ctx_err(c, "%s.%s = %s: the Ding 2006 fit exists only for epidermis and dermis; "
				    "give a number in %s", k->section, k->name, v, rng);
				return -1;
			}
			*dp = NAN;
			return 0;
		}
		if (k->kind == K_ANISO && strcmp(v, "vangemert1989") == 0) {
			*dp = NAN;
			return 0;
		}
		if (parse_number(v, &x) != 0) {
			preset_ctx_err(c, "%s.%s = %s: not a decimal number%s (range %s)", k->section, k->name, v,
			    k->kind == K_LEN ? " or inf" : k->kind == K_IOR ? " or ding2006"
			    : k->kind == K_ANISO ? " or vangemert1989" : "", rng);
			return -1;
		}
		if (!(x >= k->lo && x <= k->hi)) {
			preset_ctx_err(c, "%s.%s = %s: out of range %s", k->section, k->name, v, rng);
			return -1;
		}
		*dp = x;
		return 0;
	case K_TEXT:
		if (strlen(v) > (size_t)k->hi) {
			preset_ctx_err(c, "%s.%s: longer than %g characters", k->section, k->name, k->hi);
			return -1;
		}
		/* preset_to_ini writes the text back: a comment character in it
		 * would cut the value when that text is read again. */
		if (strpbrk(v, ";#") != NULL) {
			preset_ctx_err(c, "%s.%s = %s: ';' and '#' start comments in preset files; leave them out",
			    k->section, k->name, v);
			return -1;
		}
		if (strcmp(k->name, "name") == 0 && !valid_name(v)) {
			preset_ctx_err(c, "%s.%s = %s: use letters, digits, '.', '_' and '-' only", k->section, k->name, v);
			return -1;
		}
		if (strcmp(k->name, "name") == 0)
			c->name_set = 1;
		else
			c->desc_set = 1;
		free(*(char **)(base + k->off));
		*(char **)(base + k->off) = xstrdup(v);
		return 0;
	case K_MODEL:
		if (strcmp(v, "chromophores") == 0)
			p->model = SKIN_MODEL_CHROMOPHORES;
		else if (strcmp(v, "tables") == 0)
			p->model = SKIN_MODEL_TABLES;
		else {
			preset_ctx_err(c, "%s.%s = %s: not one of chromophores, tables", k->section, k->name, v);
			return -1;
		}
		return 0;
	case K_WL: {
		char *why = NULL;
		if (preset_wavelengths_parse(v, p->wl, &p->n_wl, &why) != 0) {
			preset_ctx_err(c, "%s.%s = %s: %s", k->section, k->name, v, why);
			free(why);
			return -1;
		}
		c->wl_set = 1;
		return 0;
	}
	case K_BASE: {
		if (c->n_calls != 1) {
			preset_ctx_err(c, "skin.base = %s: base must be the first key of the file", v);
			return -1;
		}
		if (c->depth >= PRESET_MAX_BASE_DEPTH) {
			preset_ctx_err(c, "skin.base = %s: presets nest deeper than %d bases", v, PRESET_MAX_BASE_DEPTH);
			return -1;
		}
		char *cause = NULL;
		struct skin_params *b = c->load_base(v, c->depth + 1, &cause);
		if (b == NULL) {
			preset_ctx_err(c, "skin.base = %s: %s", v, cause);
			free(cause);
			return -1;
		}
		preset_free_contents(p);
		*p = *b;
		free(b);
		free(c->ov_seen);
		c->ov_seen = xcalloc((size_t)p->n_override * SKIN_N_LAYERS * OV_N_PROPS + 1, 1);
		return 0;
	}
	}
	return -1;
}

static int find_layer(const char *s, size_t len)
{
	for (int l = 0; l < SKIN_N_LAYERS; l++)
		if (strlen(tissue_layer_name(l)) == len && strncmp(s, tissue_layer_name(l), len) == 0)
			return l;
	return -1;
}

/* A section header, checked before its keys (an empty section is checked too). */
int preset_section_check(struct preset_ctx *c, const char *section)
{
	if (strncmp(section, "override.", 9) == 0) {
		double wl;
		if (parse_number(section + 9, &wl) != 0) {
			preset_ctx_err(c, "[%s]: '%s' is not a wavelength in nm (e.g. [override.550])", section, section + 9);
			return -1;
		}
		if (!(wl >= SPECTRA_WL_MIN && wl <= SPECTRA_WL_MAX)) {
			preset_ctx_err(c, "[%s]: wavelength %g nm is out of range [%g, %g] nm", section, wl, SPECTRA_WL_MIN,
			    SPECTRA_WL_MAX);
			return -1;
		}
		return 0;
	}
	if (preset_key_find(section, "") == -2) {
		preset_ctx_err(c, "unknown section [%s] (sections: skin, sebum, epidermis, dermis, subcutis, surface, "
		    "override.WL)", section);
		return -1;
	}
	return 0;
}

/* [override.WL] LAYER.PROP = value */
int preset_override_set(struct preset_ctx *c, const char *section, const char *name, const char *v)
{
	struct skin_params *p = c->p;
	double wl, x;
	if (parse_number(section + 9, &wl) != 0) {
		preset_ctx_err(c, "[%s]: '%s' is not a wavelength in nm (e.g. [override.550])", section, section + 9);
		return -1;
	}
	if (!(wl >= SPECTRA_WL_MIN && wl <= SPECTRA_WL_MAX)) {
		preset_ctx_err(c, "[%s]: wavelength %g nm is out of range [%g, %g] nm", section, wl, SPECTRA_WL_MIN,
		    SPECTRA_WL_MAX);
		return -1;
	}
	const char *dot = strchr(name, '.');
	int l = dot ? find_layer(name, (size_t)(dot - name)) : -1, prop = -1;
	for (int i = 0; dot && i < OV_N_PROPS; i++)
		if (strcmp(dot + 1, preset_ov_props[i].name) == 0)
			prop = i;
	if (l < 0 || prop < 0) {
		preset_ctx_err(c, "unknown key '%s' in [%s] (keys: LAYER.mua, LAYER.mus, LAYER.g, LAYER.n with LAYER "
		    "one of sebum, epidermis, dermis, subcutis)", name, section);
		return -1;
	}
	char rng[96];
	range_text(rng, sizeof rng, preset_ov_props[prop].lo, preset_ov_props[prop].hi, preset_ov_props[prop].unit);
	if (parse_number(v, &x) != 0) {
		preset_ctx_err(c, "%s: %s = %s: not a decimal number (range %s)", section, name, v, rng);
		return -1;
	}
	if (!(x >= preset_ov_props[prop].lo && x <= preset_ov_props[prop].hi)) {
		preset_ctx_err(c, "%s: %s = %s: out of range %s", section, name, v, rng);
		return -1;
	}
	/* Find or insert the override, keeping them sorted by wavelength. */
	int i = 0;
	while (i < p->n_override && p->override[i].wl < wl - 1e-6)
		i++;
	if (i == p->n_override || fabs(p->override[i].wl - wl) >= 1e-6) {
		size_t per = SKIN_N_LAYERS * OV_N_PROPS;
		p->override = xreallocarray(p->override, (size_t)p->n_override + 1, sizeof *p->override);
		c->ov_seen = xreallocarray(c->ov_seen, ((size_t)p->n_override + 1) * per + 1, 1);
		memmove(&p->override[i + 1], &p->override[i], sizeof *p->override * (size_t)(p->n_override - i));
		memmove(&c->ov_seen[(i + 1) * per], &c->ov_seen[i * per], per * (size_t)(p->n_override - i));
		memset(&c->ov_seen[i * per], 0, per);
		struct skin_override *o = &p->override[i];
		o->wl = wl;
		for (int j = 0; j < SKIN_N_LAYERS; j++)
			o->mu_a[j] = o->mu_s[j] = o->g[j] = o->n[j] = NAN;
		p->n_override++;
	}
	unsigned char *seen = &c->ov_seen[((size_t)i * SKIN_N_LAYERS + (size_t)l) * OV_N_PROPS + (size_t)prop];
	if (*seen) {
		preset_ctx_err(c, "%s: %s is given twice", section, name);
		return -1;
	}
	*seen = 1;
	struct skin_override *o = &p->override[i];
	double *dst = prop == OV_MUA ? o->mu_a : prop == OV_MUS ? o->mu_s : prop == OV_G ? o->g : o->n;
	dst[l] = x;
	return 0;
}

void preset_apply_defaults(struct skin_params *p)
{
	struct preset_ctx c = { .origin = "defaults", .p = p };
	memset(p, 0, sizeof *p);
	for (int i = 0; i < N_KEYS; i++) {
		if (preset_key_table[i].dflt[0] == '\0')
			continue;
		if (preset_key_set(&c, i, preset_key_table[i].dflt) != 0)
			fatalx("preset defaults: %s", c.err);
	}
	free(c.ov_seen);
}

void preset_key_info(int i, struct preset_key_info *out)
{
	const struct preset_key *k = &preset_key_table[i];
	*out = (struct preset_key_info){ k->section, k->name, k->unit, k->lo, k->hi, k->layer, k->off,
		k->kind == K_NUM || k->kind == K_ROUGH || k->kind == K_LEN || k->kind == K_IOR || k->kind == K_ANISO };
}

int preset_key_count(void)
{
	return N_KEYS;
}

