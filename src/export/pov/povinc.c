/* povinc: write BASE.inc, the include of an export: the lights, and per skin
 * its finish, interior, lit-table pigments, bump map and stand-in textures,
 * all #declared, guarded against double inclusion, #version 3.7 inside with
 * the caller's version restored. */
#include "config.h"

#include "export/pov/povinc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "export/pov/mesh2.h"
#include "export/pov/pov_maps.h"
#include "export/pov/povao.h"
#include "export/pov/povscene.h"
#include "export/pov/sdl.h"
#include "export/pov/separable.h"
#include "export/pov/strategy.h"

/* SKIN_Light_NAME, or with times > 1 SKIN_Light_NAME_Layer: the colour
 * times `times`. */
static void write_light(FILE *fp, const struct scene_light *l, int times)
{
	double c[3] = { l->color[0] * times, l->color[1] * times, l->color[2] * times };
	const char *layer = times > 1 ? "_Layer" : "";
	fprintf(fp, "#declare SKIN_Light_%s%s = light_source { ", l->name, layer);
	sdl_vec(fp, l->position);
	fputs(" color ", fp);
	sdl_rgb(fp, c);
	if (l->type == SCENE_LIGHT_PARALLEL) {
		fputs(" parallel point_at ", fp);
		sdl_vec(fp, l->point_at);
	}
	if (l->area_size > 0)
		fprintf(fp,
		    "\n  area_light <" SDL_G ",0,0>, <0," SDL_G ",0>, %d, %d adaptive 1 circular "
		    "orient", l->area_size, l->area_size, l->area_samples, l->area_samples);
	fputs(" }\n", fp);
}


/* Include-only passes: frame k of `sh BASE.sh SCENE.pov` places light k and
 * selects its table as SKIN_s_Pigment; without animation all lights and the
 * separable fit. */
static void write_frame_selection(FILE *fp, const struct scene *s, const struct pov_options *o)
{
	fprintf(fp,
	    "// Per-light passes: render your scene with `sh %s.sh SCENE.pov` "
	    "(frames 1 to %d, one\n"
	    "// light each, summed into %s.png).  Use SKIN_Lights() for the lights and SKIN_<skin>_Pigment\n"
	    "// with SKIN_<skin>_Finish: frame k selects light k and its table.\n#macro SKIN_Lights()\n"
	    "  #switch (frame_number)\n", o->base, s->n_lights, o->base);
	for (int i = 0; i < s->n_lights; i++)
		fprintf(fp, "  #case (%d) light_source { SKIN_Light_%s } #break\n", i + 1, s->lights[i].name);
	fputs("  #else\n", fp);
	for (int i = 0; i < s->n_lights; i++)
		fprintf(fp, "    light_source { SKIN_Light_%s }\n", s->lights[i].name);
	fputs("  #end\n#end\n#switch (frame_number)\n", fp);
	for (int i = 0; i < s->n_lights; i++) {
		fprintf(fp, "#case (%d)\n", i + 1);
		for (int k = 0; k < s->n_skins; k++)
			fprintf(fp, "  #declare SKIN_%s_Pigment = SKIN_%s_Pigment_%s;\n", s->skins[k].name, s->skins[k].name,
			    s->lights[i].name);
		fputs("  #break\n", fp);
	}
	fputs("#else\n", fp);
	for (int k = 0; k < s->n_skins; k++)
		fprintf(fp, "  #declare SKIN_%s_Pigment = SKIN_%s_Pigment_Separable;\n"
		    "  #declare SKIN_%s_Finish = SKIN_%s_Finish_Separable;\n", s->skins[k].name, s->skins[k].name,
		    s->skins[k].name, s->skins[k].name);
	fputs("#end\n", fp);
}

/* Whether a mesh of skin sn gets the fill's occlusion map (povao.h). */
static int occluded(const struct scene *s, const char *sn)
{
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		if (o->material == SCENE_MAT_SKIN && !strcmp(s->skins[o->skin].name, sn) &&
		    povao_wanted(s, o))
			return 1;
	}
	return 0;
}

/* The split (povsplit.h) and the fill: SKIN_s_Diffuse and SKIN_s_Specular
 * tables, SKIN_s_Fill = albedo(theta_o), the finish of the averaged
 * entries (diffuse N for N entries) and the fill's (emission N x fill). */
static void write_split_fill(FILE *fp, const struct scene *s, const char *sn,
    const struct pov_skin *ps, const struct pov_light *l, const struct pov_view *v,
    const double lo[3], const double hi[3], const struct pov_options *o, struct pov_report *r)
{
	int n = (ps->diffuse_png ? 2 : 1) + (ps->fill ? 1 : 0);
	if (n == 1)
		return;
	if (ps->diffuse_png) {
		fputs("// The split (docs/relief.md): the diffuse part of the table under the "
		    "height map\n"
		    "// blurred by Rd(r), the surface specular under the whole relief.\n", fp);
		for (int part = 1; part <= 2; part++) {
			char *nm = xasprintf("SKIN_%s_%s", sn, part == 1 ? "Diffuse" : "Specular");
			const struct pov_brdf *t = part == 1 ? &ps->diffuse : &ps->specular;
			int g = ps->maps ? pov_maps_write_part(fp, nm, ps->maps, part, ps->spec_alpha, l, v,
			    lo, hi, o->n_theta, o->n_gamma, ps->maps_uv)
			    : littable_write_key(fp, nm, t, l, v, lo, hi, o->n_theta, o->n_gamma);
			r->n_gamma_used = g > r->n_gamma_used ? g : r->n_gamma_used;
			free(nm);
		}
	}
	if (ps->fill) {
		double e[3] = { n * s->fill[0], n * s->fill[1], n * s->fill[2] };
		char *nm = xasprintf("SKIN_%s_Fill", sn);
		fputs("// The fill: a uniform sky light gives radiance albedo(theta_o) x fill "
		    "(reciprocity).\n", fp);
		if (ps->maps)
			pov_maps_write_fill(fp, nm, ps->maps, 0, lo, hi, ps->maps_uv);
		else {
			fprintf(fp, "#declare %s = ", nm);
			sdl_albedo_pigment(fp, ps->n_albedo, ps->theta_albedo, ps->albedo_curve);
		}
		free(nm);
		if (occluded(s, sn)) {
			/* Where the sky is occluded the fill arrives bounced off the skin
			 * (povsplit_bounce_curve): BASE.pov blends toward this. */
			nm = xasprintf("SKIN_%s_FillBounce", sn);
			fputs("// The fill bounced once off the skin (the occluded fill's low "
			    "end): albedo(theta_o) x white-sky albedo.\n", fp);
			if (ps->maps)
				pov_maps_write_fill(fp, nm, ps->maps, 1, lo, hi, ps->maps_uv);
			else {
				double wa[3];
				double *ab = povsplit_bounce_curve(ps->n_albedo, ps->theta_albedo,
				    ps->albedo_curve, wa);
				fprintf(fp, "// (white-sky albedo %.4f %.4f %.4f)\n#declare %s = ",
				    wa[0], wa[1], wa[2], nm);
				sdl_albedo_pigment(fp, ps->n_albedo, ps->theta_albedo, ab);
				free(ab);
			}
			free(nm);
		}
		fprintf(fp, "#declare SKIN_%s_FillFinish = finish { diffuse 0 brilliance 1 "
		    "ambient 0 emission ", sn);
		sdl_rgb(fp, e);
		fputs(" specular 0 }\n", fp);
	}
	fprintf(fp, "#declare SKIN_%s_FinishAvg = finish { diffuse %d brilliance 1 ambient 0 "
	    "emission 0 specular 0 }\n", sn, n);
}

static int has_mesh(const struct scene *s, int k)
{
	for (int i = 0; i < s->n_objects; i++)
		if (s->objects[i].shape == SCENE_MESH && s->objects[i].material == SCENE_MAT_SKIN && s->objects[i].skin == k)
			return 1;
	return 0;
}

/* The skin's relief as POV-Ray normals: the planar tile, the diffuse
 * part's softer copy, their per-triangle mesh forms, and the cavity's black. */
static void write_normals(FILE *fp, const struct scene *s, int k, const struct pov_skin *ps)
{
	const struct scene_skin *sk = &s->skins[k];
	if (ps->height_png != NULL)
		fprintf(fp, "// bump_size = H_range * n_px / tile = " SDL_G "; one tile = " SDL_G " units, planar\n"
		    "// (map_type 0) projection along z: attach with the object's or the view's orientation.\n"
		    "#declare SKIN_%s_Normal = normal { bump_map { png \"%s\" map_type 0 interpolate 2 "
		    "bump_size " SDL_G " } scale " SDL_G " }\n", ps->bump_size, ps->tile_units, sk->name, ps->height_png,
		    ps->bump_size, ps->tile_units);
	if (ps->diffuse_png != NULL)
		fprintf(fp, "#declare SKIN_%s_NormalDiffuse = normal { bump_map { png \"%s\" "
		    "map_type 0 interpolate 2 bump_size " SDL_G " } scale " SDL_G " }\n", sk->name,
		    ps->diffuse_png, ps->diffuse_bump_size, ps->tile_units);
	if (ps->diffuse_png != NULL && has_mesh(s, k))
		fprintf(fp, "#declare SKIN_%s_NormalDiffuseMesh = normal { bump_map { png "
		    "\"%s\" map_type 0 interpolate 2 bump_size " SDL_G " } }\n", sk->name,
		    ps->diffuse_png, ps->diffuse_bump_size);
	if (ps->cavity_png != NULL)
		fputs(MESH2_CAVITY_BLACK, fp);
	if (ps->height_png != NULL && has_mesh(s, k))
		fprintf(fp, "// On meshes each triangle maps the tile onto its UVs by its own matrix (docs/pov.md).\n"
		    "#declare SKIN_%s_NormalMesh = normal { bump_map { png \"%s\" map_type 0 interpolate 2 "
		    "bump_size " SDL_G " } }\n", sk->name, ps->height_png, ps->bump_size);
}

void povinc_write(FILE *fp, const struct scene *s, const struct pov_skin *skins, const struct pov_options *o,
    enum scene_strategy st, int layered, struct pov_report *r)
{
	char *guard = sdl_ident(o->base);
	struct pov_view v;
	strategy_view(&s->camera, &v);
	fprintf(fp, "// Generated by skinbake " PACKAGE_VERSION " from %s: baked skin BRDF as POV-Ray lit tables.\n"
	    "// Lights strategy: %s.  The pigments hold pi*f_r; they are right only with the\n"
	    "// SKIN_Light_* lights below and the camera of the scene (see docs/pov.md).\n",
	    s->path ? s->path : "the command line", scene_strategy_name(st));
	fprintf(fp, "#ifndef (%s_Inc)\n#declare %s_Inc = 1;\n#local Skinbake_Saved_Version = version;\n"
	    "#version 3.7;\n\n", guard, guard);
	for (int i = 0; i < s->n_lights; i++)
		write_light(fp, &s->lights[i], 1);
	if (layered) {
		fprintf(fp, "// Per-light layers: each light shades its own copy of the skin, seen with weight 1/%d.\n",
		    s->n_lights);
		for (int i = 0; i < s->n_lights; i++)
			write_light(fp, &s->lights[i], s->n_lights);
	}
	fputs("\n", fp);
	struct pov_light pl[SCENE_MAX_LIGHTS];
	for (int i = 0; i < s->n_lights; i++)
		strategy_light(&s->lights[i], &pl[i]);
	r->n_gamma_used = 1;
	for (int k = 0; k < s->n_skins; k++) {
		const struct scene_skin *sk = &s->skins[k];
		const struct pov_skin *ps = &skins[k];
		double lo[3], hi[3];
		char *nm;
		strategy_skin_bounds(s, k, lo, hi);
		fprintf(fp, "// ---- skin '%s' (preset %s) ----\n", sk->name, sk->preset);
		const char *table = ps->sss.on ? "Remainder" : "Pigment";
		if (ps->sss.on)
			fprintf(fp, "#declare SKIN_%s_Finish = finish { diffuse %g brilliance 1 ambient 0 emission 0 specular 0",
			    sk->name, POVSSS_DIFFUSE);
		else
			fprintf(fp, "#declare SKIN_%s_Finish = finish { " POVSCENE_FINISH_LIT, sk->name);
		if (sk->reflection && !ps->sss.on)
			fputs(" reflection { 0, 1 fresnel on } conserve_energy", fp);
		fputs(" }\n", fp);
		fprintf(fp, "#declare SKIN_%s_Interior = interior { ior " SDL_G " }\n", sk->name, ps->ior);
		if (ps->sss.on && !ps->maps)
			povsss_write(fp, sk->name, &ps->sss, sk->reflection);
		if (st == SCENE_LIGHTS_KEY && ps->diffuse_png && o->write_scene) {
			/* The scene uses the parts only (povscene.c). */
			write_split_fill(fp, s, sk->name, ps, &pl[0], &v, lo, hi, o, r);
		} else if (st == SCENE_LIGHTS_KEY) {
			nm = xasprintf("SKIN_%s_%s", sk->name, table);
			int g = ps->maps ? pov_maps_write_key(fp, nm, ps->maps, &pl[0], &v, lo, hi, o->n_theta, o->n_gamma,
			    ps->maps_uv) : povfar_write_key(fp, nm, &ps->far, &ps->brdf, &pl[0], &v, lo, hi, o->n_theta, o->n_gamma);
			r->n_gamma_used = g > r->n_gamma_used ? g : r->n_gamma_used;
			free(nm);
			write_split_fill(fp, s, sk->name, ps, &pl[0], &v, lo, hi, o, r);
		} else if (st == SCENE_LIGHTS_MIXTURE) {
			double spread;
			nm = xasprintf("SKIN_%s_%s", sk->name, table);
			littable_write_mixture(fp, nm, &ps->brdf, pl, &v, lo, hi, o->n_mix, &spread);
			r->mix_gamma_spread = fmax(r->mix_gamma_spread, spread);
			free(nm);
		}
		if (ps->sss.on)
			fprintf(fp, "#declare SKIN_%s_Pigment = pigment { average pigment_map { [1 SKIN_%s_Remainder] "
			    "[%d rgbt <0, 0, 0, 1>] } }\n", sk->name, sk->name, POVSSS_CLEAR);
		if (ps->sss.on && ps->maps)
			pov_maps_write_sss(fp, sk->name, ps->maps, sk->reflection, lo, hi,
			    ps->maps_uv);
		if (st == SCENE_LIGHTS_PASSES)
			for (int i = 0; i < s->n_lights; i++) {
				nm = xasprintf("SKIN_%s_Pigment_%s", sk->name, s->lights[i].name);
				int g = povfar_write_key(fp, nm, &ps->far, &ps->brdf, &pl[i], &v, lo, hi, o->n_theta,
				    o->n_gamma);
				r->n_gamma_used = g > r->n_gamma_used ? g : r->n_gamma_used;
				free(nm);
			}
		if ((st == SCENE_LIGHTS_PASSES && !layered) || st == SCENE_LIGHTS_SEPARABLE) {
			struct pov_separable sep;
			separable_fit(&ps->brdf, &sep);
			r->sep_rms = fmax(r->sep_rms, sep.rms);
			r->sep_mean = fmax(r->sep_mean, sep.mean);
			nm = xasprintf("SKIN_%s_Pigment%s", sk->name, st == SCENE_LIGHTS_PASSES ? "_Separable" : "");
			separable_write(fp, nm, &sep);
			free(nm);
			fprintf(fp, "#declare SKIN_%s_Finish_Separable = finish { diffuse 1 brilliance %.6f ambient 0 "
			    "emission 0 specular 0%s }\n", sk->name, sep.brilliance,
			    sk->reflection ? " reflection { 0, 1 fresnel on } conserve_energy" : "");
		}
		write_normals(fp, s, k, ps);
		/* Stand-ins for comparison scenes (paper figure 7): the skin's
		 * normal-incidence albedo as Lambert and as Phong. */
		fprintf(fp, "#declare SKIN_%s_Lambert = texture { pigment { ", sk->name);
		sdl_rgb(fp, ps->albedo_rgb);
		fputs(" } finish { " POVSCENE_FINISH_LIT " } }\n", fp);
		fprintf(fp, "#declare SKIN_%s_Phong = texture { pigment { ", sk->name);
		sdl_rgb(fp, ps->albedo_rgb);
		fputs(" } finish { " POVSCENE_FINISH_LIT " phong 0.5 phong_size 40 } }\n\n", fp);
	}
	if (st == SCENE_LIGHTS_PASSES && !o->write_scene)
		write_frame_selection(fp, s, o);
	fputs("#version Skinbake_Saved_Version;\n#end\n", fp);
	free(guard);
}

