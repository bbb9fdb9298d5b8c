/* dirmap: read a preferred-direction PNG (encoding in dirmap.h). */
#include "config.h"

#include "geom/dirmap.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "geom/sites.h"
#include "io/pngio.h"
#include "base/util.h"

float *dirmap_read(const char *path, int n, char **cause)
{
	int w, h, ch, bits;
	char *why = NULL;
	uint16_t *px = pngio_read(path, &w, &h, &ch, &bits, &why);
	if (px == NULL) {
		*cause = xasprintf("%s is not a readable PNG (%s)", path,
		    why ? why : "unknown error");
		free(why);
		return NULL;
	}
	if (w != n || h != n) {
		*cause = xasprintf("%s is %dx%d px; it must be %dx%d px, the map's --size",
		    path, w, h, n, n);
		free(px);
		return NULL;
	}
	float *a = xmalloc(sizeof *a * (size_t)n * n);
	for (size_t i = 0; i < (size_t)n * n; i++) {
		const uint16_t *v = px + i * (size_t)ch;
		if (ch <= 2) {
			a[i] = (float)(v[0] / 65536.0 * M_PI);
		} else {
			double c2 = v[0] / 65535.0 * 2 - 1, s2 = v[1] / 65535.0 * 2 - 1;
			a[i] = (float)(c2 == 0 && s2 == 0 ? 0 : 0.5 * atan2(s2, c2));
		}
	}
	free(px);
	return a;
}

float *dirmap_apply(struct texture_config *cfg, const char *path, char **cause)
{
	float *a = dirmap_read(path, (int)cfg->size, cause);
	if (a == NULL)
		return NULL;
	cfg->relief.direction = a;
	cfg->relief.direction_n = (int)cfg->size;
	cfg->direction_map = path;
	return a;
}
