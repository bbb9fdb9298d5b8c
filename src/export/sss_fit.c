/* sss_fit: fit a renderer's calibrated subsurface closure to a bake's Rd(r)
 * (see sss_fit.h).  Inside a ring of the table the power is spread evenly
 * over the area, so G is linear in r^2 between edges; between colours G is
 * linear in the colour. */
#include "config.h"
#include "export/sss_fit.h"

#include <math.h>
#include <stdlib.h>

#include "base/util.h"

const double sss_ring_edges_mm[] = { 0, 0.02, 0.04, 0.07, 0.1, 0.15, 0.2, 0.3, 0.45, 0.65, 1.0, 1.5,
	2.2, 3.2, 4.6, 6.5, 9.0, 13.0, 20.0, -1 };

/* Colour node below C and the weight of the one above. */
static int colour_cell(const struct sss_table *t, double c, double *w)
{
	int k = 0;
	while (k < t->n_colour - 2 && c > t->colour[k + 1])
		k++;
	double x = (c - t->colour[k]) / (t->colour[k + 1] - t->colour[k]);
	*w = fmin(fmax(x, 0.0), 1.0);
	return k;
}

/* G at r between edges e1 < e2 (values g1, g2): a power law in r, which
 * follows the steep fall of a profile (power spread evenly over a ring's
 * area put the centroids 5-13 % too far out); linear in r^2 from r = 0 and
 * where G reaches 0. */
static double g_between(double e1, double e2, double g1, double g2, double r)
{
	if (e1 <= 0 || g1 <= 0 || g2 <= 0)
		return g1 + (g2 - g1) * (r * r - e1 * e1) / (e2 * e2 - e1 * e1);
	return g1 * pow(r / e1, log(g2 / g1) / log(e2 / e1));
}

/* Integral of G dr over [a, b] inside one ring (Simpson, 16 panels). */
static double g_integral(double e1, double e2, double g1, double g2, double a, double b)
{
	const int n = 16;
	double h = (b - a) / n, sum = 0.0;
	for (int i = 0; i <= n; i++) {
		double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
		sum += w * g_between(e1, e2, g1, g2, a + i * h);
	}
	return sum * h / 3.0;
}

/* The table's full rings' integrals of G dr, summed from r = 0 (cum[i]: to
 * edge i), per channel and colour node: inside_node's sum up to the ring
 * holding s, added in the same order, so a fit with them is the same to the
 * last bit as one without (issue 27: the fit had re-integrated every ring
 * below s at each of its ~10^6 evaluations, 27 of a translucent Blender
 * export's 37 s of CPU for three Blender versions). */
struct ring_area {
	const struct sss_table *t;
	double *cum;			/* [3][n_colour][n_edge], or NULL: integrate each time */
};

static void ring_area_init(struct ring_area *ra, const struct sss_table *t)
{
	size_t ne = (size_t)t->n_edge;
	ra->t = t;
	ra->cum = xmalloc(3 * (size_t)t->n_colour * ne * sizeof *ra->cum);
	for (size_t row = 0; row < 3 * (size_t)t->n_colour; row++) {
		const double *g = t->g + row * ne, *e = t->edge_mm;
		double *cum = ra->cum + row * ne, area = 0.0;
		cum[0] = 0.0;
		for (size_t i = 0; i + 1 < ne; i++) {
			area += g_integral(e[i], e[i + 1], g[i], g[i + 1], e[i], e[i + 1]);
			cum[i + 1] = area;
		}
	}
}

/* Power and first moment [unit length] within s at unit length, colour
 * node k: P = G(0) - G(s); the moment of -dG is -s G(s) + int_0^s G dr. */
static void inside_node(const struct ring_area *ra, int c, int k, double s, double *p0, double *p1)
{
	const struct sss_table *t = ra->t;
	size_t row = (size_t)c * (size_t)t->n_colour + (size_t)k;
	const double *g = t->g + row * (size_t)t->n_edge;
	const double *e = t->edge_mm;
	double gs = g[0], area = 0.0;
	int i = 0;
	if (ra->cum != NULL) {
		/* The rings wholly inside s from the sums, then the one holding s. */
		const double *cum = ra->cum + row * (size_t)t->n_edge;
		while (i + 2 < t->n_edge && s > e[i + 1])
			i++;
		if (s > e[0]) {
			double hi = fmin(s, e[i + 1]);
			area = i > 0 ? cum[i] : 0.0;
			area += g_integral(e[i], e[i + 1], g[i], g[i + 1], e[i], hi);
			gs = g_between(e[i], e[i + 1], g[i], g[i + 1], hi);
			i++;
		}
	} else {
		for (i = 0; i + 1 < t->n_edge && s > e[i]; i++) {
			double hi = fmin(s, e[i + 1]);
			area += g_integral(e[i], e[i + 1], g[i], g[i + 1], e[i], hi);
			gs = g_between(e[i], e[i + 1], g[i], g[i + 1], hi);
		}
	}
	if (i + 1 >= t->n_edge && s > e[t->n_edge - 1]) {
		s = e[t->n_edge - 1];	/* beyond the table: what is left is not counted */
		gs = g[t->n_edge - 1];
	}
	*p0 = g[0] - gs;
	*p1 = -s * gs + area;
}

/* Power and first moment [mm] within r_mm in channel ch for colour c at
 * length L [mm]. */
static void inside(const struct ring_area *ra, int ch, double c, double len, double r_mm,
    double *p0, double *p1)
{
	double w, a0, a1, b0, b1;
	int k = colour_cell(ra->t, c, &w);
	inside_node(ra, ch, k, r_mm / len, &a0, &a1);
	inside_node(ra, ch, k + 1, r_mm / len, &b0, &b1);
	*p0 = (1 - w) * a0 + w * b0;
	*p1 = len * ((1 - w) * a1 + w * b1);
}

/* The length whose mean radius within r_max is M (bisection in log L; the
 * mean grows with L). */
static double length_for_mean(const struct ring_area *ra, int ch, double c, double r_max, double m)
{
	double lo = log(1e-5), hi = log(1e4);
	for (int it = 0; it < 80; it++) {
		double mid = 0.5 * (lo + hi), p0, p1;
		inside(ra, ch, c, exp(mid), r_max, &p0, &p1);
		if (p0 > 0 && p1 / p0 < m)
			lo = mid;
		else
			hi = mid;
	}
	return exp(0.5 * (lo + hi));
}

/* Each bin's power is spread evenly over its annulus and split at the ring
 * edges by area: binning by centres put whole 0.02 mm bins on the wrong side
 * of edges such as 0.07 and 0.15 mm, a sawtooth of up to 0.8 in ln R over the
 * inner rings of the comparison. */
double sss_bake_ring(const struct bake *b, int c, double r1_mm, double r2_mm)
{
	double dr = b->dr_cm * 10.0, sum = 0.0;
	for (int i = 0; i < b->n_r; i++) {
		double a = i * dr, e = (i + 1) * dr;
		double lo = fmax(a, r1_mm), hi = fmin(e, r2_mm);
		if (hi <= lo)
			continue;
		double p = M_PI * (e * e - a * a) * fmax(b->rd_r_rgb[c * b->n_r + i], 0.0) * 0.01;	/* 1/cm^2 -> 1/mm^2 */
		sum += p * (hi * hi - lo * lo) / (e * e - a * a);
	}
	return sum;
}

static double fit_ring(const struct ring_area *ra, const struct sss_fit *f, int c, double r1_mm,
    double r2_mm)
{
	double a0, a1, b0, b1;
	inside(ra, c, f->colour[c], f->length_mm[c], r1_mm, &a0, &a1);
	inside(ra, c, f->colour[c], f->length_mm[c], r2_mm, &b0, &b1);
	return f->scale * (b0 - a0) + (r1_mm <= 0 && r2_mm > 0 ? f->local[c] : 0.0);
}

double sss_fit_ring(const struct sss_fit *f, int c, double r1_mm, double r2_mm)
{
	const struct ring_area ra = { f->table, NULL };
	return fit_ring(&ra, f, c, r1_mm, r2_mm);
}

/* The bake's power and mean radius within r_max, channel c. */
static void bake_moments(const struct bake *b, int c, double *p0, double *mean)
{
	double dr = b->dr_cm * 10.0, s0 = 0.0, s1 = 0.0;
	for (int i = 0; i < b->n_r; i++) {
		double r = (i + 0.5) * dr;
		double p = 2 * M_PI * r * dr * fmax(b->rd_r_rgb[c * b->n_r + i], 0.0) * 0.01;
		s0 += p;
		s1 += p * r;
	}
	*p0 = s0;
	*mean = s0 > 0 ? s1 / s0 : 0.0;
}

/* RMS of ln(fit / bake) over the comparison rings inside the radius that
 * holds 95 % of the bake's power. */
static double rms_log(const struct ring_area *ra, const struct sss_fit *f, const struct bake *b,
    int c)
{
	double total = f->integral_bake[c], cum = 0.0, sum = 0.0;
	int n = 0;
	for (int k = 0; sss_ring_edges_mm[k + 1] > 0 && sss_ring_edges_mm[k] < f->r_max_mm; k++) {
		double r1 = sss_ring_edges_mm[k], r2 = fmin(sss_ring_edges_mm[k + 1], f->r_max_mm);
		double pb = sss_bake_ring(b, c, r1, r2), pf = fit_ring(ra, f, c, r1, r2);
		if (pb > 0 && pf > 0) {
			sum += log(pf / pb) * log(pf / pb);
			n++;
		}
		cum += pb;
		if (cum >= 0.95 * total)
			break;
	}
	return n > 0 ? sqrt(sum / n) : 0.0;
}

/* The closure (colour, length) with power TARGET and mean radius M within
 * r_max, channel c: bisection on the colour (the power within r_max grows
 * with it), for each colour the length that gives the mean. */
static void fit_closure(const struct ring_area *ra, struct sss_fit *f, int c, double target,
    double m)
{
	const struct sss_table *t = f->table;
	double lo = t->colour[0], hi = t->colour[t->n_colour - 1], p0 = 0, p1 = 0;
	for (int it = 0; it < 60; it++) {
		double mid = 0.5 * (lo + hi);
		double len = length_for_mean(ra, c, mid, f->r_max_mm, m);
		inside(ra, c, mid, len, f->r_max_mm, &p0, &p1);
		if (f->scale * p0 < target)
			lo = mid;
		else
			hi = mid;
	}
	f->colour[c] = 0.5 * (lo + hi);
	f->clamped[c] = f->colour[c] <= t->colour[0] * 1.0001 || f->colour[c] >= t->colour[t->n_colour - 1] * 0.9999;
	f->length_mm[c] = length_for_mean(ra, c, f->colour[c], f->r_max_mm, m);
	inside(ra, c, f->colour[c], f->length_mm[c], f->r_max_mm, &p0, &p1);
	f->integral_fit[c] = f->scale * p0 + f->local[c];
	f->mean_fit_mm[c] = f->integral_fit[c] > 0 ? f->scale * p1 / f->integral_fit[c] : 0.0;
}

/* Channel c: the closure alone, or with a share of the power left to the
 * table at the entry point (the remainder's local part, r = 0), up to the
 * bake's power in the first comparison ring; the closure then carries the
 * rest with the mean radius that keeps the whole mean.  Skin's profile has a
 * sharper centre than one closure (dark-dry blue: 37 % of the power within
 * 0.02 mm, mean 0.1 mm), which the local part gives.  The share with the
 * least RMS of ln R wins; none when it does not help. */
static void fit_channel(const struct ring_area *ra, struct sss_fit *f, const struct bake *b, int c)
{
	const int steps = 16;
	double target = f->integral_bake[c], m = f->mean_bake_mm[c];
	double ring0 = fmin(sss_bake_ring(b, c, 0.0, sss_ring_edges_mm[1]), 0.9 * target);
	double best = -1.0, best_local = 0.0;
	for (int j = 0; j <= steps; j++) {
		f->local[c] = ring0 * j / steps;
		double keep = target - f->local[c];
		fit_closure(ra, f, c, keep, target > 0 ? m * target / keep : m);
		double rms = rms_log(ra, f, b, c);
		if (best < 0 || rms < best - 1e-4) {
			best = rms;
			best_local = f->local[c];
		}
	}
	f->local[c] = best_local;
	double keep = target - best_local;
	fit_closure(ra, f, c, keep, target > 0 ? m * target / keep : m);
	f->rms_log[c] = rms_log(ra, f, b, c);
}

int sss_fit_bake(const struct sss_table *t, const struct bake *b, double scale, struct sss_fit *f, char **cause)
{
	if (b->rd_r_rgb == NULL || b->n_r < 1) {
		*cause = xasprintf("%s: the bake has no radial profile (manifest.json: radial.rd_r); bake it again with "
		    "this skinbake", b->dir ? b->dir : "bake");
		return -1;
	}
	if (t->n_colour < 2) {
		*cause = xasprintf("%s has no calibration of its subsurface closure (%s): run `make calibrate`",
		    t->renderer, t->version);
		return -1;
	}
	*f = (struct sss_fit){ .table = t, .scale = scale, .r_max_mm = b->n_r * b->dr_cm * 10.0 };
	struct ring_area ra;
	ring_area_init(&ra, t);
	for (int c = 0; c < 3; c++) {
		bake_moments(b, c, &f->integral_bake[c], &f->mean_bake_mm[c]);
		fit_channel(&ra, f, b, c);
	}
	free(ra.cum);
	return 0;
}

double sss_far_pi_f(const struct sss_table *t, int c, double colour, double theta_i, double theta_o)
{
	double w;
	int k = colour_cell(t, colour, &w);
	double ai = fmin(theta_i * 180.0 / M_PI, t->far_deg[t->n_far - 1]);
	double ao = fmin(theta_o * 180.0 / M_PI, t->far_deg[t->n_far - 1]);
	int i = 0, j = 0;
	while (i < t->n_far - 2 && ai > t->far_deg[i + 1])
		i++;
	while (j < t->n_far - 2 && ao > t->far_deg[j + 1])
		j++;
	double u = (ai - t->far_deg[i]) / (t->far_deg[i + 1] - t->far_deg[i]);
	double v = (ao - t->far_deg[j]) / (t->far_deg[j + 1] - t->far_deg[j]);
	double val[2];
	for (int n = 0; n < 2; n++) {
		const double *g = t->far_pi_f + ((size_t)c * (size_t)t->n_colour + (size_t)(k + n)) * (size_t)(t->n_far * t->n_far);
		int nf = t->n_far;
		val[n] = (1 - u) * ((1 - v) * g[i * nf + j] + v * g[i * nf + j + 1]) +
		    u * ((1 - v) * g[(i + 1) * nf + j] + v * g[(i + 1) * nf + j + 1]);
	}
	/* Beyond the last node (85 deg) the far field goes to 0 at grazing in POV-Ray (its Fresnel
	 * transmission) and stays in Cycles; the last node's value is kept: small either way. */
	return (1 - w) * val[0] + w * val[1];
}
