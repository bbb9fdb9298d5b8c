/* povscene: write BASE.pov (camera, lights, objects, per-light layers or
 * frames) and the scene that sums .hdr passes. */
#include "config.h"

#include "export/pov/povscene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "export/pov/povao.h"
#include "export/pov/sdl.h"
#include "geom/mesh.h"
#include "export/pov/vec3.h"

static int bumped(const struct scene *s, const struct pov_skin *skins, const struct scene_object *o)
{
	if (o->material != SCENE_MAT_SKIN)
		return 0;
	return skins[o->skin].height_png != NULL && s->skins[o->skin].bumps;
}

int povscene_layers_ok(const struct scene *s)
{
	for (int i = 0; i < s->n_objects; i++)
		if (s->objects[i].material == SCENE_MAT_SKIN
		    && (s->objects[i].shape == SCENE_HAND || s->objects[i].shape == SCENE_HEAD))
			return 0;
	return 1;
}

double povscene_inset(const struct scene *s, int k)
{
	/* A twentieth of an image pixel at the look_at distance, but at least
	 * 2e-4 units: POV-Ray 3.7 skips a transmitted ray's next hit closer
	 * than about 1e-4 units (on a head in metres an inset of 0.043 mm
	 * showed the inner layer through the outer one, 0.12 mm did not).
	 * Scenes in millimetres keep this far below a pixel. */
	const struct scene_camera *c = &s->camera;
	double d[3];
	for (int i = 0; i < 3; i++)
		d[i] = c->location[i] - c->look_at[i];
	double span = c->ortho ? c->width : 2 * tan(0.5 * c->angle) * sqrt(vec3_dot(d, d));
	double px = span / s->width;
	return k * fmax(0.05 * px, 2e-4);
}

int povscene_layer_light(const struct scene *s, int k)
{
	/* Stable sort of the lights by colour, weakest first (outermost). */
	int order[SCENE_MAX_LIGHTS];
	for (int i = 0; i < s->n_lights; i++) {
		const double *c = s->lights[i].color;
		int j = i;
		for (; j > 0; j--) {
			const double *d = s->lights[order[j - 1]].color;
			if (d[0] + d[1] + d[2] <= c[0] + c[1] + c[2])
				break;
			order[j] = order[j - 1];
		}
		order[j] = i;
	}
	return order[k];
}

static void write_camera(FILE *fp, const struct scene *s)
{
	const struct scene_camera *c = &s->camera;
	double aspect = (double)s->width / s->height;
	if (c->ortho)
		fprintf(fp, "camera { orthographic location ");
	else
		fprintf(fp, "camera { perspective location ");
	sdl_vec(fp, c->location);
	fputs(" look_at ", fp);
	sdl_vec(fp, c->look_at);
	if (c->ortho)
		fprintf(fp, " right x*" SDL_G " up y*" SDL_G " }\n", c->width, c->width / aspect);
	else
		fprintf(fp, " right x*" SDL_G " up y angle " SDL_G " }\n", aspect,
		    c->angle * 180 / M_PI);
}

static void write_xform(FILE *fp, const struct scene_object *o)
{
	if (o->scale != 1)
		fprintf(fp, " scale " SDL_G, o->scale);
	if (o->rotate[0] != 0 || o->rotate[1] != 0 || o->rotate[2] != 0)
		fprintf(fp, " rotate <" SDL_G "," SDL_G "," SDL_G ">", o->rotate[0] * 180 / M_PI,
		    o->rotate[1] * 180 / M_PI, o->rotate[2] * 180 / M_PI);
	if (o->translate[0] != 0 || o->translate[1] != 0 || o->translate[2] != 0) {
		fputs(" translate ", fp);
		sdl_vec(fp, o->translate);
	}
}

/* Two corners of a box in SDL. */
#define BOX_CORNERS "<" SDL_G "," SDL_G "," SDL_G ">, <" SDL_G "," SDL_G "," SDL_G ">"

/* The shape, moved inward by `inset` world units (layer copies); a mesh is
 * the mesh2 declared for layer `layer` (-1: the only one), already placed. */
static void write_shape(FILE *fp, const struct scene_object *o, double inset, int layer)
{
	double h[3] = { 0.5 * o->size[0], 0.5 * o->size[1], 0.5 * o->size[2] };
	double e = inset / o->scale;
	switch (o->shape) {
	case SCENE_SPHERE:
		fputs("sphere { ", fp);
		sdl_vec(fp, o->center);
		fprintf(fp, ", " SDL_G, o->radius - e);
		break;
	case SCENE_BOX:
		fprintf(fp, "box { " BOX_CORNERS " translate ", -h[0] + e, -h[1] + e, -h[2] + e,
		    h[0] - e, h[1] - e, h[2] - e);
		sdl_vec(fp, o->center);
		break;
	case SCENE_PATCH:
		/* Front face at z = 0 facing -z (toward a default camera). */
		if (e > 0)
			fprintf(fp, "box { " BOX_CORNERS " translate ", -h[0] + e, -h[1] + e, e,
			    h[0] - e, h[1] - e, fmin(h[0], h[1]) * 0.02 - e);
		else
			fprintf(fp, "box { <" SDL_G "," SDL_G ",0>, <" SDL_G "," SDL_G "," SDL_G "> translate ",
			    -h[0], -h[1], h[0], h[1], fmin(h[0], h[1]) * 0.02);
		sdl_vec(fp, o->center);
		break;
	case SCENE_PLANE:
		fputs("plane { ", fp);
		sdl_vec(fp, o->normal);
		fprintf(fp, ", " SDL_G, o->offset - e);
		break;
	case SCENE_HAND:
		fputs("object { SkinbakeHand()", fp);
		break;
	case SCENE_HEAD:
		fputs("object { SkinbakeHead()", fp);
		break;
	case SCENE_MESH:
		/* Placed in world coordinates already (textures use world x, y, z). */
		if (layer >= 0)
			fprintf(fp, "object { SKIN_Mesh_%s_L%d", o->name, layer + 1);
		else
			fprintf(fp, "object { SKIN_Mesh_%s", o->name);
		return;
	}
	write_xform(fp, o);
}

/* The bump map of a non-mesh skin object: patches and boxes carry it with
 * their own orientation, curved shapes get it projected along the view. */
static void write_bump_xform(FILE *fp, const struct scene *s, const struct scene_object *o)
{
	if (o->shape == SCENE_PATCH || o->shape == SCENE_BOX) {
		fputs(" translate ", fp);
		sdl_vec(fp, o->center);
		write_xform(fp, o);
	} else {
		double d[3];
		vec3_unit_toward(s->camera.location, s->camera.look_at, d);
		sdl_align(fp, d);
	}
}

static void write_bump(FILE *fp, const struct scene *s, const struct scene_object *o,
    const char *which)
{
	fprintf(fp, "\n    normal { SKIN_%s_Normal%s", s->skins[o->skin].name, which);
	write_bump_xform(fp, s, o);
	fputs(" }", fp);
}

/* With a cavity map (mesh2.h) the skin's texture body goes into a
 * texture_map over the map, placed like the bump map: returns the text
 * that closes it, after opening it (or "\n  texture {" is the opening and
 * " }" the close without one; *open receives the opening left to write). */
static const char *cavity_open(FILE *fp, const struct scene *s, const struct scene_object *o,
    const struct pov_skin *ps, const char **open)
{
	if (ps->cavity_png == NULL || ps->sss.on) {
		*open = "\n  texture {";
		return " }";
	}
	fprintf(fp, "\n  texture { pigment_pattern { image_map { png \"%s\" interpolate 2 } scale "
	    SDL_G, ps->cavity_png, ps->tile_units);
	write_bump_xform(fp, s, o);
	fputs(" } texture_map { [0 SKIN_CavityBlack] [1", fp);
	*open = "";
	return "] } }";
}

/* The fill's pigment of skin object o: SKIN_s_Fill, or with its occlusion
 * map (povao.h) SKIN_s_Fill_OBJECT, declared in BASE.pov (caller frees). */
static char *fill_pigment(const struct scene *s, const struct scene_object *o)
{
	const char *sn = s->skins[o->skin].name;
	if (povao_wanted(s, o))
		return xasprintf("SKIN_%s_Fill_%s", sn, o->name);
	return xasprintf("SKIN_%s_Fill", sn);
}

/* The texture of a skin object; pigment/finish names depend on the pass,
 * rest > 0 averages it with `rest` parts of the clear texture (layers). */
static void write_skin_texture(FILE *fp, const struct scene *s, const struct scene_object *o,
    const struct pov_skin *skins, const char *pigment, const char *finish, int rest)
{
	const struct scene_skin *sk = &s->skins[o->skin];
	if (skins[o->skin].sss.on && skins[o->skin].maps) {
		/* A maps set: the members' layered textures blended (pov_maps.h); no bump map. */
		fprintf(fp, "\n  texture { SKIN_%s_Translucent }", sk->name);
	} else if (o->shape == SCENE_MESH && bumped(s, skins, o)) {
		/* The per-triangle textures are in the mesh2. */
	} else if (rest == 0 && povscene_averaged(&skins[o->skin])) {
		/* The split and the fill (povsplit.h, povinc.c): entries averaged,
		 * finish diffuse N. */
		const struct pov_skin *ps = &skins[o->skin];
		const char *sn = sk->name, *open;
		const char *close = bumped(s, skins, o) ? cavity_open(fp, s, o, ps, &open) : " }";
		if (!bumped(s, skins, o))
			open = "\n  texture {";
		fprintf(fp, "%s average texture_map {", open);
		for (int e = ps->diffuse_png ? 1 : 0; e <= (ps->diffuse_png ? 2 : 0); e++) {
			fprintf(fp, " [1 pigment { %s%s%s }", e ? "SKIN_" : pigment, e ? sn : "",
			    e == 1 ? "_Diffuse" : e == 2 ? "_Specular" : "");
			if (bumped(s, skins, o))
				write_bump(fp, s, o, e == 1 ? "Diffuse" : "");
			fprintf(fp, "\n    finish { SKIN_%s_FinishAvg }]", sn);
		}
		if (ps->fill) {
			char *fpig = fill_pigment(s, o);
			fprintf(fp, "\n    [1 pigment { %s } finish { SKIN_%s_FillFinish }]", fpig,
			    sn);
			free(fpig);
		}
		fprintf(fp, " }%s", close);
	} else {
		const char *open = "\n  texture {", *close = " }";
		if (skins[o->skin].sss.on)
			fprintf(fp, "\n  texture { SKIN_%s_Subsurface }", sk->name);
		if (bumped(s, skins, o))
			close = cavity_open(fp, s, o, &skins[o->skin], &open);
		if (rest > 0)
			fprintf(fp, "%s average texture_map { [1", open);
		else
			fputs(open, fp);
		fprintf(fp, " pigment { %s }", pigment);
		if (bumped(s, skins, o))
			write_bump(fp, s, o, "");
		if (rest > 0)
			fprintf(fp, "\n    finish { %s }] [%d SKIN_Clear] }%s", finish, rest,
			    close);
		else
			fprintf(fp, "\n    finish { %s }%s", finish, close);
	}
	if (sk->reflection || skins[o->skin].sss.on)
		fprintf(fp, "\n  interior { SKIN_%s_Interior }", sk->name);
}

/* Pigment and finish of skin SN for pass `pass` (0: the frame without
 * animation, k: light k) or layer. */
static void skin_names(const struct scene *s, const char *sn, enum scene_strategy st, int pass,
    int layered, char **pig, char **fin)
{
	if (st == SCENE_LIGHTS_PASSES && pass > 0) {
		*pig = xasprintf("SKIN_%s_Pigment_%s", sn, s->lights[pass - 1].name);
		*fin = xasprintf("SKIN_%s_Finish", sn);
	} else if (st == SCENE_LIGHTS_PASSES && !layered) {
		*pig = xasprintf("SKIN_%s_Pigment_Separable", sn);
		*fin = xasprintf("SKIN_%s_Finish_Separable", sn);
	} else {
		*pig = xasprintf("SKIN_%s_Pigment", sn);
		if (st == SCENE_LIGHTS_SEPARABLE)
			*fin = xasprintf("SKIN_%s_Finish_Separable", sn);
		else
			*fin = xasprintf("SKIN_%s_Finish", sn);
	}
}

int povscene_averaged(const struct pov_skin *ps)
{
	return ps->diffuse_png != NULL || ps->fill;
}

/* The averaged texture of povscene_averaged's skins on a mesh: normals
 * around the per-triangle matrix (pre MATRIX mid MATRIX post, or pre
 * MATRIX post without the split), plain without normals. */
static void mesh_averaged(const struct pov_skin *ps, const char *sn, const char *pig,
    const char *fillpig, char **pre, char **mid, char **post, char **plain)
{
	char *fill = ps->fill
	    ? xasprintf(" [1 pigment { %s } finish { SKIN_%s_FillFinish }]", fillpig, sn)
	    : xstrdup("");
	if (ps->diffuse_png) {
		*pre = xasprintf("texture { average texture_map { [1 pigment { SKIN_%s_Diffuse } normal { "
				 "SKIN_%s_NormalDiffuseMesh", sn, sn);
		*mid = xasprintf(" } finish { SKIN_%s_FinishAvg }] [1 pigment { SKIN_%s_Specular } normal { "
				 "SKIN_%s_NormalMesh", sn, sn, sn);
		*plain = xasprintf("texture { average texture_map { [1 pigment { SKIN_%s_Diffuse } finish { "
				   "SKIN_%s_FinishAvg }] [1 pigment { SKIN_%s_Specular } finish { SKIN_%s_FinishAvg }]%s } }",
		    sn, sn, sn, sn, fill);
	} else {
		*pre = xasprintf("texture { average texture_map { [1 pigment { %s } normal { SKIN_%s_NormalMesh", pig, sn);
		*mid = NULL;
		*plain = xasprintf("texture { average texture_map { [1 pigment { %s } finish { SKIN_%s_FinishAvg }]%s } }",
		    pig, sn, fill);
	}
	*post = xasprintf(" } finish { SKIN_%s_FinishAvg }]%s } }", sn, fill);
	free(fill);
}

void povscene_mesh_texture(const struct scene *s, const struct pov_skin *skins,
    const struct scene_object *o, enum scene_strategy st, int layer, char **pre, char **mid,
    char **post, char **plain)
{
	const char *sn = s->skins[o->skin].name;
	char *pig, *fin;
	*mid = NULL;
	if (layer >= 0)
		skin_names(s, sn, st, povscene_layer_light(s, layer) + 1, 1, &pig, &fin);
	else if (st == SCENE_LIGHTS_PASSES) {	/* frames: declared per frame in BASE.pov */
		pig = xasprintf("SKIN_%s_PassPigment", sn);
		fin = xasprintf("SKIN_%s_PassFinish", sn);
	} else
		skin_names(s, sn, st, 0, 0, &pig, &fin);
	int rest = layer >= 0 ? s->n_lights - 1 - layer : 0;
	if (layer < 0 && st == SCENE_LIGHTS_KEY && povscene_averaged(&skins[o->skin])) {
		char *fp = fill_pigment(s, o);
		mesh_averaged(&skins[o->skin], sn, pig, fp, pre, mid, post, plain);
		free(fp);
	} else if (rest > 0) {
		*pre = xasprintf("texture { average texture_map { [1 pigment { %s } normal { SKIN_%s_NormalMesh", pig, sn);
		*post = xasprintf(" } finish { %s }] [%d SKIN_Clear] } }", fin, rest);
		*plain = xasprintf("texture { average texture_map { [1 pigment { %s } finish { %s }] [%d SKIN_Clear] } }", pig,
		    fin, rest);
	} else {
		*pre = xasprintf("texture { pigment { %s } normal { SKIN_%s_NormalMesh", pig, sn);
		*post = xasprintf(" } finish { %s } }", fin);
		*plain = xasprintf("texture { pigment { %s } finish { %s } }", pig, fin);
	}
	free(pig);
	free(fin);
}

/* One object; for a skin object pass/layer select the table. */
static void write_object(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const struct scene_object *o, enum scene_strategy st, int pass, int layer, const char *base)
{
	const char *sn = o->skin >= 0 ? s->skins[o->skin].name : "";
	int layered = layer >= 0;
	fprintf(fp, "// object %s\n", o->name);
	double inset = layered ? povscene_inset(s, layer) : 0;
	write_shape(fp, o, inset, layered && o->material == SCENE_MAT_SKIN ? layer : -1);
	/* Textures attach after the object's transforms, so texture space is
	 * world space (the gamma function uses x, y, z). */
	if (o->material == SCENE_MAT_PLAIN) {
		fputs("\n  texture { pigment { ", fp);
		sdl_rgb(fp, o->color);
		fputs(" } finish { " POVSCENE_FINISH_LIT, fp);
		int filled = s->fill[0] > 0 || s->fill[1] > 0 || s->fill[2] > 0;
		if (st == SCENE_LIGHTS_KEY && filled) {
			fputs(" emission ", fp);
			sdl_rgb(fp, s->fill);
		}
		fputs(" } }", fp);
	} else if (o->material == SCENE_MAT_MODEL) {
		char *ao = NULL;
		if (st == SCENE_LIGHTS_KEY && povao_wanted(s, o))
			ao = povao_name(base, o);
		povmodel_write_texture(fp, o, base, st == SCENE_LIGHTS_KEY ? s->fill : NULL, ao);
		free(ao);
	} else if (o->material == SCENE_MAT_LAMBERT)
		fprintf(fp, "\n  texture { SKIN_%s_Lambert }", sn);
	else if (o->material == SCENE_MAT_PHONG)
		fprintf(fp, "\n  texture { SKIN_%s_Phong }", sn);
	else {
		char *pig, *fin;
		int p = layered ? povscene_layer_light(s, layer) + 1 : pass;
		skin_names(s, sn, st, p, layered, &pig, &fin);
		write_skin_texture(fp, s, o, skins, pig, fin, layered ? s->n_lights - 1 - layer : 0);
		free(pig);
		free(fin);
		if (layered && layer < s->n_lights - 1)
			fputs(" no_shadow", fp);
	}
	fputs(" }\n", fp);
}

static void write_objects(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const struct pov_options *o, enum scene_strategy st, int pass)
{
	for (int i = 0; i < s->n_objects; i++)
		write_object(fp, s, skins, &s->objects[i], st, pass, -1, o->base);
}

static int n_meshes(const struct scene *s)
{
	int n = 0;
	for (int i = 0; i < s->n_objects; i++)
		n += s->objects[i].shape == SCENE_MESH;
	return n;
}

static void write_mesh_includes(FILE *fp, const struct scene *s, const struct pov_options *o)
{
	for (int i = 0; i < s->n_objects; i++)
		if (s->objects[i].shape == SCENE_MESH)
			fprintf(fp, "#include \"%s_mesh_%s.inc\"\n", o->base, s->objects[i].name);
}

/* Frames: light k and its tables in frame k, all lights with the separable
 * fit without animation. */
static void write_frames(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const struct pov_options *o, enum scene_strategy st)
{
	fputs("#switch (frame_number)\n", fp);
	for (int i = 0; i < s->n_lights; i++) {
		const char *ln = s->lights[i].name;
		fprintf(fp, "#case (%d)\nlight_source { SKIN_Light_%s }\n", i + 1, ln);
		for (int k = 0; k < s->n_skins; k++)
			if (n_meshes(s) > 0)
				fprintf(fp, "#declare SKIN_%s_PassPigment = SKIN_%s_Pigment_%s;\n"
				    "#declare SKIN_%s_PassFinish = SKIN_%s_Finish;\n", s->skins[k].name, s->skins[k].name,
				    s->lights[i].name, s->skins[k].name, s->skins[k].name);
		write_mesh_includes(fp, s, o);
		write_objects(fp, s, skins, o, st, i + 1);
		fputs("#break\n", fp);
	}
	fputs("#else\n", fp);
	for (int i = 0; i < s->n_lights; i++)
		fprintf(fp, "light_source { SKIN_Light_%s }\n", s->lights[i].name);
	for (int k = 0; k < s->n_skins; k++)
		if (n_meshes(s) > 0)
			fprintf(fp, "#declare SKIN_%s_PassPigment = SKIN_%s_Pigment_Separable;\n"
			    "#declare SKIN_%s_PassFinish = SKIN_%s_Finish_Separable;\n", s->skins[k].name, s->skins[k].name,
			    s->skins[k].name, s->skins[k].name);
	write_mesh_includes(fp, s, o);
	write_objects(fp, s, skins, o, st, 0);
	fputs("#end\n", fp);
}

/* Layers: every light for the other objects; one light group per light
 * with its copy of the skin objects. */
static void write_layers(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const struct pov_options *o, enum scene_strategy st)
{
	fputs("#declare SKIN_Clear = texture { pigment { rgbt 1 } "
	    "finish { diffuse 0 ambient 0 emission 0 specular 0 } }\n", fp);
	write_mesh_includes(fp, s, o);
	for (int i = 0; i < s->n_lights; i++)
		fprintf(fp, "light_source { SKIN_Light_%s }\n", s->lights[i].name);
	for (int i = 0; i < s->n_objects; i++)
		if (s->objects[i].material != SCENE_MAT_SKIN)
			write_object(fp, s, skins, &s->objects[i], st, 0, -1, o->base);
	for (int k = 0; k < s->n_lights; k++) {
		const char *ln = s->lights[povscene_layer_light(s, k)].name;
		fprintf(fp, "// light %s shades layer %d of %d of the skin (weight 1/%d, light x %d)\n"
		    "light_group {\n  light_source { SKIN_Light_%s_Layer }\n", ln, k + 1, s->n_lights, s->n_lights,
		    s->n_lights, ln);
		for (int i = 0; i < s->n_objects; i++)
			if (s->objects[i].material == SCENE_MAT_SKIN)
				write_object(fp, s, skins, &s->objects[i], st, 0, k, o->base);
		fputs("  global_lights off\n}\n", fp);
	}
}

/* The fill of skin meshes seen past their occlusion maps (povao.h): the
 * visible sky's fill, and where the sky is occluded the fill bounced once
 * off the skin (SKIN_s_FillBounce, povinc.c), blended linearly in V:
 * albedo x fill x (V + (1 - V) x white-sky albedo). */
static void write_fill_occlusion(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const char *base)
{
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		if (o->material != SCENE_MAT_SKIN || !skins[o->skin].fill || !povao_wanted(s, o))
			continue;
		char *ao = povao_name(base, o);
		const char *sn = s->skins[o->skin].name;
		fprintf(fp, "// The fill seen past the meshes: %d rays per vertex (povao).\n",
		    s->fill_occlusion);
		fprintf(fp, "#declare SKIN_%s_Fill_%s = pigment { uv_mapping image_pattern { png "
		    "\"%s\" gamma 1.0 map_type 0 interpolate 2 }\n  pigment_map { "
		    "[0 SKIN_%s_FillBounce] [1 SKIN_%s_Fill] } }\n", sn, o->name, ao, sn, sn);
		free(ao);
	}
}

/* Translucent skin meshes: the back light through their thin parts. */
static void write_back_light(FILE *fp, const struct scene *s, const struct pov_skin *skins)
{
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		if (o->shape != SCENE_MESH || o->material != SCENE_MAT_SKIN)
			continue;
		const struct pov_skin *ps = &skins[o->skin];
		if (!ps->sss.on || ps->maps)
			continue;
		struct povback_stats st;
		povback_write(fp, s, o, &ps->sss.back, povscene_inset(s, 1), &st);
	}
}

void povscene_write(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const struct pov_options *o, enum scene_strategy st, int layered)
{
	const char *title = s->title ? s->title : o->base;
	fprintf(fp, "#version 3.7;\n// %s\n// Generated by skinbake " PACKAGE_VERSION " from %s.\n",
	    title, s->path);
	if (st == SCENE_LIGHTS_PASSES && layered)
		fprintf(fp, "// Per-light passes summed in one run (one light group and skin layer per light):\n"
		    "// povray %s.ini  ->  %s.png\n", o->base, o->base);
	else if (st == SCENE_LIGHTS_PASSES)
		fprintf(fp, "// Per-light passes: `povray %s.ini` renders frame k with light k only and its\n"
		    "// own table to %s_passK.hdr; then `povray %s_combine.ini` sums them into %s.png.\n"
		    "// Rendered without animation (frame 0) it shows all lights with the separable fit.\n",
		    o->base, o->base, o->base, o->base);
	else
		fprintf(fp, "// Render: povray %s.ini   (or povray +I%s.pov +W%d +H%d)\n", o->base,
		    o->base, s->width, s->height);
	int depth = layered ? 5 + s->n_lights : 5;
	fprintf(fp, "global_settings { assumed_gamma 1.0 ambient_light 0 max_trace_level %d", depth);
	if (o->sss_samples > 0)
		povsss_write_global(fp, s->unit_mm, o->sss_samples);
	fputs(" }\n", fp);
	if (o->shapes_inc)
		fprintf(fp, "#include \"%s\"\n", o->shapes_inc);
	fprintf(fp, "#include \"%s.inc\"\n", o->base);
	fputs("background { ", fp);
	int frames = st == SCENE_LIGHTS_PASSES && !layered;
	if (frames) /* passes are summed: background in pass 1 only */
		fputs("#if (frame_number < 2) ", fp);
	sdl_rgb(fp, s->background);
	if (frames)
		fputs(" #else rgb 0 #end", fp);
	fputs(" }\n", fp);
	write_camera(fp, s);
	if (frames)
		write_frames(fp, s, skins, o, st);
	else if (layered)
		write_layers(fp, s, skins, o, st);
	else {
		write_fill_occlusion(fp, s, skins, o->base);
		write_mesh_includes(fp, s, o);
		for (int i = 0; i < s->n_lights; i++)
			fprintf(fp, "light_source { SKIN_Light_%s }\n", s->lights[i].name);
		write_objects(fp, s, skins, o, st, 0);
		write_back_light(fp, s, skins);
	}
}

char *povscene_pass_name(const char *base, int k, int n)
{
	int digits = n >= 100 ? 3 : n >= 10 ? 2 : 1;
	return xasprintf("%s_pass%0*d.hdr", base, digits, k);
}

void povscene_write_combine(FILE *fp, const struct scene *s, const char *base,
    const char *scene_name)
{
	fprintf(fp, "#version 3.7;\n// Sum of the per-light passes of %s (POV-Ray does the sum: each .hdr is\n"
	    "// shown 1:1 on a unit square, averaged, times the number of passes).\n"
	    "// Render without antialiasing: povray %s_combine.ini\n", scene_name, base);
	fputs("global_settings { assumed_gamma 1.0 ambient_light 0 }\n"
	    "camera { orthographic location <0.5,0.5,-1> look_at <0.5,0.5,0> right x up y }\n", fp);
	for (int i = 0; i < s->n_lights; i++) {
		char *p = povscene_pass_name(base, i + 1, s->n_lights);
		fprintf(fp, "#declare Skinbake_Pass%d = pigment { image_map { hdr \"%s\" } }\n",
		    i + 1, p);
		free(p);
	}
	fputs("plane { z, 0 texture { pigment { average pigment_map {", fp);
	for (int i = 0; i < s->n_lights; i++)
		fprintf(fp, " [1 Skinbake_Pass%d]", i + 1);
	fprintf(fp, " } }\n  finish { emission %d diffuse 0 ambient 0 specular 0 } } }\n",
	    s->n_lights);
}
