/* source: a struct brdf_source over a bake directory and a texture
 * directory (see source.h). */
#include "config.h"
#include "export/source.h"

#include <stdlib.h>

#include "base/util.h"

static void bake_rgb(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	bake_eval_rgb(ctx, ti, to, dphi, rgb);
}

static void bake_diffuse(void *ctx, double ti, double to, double dphi, double *f, double *err)
{
	bake_eval_diffuse(ctx, ti, to, dphi, f, err);
}

static void bake_specular(void *ctx, double ti, double to, double dphi, double *f)
{
	bake_eval_specular(ctx, ti, to, dphi, f);
}

/* Whether every wavelength of b holds point values (the table's exit
 * nodes are then theta_o_nodes, not the bin centres). */
static int points_everywhere(const struct bake *b)
{
	int all = b->points != NULL && b->theta_o_nodes != NULL;
	for (int w = 0; all && w < b->n_wl; w++)
		all = b->points[w];
	return all;
}

struct brdf_source *brdf_source_open(const char *bake_dir, char **cause)
{
	struct bake *b = bake_load(bake_dir, cause);
	return b ? brdf_source_of_bake(b, 1) : NULL;
}

struct brdf_source *brdf_source_of_bake(struct bake *b, int own)
{
	struct brdf_source *s = xcalloc(1, sizeof *s);
	*s = (struct brdf_source){
		.f_rgb = bake_rgb,
		.ctx = b,
		.n_wl = b->n_wl,
		.wl_nm = b->wl_nm,
		.f_diffuse = bake_diffuse,
		.f_specular = bake_specular,
		.n_ti = b->n_ti,
		.n_to = b->n_to,
		.theta_i = b->theta_i,
		.theta_o = points_everywhere(b) ? b->theta_o_nodes : b->theta_o,
		.n_albedo = b->n_ti,
		.theta_albedo = b->theta_i,
		.albedo_rgb = b->albedo_rgb,
		.ior = b->ior,
		.roughness = b->roughness,
		.sss_radius_cm = { b->sss_radius_rgb_cm[0], b->sss_radius_rgb_cm[1], b->sss_radius_rgb_cm[2] },
		.source = b->dir,
		.preset = b->preset,
		.bake = own ? b : NULL,
	};
	return s;
}

int brdf_source_add_textures(struct brdf_source *s, const char *tex_dir, char **cause)
{
	struct texdir *t = texdir_load(tex_dir, 1, cause);
	if (t == NULL)
		return -1;
	texdir_free(s->textures);
	s->textures = t;
	s->detail = t;
	return 0;
}

void brdf_source_free(struct brdf_source *s)
{
	if (s == NULL)
		return;
	bake_free(s->bake);
	texdir_free(s->textures);
	free(s);
}
