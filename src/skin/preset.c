/* preset: reading presets, from files and built-in INI text (the keys and
 * their setters are preset_keys.c).  One parser: files are read into memory
 * and, like the built-in presets' INI text, fed to ini_parse_stream through
 * a reader that counts lines (for file:line messages whatever the library's
 * handler signature) and rejects over-long lines, which libinih would
 * otherwise split silently (../shared/notes/dependencies.md section 6).
 * Defaults are the key table's default texts applied through the same
 * setters, so docs, `preset keys` and behaviour cannot drift apart. */
#include "config.h"
#include "skin/preset.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "skin/preset_builtin.h"
#include "skin/preset_keys.h"
#include "skin/spectra.h"

#define MAX_FILE_BYTES (1 << 20)

static int parse_text(struct preset_ctx *c, const char *text);

static char *builtin_names(void)
{
	char *s = xstrdup("");
	for (int i = 0; i < preset_count(); i++) {
		char *t = xasprintf("%s%s%s", s, i ? ", " : "", preset_name(i));
		free(s);
		s = t;
	}
	return s;
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
	struct preset_ctx *c = user;
	if (c->err)
		return 0;
	c->n_calls++;
	/* libinih passes indented lines after a key as continuations of it. */
	if (c->n_calls > 1 && c->in.line != c->last_line && strcmp(section, c->last_section) == 0
	    && strcmp(name, c->last_name) == 0 && (*c->in.cur == ' ' || *c->in.cur == '\t')) {
		preset_ctx_err(c, "indented line continues '%s'; continuation lines are not supported "
		    "(remove the indentation)", name);
		return 0;
	}
	snprintf(c->last_section, sizeof c->last_section, "%s", section);
	snprintf(c->last_name, sizeof c->last_name, "%s", name);
	c->last_line = c->in.line;
	if (*section == '\0') {
		preset_ctx_err(c, "key '%s' outside any section (sections: skin, sebum, epidermis, dermis, "
		    "subcutis, surface, override.WL)", name);
		return 0;
	}
	if (strncmp(section, "override.", 9) == 0)
		return preset_override_set(c, section, name, value) == 0;
	int ki = preset_key_find(section, name);
	if (ki >= 0) {
		if (c->seen[ki]) {
			preset_ctx_err(c, "%s.%s is given twice", section, name);
			return 0;
		}
		c->seen[ki] = 1;
		return preset_key_set(c, ki, value) == 0;
	}
	if (ki == -2) {
		preset_ctx_err(c, "unknown section [%s] (sections: skin, sebum, epidermis, dermis, subcutis, surface, "
		    "override.WL)", section);
		return 0;
	}
	char *list = preset_key_names(section);
	preset_ctx_err(c, "unknown key '%s' in [%s] (keys: %s)", name, section, list);
	free(list);
	return 0;
}

static int on_section(void *user, const char *section)
{
	struct preset_ctx *c = user;
	return c->err == NULL && preset_section_check(c, section) == 0;
}

/* Parse text into c->p (already holding defaults); 0 or -1 with c->err. */
static int parse_text(struct preset_ctx *c, const char *text)
{
	int rc = inifile_parse(&c->in, c->origin, text, handler, on_section, c);
	if (c->in.error && (c->err == NULL || c->in.bad_header < c->err_line)) {
		free(c->err);
		c->err = c->in.error;
		c->err_line = c->in.bad_header;
		c->in.error = NULL;
	} else if (c->in.too_long && (c->err == NULL || c->in.too_long < c->err_line)) {
		free(c->err);
		c->err = NULL;
		c->in.line = c->in.too_long;
		preset_ctx_err(c, "line %d is longer than %d characters", c->in.too_long, c->in.max_line);
	} else if (rc > 0 && (c->err == NULL || rc < c->err_line)) {
		free(c->err);
		c->err = NULL;
		c->in.line = rc;
		preset_ctx_err(c, "syntax error (expected '[section]', 'key = value' or a ';' or '#' comment)");
	} else if (rc < 0 && c->err == NULL) {
		c->in.line = 0;
		preset_ctx_err(c, "libinih failed (code %d)", rc);
	}
	free(c->in.error);
	c->in.error = NULL;
	return c->err ? -1 : 0;
}

/* A name or description made from a file name must obey the rules of one
 * given in the file (preset_to_ini writes it out): at most max characters,
 * no comment or control characters, no white space at the ends (the reader
 * strips it), and for a name only [A-Za-z0-9._-]. */
static void fit_text(char *s, size_t max, int name)
{
	if (strlen(s) > max)
		s[max] = '\0';
	for (char *q = s; *q; q++) {
		int ok_name = (*q >= 'a' && *q <= 'z') || (*q >= 'A' && *q <= 'Z') || (*q >= '0' && *q <= '9') ||
		    *q == '.' || *q == '_' || *q == '-';
		if (*q == ';' || *q == '#' || (unsigned char)*q < 0x20 || *q == 0x7f || (name && !ok_name))
			*q = '_';
	}
	size_t n = strlen(s), lead = strspn(s, " ");
	while (n > lead && s[n - 1] == ' ')
		n--;
	memmove(s, s + lead, n - lead);
	s[n - lead] = '\0';
}

static const char *base_name(const char *path)
{
	const char *s = strrchr(path, '/');
	return s ? s + 1 : path;
}

static struct skin_params *preset_load_base(const char *name, int depth, char **cause);

/* Parse text; builtin >= 0 names a built-in preset (its name and summary
 * are the defaults for name and description). */
static struct skin_params *load_text(const char *text, const char *origin, int builtin, int depth,
    char **cause)
{
	struct skin_params *p = xcalloc(1, sizeof *p);
	struct preset_ctx c = { .origin = origin, .p = p, .depth = depth, .load_base = preset_load_base };
	preset_apply_defaults(p);
	c.ov_seen = xcalloc(1, 1);
	if (parse_text(&c, text) != 0) {
		*cause = c.err;
		free(c.ov_seen);
		preset_free(p);
		return NULL;
	}
	free(c.ov_seen);
	if (!c.name_set) {
		free(p->name);
		if (builtin >= 0)
			p->name = xstrdup(preset_name(builtin));
		else {
			char *n = xstrdup(base_name(origin));
			size_t len = strlen(n);
			if (len > 4 && strcmp(n + len - 4, ".ini") == 0)
				n[len - 4] = '\0';
			fit_text(n, 64, 1);
			if (*n == '\0') {
				free(n);
				n = xstrdup("preset");
			}
			p->name = n;
		}
	}
	if (!c.desc_set) {
		free(p->description);
		if (builtin >= 0)
			p->description = xstrdup(preset_summary(builtin));
		else {
			p->description = xasprintf("preset file %s", origin);
			fit_text(p->description, 160, 0);
		}
	}
	free(p->origin);
	p->origin = xstrdup(builtin >= 0 ? "built-in" : origin);
	/* A tables preset defaults to all of its tabulated wavelengths. */
	if (p->model == SKIN_MODEL_TABLES && !c.wl_set) {
		p->n_wl = p->n_override < SKIN_MAX_WL ? p->n_override : SKIN_MAX_WL;
		for (int i = 0; i < p->n_wl; i++)
			p->wl[i] = p->override[i].wl;
	}
	char *why = NULL;
	if (tissue_check(p, &why) != 0) {
		*cause = xasprintf("%s: %s", origin, why);
		free(why);
		preset_free(p);
		return NULL;
	}
	return p;
}

static struct skin_params *preset_load_base(const char *name, int depth, char **cause)
{
	int i = preset_find(name);
	if (i < 0) {
		char *list = builtin_names();
		*cause = xasprintf("unknown preset '%s' (presets: %s)", name, list);
		free(list);
		return NULL;
	}
	char *origin = xasprintf("built-in preset %s", preset_name(i));
	struct skin_params *p = load_text(builtin_presets[i].ini, origin, i, depth, cause);
	free(origin);
	return p;
}

struct skin_params *preset_load_builtin(const char *name, char **cause)
{
	return preset_load_base(name, 0, cause);
}

struct skin_params *preset_load_string(const char *text, const char *origin, char **cause)
{
	return load_text(text, origin, -1, 0, cause);
}

struct skin_params *preset_load_file(const char *path, char **cause)
{
	FILE *fp = fopen(path, "rb");
	if (fp == NULL) {
		*cause = xasprintf("cannot open %s: %s", path, strerror(errno));
		return NULL;
	}
	char *buf = xmalloc(MAX_FILE_BYTES + 1);
	size_t n = fread(buf, 1, MAX_FILE_BYTES + 1, fp);
	int bad = ferror(fp);
	fclose(fp);
	struct skin_params *p = NULL;
	if (bad)
		*cause = xasprintf("cannot read %s: %s", path, strerror(errno ? errno : EIO));
	else if (n > MAX_FILE_BYTES)
		*cause = xasprintf("%s: larger than %d bytes; not a preset file", path, MAX_FILE_BYTES);
	else if (memchr(buf, '\0', n) != NULL)
		*cause = xasprintf("%s: contains NUL bytes; not a preset file", path);
	else {
		buf[n] = '\0';
		p = load_text(buf, path, -1, 0, cause);
	}
	free(buf);
	return p;
}

void preset_free(struct skin_params *p)
{
	if (p == NULL)
		return;
	preset_free_contents(p);
	free(p);
}

int preset_count(void)
{
	return builtin_preset_count;
}

const char *preset_name(int i)
{
	return i >= 0 && i < preset_count() ? builtin_presets[i].name : NULL;
}

const char *preset_summary(int i)
{
	return i >= 0 && i < preset_count() ? builtin_presets[i].summary : NULL;
}

const char *preset_builtin_text(int i)
{
	return i >= 0 && i < preset_count() ? builtin_presets[i].ini : NULL;
}

int preset_find(const char *name)
{
	for (int i = 0; i < preset_count(); i++)
		if (strcmp(builtin_presets[i].name, name) == 0)
			return i;
	return -1;
}

int preset_default_wavelengths(const struct skin_params *p, double *wl_nm, int max)
{
	int n = p->n_wl < max ? p->n_wl : max;
	for (int i = 0; i < n; i++)
		wl_nm[i] = p->wl[i];
	return n;
}

double preset_surface_ior(const struct skin_params *p)
{
	if (tissue_layer_present(p, SKIN_SEBUM))
		return p->layer[SKIN_SEBUM].n;
	double n = p->layer[SKIN_EPIDERMIS].n;
	return isnan(n) ? spectra_n_epidermis(550.0) : n;
}

double preset_surface_roughness(const struct skin_params *p)
{
	if (p->roughness_top > 0.0)
		return p->roughness_top;	/* one surface for the lobe and the transport */
	return tissue_layer_present(p, SKIN_SEBUM) ? p->roughness_sebum : p->roughness_skin;
}

const char *preset_get_name(const struct skin_params *p)
{
	return p->name;
}

/* Numeric key "section.name": 0 and its table row, or -1. */
static int number_key(const char *key, struct preset_key_info *ki)
{
	const char *dot = strchr(key, '.');
	if (dot == NULL || (size_t)(dot - key) >= 32)
		return -1;
	char sec[32];
	memcpy(sec, key, (size_t)(dot - key));
	sec[dot - key] = '\0';
	int i = preset_key_find(sec, dot + 1);
	if (i < 0)
		return -1;
	preset_key_info(i, ki);
	return ki->numeric ? 0 : -1;
}

int preset_number_key(const char *key, double *lo, double *hi, const char **unit, char **cause)
{
	struct preset_key_info ki;
	if (number_key(key, &ki) != 0) {
		char *list = xstrdup("");
		for (int j = 0; j < preset_key_count(); j++) {
			preset_key_info(j, &ki);
			if (!ki.numeric)
				continue;
			char *t = xasprintf("%s%s%s.%s", list, *list ? ", " : "", ki.section, ki.name);
			free(list);
			list = t;
		}
		*cause = xasprintf("'%s' is not a numeric preset key (one of %s)", key, list);
		free(list);
		return -1;
	}
	*lo = ki.lo;
	*hi = ki.hi;
	if (unit)
		*unit = ki.unit;
	return 0;
}

int preset_set_number(struct skin_params *p, const char *key, double v, char **cause)
{
	struct preset_key_info ki;
	double lo, hi;
	if (preset_number_key(key, &lo, &hi, NULL, cause) != 0)
		return -1;
	number_key(key, &ki);
	if (!(v >= lo && v <= hi)) {
		*cause = xasprintf("%s = %g: out of range [%g, %g]%s%s", key, v, lo, hi, *ki.unit ? " " : "", ki.unit);
		return -1;
	}
	char *base = ki.layer < 0 ? (char *)p : (char *)&p->layer[ki.layer];
	*(double *)(base + ki.off) = v;
	return 0;
}

int preset_get_number(const struct skin_params *p, const char *key, double *v)
{
	struct preset_key_info ki;
	if (number_key(key, &ki) != 0)
		return -1;
	const char *base = ki.layer < 0 ? (const char *)p : (const char *)&p->layer[ki.layer];
	*v = *(const double *)(base + ki.off);
	return 0;
}

int preset_parse_wavelengths(const char *s, double *wl, char **cause)
{
	int n = 0;
	if (preset_wavelengths_parse(s, wl, &n, cause) != 0)
		return -1;
	return n;
}
