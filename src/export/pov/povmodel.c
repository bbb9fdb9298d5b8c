/* povmodel: a mesh's own material from its model file, in POV-Ray SDL
 * (textures through the UVs, colour, Phong highlight, fill). */
#include "config.h"

#include "export/pov/povmodel.h"

#include <math.h>
#include <stdlib.h>
#include <strings.h>

#include "base/util.h"
#include "export/pov/sdl.h"
#include "geom/mesh.h"

/* Image types POV-Ray reads: file type, SDL keyword. */
static const char *image_types[][2] = {
	{ "png", "png" },
	{ "jpg", "jpeg" },
	{ "jpeg", "jpeg" },
	{ "tga", "tga" },
	{ "tif", "tiff" },
	{ "tiff", "tiff" },
	{ "ppm", "ppm" },
	{ "exr", "exr" },
	{ "hdr", "hdr" },
};

#define N_IMAGE_TYPES (sizeof image_types / sizeof image_types[0])

char *povmodel_texture_file(const struct scene_object *o, const char *base)
{
	const struct mesh *m = o->mesh;
	if (m == NULL || m->uv == NULL)
		return NULL;
	if (m->texture == NULL && m->texture_file == NULL)
		return NULL;
	for (size_t i = 0; i < N_IMAGE_TYPES; i++)
		if (!strcasecmp(m->texture_type, image_types[i][0]))
			return xasprintf("%s_%s_texture.%s", base, o->name, image_types[i][0]);
	return NULL;
}

/* The model file's own material: its diffuse texture through the UVs (POV
 * 3.7 maps uv pigments right; only uv bumps are wrong) or colour. */
static void write_model_pigment(FILE *fp, const struct scene_object *o, const char *tex)
{
	const struct mesh *m = o->mesh;
	if (tex == NULL) {
		sdl_rgb(fp, m->diffuse_rgb);
		return;
	}
	const char *kw = "png";
	for (size_t i = 0; i < N_IMAGE_TYPES; i++)
		if (!strcasecmp(m->texture_type, image_types[i][0]))
			kw = image_types[i][1];
	fprintf(fp, "uv_mapping image_map { %s \"%s\" interpolate 2 }", kw, tex);
}

/* The second averaged entry: the pigment times the occlusion map, lit by
 * the fill (doubled, as the average halves it). */
static void write_fill_entry(FILE *fp, const struct scene_object *o, const char *tex,
    const double *fill, const char *ao)
{
	double e[3] = { 2 * fill[0], 2 * fill[1], 2 * fill[2] };
	fputs(" }]\n    [1 pigment { uv_mapping image_pattern { png \"", fp);
	fputs(ao, fp);
	fputs("\" gamma 1.0 map_type 0 interpolate 2 } pigment_map { [0 rgb 0] [1 ", fp);
	write_model_pigment(fp, o, tex);
	fputs("] } } finish { diffuse 0 brilliance 1 ambient 0 specular 0 emission ", fp);
	sdl_rgb(fp, e);
	fputs(" }] } }", fp);
}

/* With an occlusion map (ao, povao.h) the fill is a second averaged entry,
 * the pigment times the map, and the lit entry's weights are doubled. */
void povmodel_write_texture(FILE *fp, const struct scene_object *o, const char *base,
    const double *fill, const char *ao)
{
	const struct mesh *m = o->mesh;
	char *tex = povmodel_texture_file(o, base);
	int lit = fill != NULL && (fill[0] > 0 || fill[1] > 0 || fill[2] > 0);
	int k = lit && ao ? 2 : 1;
	if (k == 2)
		fputs("\n  texture { average texture_map { [1 pigment { ", fp);
	else
		fputs("\n  texture { pigment { ", fp);
	write_model_pigment(fp, o, tex);
	if (k == 2)
		fputs(" } finish { diffuse 2 brilliance 1 ambient 0 emission 0 specular 0", fp);
	else
		fputs(" } finish { " POVMODEL_FINISH_LIT, fp);
	if (lit && k == 1) {
		fputs(" emission ", fp);
		sdl_rgb(fp, fill);
	}
	if (m->specular > 0) {
		double size = fmin(fmax(m->shininess, 1), 1000);
		fprintf(fp, " phong " SDL_G " phong_size " SDL_G, k * fmin(m->specular, 1), size);
	}
	if (k == 2)
		write_fill_entry(fp, o, tex, fill, ao);
	else
		fputs(" } }", fp);
	free(tex);
}
