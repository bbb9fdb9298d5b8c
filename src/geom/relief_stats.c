/* relief_stats: Sa, Sz, furrow density and depth, structure-tensor
 * anisotropy and pore regions of a periodic height map (definitions in
 * relief_stats.h). */
#include "config.h"

#include "geom/relief_stats.h"

#include <json-c/json.h>
#include <math.h>
#include <stdlib.h>

#include "base/util.h"
#include "io/json.h"

static double map_mean(size_t npx, const float *h)
{
	double s = 0;
	for (size_t i = 0; i < npx; i++)
		s += h[i];
	return s / (double)npx;
}

/* Sa and Sz of h. */
static void heights(size_t npx, const float *h, struct relief_stats *st)
{
	double m = map_mean(npx, h), a = 0, lo = h[0], hi = h[0];
	for (size_t i = 0; i < npx; i++) {
		a += fabs(h[i] - m);
		lo = fmin(lo, h[i]);
		hi = fmax(hi, h[i]);
	}
	st->sa = a / (double)npx;
	st->sz = hi - lo;
}

/* Furrow excursions along the wrap-around lines of step (dr, dc): count
 * the downward crossings of `level` and add the depth of each excursion's
 * deepest point below `mean` to *depth.  Each line starts at a pixel above
 * the level so that no excursion is split by the start. */
static long crossings(int n, const float *f, int dr, int dc, double level, double mean,
    double *depth)
{
	long count = 0;
	for (int line = 0; line < n; line++) {
		int r0 = dc == 0 ? 0 : line, c0 = dc == 0 ? line : 0;
		int start = -1;
		for (int k = 0; k < n && start < 0; k++) {
			if (f[(size_t)((r0 + k * dr) % n) * n + (c0 + k * dc) % n] >= level)
				start = k;
		}
		if (start < 0)
			continue;	/* the whole line is inside one furrow */
		int below = 0;
		double deepest = 0;
		for (int k = 1; k <= n; k++) {
			int r = (r0 + (start + k) * dr) % n, c = (c0 + (start + k) * dc) % n;
			double v = f[(size_t)r * n + c];
			if (v < level && !below) {
				below = 1;
				deepest = v;
				count++;
			} else if (v < level) {
				deepest = fmin(deepest, v);
			} else if (below) {
				below = 0;
				*depth += mean - deepest;
			}
		}
	}
	return count;
}

static void furrows(int n, const float *f, double pitch, double t, struct relief_stats *st)
{
	static const int steps[4][2] = { { 0, 1 }, { 1, 0 }, { 1, 1 }, { 1, -1 } };
	double mean = map_mean((size_t)n * n, f), depth = 0, density = 0;
	long total = 0;
	for (int d = 0; d < 4; d++) {
		int dr = steps[d][0], dc = (steps[d][1] + n) % n;	/* -1 wraps to n - 1 */
		double step = (d >= 2 ? sqrt(2.0) : 1.0) * pitch;
		long c = crossings(n, f, dr, dc, mean - t, mean, &depth);
		/* n lines of n steps each. */
		density += (double)c / ((double)n * n * step) / 4;
		total += c;
	}
	st->furrow_density = density;
	st->furrow_depth = total > 0 ? depth / (double)total : 0;
}

/* Mean gradient structure tensor and its eigen-decomposition, and the
 * developed area ratio from the same gradients. */
static void tensor(int n, const float *h, double pitch, struct relief_stats *st)
{
	double jxx = 0, jyy = 0, jxy = 0, dev = 0;
	for (int r = 0; r < n; r++) {
		for (int c = 0; c < n; c++) {
			/* y is up, toward row 0. */
			double gx = (h[(size_t)r * n + (c + 1) % n]
			    - h[(size_t)r * n + (c + n - 1) % n]) / (2 * pitch);
			double gy = (h[(size_t)((r + n - 1) % n) * n + c]
			    - h[(size_t)((r + 1) % n) * n + c]) / (2 * pitch);
			jxx += gx * gx;
			jyy += gy * gy;
			jxy += gx * gy;
			dev += sqrt(1 + gx * gx + gy * gy) - 1;
		}
	}
	st->sdr = dev / ((double)n * n);
	double tr = jxx + jyy, disc = sqrt((jxx - jyy) * (jxx - jyy) + 4 * jxy * jxy);
	double lmax = (tr + disc) / 2, lmin = (tr - disc) / 2;
	st->anisotropy = lmax > 0 ? 1 - fmax(lmin, 0) / lmax : 0;
	/* Dominant gradient direction, then the furrows run across it. */
	double grad = 0.5 * atan2(2 * jxy, jxx - jyy), dir = grad + M_PI / 2;
	st->direction = fmod(dir + 2 * M_PI, M_PI);
}

static int uf_find(int *parent, int i)
{
	while (parent[i] != i) {
		parent[i] = parent[parent[i]];
		i = parent[i];
	}
	return i;
}

static void uf_join(int *parent, int a, int b)
{
	a = uf_find(parent, a);
	b = uf_find(parent, b);
	if (a != b)
		parent[a < b ? b : a] = a < b ? a : b;
}

/* Periodic 4-connected labelling of the pixels deeper than the threshold. */
static void pore_regions(int n, const float *p, double pitch, double t, struct relief_stats *st)
{
	size_t npx = (size_t)n * n;
	int *parent = xmalloc(sizeof *parent * npx), *area = xcalloc(npx, sizeof *area);
	float *deep = xcalloc(npx, sizeof *deep);
	for (size_t i = 0; i < npx; i++)
		parent[i] = (int)i;
	for (int r = 0; r < n; r++) {
		for (int c = 0; c < n; c++) {
			int i = r * n + c;
			int right = r * n + (c + 1) % n;
			int down = ((r + 1) % n) * n + c;
			if (!(p[i] < -t))
				continue;
			if (p[right] < -t)
				uf_join(parent, i, right);
			if (p[down] < -t)
				uf_join(parent, i, down);
		}
	}
	int regions = 0;
	double dsum = 0;
	for (size_t i = 0; i < npx; i++) {
		if (p[i] < -t) {
			int root = uf_find(parent, (int)i);
			area[root]++;
			if (p[i] < deep[root])
				deep[root] = p[i];
		}
	}
	double zsum = 0;
	for (size_t i = 0; i < npx; i++) {
		if (area[i] > 0) {
			regions++;
			dsum += 2 * sqrt(area[i] * pitch * pitch / M_PI);
			zsum -= deep[i];
		}
	}
	free(parent);
	free(area);
	free(deep);
	st->pores = regions;
	st->pore_density = regions / ((double)npx * pitch * pitch);
	st->pore_diameter = regions > 0 ? dsum / regions : 0;
	st->pore_depth = regions > 0 ? zsum / regions : 0;
}

struct relief_stats_spec relief_stats_spec_for(const struct relief_params *p, int n)
{
	return (struct relief_stats_spec){ p->tile / (double)n, fmax(p->furrow_depth / 2, 1e-5),
		fmax(p->pore_depth / 10, 1e-5) };
}

int relief_stats_for(const struct relief_params *p, int n, const float *h, const float *furrows,
    const float *pores, struct relief_stats *st)
{
	struct relief_stats_spec spec = relief_stats_spec_for(p, n);
	return relief_stats_compute(n, h, furrows, pores, &spec, st, NULL);
}

int relief_stats_compute(int n, const float *h, const float *furrow_map, const float *pores,
    const struct relief_stats_spec *spec, struct relief_stats *st, char **cause)
{
	if (n < 3 || !(spec->pitch > 0) || !(spec->furrow_threshold > 0) ||
	    !(spec->pore_threshold > 0)) {
		if (cause)
			*cause = xasprintf("relief statistics need n >= 3 and positive pitch and "
			    "thresholds (n = %d, pitch = %g cm, furrow threshold = %g cm, pore "
			    "threshold = %g cm)",
			    n, spec->pitch, spec->furrow_threshold, spec->pore_threshold);
		return -1;
	}
	*st = (struct relief_stats){ 0 };
	heights((size_t)n * n, h, st);
	furrows(n, furrow_map ? furrow_map : h, spec->pitch, spec->furrow_threshold, st);
	tensor(n, h, spec->pitch, st);
	if (pores)
		pore_regions(n, pores, spec->pitch, spec->pore_threshold, st);
	return 0;
}

static const char *const keys[RELIEF_STATS_KEYS] = { "sa_um", "sz_um", "furrow_density_per_mm",
	"furrow_depth_um", "anisotropy", "direction_deg", "pore_density_per_mm2",
	"pore_diameter_um", "sdr_pct", "pore_depth_um" };

const char *relief_stats_key(int i)
{
	return keys[i];
}

double relief_stats_value(const struct relief_stats *st, int i)
{
	switch (i) {
	case 0: return st->sa * 1e4;
	case 1: return st->sz * 1e4;
	case 2: return st->furrow_density / 10;
	case 3: return st->furrow_depth * 1e4;
	case 4: return st->anisotropy;
	case 5: return st->direction * 180 / M_PI;
	case 6: return st->pore_density / 100;
	case 7: return st->pore_diameter * 1e4;
	case 8: return st->sdr * 100;
	default: return st->pore_depth * 1e4;
	}
}

struct json_object *relief_stats_json(const struct relief_stats *st)
{
	json_object *js = json_object_new_object();
	for (int i = 0; i < RELIEF_STATS_KEYS; i++)
		json_object_object_add(js, keys[i], json_num(relief_stats_value(st, i)));
	json_object_object_add(js, "pores_found", json_object_new_int(st->pores));
	return js;
}
