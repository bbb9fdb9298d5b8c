/* povfar: the lit table blended with a rough copy of itself by the relief's
 * far roughness map (povfar.h). */
#include "config.h"

#include "export/pov/povfar.h"

#include <math.h>
#include <stdlib.h>

#include "io/pngio.h"
#include "base/util.h"

int povfar_read(const char *dir, uint16_t **out, int *n, char **cause)
{
	char *path = xasprintf("%s/roughness_far.png", dir);
	FILE *f = fopen(path, "rb");
	if (f == NULL) {
		free(path);
		return 0;
	}
	fclose(f);
	int w, h, ch, bits;
	uint16_t *px = pngio_read(path, &w, &h, &ch, &bits, cause);
	if (px == NULL) {
		free(path);
		return -1;
	}
	if (w != h || ch != 1 || bits != 16) {
		*cause = xasprintf("%s: %dx%d px, %d channel(s) of %d bits; a far roughness map is "
		    "square 16-bit gray", path, w, h, ch, bits);
		free(px);
		free(path);
		return -1;
	}
	*out = px;
	*n = w;
	free(path);
	return 1;
}

/* Overlap of [a, a + 1) with [b0, b1). */
static double overlap(double a, double b0, double b1)
{
	return fmax(0, fmin(a + 1, b1) - fmax(a, b0));
}

uint16_t *povfar_filter(const uint16_t *px, int n, int m, double *alpha_max)
{
	uint16_t *o = xmalloc(sizeof *o * (size_t)m * (size_t)m);
	double r = (double)n / m, mx = 0;
	for (int i = 0; i < m; i++)
		for (int j = 0; j < m; j++) {
			double s = 0, wsum = 0;
			for (int y = (int)floor(i * r); y < n && y < (int)ceil((i + 1) * r); y++)
				for (int x = (int)floor(j * r); x < n &&
				    x < (int)ceil((j + 1) * r); x++) {
					double w = overlap(y, i * r, (i + 1) * r)
					    * overlap(x, j * r, (j + 1) * r);
					double a = px[(size_t)y * n + x] / 65535.0;
					s += w * a * a;
					wsum += w;
				}
			double a = sqrt(s / wsum);
			mx = fmax(mx, a);
			o[(size_t)i * m + j] = (uint16_t)lround(fmin(a, 1) * 65535);
		}
	*alpha_max = mx;
	return o;
}

void povfar_brdf(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3])
{
	const struct pov_far *far = ctx;
	double L[3] = { sin(theta_i), 0, cos(theta_i) };
	double V[3] = { sin(theta_o) * cos(dphi), sin(theta_o) * sin(dphi), cos(theta_o) };
	double cos_g = L[0] * V[0] + L[1] * V[1] + L[2] * V[2], t = far->alpha_max;
	double sum[3] = { 0, 0, 0 };
	int seen = 0;
	for (int k = 0; k < POVFAR_RING; k++) {
		double b = 2 * M_PI * (k + 0.5) / POVFAR_RING, s = 1 / sqrt(1 + t * t);
		double m[3] = { -t * cos(b) * s, -t * sin(b) * s, s };
		double cl = L[0] * m[0] + L[1] * m[1] + L[2] * m[2];
		double cv = V[0] * m[0] + V[1] * m[1] + V[2] * m[2];
		if (cv <= 0)
			continue;	/* a facet the camera does not see */
		seen++;
		if (cl <= 0)
			continue;	/* a facet in its own shade */
		double ti = acos(fmin(cl, 1)), to = acos(fmin(cv, 1)), f[3];
		far->base->f_rgb(far->base->ctx, ti, to, littable_dphi(ti, to, cos_g), f);
		for (int c = 0; c < 3; c++)
			sum[c] += f[c] * cl;
	}
	/* Near grazing the ratio would blow up between the table's nodes. */
	double cn = fmax(cos(theta_i), 0.05);
	for (int c = 0; c < 3; c++)
		rgb[c] = seen > 0 ? sum[c] / (seen * cn) : 0;
}

int povfar_write_key(FILE *fp, const char *name, const struct pov_far *far,
    const struct pov_brdf *f, const struct pov_light *l, const struct pov_view *v,
    const double lo[3], const double hi[3], int n_theta, int n_gamma)
{
	int g = littable_write_key(fp, name, f, l, v, lo, hi, n_theta, n_gamma);
	if (far == NULL || !far->on)
		return g;
	struct pov_far fr = *far;
	fr.base = f;
	struct pov_brdf rough = {
		povfar_brdf, &fr, f->n_ti_hint, f->n_to_hint, f->ti_hint, f->to_hint
	};
	char *rn = xasprintf("%s_Rough", name);
	int g2 = littable_write_key(fp, rn, &rough, l, v, lo, hi, n_theta, n_gamma);
	double T = far->tile_units;
	fprintf(fp, "// The relief below a pixel: the table blended with its rough copy by "
	    "alpha_relief\n"
	    "// (roughness_far.png, one tile of %.6g units, projected along z; docs/relief.md).\n"
	    "#declare %s = pigment { image_pattern { png \"%s\" map_type 0 interpolate 2 }\n"
	    "  pigment_map { [0 %s scale %.9g] [%.6f %s scale %.9g] } scale %.9g }\n",
	    T, name, far->png, name, 1 / T, far->alpha_max, rn, 1 / T, T);
	free(rn);
	return g2 > g ? g2 : g;
}
