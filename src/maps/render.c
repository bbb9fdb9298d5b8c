/* render: albedo and subsurface radius per texel from parameter maps. */
#include "config.h"
#include "maps/render.h"

#include <stdlib.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/check.h"
#include "base/srgb.h"
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
	(void)threads; /* without OpenMP the pragma below is ignored */
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

int maps_render_write(const char *out, int exr, int bits, int srgb, struct image *im, const char *radius_path,
    const struct image *rad, char **cause)
{
	static const char *names[] = { "R", "G", "B" };
	const char *kv[] = { "skinbake:content", "diffuse albedo, linear sRGB (D65)" };
	int rc;
	if (exr)
		rc = image_write_exr(out, im, names, 1, kv, cause);
	else {
		if (srgb)
			for (size_t i = 0; i < (size_t)im->w * im->h * 3; i++)
				im->v[i] = (float)srgb_encode(im->v[i]);
		struct png_text_kv tx[] = { { "Software", PACKAGE_STRING }, { "Comment", srgb
			? "diffuse albedo, sRGB-encoded" : "diffuse albedo, linear sRGB values (no transfer function)" } };
		rc = image_write_png(out, im, bits, srgb && bits == 8, 2, tx, cause);
	}
	const char *rkv[] = { "skinbake:content", "subsurface radius (mean exit radius) per R, G, B [cm]" };
	if (rc == 0 && rad)
		rc = image_write_exr(radius_path, rad, names, 1, rkv, cause);
	return rc;
}
