/* relief_cavity: horizon-based ambient occlusion of a height map
 * (relief_cavity.h). */
#include "config.h"

#include "geom/relief_cavity.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "io/pngio.h"
#include "base/util.h"

/* h at (x, y) [px, x right along columns, y down along rows], bilinear,
 * wrapped. */
static double sample(int n, const float *h, double x, double y)
{
	double fx = floor(x), fy = floor(y);
	double ax = x - fx, ay = y - fy;
	int x0 = (int)fx % n, y0 = (int)fy % n;
	if (x0 < 0)
		x0 += n;
	if (y0 < 0)
		y0 += n;
	int x1 = x0 + 1 == n ? 0 : x0 + 1, y1 = y0 + 1 == n ? 0 : y0 + 1;
	double top = h[(size_t)y0 * n + x0] * (1 - ax) + h[(size_t)y0 * n + x1] * ax;
	double bot = h[(size_t)y1 * n + x0] * (1 - ax) + h[(size_t)y1 * n + x1] * ax;
	return top * (1 - ay) + bot * ay;
}

double relief_cavity_radius(double cell, double tile)
{
	return fmin(cell, tile / 2);
}

void relief_cavity(int n, double pitch, const float *h, double radius, float *cav)
{
	double rpx = fmax(radius / pitch, 1.0);
	int steps = (int)fmin(ceil(rpx), RELIEF_CAVITY_MAX_STEPS);
	double dstep = rpx / steps;	/* px per step */
	double dx[RELIEF_CAVITY_DIRS], dy[RELIEF_CAVITY_DIRS];
	for (int k = 0; k < RELIEF_CAVITY_DIRS; k++) {
		double phi = 2 * M_PI * (k + 0.5) / RELIEF_CAVITY_DIRS;
		dx[k] = cos(phi);
		dy[k] = sin(phi);
	}
#pragma omp parallel for schedule(static)
	for (int r = 0; r < n; r++) {
		int rn = r == 0 ? n - 1 : r - 1, rs = r == n - 1 ? 0 : r + 1;
		for (int c = 0; c < n; c++) {
			int cw = c == 0 ? n - 1 : c - 1, ce = c == n - 1 ? 0 : c + 1;
			double h0 = h[(size_t)r * n + c];
			/* Slopes [1] per pixel step, x along columns, y down rows. */
			double gx = (h[(size_t)r * n + ce] - h[(size_t)r * n + cw]) / (2 * pitch);
			double gy = (h[(size_t)rs * n + c] - h[(size_t)rn * n + c]) / (2 * pitch);
			double occl = 0;
			for (int k = 0; k < RELIEF_CAVITY_DIRS; k++) {
				double t = atan(gx * dx[k] + gy * dy[k]);
				double best = t;
				for (int s = 1; s <= steps; s++) {
					double d = s * dstep;
					double hs = sample(n, h, c + d * dx[k], r + d * dy[k]);
					double e = atan((hs - h0) / (d * pitch));
					if (e > best)
						best = e;
				}
				double sn = sin(best - t);
				occl += sn * sn;
			}
			cav[(size_t)r * n + c] = (float)(1 - occl / RELIEF_CAVITY_DIRS);
		}
	}
}

void relief_cavity_combined(int n, double pitch, const float *pores, const float *furrows,
    double radius, float *cav)
{
	size_t np = (size_t)n * n;
	float *cf = xmalloc(sizeof *cf * np);
	relief_cavity(n, pitch, pores, radius, cav);
	relief_cavity(n, pitch, furrows, radius, cf);
	for (size_t i = 0; i < np; i++)
		cav[i] *= (float)pow(fmax(cf[i], 0.0), RELIEF_CAVITY_FURROW_WEIGHT);
	free(cf);
}

int relief_cavity_write(const char *path, int n, const float *cav, double radius_um,
    const char *site, const char *software, char **cause)
{
	size_t np = (size_t)n * n;
	uint16_t *q = xmalloc(sizeof *q * np);
	for (size_t i = 0; i < np; i++)
		q[i] = (uint16_t)nearbyint(fmin(fmax(cav[i], 0.0), 1.0) * 65535);
	char rad[32];
	snprintf(rad, sizeof rad, "%.6g", radius_um);
	struct png_text_kv text[] = {
		{ "Software", software },
		{ "skinbake:site", site },
		{ "skinbake:component", "cavity" },
		{ "skinbake:radius_um", rad },
		{ "skinbake:encoding", "cavity = value / 65535: the cosine-weighted fraction of "
		  "the sky about the local normal not hidden by the relief within radius_um "
		  "(horizon-based ambient occlusion, 16 directions): AO(pores) * "
		  "AO(furrows)^0.3; 1 = open" },
	};
	int nt = (int)(sizeof text / sizeof text[0]);
	int rc = pngio_write(path, n, n, 1, 16, q, 0, nt, text, cause);
	free(q);
	return rc;
}
