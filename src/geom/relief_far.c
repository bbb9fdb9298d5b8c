/* relief_far: Toksvig roughness of averaged normals (relief_far.h). */
#include "config.h"

#include "geom/relief_far.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "io/pngio.h"
#include "base/util.h"

int relief_far_size(int n, double pitch, double cell)
{
	double m = nearbyint(n * pitch / cell);
	return m < 1 ? 1 : m > n ? n : (int)m;
}

void relief_far_alpha(int n, const float *nx, const float *ny, const float *nz, int m, float *alpha)
{
#pragma omp parallel for schedule(static)
	for (int bi = 0; bi < m; bi++) {
		int r0 = (int)((long)bi * n / m), r1 = (int)((long)(bi + 1) * n / m);
		for (int bj = 0; bj < m; bj++) {
			int c0 = (int)((long)bj * n / m), c1 = (int)((long)(bj + 1) * n / m);
			double sx = 0, sy = 0, sz = 0;
			for (int r = r0; r < r1; r++)
				for (int c = c0; c < c1; c++) {
					size_t i = (size_t)r * n + c;
					sx += nx[i];
					sy += ny[i];
					sz += nz[i];
				}
			double cnt = (double)(r1 - r0) * (c1 - c0);
			double len = sqrt(sx * sx + sy * sy + sz * sz) / cnt;
			/* Float normals can average to a length a hair over 1. */
			len = fmin(len, 1.0);
			alpha[(size_t)bi * m + bj] = (float)sqrt(2 * (1 - len) / len);
		}
	}
}

int relief_far_write(const char *path, int m, const float *alpha, double block_um, const char *site,
    const char *software, char **cause)
{
	size_t np = (size_t)m * m;
	uint16_t *q = xmalloc(sizeof *q * np);
	for (size_t i = 0; i < np; i++)
		q[i] = (uint16_t)nearbyint(fmin(alpha[i], 1.0) * 65535);
	char block[32];
	snprintf(block, sizeof block, "%.6g", block_um);
	struct png_text_kv text[] = {
		{ "Software", software },
		{ "skinbake:site", site },
		{ "skinbake:component", "alpha_relief" },
		{ "skinbake:block_um", block },
		{ "skinbake:encoding", "alpha_relief = value / 65535 (clipped at 1); "
		  "alpha_total^2 = alpha_skin^2 + alpha_relief^2 where the relief is "
		  "below a pixel; Toksvig 2005" },
	};
	int nt = (int)(sizeof text / sizeof text[0]);
	int rc = pngio_write(path, m, m, 1, 16, q, 0, nt, text, cause);
	free(q);
	return rc;
}
