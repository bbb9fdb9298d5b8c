/* preset_ini: the resolved parameters as preset INI text (preset_to_ini)
 * and the key listing of `skinbake preset keys`, both from the key table of
 * preset_keys.c. */
#include "config.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "skin/preset.h"
#include "skin/preset_keys.h"

#define N_KEYS preset_key_count()

/* Append printf output to *s. */
static void cat(char **s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void cat(char **s, const char *fmt, ...)
{
	va_list ap;
	char *m;
	va_start(ap, fmt);
	if (vasprintf(&m, fmt, ap) < 0)
		fatalx("out of memory");
	va_end(ap);
	char *t = xasprintf("%s%s", *s, m);
	free(*s);
	free(m);
	*s = t;
}

/* Wavelength list with uniform runs of 3 or more written as ranges. */
static void cat_wavelengths(char **s, const double *wl, int n)
{
	for (int i = 0; i < n;) {
		int j = i + 1;
		double st = j < n ? wl[j] - wl[i] : 0.0;
		while (j + 1 < n && fabs((wl[j + 1] - wl[j]) - st) < 1e-9)
			j++;
		if (j - i >= 2) {
			cat(s, "%s%.15g:%.15g:%.15g", i ? ", " : "", wl[i], wl[j], st);
			i = j + 1;
		} else {
			cat(s, "%s%.15g", i ? ", " : "", wl[i]);
			i++;
		}
	}
}

char *preset_to_ini(const struct skin_params *p)
{
	char *s = xasprintf("; skinbake preset (resolved)\n");
	const char *sec = "";
	for (int i = 0; i < N_KEYS; i++) {
		const struct preset_key *k = &preset_key_table[i];
		if (k->kind == K_BASE)
			continue;
		if (strcmp(sec, k->section) != 0) {
			cat(&s, "%s[%s]\n", *sec ? "\n" : "", k->section);
			sec = k->section;
		}
		const char *base = k->layer < 0 ? (const char *)p : (const char *)&p->layer[k->layer];
		double x = *(const double *)(base + k->off);
		if (k->kind == K_ROUGH && x == 0.0)
			continue;	/* smooth: the text of presets from before roughness */
		switch (k->kind) {
		case K_TEXT:
			cat(&s, "%s = %s\n", k->name, *(char *const *)(base + k->off));
			break;
		case K_MODEL:
			cat(&s, "%s = %s\n", k->name, p->model == SKIN_MODEL_TABLES ? "tables" : "chromophores");
			break;
		case K_WL:
			cat(&s, "%s = ", k->name);
			cat_wavelengths(&s, p->wl, p->n_wl);
			cat(&s, "\n");
			break;
		default:
			if (isinf(x))
				cat(&s, "%s = inf\n", k->name);
			else if (isnan(x))
				cat(&s, "%s = %s\n", k->name, k->kind == K_IOR ? "ding2006" : "vangemert1989");
			else
				cat(&s, "%s = %.15g\n", k->name, x);
			break;
		}
	}
	for (int i = 0; i < p->n_override; i++) {
		const struct skin_override *o = &p->override[i];
		cat(&s, "\n[override.%.15g]\n", o->wl);
		for (int l = 0; l < SKIN_N_LAYERS; l++) {
			const double *v[OV_N_PROPS] = { o->mu_a, o->mu_s, o->g, o->n };
			for (int j = 0; j < OV_N_PROPS; j++)
				if (!isnan(v[j][l]))
					cat(&s, "%s.%s = %.15g\n", tissue_layer_name(l), preset_ov_props[j].name, v[j][l]);
		}
	}
	return s;
}

void preset_print_keys(FILE *fp)
{
	fprintf(fp, "%-28s %-6s %-14s %-20s %s\n", "key", "unit", "default", "range", "meaning");
	for (int i = 0; i < N_KEYS; i++) {
		const struct preset_key *k = &preset_key_table[i];
		char full[64], rng[64];
		snprintf(full, sizeof full, "%s.%s", k->section, k->name);
		if (k->kind == K_NUM || k->kind == K_ROUGH || k->kind == K_LEN || k->kind == K_IOR || k->kind == K_ANISO)
			snprintf(rng, sizeof rng, "[%g, %g]%s", k->lo, k->hi, k->kind == K_LEN ? " | inf" : "");
		else if (k->kind == K_WL)
			snprintf(rng, sizeof rng, "[%g, %g]", k->lo, k->hi);
		else if (k->kind == K_MODEL)
			snprintf(rng, sizeof rng, "chromophores|tables");
		else if (k->kind == K_BASE)
			snprintf(rng, sizeof rng, "built-in name");
		else
			snprintf(rng, sizeof rng, "<= %g chars", k->hi);
		fprintf(fp, "%-28s %-6s %-14s %-20s %s\n", full, *k->unit ? k->unit : "-", *k->dflt ? k->dflt : "-",
		    rng, k->doc);
	}
	for (int j = 0; j < OV_N_PROPS; j++) {
		char full[64], rng[64];
		snprintf(full, sizeof full, "override.WL:LAYER.%s", preset_ov_props[j].name);
		snprintf(rng, sizeof rng, "[%g, %g]", preset_ov_props[j].lo, preset_ov_props[j].hi);
		fprintf(fp, "%-28s %-6s %-14s %-20s %s at wavelength WL [nm] (replaces the computed value)\n", full,
		    *preset_ov_props[j].unit ? preset_ov_props[j].unit : "-", "-", rng, preset_ov_props[j].doc);
	}
}
