/* sites: skin micro-relief parameters per body site, the parameter table
 * and the [texture] INI section.
 *
 * Sources (values we could not pin to a publication are marked
 * "assumption"; they are chosen to be of the published order of magnitude):
 * - Blume U, Ferracin J, Verschoore M, Czernielewski JM, Schaefer H.
 *   Physiology of the vellus hair follicle: hair growth and sebum excretion.
 *   Br J Dermatol 1991;124:21-28: vellus hair density 439 /cm^2 on the
 *   forehead and 85 /cm^2 on the back (each vellus hair leaves an opening).
 * - Otberg N, Richter H, Schaefer H, Blume-Peytavi U, Sterry W, Lademann J.
 *   Variations of hair follicle size and distribution in different body
 *   sites.  J Invest Dermatol 2004;122:14-19: follicle density highest on
 *   the forehead and lowest on the calf; the smallest follicle openings and
 *   lowest values of every other parameter on the forearm; the largest
 *   openings on the calf.
 * - Pagnoni A, Kligman AM, el Gammal S, Stoudemayer T.  Determination of
 *   density of follicles on various regions of the face by cyanoacrylate
 *   biopsy.  Br J Dermatol 1994;131:862-865: follicle density falls from the
 *   centre of the face (nose) to the sides (cheek).
 * - Flament F et al.  Facial skin pores: a multiethnic study.  Clin Cosmet
 *   Investig Dermatol 2015;8:85-93: visible cheek pores counted above a
 *   250 um detection threshold; size and density vary strongly with
 *   ethnicity (lowest in Chinese women, highest in Brazilian women).
 * - Hashimoto K.  New methods for surface ultrastructure: comparative
 *   studies of scanning electron microscopy, transmission electron
 *   microscopy and replica method.  Int J Dermatol 1974;13:357-381, as
 *   summarised in the skin-topography literature: primary lines 20-100 um
 *   deep, secondary lines 5-40 um deep (tertiary and quaternary lines are
 *   below the resolution of these maps).
 * - Lagarde JM, Rouvrais C, Black D.  Topography and anisotropy of the skin
 *   surface with ageing.  Skin Res Technol 2005;11:110-119: the furrow net
 *   of the forearm and temple is anisotropic, more so with age.
 * - Skin relief and aging.  J Soc Cosmet Chem 1983;34(4): the developed
 *   surface of the volar forearm is 8-30 % larger than its projection
 *   (the forearm widths and depths are chosen to fall inside it).
 * - Yuan Y, Verma R.  Colloids Surf B 2006;48:6-12: corneocytes 20-40 um
 *   across and about 0.5 um thick (the plateau texture's scale; its RMS
 *   0.3 um is an assumption of that order).
 * Bend, fading, direction gains, the secondary stars and the pores on the
 * face's junctions are assumptions (docs/relief.md).
 * Furrow cell sizes, widths and the plateau dome heights are assumptions
 * read off the appearance of the back of the hand (a net of triangles of a
 * fraction of a millimetre, Li & Ng figures 8-10). */
#include "config.h"

#include "geom/sites.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/inifile.h"
#include "base/util.h"

#define MM(x) ((x) * 0.1)	/* mm -> cm */
#define UM(x) ((x) * 1e-4)	/* um -> cm */
#define PER_MM2(x) ((x) * 100.0)	/* 1/mm^2 -> 1/cm^2 */
#define DEG(x) ((x) * M_PI / 180)	/* degrees -> radians */

struct site {
	const char *name;
	const char *summary;
	struct relief_params p;
};

/* Every field is given for every site, so that a site is read at a glance. */
static const struct site sites[] = {
	{ "face", "generic facial skin (cheek/forehead average): fine pores, shallow furrows", {
		.tile = MM(8),
		/* Between the forehead (Blume 1991) and the cheek (Pagnoni 1994);
		 * assumption. */
		.pore_density = PER_MM2(2.0),
		.pore_radius = UM(45), .pore_radius_sd = 0.35,	/* assumption (Otberg 2004 order) */
		.pore_depth = UM(35), .pore_depth_sd = 0.3,	/* assumption */
		.pore_aspect = 1.3, .pore_junction = 1.0, .pore_regularity = 0.5,
		.levels = 2,
		.furrow_cell = MM(0.35), .furrow_width = UM(60),	/* assumption */
		/* Hashimoto 1974: 20-100 um, the shallow part. */
		.furrow_depth = UM(28), .furrow_depth_sd = 0.35,
		.ridge_height = UM(4),
		.level_scale = 0.45, .level_gain = 0.25,
		.stretch = 1.15, .orientation = DEG(0), .furrow_regularity = 0.6,
		.hierarchy = 1, .bend = 0.12, .furrow_fade = 0.5, .region_sd = 0.25,
		.direction_gain = 1.3,
		.plateau_roughness = UM(0.3), .plateau_scale = UM(30) } },
	{ "cheek", "cheek with enlarged, visible pores (Flament 2015 style)", {
		.tile = MM(8),
		.pore_density = PER_MM2(0.8),	/* visible pores only; assumption */
		/* ~ Flament 2015 250 um threshold */
		.pore_radius = UM(110), .pore_radius_sd = 0.3,
		.pore_depth = UM(60), .pore_depth_sd = 0.3,	/* assumption */
		.pore_aspect = 1.4, .pore_junction = 1.0, .pore_regularity = 0.5,
		.levels = 2,
		.furrow_cell = MM(0.35), .furrow_width = UM(60),
		.furrow_depth = UM(28), .furrow_depth_sd = 0.35,	/* as face */
		.ridge_height = UM(4),
		.level_scale = 0.45, .level_gain = 0.25,
		.stretch = 1.15, .orientation = DEG(0), .furrow_regularity = 0.6,
		.hierarchy = 1, .bend = 0.12, .furrow_fade = 0.5, .region_sd = 0.25,
		.direction_gain = 1.3,
		.plateau_roughness = UM(0.3), .plateau_scale = UM(30) } },
	{ "forehead", "forehead: dense small follicle openings (Blume 1991: 439 /cm^2)", {
		.tile = MM(8),
		.pore_density = PER_MM2(4.39),	/* Blume 1991 */
		.pore_radius = UM(35), .pore_radius_sd = 0.3,	/* assumption */
		.pore_depth = UM(35), .pore_depth_sd = 0.3,	/* assumption */
		.pore_aspect = 1.2, .pore_junction = 1.0, .pore_regularity = 0.5,
		.levels = 2,
		.furrow_cell = MM(0.4), .furrow_width = UM(60),
		.furrow_depth = UM(28), .furrow_depth_sd = 0.35,	/* as face */
		.ridge_height = UM(4),
		.level_scale = 0.45, .level_gain = 0.25,
		.stretch = 1.3, .orientation = DEG(0), .furrow_regularity = 0.6,
		.hierarchy = 1, .bend = 0.12, .furrow_fade = 0.5, .region_sd = 0.25,
		.direction_gain = 1.5,
		.plateau_roughness = UM(0.3), .plateau_scale = UM(30) } },
	{ "nose", "nose: large sebaceous pores, weak furrows (Pagnoni 1994 gradient)", {
		.tile = MM(6),
		.pore_density = PER_MM2(4.0),	/* assumption, above the forehead */
		.pore_radius = UM(70), .pore_radius_sd = 0.35,	/* assumption */
		.pore_depth = UM(60), .pore_depth_sd = 0.3,	/* assumption */
		.pore_aspect = 1.2, .pore_junction = 1.0, .pore_regularity = 0.55,
		.levels = 1,
		.furrow_cell = MM(0.5), .furrow_width = UM(30),
		.furrow_depth = UM(8), .furrow_depth_sd = 0.3,
		.ridge_height = UM(3),
		.level_scale = 0.45, .level_gain = 0.35,
		.stretch = 1.0, .orientation = DEG(0), .furrow_regularity = 0.6,
		.hierarchy = 1, .bend = 0.12, .furrow_fade = 0.5, .region_sd = 0.25,
		.direction_gain = 1,
		.plateau_roughness = UM(0.3), .plateau_scale = UM(30) } },
	{ "hand", "back of the hand: deep anisotropic triangular furrow net, sparse pores", {
		.tile = MM(12),
		.pore_density = PER_MM2(0.15),	/* assumption: sparse vellus follicles */
		.pore_radius = UM(30), .pore_radius_sd = 0.3,
		.pore_depth = UM(20), .pore_depth_sd = 0.3,
		.pore_aspect = 1.2, .pore_junction = 1.0, .pore_regularity = 0.5,
		.levels = 3,
		.furrow_cell = MM(0.6), .furrow_width = UM(60),	/* assumption */
		/* Hashimoto 1974: 20-100 um */
		.furrow_depth = UM(60), .furrow_depth_sd = 0.35,
		.ridge_height = UM(12),
		.level_scale = 0.4, .level_gain = 0.3,	/* secondary 5-40 um */
		.stretch = 1.8, .orientation = DEG(0), .furrow_regularity = 0.6,
		.hierarchy = 1, .bend = 0.12, .furrow_fade = 0.5, .region_sd = 0.25,
		.direction_gain = 2,
		.plateau_roughness = UM(0.3), .plateau_scale = UM(30) } },
	{ "forearm", "volar forearm: moderately anisotropic furrows, few small pores", {
		.tile = MM(10),
		.pore_density = PER_MM2(0.2),	/* assumption, Otberg 2004: low density */
		.pore_radius = UM(25), .pore_radius_sd = 0.3,	/* Otberg 2004: smallest openings */
		.pore_depth = UM(15), .pore_depth_sd = 0.3,
		.pore_aspect = 1.2, .pore_junction = 0.8, .pore_regularity = 0.5,
		.levels = 3,
		/* Width and depth (assumptions) chosen so that the developed area
		 * is inside the 8-30 % of the 1983 forearm replicas: 15.5-18.3 %
		 * over seeds 1-5 at 7.8 um pixels (docs/relief.md). */
		.furrow_cell = MM(0.45), .furrow_width = UM(70),
		.furrow_depth = UM(30), .furrow_depth_sd = 0.3,
		.ridge_height = UM(8),
		.level_scale = 0.4, .level_gain = 0.3,
		.stretch = 1.4, .orientation = DEG(0), .furrow_regularity = 0.6,
		.hierarchy = 1, .bend = 0.12, .furrow_fade = 0.5, .region_sd = 0.25,
		.direction_gain = 1.6,
		.plateau_roughness = UM(0.3), .plateau_scale = UM(30) } },	/* Lagarde 2005 */
	{ "back", "upper back: isotropic furrows, vellus pores (Blume 1991: 85 /cm^2)", {
		.tile = MM(12),
		.pore_density = PER_MM2(0.85),	/* Blume 1991 */
		.pore_radius = UM(40), .pore_radius_sd = 0.3,
		.pore_depth = UM(25), .pore_depth_sd = 0.3,
		.pore_aspect = 1.2, .pore_junction = 0.5, .pore_regularity = 0.5,
		.levels = 2,
		.furrow_cell = MM(0.6), .furrow_width = UM(50),
		.furrow_depth = UM(30), .furrow_depth_sd = 0.3,
		.ridge_height = UM(8),
		.level_scale = 0.45, .level_gain = 0.3,
		.stretch = 1.1, .orientation = DEG(0), .furrow_regularity = 0.6,
		.hierarchy = 1, .bend = 0.12, .furrow_fade = 0.5, .region_sd = 0.25,
		.direction_gain = 1.2,
		.plateau_roughness = UM(0.3), .plateau_scale = UM(30) } },
};

#define F(field) offsetof(struct texture_config, field)
#define R(field) offsetof(struct texture_config, relief.field)
static const struct texture_param params[] = {
	{ "size", "px", 1, 16, 16384, SITES_LONG, F(size), "edge length of the square maps" },
	{ "seed", "1", 1, 0, 18446744073709551615.0, SITES_SEED, F(seed), "random seed (exact)" },
	{ "tile-mm", "mm", 0.1, 0.5, 500, SITES_REAL, R(tile),
	  "edge length of the tile on the skin" },
	{ "pore-density", "1/mm^2", 100, 0, 100, SITES_REAL, R(pore_density), "pores per area" },
	{ "pore-radius", "um", 1e-4, 1, 5000, SITES_REAL, R(pore_radius),
	  "median pore radius at the surface" },
	{ "pore-radius-sd", "1", 1, 0, 1.5, SITES_REAL, R(pore_radius_sd),
	  "log-normal sigma of the pore radius" },
	{ "pore-depth", "um", 1e-4, 0, 2000, SITES_REAL, R(pore_depth),
	  "median pore depth (scales with the radius)" },
	{ "pore-depth-sd", "1", 1, 0, 1.5, SITES_REAL, R(pore_depth_sd),
	  "log-normal sigma of the pore depth" },
	{ "pore-aspect", "1", 1, 1, 5, SITES_REAL, R(pore_aspect),
	  "long/short axis of the elliptic pore openings" },
	{ "pore-junction", "1", 1, 0, 1, SITES_REAL, R(pore_junction),
	  "fraction of pores placed on primary furrow junctions" },
	{ "pore-regularity", "1", 1, 0, 0.8, SITES_REAL, R(pore_regularity),
	  "Poisson-disk distance between pores / mean spacing (0 = uniform random)" },
	{ "levels", "1", 1, 0, RELIEF_MAX_LEVELS, SITES_INT, R(levels),
	  "furrow levels (1 = primary only, 0 = no furrows)" },
	{ "furrow-cell", "mm", 0.1, 0.02, 50, SITES_REAL, R(furrow_cell),
	  "mean spacing of primary furrow junctions" },
	{ "furrow-width", "um", 1e-4, 1, 5000, SITES_REAL, R(furrow_width),
	  "width of a primary furrow at the surface" },
	{ "furrow-depth", "um", 1e-4, 0, 2000, SITES_REAL, R(furrow_depth),
	  "median depth of a primary furrow" },
	{ "furrow-depth-sd", "1", 1, 0, 1.5, SITES_REAL, R(furrow_depth_sd),
	  "log-normal sigma of the depth of each primary line (a third of it per "
	  "edge) and of each finer furrow" },
	{ "ridge-height", "um", 1e-4, 0, 1000, SITES_REAL, R(ridge_height),
	  "dome height of the plateaus between primary furrows" },
	{ "level-scale", "1", 1, 0.1, 0.8, SITES_REAL, R(level_scale),
	  "cell size of each finer level / the previous one" },
	{ "level-gain", "1", 1, 0, 1, SITES_REAL, R(level_gain),
	  "depth and dome of each finer level / the previous one" },
	{ "stretch", "1", 1, 1, 10, SITES_REAL, R(stretch),
	  "elongation of the furrow cells along --orientation" },
	{ "orientation", "deg", M_PI / 180, -180, 180, SITES_REAL, R(orientation),
	  "direction of elongation, from +x (right) toward +y (up)" },
	{ "furrow-regularity", "1", 1, 0, 0.8, SITES_REAL, R(furrow_regularity),
	  "Poisson-disk distance between junctions / mean spacing" },
	{ "hierarchy", "1", 1, 0, 1, SITES_INT, R(hierarchy),
	  "1: level 2 splits each primary triangle (secondary lines end on primary ones); "
	  "0: own net" },
	{ "bend", "1", 1, 0, 0.3, SITES_REAL, R(bend),
	  "largest sideways bend of a furrow / its length" },
	{ "region-sd", "1", 1, 0, 1, SITES_REAL, R(region_sd),
	  "log-normal sigma of a smooth depth factor over the tile (regions of deeper lines)" },
	{ "furrow-fade", "1", 1, 0, 1.5, SITES_REAL, R(furrow_fade),
	  "fading along a furrow: depth exp(-f |z|) at its inner joints, full at the ends" },
	{ "direction-gain", "1", 1, 1, 10, SITES_REAL, R(direction_gain),
	  "depth of furrows along --orientation (or --direction-map) / across it" },
	{ "plateau-roughness", "um", 1e-4, 0, 20, SITES_REAL, R(plateau_roughness),
	  "RMS height of the fine texture on the plateaus" },
	{ "plateau-scale", "um", 1e-4, 2, 5000, SITES_REAL, R(plateau_scale),
	  "wavelength of the plateau texture" },
};
#undef F
#undef R

const struct texture_param *sites_params(int *n)
{
	*n = (int)(sizeof params / sizeof params[0]);
	return params;
}

const struct texture_param *sites_param_find(const char *key)
{
	for (size_t i = 0; i < sizeof params / sizeof params[0]; i++) {
		const char *a = params[i].key, *b = key;
		/* '-' and '_' are the same character here. */
		while (*a && *b && (*a == *b || (*a == '-' && *b == '_'))) {
			a++;
			b++;
		}
		if (*a == '\0' && *b == '\0')
			return &params[i];
	}
	return NULL;
}

int sites_count(void)
{
	return (int)(sizeof sites / sizeof sites[0]);
}

const char *sites_name(int i)
{
	return sites[i].name;
}

const char *sites_summary(int i)
{
	return sites[i].summary;
}

int sites_load(const char *name, struct texture_config *cfg, char **cause)
{
	for (int i = 0; i < sites_count(); i++)
		if (strcmp(sites[i].name, name) == 0) {
			memset(cfg, 0, sizeof *cfg);
			snprintf(cfg->site, sizeof cfg->site, "%s", name);
			cfg->size = 1024;
			cfg->seed = 1;
			cfg->relief = sites[i].p;
			return 0;
		}
	size_t len = 0;
	for (int i = 0; i < sites_count(); i++)
		len += strlen(sites[i].name) + 2;
	char *list = xcalloc(len + 1, 1);
	for (int i = 0; i < sites_count(); i++) {
		if (i)
			strcat(list, ", ");
		strcat(list, sites[i].name);
	}
	*cause = xasprintf("unknown site '%s' (known: %s)", name, list);
	free(list);
	return -1;
}

int sites_set(struct texture_config *cfg, const struct texture_param *p, const char *label,
    const char *value, char **cause)
{
	double x;
	const char *unit = strcmp(p->unit, "1") == 0 ? "" : p->unit;
	if (p->type == SITES_SEED && value[0] >= '0' && value[0] <= '9' &&
	    strspn(value, "0123456789") == strlen(value)) {
		/* Digits: exact, not through a double (2^53 + 1 stays itself). */
		errno = 0;
		unsigned long long u = strtoull(value, NULL, 10);
		if (errno == ERANGE) {
			*cause = xasprintf("%s = %s is out of range [0, 18446744073709551615]",
			    label, value);
			return -1;
		}
		*(uint64_t *)(void *)((char *)cfg + p->offset) = u;
		return 0;
	}
	if (util_parse_decimal(value, &x) != 0) {
		*cause = xasprintf("%s = '%s' is not a decimal number in [%.15g, %.15g]%s%s", label,
		    value, p->lo, p->hi, *unit ? " " : "", unit);
		return -1;
	}
	if (x < p->lo || x > p->hi) {
		*cause = xasprintf("%s = %s is out of range [%.15g, %.15g]%s%s", label, value,
		    p->lo, p->hi, *unit ? " " : "", unit);
		return -1;
	}
	if (p->type != SITES_REAL && x != floor(x)) {
		*cause = xasprintf("%s = %s is not a whole number", label, value);
		return -1;
	}
	char *field = (char *)cfg + p->offset;
	switch (p->type) {
	case SITES_REAL:
		*(double *)(void *)field = x * p->scale;
		break;
	case SITES_LONG:
		*(long *)(void *)field = (long)x;
		break;
	case SITES_INT:
		*(int *)(void *)field = (int)x;
		break;
	case SITES_SEED:
		if (x >= 18446744073709551616.0) {
			*cause = xasprintf("%s = %s is out of range [0, 18446744073709551615]",
			    label, value);
			return -1;
		}
		*(uint64_t *)(void *)field = (uint64_t)x;
		break;
	}
	if (cfg->site[0] == '\0')
		snprintf(cfg->site, sizeof cfg->site, "custom");
	return 0;
}

double sites_get(const struct texture_config *cfg, const struct texture_param *p)
{
	const char *field = (const char *)cfg + p->offset;
	switch (p->type) {
	case SITES_REAL:
		return *(const double *)(const void *)field / p->scale;
	case SITES_LONG:
		return (double)*(const long *)(const void *)field;
	case SITES_INT:
		return *(const int *)(const void *)field;
	case SITES_SEED:
		return (double)*(const uint64_t *)(const void *)field;
	}
	return 0;
}

struct ini_state {
	struct texture_config *cfg;
	const char *path;
	int pass;	/* 0: look for site, 1: apply the other keys */
	char *error;	/* first message */
	int line[64];	/* pass 0: line of each parameter (index in sites_params, the
			 * last: site) seen, 0 if none */
	struct inifile *in;
};

/* A key given twice would silently take its last value. */
static int repeated(struct ini_state *st, const char *name, char **cause)
{
	int n;
	const struct texture_param *all = sites_params(&n), *p = sites_param_find(name);
	int i = strcmp(name, "site") == 0 ? 63 : p ? (int)(p - all) : -1;
	if (st->pass != 0 || i < 0 || i > 63)
		return 0;
	if (st->line[i]) {
		*cause = xasprintf("%s is given twice in [texture] (first on line %d)", name,
		    st->line[i]);
		return 1;
	}
	st->line[i] = st->in->line;
	return 0;
}

static int on_ini(void *user, const char *section, const char *name, const char *value)
{
	struct ini_state *st = user;
	if (strcmp(section, "texture") != 0) {
		if (section[0] != '\0')
			return 1;	/* a skin preset's section (on_section checked the name) */
		if (st->error == NULL)
			st->error = xasprintf("key '%s' outside the [texture] section", name);
		return 0;
	}
	char *cause = NULL;
	if (repeated(st, name, &cause))
		goto bad;
	if (strcmp(name, "site") == 0) {
		if (st->pass == 0 && sites_load(value, st->cfg, &cause) != 0)
			goto bad;
		return 1;
	}
	if (st->pass == 0)
		return 1;
	const struct texture_param *p = sites_param_find(name);
	if (p == NULL) {
		cause = xasprintf("unknown key '%s' in [texture] (see skinbake texture --help)",
		    name);
		goto bad;
	}
	if (sites_set(st->cfg, p, name, value, &cause) != 0)
		goto bad;
	return 1;
bad:
	if (st->error == NULL)
		st->error = cause;
	else
		free(cause);
	return 0;
}

/* [texture], or a section of a skin preset (skin/preset_keys.c; a preset
 * file may carry the texture of its skin), whose keys are ignored here. */
static int on_section(void *user, const char *section)
{
	static const char *const preset_sections[] = { "skin", "sebum", "epidermis", "dermis",
	    "subcutis", "surface" };
	struct ini_state *st = user;
	if (strcmp(section, "texture") == 0 || strncmp(section, "override.", 9) == 0)
		return 1;
	for (size_t i = 0; i < sizeof preset_sections / sizeof preset_sections[0]; i++)
		if (strcmp(section, preset_sections[i]) == 0)
			return 1;
	if (st->error == NULL)
		st->error = xasprintf("unknown section [%s] (a texture file has [texture], and may "
		    "have a skin preset's sections: skin, sebum, epidermis, dermis, subcutis, "
		    "surface, override.WL)", section);
	return 0;
}

int sites_read_ini(const char *path, struct texture_config *cfg, char **cause)
{
	struct ini_state st = { .cfg = cfg, .path = path };
	char *text = inifile_read(path, cause);
	if (text == NULL)
		return -1;
	for (st.pass = 0; st.pass < 2; st.pass++) {
		struct inifile in;
		st.in = &in;
		int rc = inifile_parse(&in, path, text, on_ini, on_section, &st);
		if (in.error || (in.refused && st.error)) {
			*cause = in.error ? in.error
			    : xasprintf("%s:%d: %s", path, in.refused, st.error);
			free(st.error);	/* in.error, when set, is *cause */
			free(text);
			return -1;
		}
		if (in.too_long) {
			*cause = xasprintf("%s:%d: line %d is longer than %d characters", path,
			    in.too_long, in.too_long, in.max_line);
			free(st.error);
			free(text);
			return -1;
		}
		if (rc < 0) {
			*cause = xasprintf("%s: libinih failed (code %d)", path, rc);
			free(text);
			return -1;
		}
		if (rc > 0) {
			if (st.error)
				*cause = xasprintf("%s:%d: %s", path, rc, st.error);
			else
				*cause = xasprintf("%s:%d: syntax error", path, rc);
			free(st.error);
			free(text);
			return -1;
		}
	}
	free(text);
	return 0;
}

char *sites_ini_text(const struct texture_config *cfg)
{
	int n;
	const struct texture_param *p = sites_params(&n);
	char *s = xasprintf("[texture]\nsite = %s\n", cfg->site);
	for (int i = 0; i < n; i++) {
		char key[64];
		snprintf(key, sizeof key, "%s", p[i].key);
		for (char *c = key; *c; c++)
			if (*c == '-')
				*c = '_';
		const void *field = (const char *)cfg + p[i].offset;
		char *t = p[i].type == SITES_SEED
		    ? xasprintf("%s%s = %llu\n", s, key,
		    (unsigned long long)*(const uint64_t *)field)
		    : xasprintf("%s%s = %.17g\n", s, key, sites_get(cfg, &p[i]));
		free(s);
		s = t;
	}
	return s;
}
