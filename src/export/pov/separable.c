/* separable: fit the separable fallback (aoi pigment x brilliance) to a BRDF
 * and write it. */
#include "config.h"

#include "export/pov/separable.h"

#include <math.h>
#include <stdlib.h>

#include "base/util.h"
#include "export/pov/sdl.h"

/* Squared error of the separable model with brilliance b; fills a[][]
 * (the optimal pigment for that b, in closed form per theta_o node and
 * channel) and the target's squared norm. */
#define SEP_NI 24
/* Fit and error over theta_i, theta_o <= 80 degrees: toward grazing the
 * specular lobe grows without bound (1/cos) and would decide everything,
 * while it covers only silhouettes and terminators in an image. */
#define SEP_TMAX (80 * M_PI / 180)
#define SEP_NP 24
static double sep_error(const double *t, double b, double a[SEPARABLE_NODES][3], double *norm, double *mean_rel)
{
	double err = 0, tn = 0, ea = 0, ta = 0;
	for (int m = 0; m < SEPARABLE_NODES; m++) {
		double to = (M_PI / 2) * m / (SEPARABLE_NODES - 1), wo = fmax(sin(to), 1e-3);
		for (int c = 0; c < 3; c++) {
			double num = 0, den = 0;
			for (int i = 0; i < SEP_NI; i++) {
				double ti = (i + 0.5) * SEP_TMAX / SEP_NI, ci = cos(ti), w = sin(ti), cb = pow(ci, b);
				for (int p = 0; p < SEP_NP; p++) {
					double tv = t[((m * SEP_NI + i) * SEP_NP + p) * 3 + c];
					num += w * tv * cb;
					den += w * cb * cb;
				}
			}
			a[m][c] = num / den;
			for (int i = 0; i < SEP_NI; i++) {
				double ti = (i + 0.5) * SEP_TMAX / SEP_NI, ci = cos(ti), w = sin(ti) * wo * (to <= SEP_TMAX);
				for (int p = 0; p < SEP_NP; p++) {
					double tv = t[((m * SEP_NI + i) * SEP_NP + p) * 3 + c], d = a[m][c] * pow(ci, b) - tv;
					err += w * d * d;
					tn += w * tv * tv;
					ea += w * fabs(d);
					ta += w * fabs(tv);
				}
			}
		}
	}
	*norm = tn;
	*mean_rel = ta > 0 ? ea / ta : 0;
	return err;
}

void separable_fit(const struct pov_brdf *f, struct pov_separable *out)
{
	/* Target pi f cos(theta_i) on a grid over both hemispheres, weighted
	 * by solid angle (sin theta_i sin theta_o). */
	double *t = xmalloc(sizeof(double) * SEPARABLE_NODES * SEP_NI * SEP_NP * 3);
	for (int m = 0; m < SEPARABLE_NODES; m++)
		for (int i = 0; i < SEP_NI; i++)
			for (int p = 0; p < SEP_NP; p++) {
				double to = (M_PI / 2) * m / (SEPARABLE_NODES - 1), ti = (i + 0.5) * SEP_TMAX / SEP_NI;
				double dp = (p + 0.5) * M_PI / SEP_NP, rgb[3];
				f->f_rgb(f->ctx, ti, to, dp, rgb);
				for (int c = 0; c < 3; c++)
					t[((m * SEP_NI + i) * SEP_NP + p) * 3 + c] = M_PI * rgb[c] * cos(ti);
			}
	/* Golden-section search for the brilliance. */
	double lo = 0.3, hi = 4.0, gr = 0.5 * (sqrt(5) - 1), norm, mr;
	double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
	double e1 = sep_error(t, x1, out->a, &norm, &mr), e2 = sep_error(t, x2, out->a, &norm, &mr);
	for (int it = 0; it < 40; it++) {
		if (e1 < e2) {
			hi = x2;
			x2 = x1;
			e2 = e1;
			x1 = hi - gr * (hi - lo);
			e1 = sep_error(t, x1, out->a, &norm, &mr);
		} else {
			lo = x1;
			x1 = x2;
			e1 = e2;
			x2 = lo + gr * (hi - lo);
			e2 = sep_error(t, x2, out->a, &norm, &mr);
		}
	}
	out->brilliance = 0.5 * (lo + hi);
	double e = sep_error(t, out->brilliance, out->a, &norm, &out->mean);
	out->rms = norm > 0 ? sqrt(e / norm) : 0;
	free(t);
}

void separable_write(FILE *fp, const char *name, const struct pov_separable *sep)
{
	fprintf(fp, "#declare %s = pigment { // separable fit: brilliance %.4f, mean error %.1f %%, rms %.1f %%\n"
	    " aoi color_map {", name, sep->brilliance, 100 * sep->mean, 100 * sep->rms);
	for (int k = 0; k < SEPARABLE_NODES; k++) {
		int m = SEPARABLE_NODES - 1 - k;
		double to = (M_PI / 2) * m / (SEPARABLE_NODES - 1);
		sdl_aoi_entry(fp, k == 0, to, sep->a[m]);
	}
	fputs(" }\n}\n", fp);
}
