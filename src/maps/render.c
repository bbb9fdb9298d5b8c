/* render: albedo and subsurface radius per texel from parameter maps. */
#include "config.h"
#include "maps/render.h"

#include <stdlib.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/check.h"
#include "base/util.h"

struct image *maps_render_albedo(struct family *f, const struct mapset *m, struct image **radius, int threads)
{
	CHECK(m->n == f->n_axes);
	family_albedo_prepare(f);
	struct image *im = image_new(m->w, m->h, 3, 32), *rad = radius ? image_new(m->w, m->h, 3, 32) : NULL;
	long n = (long)m->w * m->h;
#ifdef _OPENMP
	int nt = threads > 0 ? threads : omp_get_max_threads();
#else
	int nt = 1;
	(void)threads;
#endif
#pragma omp parallel for schedule(static) num_threads(nt)
	for (long i = 0; i < n; i++) {
		double x[FAMILY_MAX_AXES], rgb[3], r[3];
		for (int a = 0; a < m->n; a++)
			x[a] = m->p[a].v[i];
		family_albedo(f, x, NULL, rgb, rad ? r : NULL);
		for (int c = 0; c < 3; c++) {
			im->v[3 * i + c] = (float)rgb[c];
			if (rad)
				rad->v[3 * i + c] = (float)r[c];
		}
	}
	if (radius)
		*radius = rad;
	return im;
}
