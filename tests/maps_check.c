/* maps_check: test and benchmark helper for parameter maps (not a test by
 * itself; tests/maps_cli.sh, scripts/bench-maps.sh and the showcase use it).
 *
 *   maps_check synth FAM OUT W H [SEED]
 *       made-up maps for family FAM: smooth fields over most of each
 *       axis' range (sums of two sines in the axis' coordinate) plus
 *       freckles (small discs of 2.5 times the melanin, when an axis is
 *       epidermis.melanin), written as a maps directory OUT.
 *   maps_check compare FAM TRUE FIT ALBEDO_TRUE ALBEDO_REFIT [SENS]
 *       the round trip: CIEDE2000 between the two albedo images (as the
 *       fit reads them) and, per parameter, the relative error of the
 *       fitted maps FIT against TRUE over the texels where the colour is
 *       sensitive to it (a 5 % change of the parameter moves the albedo by
 *       at least SENS CIEDE2000, default 0.5), and the share of texels
 *       that are not.  Prints "key value" lines.
 *   maps_check offnode FAM KEY=V[,KEY=V...]
 *       a direct bake of FAM's settings at an off-node parameter point
 *       against family_bake_at there: the solid-angle-weighted RMS relative
 *       difference of the tables, and the family's own error.
 *   maps_check swatch FILE.exr R G B [R G B ...]
 *       a 1-pixel-high linear EXR of the given colours.
 *   maps_check noise IN.png OUT.png AMP [SEED]
 *       IN (a 16-bit RGB PNG) with uniform noise of +-AMP 16-bit levels
 *       added to each channel (clamped), as a 16-bit PNG: with AMP of a
 *       few dozen nearly every texel is a distinct colour, the fit's
 *       worst case (scripts/bench-maps.sh).
 *   maps_check fit-memory FAM ALBEDO OUT png|exr [MASK]
 *       maps fit's defaults (max-de 2.5, input by the file's kind) by the
 *       in-memory path: the images read whole, maps_fit, mapset_write;
 *       for tests/maps_stream.sh, which holds the streamed files to it.
 *   maps_check fit-reread FAM ALBEDO OUT png|exr [MASK]
 *       the same by maps_fit_files with the albedo read a second time for
 *       the maps (o.reread, as for albedos beyond MAPS_FIT_IDS_MAX).
 *   maps_check values MAPS
 *       per texel of a 1-pixel-high maps directory: its index, each map's
 *       value and the fit's CIEDE2000 ("i v0 v1 ... de").
 *   maps_check spectra TABLE.tsv OUT.exr [R0]
 *       measured reflectance spectra (a column of wavelengths [nm], then
 *       one column per spectrum; '#' lines are comments), less R0 (a
 *       surface reflection a d/8 instrument includes, 0 by default, floored
 *       at 0.001), as a 1-pixel-high
 *       linear sRGB EXR (CIE 1931 2-degree, D65, white = 1), one texel per
 *       spectrum; prints per spectrum its CIELAB D65/10-degree, ITA and the
 *       Fitzpatrick type of its ITA class (Chardon 1991, Del Bino 2013:
 *       > 55 I, 41-55 II, 28-41 III, 10-28 IV, -30-10 V, < -30 VI). */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "family/family.h"
#include "base/srgb.h"
#include "base/util.h"
#include "maps/fit.h"
#include "maps/image.h"
#include "maps/mapset.h"
#include "skin/colour.h"
#include "skin/preset.h"

static struct family *fam(const char *dir)
{
	char *cause = NULL;
	struct family *f = family_load(dir, &cause);
	if (f == NULL)
		fatalx("%s", cause);
	family_albedo_prepare(f);
	return f;
}

static int synth(int argc, char **argv)
{
	if (argc < 6)
		fatalx("usage: maps_check synth FAM OUT W H [SEED]");
	struct family *f = fam(argv[2]);
	int w = atoi(argv[4]), h = atoi(argv[5]);
	unsigned long seed = argc > 6 ? strtoul(argv[6], NULL, 10) : 1;
	struct mapset *m = mapset_new(f, w, h, NULL);
	for (int a = 0; a < f->n_axes; a++) {
		const struct family_axis *ax = &f->axis[a];
		double c0 = family_axis_coord(ax, ax->node[0]);
		double c1 = family_axis_coord(ax, ax->node[ax->n - 1]);
		double mid = 0.5 * (c0 + c1);
		double half = 0.5 * (c1 - c0);
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				double u = (double)x / w, v = (double)y / h, p = 1.7 * a + 0.3;
				double s = 0.55 * sin(2 * M_PI * ((0.8 + 0.3 * a) * u + (0.5 - 0.2 * a) * v) + p) +
				    0.35 * cos(2 * M_PI * ((1.6 - 0.4 * a) * v - 0.7 * u) + 2 * p);
				m->p[a].v[(size_t)y * w + x] = (float)family_axis_value(ax, mid + 0.92 * half * s);
			}
	}
	int mel = mapset_find(m, "epidermis.melanin");
	if (mel >= 0) {
		const struct family_axis *ax = &f->axis[mel];
		int n = w * h / 400 + 1;
		for (int k = 0; k < n; k++) {
			seed = seed * 6364136223846793005UL + 1442695040888963407UL;
			double cx = (double)(seed >> 33) / (1UL << 31) * w;
			seed = seed * 6364136223846793005UL + 1442695040888963407UL;
			double cy = (double)(seed >> 33) / (1UL << 31) * h, r = 1.0 + 0.015 * w * ((seed >> 20) & 255) / 255.0;
			for (int y = (int)(cy - r); y <= (int)(cy + r); y++)
				for (int x = (int)(cx - r); x <= (int)(cx + r); x++) {
					if (x < 0 || y < 0 || x >= w || y >= h || hypot(x - cx, y - cy) > r)
						continue;
					float *v = &m->p[mel].v[(size_t)y * w + x];
					*v = (float)fmin(*v * 2.5, ax->node[ax->n - 1]);
				}
		}
	}
	mapset_add_history(m, "maps_check synth (made-up smooth fields plus freckles)");
	char *cause = NULL;
	if (mapset_write(argv[3], m, &cause) != 0)
		fatalx("%s", cause);
	mapset_free(m);
	family_free(f);
	return 0;
}

static void lab_at(const struct family *f, const double *x, double lab[3])
{
	double rgb[3];
	family_albedo(f, x, NULL, rgb, NULL);
	colour_linear_srgb_to_lab(rgb, lab);
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static double pct(double *v, long n, double p)
{
	if (n == 0)
		return 0.0;
	qsort(v, (size_t)n, sizeof *v, cmp_double);
	long i = (long)floor(p * (n - 1) + 0.5);
	return v[i];
}

static int compare(int argc, char **argv)
{
	if (argc < 7)
		fatalx("usage: maps_check compare FAM TRUE FIT ALBEDO_TRUE ALBEDO_REFIT [SENS]");
	struct family *f = fam(argv[2]);
	char *cause = NULL;
	struct mapset *mt = mapset_read(argv[3], &cause), *mf = mt ? mapset_read(argv[4], &cause) : NULL;
	struct image *at = mf ? image_read(argv[5], &cause) : NULL, *ar = at ? image_read(argv[6], &cause) : NULL;
	if (ar == NULL)
		fatalx("%s", cause);
	double sens = argc > 7 ? atof(argv[7]) : 0.5;
	long n = (long)mt->w * mt->h;
	double *de = xmalloc(sizeof(double) * (size_t)n), *err = xmalloc(sizeof(double) * (size_t)n);
	for (long i = 0; i < n; i++) {
		double r1[3], r2[3], l1[3], l2[3];
		maps_texel_linear(at, (size_t)i, at->bits == 32, r1);
		maps_texel_linear(ar, (size_t)i, ar->bits == 32, r2);
		colour_linear_srgb_to_lab(r1, l1);
		colour_linear_srgb_to_lab(r2, l2);
		de[i] = colour_de2000(l1, l2);
	}
	printf("texels %ld\nde2000_median %.4f\nde2000_p95 %.4f\nde2000_max %.4f\n", n, pct(de, n, 0.5), pct(de, n, 0.95),
	    pct(de, n, 1.0));
	for (int a = 0; a < f->n_axes; a++) {
		long ns = 0, within = 0;
		for (long i = 0; i < n; i++) {
			double x[FAMILY_MAX_AXES], x2[FAMILY_MAX_AXES], l1[3], l2[3];
			for (int b = 0; b < f->n_axes; b++)
				x[b] = x2[b] = mt->p[b].v[i];
			const struct family_axis *ax = &f->axis[a];
			x2[a] = x[a] * 1.05 <= ax->node[ax->n - 1] ? x[a] * 1.05 : x[a] / 1.05;
			lab_at(f, x, l1);
			lab_at(f, x2, l2);
			if (colour_de2000(l1, l2) < sens)
				continue;
			double e = fabs(mf->p[a].v[i] / mt->p[a].v[i] - 1.0);
			err[ns++] = e;
			within += e <= 0.05;
		}
		printf("%s_sensitive_share %.4f\n%s_within_5pct_share %.4f\n%s_relerr_median %.5f\n%s_relerr_p99 %.5f\n"
		    "%s_relerr_max %.5f\n", f->axis[a].key, (double)ns / n, f->axis[a].key, ns ? (double)within / ns : 1.0,
		    f->axis[a].key, pct(err, ns, 0.5), f->axis[a].key, pct(err, ns, 0.99), f->axis[a].key, pct(err, ns, 1.0));
	}
	free(de);
	free(err);
	image_free(at);
	image_free(ar);
	mapset_free(mt);
	mapset_free(mf);
	family_free(f);
	return 0;
}

static int offnode(int argc, char **argv)
{
	if (argc < 4)
		fatalx("usage: maps_check offnode FAM KEY=V[,KEY=V...]");
	struct family *f = fam(argv[2]);
	char *cause = NULL;
	if (family_load_tables(f, &cause) != 0)
		fatalx("%s", cause);
	double x[FAMILY_MAX_AXES];
	for (int a = 0; a < f->n_axes; a++)
		x[a] = f->axis[a].node[0];
	char *spec = xstrdup(argv[3]), *save = NULL;
	for (char *t = strtok_r(spec, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		char *eq = strchr(t, '=');
		if (eq == NULL)
			fatalx("'%s' is not KEY=V", t);
		*eq = '\0';
		int a = -1;
		for (int b = 0; b < f->n_axes; b++)
			if (strcmp(f->axis[b].key, t) == 0)
				a = b;
		if (a < 0)
			fatalx("%s is not an axis", t);
		x[a] = atof(eq + 1);
	}
	free(spec);
	struct skin_params *base = preset_load_string(f->preset_ini, "family preset.ini", &cause);
	struct skin_params *p = base ? family_params(base, f->axis, f->n_axes, x, &cause) : NULL;
	struct bake_spec *s = f->spec;
	if (p == NULL || bake_spec_layers(s, p, "direct", &cause) != 0)
		fatalx("%s", cause);
	struct bake_result r;
	if (bake_run(s, &r, &cause) != 0)
		fatalx("%s", cause);
	struct bake *bi = family_bake_at(f, x);
	/* The table difference weighted as brdf_table_rms weighs errors. */
	double num = 0, den = 0, amax = 0;
	size_t npx = (size_t)s->n_ti * s->n_to * s->n_phi;
	for (int w = 0; w < s->n_wl; w++)
		for (int ti = 0; ti < s->n_ti; ti++) {
			const struct brdf_entry *e = &r.table.entry[w * s->n_ti + ti];
			for (int to = 0; to < s->n_to; to++) {
				double om = cos(M_PI / 2 * to / s->n_to) - cos(M_PI / 2 * (to + 1) / s->n_to);
				for (int ph = 0; ph < s->n_phi; ph++) {
					double d = e->fr[to * s->n_phi + ph], v = bi->fr[w * npx + ((size_t)ti * s->n_to + to) * s->n_phi + ph];
					num += om * (v - d) * (v - d) / (d * d);
					den += om;
				}
			}
			double ai = bi->albedo[w * s->n_ti + ti], ad = e->albedo.v;
			amax = fmax(amax, fabs(ai / ad - 1));
		}
	printf("table_rms_rel_diff %.5f\nalbedo_max_rel_diff %.5f\nfamily_rms_rel_err %.5f\ndirect_rms_rel_err %.5f\n",
	    sqrt(num / den), amax, f->rms_rel_err, r.table.rms_rel_err);
	bake_result_free(&r);
	bake_free(bi);
	preset_free(p);
	preset_free(base);
	family_free(f);
	return 0;
}

static int swatch(int argc, char **argv)
{
	if (argc < 6 || (argc - 3) % 3 != 0)
		fatalx("usage: maps_check swatch FILE.exr R G B [R G B ...]");
	int n = (argc - 3) / 3;
	struct image *im = image_new(n, 1, 3, 32);
	for (int i = 0; i < 3 * n; i++)
		im->v[i] = (float)atof(argv[3 + i]);
	const char *names[] = { "R", "G", "B" };
	char *cause = NULL;
	if (image_write_exr(argv[2], im, names, 0, NULL, &cause) != 0)
		fatalx("%s", cause);
	image_free(im);
	return 0;
}

static int spectra(int argc, char **argv)
{
	if (argc < 4)
		fatalx("usage: maps_check spectra TABLE.tsv OUT.exr [R0]");
	double r0 = argc > 4 ? atof(argv[4]) : 0.0;
	FILE *fp = fopen(argv[2], "r");
	if (fp == NULL)
		fatalx("cannot read %s", argv[2]);
	enum { MAXS = 16, MAXW = 128 };
	double wl[MAXW], r[MAXS][MAXW];
	int nw = 0, ns = -1;
	char line[4096];
	while (fgets(line, sizeof line, fp) && nw < MAXW) {
		if (line[0] == '#')
			continue;
		char *p = line, *e;
		double v = strtod(p, &e);
		if (e == p)
			continue;	/* the header row */
		wl[nw] = v;
		int k = 0;
		for (p = e; k < MAXS; k++, p = e) {
			v = strtod(p, &e);
			if (e == p)
				break;
			r[k][nw] = fmax(v - r0, r0 > 0 ? 0.001 : v);
		}
		if (ns >= 0 && k != ns)
			fatalx("%s: row %d has %d spectra, expected %d", argv[2], nw, k, ns);
		ns = k;
		nw++;
	}
	fclose(fp);
	struct image *im = image_new(ns, 1, 3, 32);
	double w2[3], w10[3], wr[3];
	colour_white_xyz(COLOUR_CIE1931_2DEG, w2);
	colour_xyz_to_linear_srgb(w2, wr);
	colour_white_xyz(COLOUR_CIE1964_10DEG, w10);
	for (int k = 0; k < ns; k++) {
		double xyz[3], rgb[3], lab[3];
		colour_spectrum_xyz(COLOUR_CIE1931_2DEG, nw, wl, r[k], xyz);
		colour_xyz_to_linear_srgb(xyz, rgb);
		for (int c = 0; c < 3; c++)
			im->v[3 * k + c] = (float)(rgb[c] / wr[c]);
		colour_spectrum_xyz(COLOUR_CIE1964_10DEG, nw, wl, r[k], xyz);
		colour_xyz_to_lab(xyz, w10, lab);
		double ita = colour_ita(lab);
		int type = ita > 55 ? 1 : ita > 41 ? 2 : ita > 28 ? 3 : ita > 10 ? 4 : ita > -30 ? 5 : 6;
		printf("%d %.2f %.2f %.2f %.1f %d\n", k, lab[0], lab[1], lab[2], ita, type);
	}
	const char *names[] = { "R", "G", "B" };
	char *cause = NULL;
	if (image_write_exr(argv[3], im, names, 0, NULL, &cause) != 0)
		fatalx("%s", cause);
	image_free(im);
	return 0;
}

static int noise(int argc, char **argv)
{
	if (argc < 5)
		fatalx("usage: maps_check noise IN.png OUT.png AMP [SEED]");
	char *cause = NULL;
	struct image *im = image_read(argv[2], &cause);
	if (im == NULL)
		fatalx("%s", cause);
	int amp = atoi(argv[4]);
	unsigned long seed = argc > 5 ? strtoul(argv[5], NULL, 10) : 1;
	size_t n = (size_t)im->w * im->h * im->nch;
	for (size_t i = 0; i < n; i++) {
		seed = seed * 6364136223846793005UL + 1442695040888963407UL;
		int d = (int)((seed >> 33) % (unsigned long)(2 * amp + 1)) - amp;
		long q = lround(im->v[i] * 65535.0) + d;
		im->v[i] = (float)((q < 0 ? 0 : q > 65535 ? 65535 : q) / 65535.0);
	}
	if (image_write_png(argv[3], im, 16, 0, 0, NULL, &cause) != 0)
		fatalx("%s", cause);
	image_free(im);
	return 0;
}

static int fit_memory(int argc, char **argv)
{
	if (argc < 6)
		fatalx("usage: maps_check fit-memory FAM ALBEDO OUT png|exr [MASK]");
	struct family *f = fam(argv[2]);
	char *cause = NULL;
	struct image *a = image_read(argv[3], &cause), *mk = NULL;
	if (a == NULL || (argc > 6 && (mk = image_read(argv[6], &cause)) == NULL))
		fatalx("%s", cause);
	struct maps_fit_opts o = { .input_linear = a->bits == 32, .max_de = 2.5, .threads = 0 };
	struct maps_fit_summary s;
	struct mapset *m;
	if (maps_fit(f, a, mk, &o, &m, &s, &cause) != 0)
		fatalx("%s", cause);
	m->fit = maps_fit_summary_json(&s, &o, argv[3]);
	m->exr = strcmp(argv[5], "exr") == 0;
	mapset_add_history(m, "maps_check fit-memory");
	if (mapset_write(argv[4], m, &cause) != 0)
		fatalx("%s", cause);
	mapset_free(m);
	image_free(a);
	image_free(mk);
	family_free(f);
	return 0;
}

static int fit_reread(int argc, char **argv)
{
	if (argc < 6)
		fatalx("usage: maps_check fit-reread FAM ALBEDO OUT png|exr [MASK]");
	struct family *f = fam(argv[2]);
	char *cause = NULL;
	struct maps_fit_opts o = { .input_linear = image_kind(argv[3], &cause) == IMAGE_EXR, .max_de = 2.5,
		.threads = 0, .reread = 1 };
	struct maps_fit_summary s;
	int input_error;
	if (maps_fit_files(f, argv[3], argc > 6 ? argv[6] : NULL, &o, argv[4], strcmp(argv[5], "exr") == 0,
	    "maps_check fit-reread", &s, &input_error, &cause) != 0)
		fatalx("%s", cause);
	family_free(f);
	return 0;
}

static int values(int argc, char **argv)
{
	if (argc != 3)
		fatalx("usage: maps_check values MAPS");
	char *cause = NULL;
	struct mapset *m = mapset_read(argv[2], &cause);
	if (m == NULL)
		fatalx("%s", cause);
	for (int i = 0; i < m->w; i++) {
		printf("%d", i);
		for (int a = 0; a < m->n; a++)
			printf(" %.5g", m->p[a].v[i]);
		printf(" %.4f\n", m->de2000 ? m->de2000[i] : -1.0);
	}
	mapset_free(m);
	return 0;
}

int main(int argc, char **argv)
{
	if (argc >= 2 && strcmp(argv[1], "values") == 0)
		return values(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "spectra") == 0)
		return spectra(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "synth") == 0)
		return synth(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "compare") == 0)
		return compare(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "offnode") == 0)
		return offnode(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "swatch") == 0)
		return swatch(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "noise") == 0)
		return noise(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "fit-memory") == 0)
		return fit_memory(argc, argv);
	if (argc >= 2 && strcmp(argv[1], "fit-reread") == 0)
		return fit_reread(argc, argv);
	fprintf(stderr, "usage: maps_check synth|compare|offnode|swatch|spectra|noise|fit-memory|fit-reread|values ...\n");
	return 2;
}
