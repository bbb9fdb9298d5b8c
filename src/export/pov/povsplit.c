/* povsplit: the diffuse part of the skin under a relief smoothed by Rd(r)
 * (povsplit.h). */
#include "config.h"

#include "export/pov/povsplit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakefile.h"
#include "base/util.h"
#include "engine/microfacet_ms.h"
#include "engine/specular.h"

void povsplit_specular(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3])
{
	const struct povsplit_spec *sp = ctx;
	const struct bake *b = sp->b;
	if (sp->alpha == b->roughness) {	/* the bake's own lobe (with its macro roughness) */
		bake_eval_specular_rgb(b, theta_i, theta_o, dphi, rgb);
		return;
	}
	double ph = fmod(fabs(dphi), 2 * M_PI);
	ph = ph > M_PI ? 2 * M_PI - ph : ph;
	for (int c = 0; c < 3; c++)
		rgb[c] = 0.0;
	for (int w = 0; w < b->n_wl; w++) {
		double f = specular_ggx(&b->stack[w], sp->alpha, theta_i, theta_o, ph);
		/* The facets' later reflections (multiple scattering on the rough top,
		 * engine/microfacet_ms.h) at the bake's alpha, as eval adds them: the
		 * widened alpha shapes only the single-scattering lobe. */
		if (b->ms)
			f += microfacet_ms_eval(&b->ms[w], cos(theta_i), cos(theta_o));
		for (int c = 0; c < 3; c++)
			rgb[c] += b->rgb_from_wl[c * b->n_wl + w] * f;
	}
}

double povsplit_slope2(const struct bumpmap *h)
{
	int n = h->size_px;
	double s = 0, k = h->h_range_um / 65535.0 / (h->tile_mm * 1e3 / n);
	for (int y = 0; y < n; y++)
		for (int x = 0; x < n; x++) {
			double v = h->px[(size_t)y * n + x];
			double dx = h->px[(size_t)y * n + (x + 1) % n] - v;
			double dy = h->px[(size_t)((y + 1) % n) * n + x] - v;
			s += dx * dx + dy * dy;
		}
	return s * k * k / ((double)n * n);
}

void povsplit_diffuse(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3])
{
	bake_eval_diffuse_rgb(ctx, theta_i, theta_o, dphi, rgb);
}

double *povsplit_fill_curve(const struct bake *b, int n, const double *th, const double *diffuse)
{
	enum { NU = 96, NP = 96 };
	double *a = xmalloc(sizeof *a * 3 * (size_t)n);
	for (int i = 0; i < n; i++) {
		double sum[3] = { 0, 0, 0 };
		for (int u = 0; u < NU; u++) {
			double co = (u + 0.5) / NU, to = acos(co);
			for (int p = 0; p < NP; p++) {
				double rgb[3];
				bake_eval_specular_rgb(b, th[i], to, M_PI * (p + 0.5) / NP, rgb);
				for (int c = 0; c < 3; c++)
					sum[c] += rgb[c] * co;
			}
		}
		/* d omega = d(cos) d(phi) over phi in [0, 2 pi): twice [0, pi]. */
		for (int c = 0; c < 3; c++)
			a[c * n + i] = diffuse[c * n + i] + sum[c] * (1.0 / NU) * (2 * M_PI / NP);
	}
	return a;
}

double *povsplit_bounce_curve(int n, const double *th, const double *a, double white[3])
{
	enum { NM = 512 };
	double w[3] = { 0, 0, 0 };
	for (int u = 0; u < NM; u++) {
		double mu = (u + 0.5) / NM, t = acos(mu);
		int j = 0;
		while (j < n - 1 && th[j + 1] < t)
			j++;
		double f = 0;
		if (j < n - 1 && t > th[j])
			f = (t - th[j]) / (th[j + 1] - th[j]);
		for (int c = 0; c < 3; c++) {
			const double *ac = a + c * n;
			double v = ac[j] + (j < n - 1 ? f * (ac[j + 1] - ac[j]) : 0);
			w[c] += v * 2 * mu / NM;
		}
	}
	double *b = xmalloc(sizeof *b * 3 * (size_t)n);
	for (int c = 0; c < 3; c++)
		for (int i = 0; i < n; i++)
			b[c * n + i] = a[c * n + i] * w[c];
	if (white != NULL)
		for (int c = 0; c < 3; c++)
			white[c] = w[c];
	return b;
}

/* Mean radius of a 2-D Gaussian: sigma sqrt(pi / 2). */
#define MEAN_PER_SIGMA 1.2533141373155

int povsplit_kernel_make(const struct bake *b, double texel_um, struct povsplit_kernel *k)
{
	static const double lum[3] = { 0.2126, 0.7152, 0.0722 };	/* Rec. 709 luminance */
	*k = (struct povsplit_kernel){ 0 };
	if (b->n_r > 0 && b->rd_r_rgb != NULL) {
		double p[3] = { 0, 0, 0 }, dr = b->dr_cm * 1e4, total = 0, mean = 0;
		for (int c = 0; c < 3; c++)
			for (int i = 0; i < b->n_r; i++)
				p[c] += b->rd_r_rgb[c * b->n_r + i] * (i + 0.5);
		for (int i = 0; i < b->n_r; i++) {
			double r = (i + 0.5) * dr, q = 0;
			for (int c = 0; c < 3; c++) {
				const double *rd = b->rd_r_rgb + c * b->n_r;
				if (p[c] > 0)
					q += lum[c] * rd[i] * (i + 0.5) / p[c];
			}
			if (!(q > 0))
				continue;
			total += q;
			mean += q * r;
			/* The Gaussian whose mean radius is nearest in log radius. */
			int j = (int)lround(2 * log2(r / texel_um));
			if (r < 0.5 * texel_um || j < 0)
				k->w0 += q;
			else {
				j = j >= POVSPLIT_MAX_G ? POVSPLIT_MAX_G - 1 : j;
				k->w[j] += q;
			}
		}
		if (!(total > 0))
			return -1;
		k->w0 /= total;
		k->mean_um = mean / total;
		for (int j = 0; j < POVSPLIT_MAX_G; j++) {
			k->w[j] /= total;
			k->sigma_px[j] = pow(2, 0.5 * j) / MEAN_PER_SIGMA;
		}
		k->n = POVSPLIT_MAX_G;
		return 0;
	}
	double m = 0;
	for (int c = 0; c < 3; c++)
		m += lum[c] * b->sss_radius_rgb_cm[c] * 1e4;
	if (!(m > 0))
		return -1;
	k->n = 1;
	k->w[0] = 1;
	k->sigma_px[0] = m / texel_um / MEAN_PER_SIGMA;
	k->mean_um = m;
	return 0;
}

/* One periodic box pass of half-width r over n values of line (stride s). */
static void box(double *v, int n, int s, int r, double *tmp)
{
	double sum = 0;
	for (int i = -r; i <= r; i++)
		sum += v[(size_t)(((i % n) + n) % n) * s];
	for (int i = 0; i < n; i++) {
		tmp[i] = sum / (2 * r + 1);
		sum += v[(size_t)((i + r + 1) % n) * s] - v[(size_t)(((i - r) % n + n) % n) * s];
	}
	for (int i = 0; i < n; i++)
		v[(size_t)i * s] = tmp[i];
}

void povsplit_blur(const double *h, int n, const struct povsplit_kernel *k, double *out)
{
	size_t nn = (size_t)n * n;
	double *g = xmalloc(sizeof *g * nn), *tmp = xmalloc(sizeof *tmp * (size_t)n);
	for (size_t i = 0; i < nn; i++)
		out[i] = k->w0 * h[i];
	for (int j = 0; j < k->n; j++) {
		if (!(k->w[j] > 0))
			continue;
		/* Three boxes of width w: variance (w^2 - 1) / 4 = sigma^2. */
		int r = (int)lround(0.5 * (sqrt(4 * k->sigma_px[j] * k->sigma_px[j] + 1) - 1));
		r = r > n / 2 - 1 ? n / 2 - 1 : r;
		if (r < 1) {
			for (size_t i = 0; i < nn; i++)
				out[i] += k->w[j] * h[i];
			continue;
		}
		memcpy(g, h, sizeof *g * nn);
		for (int pass = 0; pass < 3; pass++)
			for (int y = 0; y < n; y++)
				box(g + (size_t)y * n, n, 1, r, tmp);
		for (int pass = 0; pass < 3; pass++)
			for (int x = 0; x < n; x++)
				box(g + x, n, n, r, tmp);
		for (size_t i = 0; i < nn; i++)
			out[i] += k->w[j] * g[i];
	}
	free(g);
	free(tmp);
}

/* RMS of the periodic central-difference slope of h [height per texel]. */
static double rms_slope(const double *h, int n)
{
	double s = 0;
	for (int y = 0; y < n; y++)
		for (int x = 0; x < n; x++) {
			double dx = h[(size_t)y * n + (x + 1) % n] - h[(size_t)y * n + x];
			double dy = h[(size_t)((y + 1) % n) * n + x] - h[(size_t)y * n + x];
			s += dx * dx + dy * dy;
		}
	return sqrt(s / ((double)n * n));
}

int povsplit_make(const struct bumpmap *h, const struct bake *b, struct bumpmap *out,
    struct povsplit_kernel *k, double *slope_ratio, char **cause)
{
	int n = h->size_px;
	size_t nn = (size_t)n * n;
	if (povsplit_kernel_make(b, h->tile_mm * 1e3 / n, k) != 0) {
		*cause = xstrdup("the bake has neither a radial profile Rd(r) nor a mean exit "
		    "radius");
		return -1;
	}
	double *a = xmalloc(sizeof *a * nn), *o = xmalloc(sizeof *o * nn);
	double lo = INFINITY, hi = -INFINITY;
	for (size_t i = 0; i < nn; i++)
		a[i] = h->h_min_um + h->h_range_um * h->px[i] / 65535.0;
	povsplit_blur(a, n, k, o);
	for (size_t i = 0; i < nn; i++) {
		lo = fmin(lo, o[i]);
		hi = fmax(hi, o[i]);
	}
	double sa = rms_slope(a, n);
	*slope_ratio = sa > 0 ? rms_slope(o, n) / sa : 0;
	*out = (struct bumpmap){ .src = xstrdup(h->src), .size_px = n, .tile_mm = h->tile_mm,
		.h_min_um = lo, .h_range_um = hi - lo, .px = xmalloc(sizeof(uint16_t) * nn),
		.filter = h->filter };
	for (size_t i = 0; i < nn; i++)
		out->px[i] = hi > lo ? (uint16_t)lround((o[i] - lo) / (hi - lo) * 65535.0) : 0;
	free(a);
	free(o);
	return 0;
}
