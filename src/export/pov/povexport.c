/* povexport: run a POV-Ray export: build the scene, bind bakes and texture
 * directories to its skins, load and check every input, then write.
 * Over 600 lines because the translucent mode's fit and the ownership and
 * checksum checks of this session landed here; splitting the skin binding
 * into its own file is the next step. */
#include "config.h"

#include "export/pov/povexport.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/util.h"
#include "export/source.h"
#include "export/pov/bumpmap.h"
#include "io/pngio.h"
#include "export/pov/povfiles.h"
#include "export/pov/pov_maps.h"
#include "export/pov/povsplit.h"
#include "export/pov/povao.h"
#include "scene/placement.h"
#include "scene/scene_load.h"
#include "export/pov/povscene.h"
#include "geom/mesh.h"
#include "export/pov/strategy.h"

static void msg(struct povexport_result *r, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void msg(struct povexport_result *r, const char *fmt, ...)
{
	va_list ap;
	if (r->n_msgs == POVEXPORT_MAX_MSGS)
		return;
	va_start(ap, fmt);
	if (vasprintf(&r->msgs[r->n_msgs], fmt, ap) >= 0)
		r->n_msgs++;
	va_end(ap);
}

void povexport_result_free(struct povexport_result *r)
{
	for (int i = 0; i < r->n_msgs; i++)
		free(r->msgs[i]);
	for (int i = 0; i < r->n_files; i++)
		free(r->files[i]);
	r->n_msgs = r->n_files = 0;
}

/* "SKIN=DIR" binds DIR to one skin, "DIR" to every skin without its own. */
static const char *bind_find(const char *const *b, int n, const char *skin)
{
	const char *any = NULL;
	for (int i = 0; i < n; i++) {
		const char *eq = strchr(b[i], '=');
		int named = eq != NULL && eq != b[i] && strcspn(b[i], "/") > (size_t)(eq - b[i]);
		if (named && strlen(skin) == (size_t)(eq - b[i]) &&
		    !strncmp(b[i], skin, strlen(skin)))
			return eq + 1;
		if (!named && any == NULL)
			any = b[i];
	}
	return any;
}

/* The skin a binding names ("" for a bare DIR), in buf. */
static const char *bind_skin(const char *b, char *buf, size_t len)
{
	const char *eq = strchr(b, '=');
	if (eq == NULL || eq == b || strcspn(b, "/") <= (size_t)(eq - b))
		return "";
	snprintf(buf, len, "%.*s", (int)(eq - b), b);
	return buf;
}

static char *find_shapes(const char *data_dir, const char *scene_path)
{
	const char *env = getenv("SKINBAKE_DATADIR");
	char *cand[4] = { 0 };
	int n = 0;
	if (data_dir)
		cand[n++] = xasprintf("%s/skinbake_shapes.inc", data_dir);
	if (env && *env)
		cand[n++] = xasprintf("%s/skinbake_shapes.inc", env);
	cand[n++] = xasprintf("%s/skinbake_shapes.inc", PKGDATADIR);
	if (scene_path) {
		const char *sl = strrchr(scene_path, '/');
		cand[n++] = sl ? xasprintf("%.*s/../exporters/pov/skinbake_shapes.inc",
		    (int)(sl - scene_path), scene_path)
			       : xstrdup("../exporters/pov/skinbake_shapes.inc");
	}
	char *found = NULL;
	for (int i = 0; i < n; i++) {
		if (found == NULL && access(cand[i], R_OK) == 0)
			found = cand[i];
		else
			free(cand[i]);
	}
	return found;
}

/* The face normal -z of a patch or box rotated (x, then y, then z). */
static void rotated_face_normal(const struct scene_object *o, double n[3])
{
	double a = o->rotate[0], b = o->rotate[1], c = o->rotate[2], t[3];
	n[0] = 0;
	n[1] = 0;
	n[2] = -1;
	t[0] = n[0];
	t[1] = n[1] * cos(a) - n[2] * sin(a);
	t[2] = n[1] * sin(a) + n[2] * cos(a);
	n[0] = t[0] * cos(b) + t[2] * sin(b);
	n[1] = t[1];
	n[2] = -t[0] * sin(b) + t[2] * cos(b);
	t[0] = n[0] * cos(c) - n[1] * sin(c);
	t[1] = n[0] * sin(c) + n[1] * cos(c);
	t[2] = n[2];
	memcpy(n, t, sizeof t);
}

/* --plan: which incidence angles the scene's lights meet on skin.  Curved
 * shapes see every angle; flat ones (patch, box, plane) only the angles
 * between their face normals and the lights. */
static void print_plan(FILE *fp, const struct scene *s)
{
	int curved = 0, n_ang = 0;
	double ang[SCENE_MAX_OBJECTS * SCENE_MAX_LIGHTS];
	fprintf(fp, "scene %s: lights strategy %s\n", s->path,
	    scene_strategy_name(strategy_resolve(s, NULL, NULL)));
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		if (o->material == SCENE_MAT_PLAIN)
			continue;
		if (o->shape == SCENE_SPHERE || o->shape == SCENE_HAND || o->shape == SCENE_HEAD ||
		    o->shape == SCENE_MESH) {
			curved = 1;
			continue;
		}
		for (int l = 0; l < s->n_lights; l++) {
			double n[3], d[3];
			double p[3];
			for (int j = 0; j < 3; j++)
				p[j] = o->center[j] + o->translate[j];
			if (o->shape == SCENE_PLANE)
				memcpy(n, o->normal, sizeof n);
			else
				rotated_face_normal(o, n);
			placement_light_dir(&s->lights[l], p, d);
			double ct = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
			double a = acos(fmax(-1, fmin(1, ct))) * 180 / M_PI;
			fprintf(fp, "object %s, light %s: theta_in %.2f deg%s\n", o->name,
			    s->lights[l].name, a, a >= 90 ? " (unlit)" : "");
			if (a < 90)
				ang[n_ang++] = a;
		}
	}
	if (curved)
		fprintf(fp,
		    "curved skin objects: theta_in over [0, 90] deg (the table nodes are uniform "
		    "in angle)\n");
	fprintf(fp,
	    "wavelengths: the visible range (the tables are linear sRGB from the spectral bake)\n");
	for (int k = 0; k < s->n_skins; k++) {
		fprintf(fp, "skin %s: skinbake bake --preset %s ", s->skins[k].name,
		    s->skins[k].preset);
		if (curved || n_ang == 0)
			fprintf(fp, "--theta-nodes 10");
		else
			for (int i = 0; i < n_ang; i++)
				fprintf(fp, "%s%.2f", i ? "," : "--theta-in ", ang[i]);
		fprintf(fp, " --out %s\n", s->skins[k].bake ? s->skins[k].bake : "DIR");
	}
	if (!curved && n_ang > 0)
		fprintf(fp, "(bump maps tilt the normal: add neighbouring angles if the skin "
		    "has relief)\n");
}

/* Size of one image pixel [units] on the nearest object of skin k. */
static double pixel_footprint(const struct scene *s, int k)
{
	const struct scene_camera *c = &s->camera;
	if (c->ortho)
		return c->width / s->width;
	double dmin = INFINITY;
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		double lo[3], hi[3], d2 = 0, r;
		if (o->skin != k || o->material != SCENE_MAT_SKIN)
			continue;
		if (o->shape == SCENE_MESH) {
			/* The nearest vertex in view. */
			for (int v = 0; v < o->mesh->n_vertices; v++)
				if (strategy_in_view(s, o->mesh->position[v], 0)) {
					const double *pv = o->mesh->position[v];
					double q[3];
					for (int j = 0; j < 3; j++)
						q[j] = pv[j] - c->location[j];
					double dist = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
					dmin = fmin(dmin, dist);
				}
			continue;
		}
		placement_bounds(o, lo, hi);
		for (int j = 0; j < 3; j++) {
			double m = 0.5 * (lo[j] + hi[j]) - c->location[j];
			d2 += m * m;
		}
		/* How far the visible surface may come toward the camera from the
		 * centre: the radius, half the thinnest box edge, or for the shape
		 * macros their front (palm at z ~ 0.25, face at z ~ -0.8). */
		r = o->shape == SCENE_SPHERE ? o->radius
		    : o->shape == SCENE_HAND ? 0.3 * o->scale
		    : o->shape == SCENE_HEAD ? 0.8 * o->scale
		    : o->shape == SCENE_PLANE ? 0
		    : 0.5 * fmin(o->size[0], fmin(o->size[1], o->size[2])) * o->scale;
		dmin = fmin(dmin, fmax(sqrt(d2) - r, 0.1 * sqrt(d2)));
	}
	if (!isfinite(dmin)) { /* include-only: the look_at distance */
		double d2 = 0;
		for (int j = 0; j < 3; j++)
			d2 += (c->look_at[j] - c->location[j]) * (c->look_at[j] - c->location[j]);
		dmin = sqrt(d2);
	}
	return dmin * 2 * tan(0.5 * c->angle) / s->width;
}

static char *base_from_scene(const char *path)
{
	const char *sl = strrchr(path, '/');
	const char *b = sl ? sl + 1 : path;
	size_t n = strlen(b);
	if (n > 6 && !strcmp(b + n - 6, ".scene"))
		n -= 6;
	char *r = xasprintf("%.*s", (int)n, b);
	for (char *c = r; *c; c++)
		if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
		    (*c >= '0' && *c <= '9') || *c == '_'
		    || *c == '-'))
			*c = '_';
	return r;
}

/* As a scene file's reader: no light or camera pointing at itself. */
static int check_parts(const struct scene *s, char **cause)
{
	const double *c = s->camera.location, *a = s->camera.look_at;
	for (int i = 0; i < s->n_lights; i++) {
		const double *p = s->lights[i].position, *q = s->lights[i].point_at;
		if (s->lights[i].type == SCENE_LIGHT_PARALLEL &&
		    hypot(hypot(p[0] - q[0], p[1] - q[1]), p[2] - q[2]) < 1e-9)
			return *cause = xasprintf(
			    "--light %s: position %g:%g:%g and point_at coincide (default 0:0:0)",
			    s->lights[i].name, p[0], p[1], p[2]), -1;
	}
	if (hypot(hypot(c[0] - a[0], c[1] - a[1]), c[2] - a[2]) < 1e-9) {
		*cause = xasprintf("--camera: location and look_at coincide");
		return -1;
	}
	return 0;
}

/* The scene: from the file, or synthetic from --light/--camera; then the
 * strategy override and the checks that need the scene. */
static struct scene *make_scene(const struct povexport_options *o, char **cause)
{
	struct scene *s;
	if (o->scene_path != NULL) {
		if (o->cmdline->n_lights > 0 || o->have_camera) {
			*cause = xstrdup("--scene and --light/--camera exclude each other");
			return NULL;
		}
		if ((s = scene_load(o->scene_path, cause)) == NULL)
			return NULL;
	} else {
		if (o->cmdline->n_lights == 0 || !o->have_camera) {
			*cause = xstrdup(
			    "give --scene FILE, or --light SPEC and --camera SPEC (see --help)");
			return NULL;
		}
		s = scene_from_parts(o->cmdline, o->unit_mm);
		if (check_parts(s, cause) != 0)
			goto bad;
	}
	if (o->width > 0) {
		s->width = o->width;
		s->height = o->height;
	}
	if (o->scene_path != NULL && o->unit_mm > 0) {
		*cause = xstrdup(
		    "--unit-mm is for --light/--camera: a scene file sets unit_mm in [scene]");
		goto bad;
	}
	if (o->lights != NULL) {
		int i;
		for (i = 0; i < 5 &&
		    strcmp(o->lights, scene_strategy_name((enum scene_strategy)i)); i++)
			;
		if (i == 5) {
			*cause = xasprintf(
			    "--lights = '%s' is not one of auto, key, mixture, passes, separable",
			    o->lights);
			goto bad;
		}
		s->lights_strategy = (enum scene_strategy)i;
	}
	if (s->lights_strategy == SCENE_LIGHTS_MIXTURE && s->n_lights != 2) {
		*cause = xasprintf("lights = mixture needs exactly 2 lights, %s has %d", s->path,
		    s->n_lights);
		goto bad;
	}
	for (int t = 0; t < 2; t++) {
		const char *const *b = t == 0 ? o->bakes : o->texs;
		for (int i = 0; i < (t == 0 ? o->n_bakes : o->n_texs); i++) {
			char buf[64];
			const char *sk = bind_skin(b[i], buf, sizeof buf);
			if (*sk && scene_find_skin(s, sk) < 0) {
				*cause = xasprintf("--%s %s=...: the scene has no skin '%s'",
				    t == 0 ? "bake" : "textures", sk, sk);
				goto bad;
			}
		}
	}
	return s;
bad:
	scene_free(s);
	return NULL;
}

/* Everything read for the skins before writing. */
struct inputs {
	struct brdf_source *src[SCENE_MAX_SKINS];
	struct bumpmap hm[SCENE_MAX_SKINS];
	struct pov_skin ps[SCENE_MAX_SKINS];
	char *heights[SCENE_MAX_SKINS];
	uint16_t *far_px[SCENE_MAX_SKINS];	/* roughness_far.png filtered to the
						 * pixel (povfar.h), or NULL */
	int far_m[SCENE_MAX_SKINS];	/* its edge [px] */
	char *fars[SCENE_MAX_SKINS];	/* its name in the output directory */
	char *cav_src[SCENE_MAX_SKINS];	/* the texture directory's cavity.png, or NULL */
	char *cavs[SCENE_MAX_SKINS];	/* its name in the output directory */
	struct bumpmap blur[SCENE_MAX_SKINS];	/* the height map blurred by Rd(r) */
	char *blurs[SCENE_MAX_SKINS];	/* its name in the output directory, or NULL */
	double *fill_curve[SCENE_MAX_SKINS];	/* the fill's whole albedo, or NULL */
	struct pov_maps *maps[SCENE_MAX_SKINS];
	char *shapes;
};

static void inputs_free(struct inputs *in)
{
	for (int k = 0; k < SCENE_MAX_SKINS; k++) {
		brdf_source_free(in->src[k]);
		bumpmap_free(&in->hm[k]);
		free(in->heights[k]);
		free(in->far_px[k]);
		free(in->fars[k]);
		free(in->cav_src[k]);
		free(in->cavs[k]);
		bumpmap_free(&in->blur[k]);
		free(in->blurs[k]);
		free(in->fill_curve[k]);
		pov_maps_free(in->maps[k]);
	}
	free(in->shapes);
}

/* --family --maps: skin k blends the family's members by the maps (key
 * light only); the member at the maps' median stands in where one BRDF is
 * needed (strategy, Lambert and Phong stand-ins). */
static int load_maps(const struct povexport_options *o, struct scene *s, const char *base, int k,
    struct inputs *in, char **cause)
{
	struct scene_skin *sk = &s->skins[k];
	struct pov_skin *ps = &in->ps[k];
	if (s->n_lights != 1 ||
	    (s->lights_strategy != SCENE_LIGHTS_AUTO && s->lights_strategy != SCENE_LIGHTS_KEY))
		return *cause = xasprintf(
		    "--maps: the scene has %d lights and lights = %s; maps take one light (key)",
			   s->n_lights, scene_strategy_name(s->lights_strategy)), -1;
	struct pov_maps *pm = in->maps[k] = pov_maps_open(o->family, o->maps, base, sk->name,
	    cause);
	if (pm == NULL)
		return -1;
	const struct brdf_source *b = pm->src[pm->ref];
	ps->brdf = pov_maps_brdf(pm, pm->ref);
	ps->ior = b->ior;
	for (int ch = 0; ch < 3; ch++)
		ps->albedo_rgb[ch] = b->albedo_rgb[ch * b->n_albedo];
	ps->maps = pm;
	if (o->scene_path == NULL && pm->fam->preset) {
		free(sk->preset);
		sk->preset = xstrdup(pm->fam->preset);
	}
	for (int i = 0; i < s->n_objects; i++)
		ps->maps_uv |= s->objects[i].shape == SCENE_MESH &&
		    s->objects[i].material == SCENE_MAT_SKIN && s->objects[i].skin == k;
	return 0;
}

static int load_brdf(const struct povexport_options *o, struct scene *s, int k, struct inputs *in,
    struct povexport_result *r, char **cause)
{
	struct scene_skin *sk = &s->skins[k];
	struct pov_skin *ps = &in->ps[k];
	char *err = NULL;
	*ps = (struct pov_skin){ .ior = 1.5, .albedo_rgb = { 0.62, 0.42, 0.33 } };
	if (o->analytic) {
		ps->brdf = (struct pov_brdf){ .f_rgb = littable_brdf_analytic };
		return 0;
	}
	if (o->family)
		return 0;	/* load_maps */
	const char *dir = bind_find(o->bakes, o->n_bakes, sk->name);
	if (dir == NULL)
		dir = sk->bake;
	if (dir == NULL)
		return *cause = xasprintf(
		    "skin '%s': no bake (give --bake DIR or bake = DIR in [skin %s])", sk->name,
			   sk->name),
		       -1;
	struct brdf_source *b = in->src[k] = brdf_source_open(dir, &err);
	if (b == NULL) {
		*cause = xasprintf("skin '%s': bake %s: %s", sk->name, dir, err);
		free(err);
		return -1;
	}
	if (o->scene_path && b->preset && strcmp(b->preset, sk->preset))
		msg(r, "note: skin '%s' asks for preset '%s', the bake %s has '%s'", sk->name,
		    sk->preset, dir, b->preset);
	if (o->scene_path == NULL && b->preset) {
		free(sk->preset);
		sk->preset = xstrdup(b->preset);
	}
	ps->brdf = (struct pov_brdf){ b->f_rgb, b->ctx, b->n_ti, b->n_to, b->theta_i, b->theta_o };
	ps->diffuse = (struct pov_brdf){ povsplit_diffuse, b->bake, b->n_ti, b->n_to, b->theta_i,
		b->theta_o };
	ps->spec = (struct povsplit_spec){ b->bake, b->bake ? b->bake->roughness : 0 };
	ps->specular = (struct pov_brdf){ povsplit_specular, &ps->spec, b->n_ti, b->n_to,
		b->theta_i, b->theta_o };
	ps->n_albedo = b->n_albedo;
	ps->theta_albedo = b->theta_albedo;
	ps->albedo_curve = b->albedo_rgb;
	ps->ior = b->ior;
	for (int ch = 0; ch < 3; ch++)
		ps->albedo_rgb[ch] = b->albedo_rgb[ch * b->n_albedo];
	return 0;
}

/* The relief below a pixel (povfar.h): where a block of roughness_far.png
 * (about one primary cell) is smaller than an image pixel on the nearest
 * object, the bump map gives way to the table blended with its rough copy;
 * not for maps, translucent skins, the mixture table or --bump-filter off
 * (docs/relief.md). */
static int load_far(const struct scene *s, const char *base, int k, const char *tdir,
    struct inputs *in, struct povexport_result *r, char **cause)
{
	struct pov_skin *ps = &in->ps[k];
	double amax;
	int n;
	uint16_t *far;
	if (ps->maps || ps->sss.on)
		return 0;
	int e = povfar_read(tdir, &far, &n, cause);
	if (e <= 0)
		return e;
	double block = ps->tile_units / n, px = pixel_footprint(s, k);
	/* Blocks per tile at about one per pixel (at least 1: one alpha). */
	int m = (int)fmax(1, fmin(n, floor(ps->tile_units / px)));
	in->far_px[k] = povfar_filter(far, n, m, &amax);
	in->far_m[k] = m;
	free(far);
	if (!(amax > 0) || block >= px) {
		free(in->far_px[k]);
		in->far_px[k] = NULL;
		return 0;
	}
	in->fars[k] = xasprintf("%s_%s_roughness_far.png", base, s->skins[k].name);
	ps->far = (struct pov_far){ 1, in->fars[k], amax, ps->tile_units, NULL };
	ps->height_png = NULL;
	free(in->heights[k]);
	in->heights[k] = NULL;
	msg(r, "skin '%s': relief cells (%.3g mm) below the image pixel (%.3g mm on the nearest "
	    "object): the bump map gives way to the table blended with its rough copy by "
	    "roughness_far.png (%d -> %d px, alpha_relief up to "
	    "%.3g)", s->skins[k].name, block * s->unit_mm, px * s->unit_mm, n, m, amax);
	return 0;
}

/* --mode auto: why skin k stays exact (NULL: it goes translucent).  It needs
 * a mesh of that skin, lights key or mixture, a bake (not --analytic or a
 * family), no fill (the fill is not layered over the closure) and no bump map
 * asked for (a translucent mesh cannot carry its per-triangle bump maps). */
static const char *auto_exact(const struct povexport_options *o, const struct scene *s, int k)
{
	const struct scene_skin *sk = &s->skins[k];
	enum scene_strategy st = strategy_resolve(s, NULL, NULL);
	int mesh = 0;
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *ob = &s->objects[i];
		mesh |= ob->shape == SCENE_MESH && ob->material == SCENE_MAT_SKIN && ob->skin == k;
	}
	if (!mesh)
		return "no mesh of this skin";
	if (o->analytic || o->family)
		return "--analytic or --family";
	if (st != SCENE_LIGHTS_KEY && st != SCENE_LIGHTS_MIXTURE)
		return "lights neither key nor mixture";
	if (s->fill[0] > 0 || s->fill[1] > 0 || s->fill[2] > 0)
		return "the scene has a fill";
	const char *tdir = bind_find(o->texs, o->n_texs, sk->name);
	if ((tdir != NULL || sk->textures != NULL) && sk->bumps)
		return "its bump map is asked for";
	return NULL;
}

/* --mode translucent: POV-Ray's subsurface closure under the remainder of
 * the table (povsss.h).  The subsurface layer goes under one lit table per
 * skin, so the lights are key or mixture; the fit needs the bake's Rd(r).
 * --mode auto: the same where auto_exact allows it and the fit succeeds,
 * else exact, saying why. */
static int load_sss(const struct povexport_options *o, struct scene *s, int k, struct inputs *in,
    struct povexport_result *r, char **cause)
{
	const char *sn = s->skins[k].name;
	struct pov_skin *ps = &in->ps[k];
	enum scene_strategy st = strategy_resolve(s, NULL, NULL);
	if (o->translucent == POVEXPORT_EXACT)
		return 0;
	if (o->translucent == POVEXPORT_AUTO) {
		const char *why = auto_exact(o, s, k);
		char *err = NULL;
		if (why == NULL && povsss_setup(&ps->sss, &ps->brdf, &ps->ior, in->src[k]->bake,
		    &err) != 0)
			why = err;
		if (why != NULL) {
			msg(r, "skin '%s': exact (--mode auto: %s)", sn, why);
			free(err);
			return 0;
		}
		msg(r, "skin '%s': translucent (--mode auto: a mesh lit by key or mixture)", sn);
		return 0;
	}
	if (o->analytic)
		return *cause = xstrdup("--mode translucent needs a bake and its radial profile, "
					"not --analytic"), -1;
	if (st != SCENE_LIGHTS_KEY && st != SCENE_LIGHTS_MIXTURE)
		return *cause = xasprintf("--mode translucent: lights = %s, but the subsurface "
		    "layer goes under one lit table per skin: lights key or mixture (one or two "
		    "lights)", scene_strategy_name(st)),
		       -1;
	char *err = NULL;
	if (o->family && pov_maps_sss_setup(in->maps[k], &ps->ior, &err) == 0) {
		/* Each member its closure; the median member's stands in (stand-ins, messages). */
		ps->sss = in->maps[k]->sss[in->maps[k]->ref];
		ps->brdf = pov_maps_brdf(in->maps[k], in->maps[k]->ref);
	} else if (o->family ||
	    povsss_setup(&ps->sss, &ps->brdf, &ps->ior, in->src[k]->bake, &err) != 0) {
		*cause = xasprintf("skin '%s': --mode translucent: %s", sn, err);
		free(err);
		return -1;
	}
	const struct sss_fit *f = &ps->sss.fit;
	msg(r, "skin '%s': translucent: POV-Ray subsurface colour %.4g %.4g %.4g, translucency "
	    "%.4g %.4g %.4g mm; power %.4g %.4g %.4g, mean radius %.3g %.3g %.3g mm as the bake's; "
	    "RMS ln R(r) %.2f %.2f %.2f (predicted); the remainder clips at most %.1f %% of the "
	    "table",
	    sn, f->colour[0], f->colour[1], f->colour[2],
	    f->length_mm[0], f->length_mm[1], f->length_mm[2],
	    f->integral_fit[0], f->integral_fit[1], f->integral_fit[2],
	    f->mean_fit_mm[0], f->mean_fit_mm[1], f->mean_fit_mm[2],
	    f->rms_log[0], f->rms_log[1], f->rms_log[2], 100 * ps->sss.clipped);
	return 0;
}

/* Whether a skin of S is translucent. */
static int any_sss(const struct scene *s, const struct inputs *in)
{
	for (int k = 0; k < s->n_skins; k++)
		if (in->ps[k].sss.on)
			return 1;
	return 0;
}

/* Whether the lights resolve to key (one table per skin). */
static int key_only(const struct scene *s)
{
	return s->lights_strategy == SCENE_LIGHTS_KEY ||
	    (s->lights_strategy == SCENE_LIGHTS_AUTO && s->n_lights == 1);
}

/* The scene's fill on skin k: one light (key), not translucent. */
static void set_fill(const struct scene *s, int k, struct inputs *in, struct povexport_result *r)
{
	struct pov_skin *ps = &in->ps[k];
	if (!(s->fill[0] > 0 || s->fill[1] > 0 || s->fill[2] > 0))
		return;
	if (!key_only(s) || ps->sss.on || (!ps->maps && ps->n_albedo < 1)) {
		msg(r, "skin '%s': fill left out (it needs lights key, a bake, and not --mode "
		    "translucent)",
		    s->skins[k].name);
		return;
	}
	ps->fill = 1;
	const struct bake *b = !ps->maps && in->src[k] ? in->src[k]->bake : NULL;
	if (b != NULL)
		in->fill_curve[k] = povsplit_fill_curve(b, ps->n_albedo, ps->theta_albedo,
		    ps->albedo_curve);
	if (in->fill_curve[k])
		ps->albedo_curve = in->fill_curve[k];
}

/* The bake whose Rd(r) blurs skin k's relief for the split (the maps'
 * median member), or NULL when the split does not apply: it needs one
 * light (key), a bake, no reflection and not translucent (povsplit.h). */
static const struct bake *split_bake(const struct povexport_options *o, const struct scene *s,
    int k, const struct inputs *in)
{
	const struct pov_skin *ps = &in->ps[k];
	const struct bake *b = ps->maps ? brdf_family_member_bake(ps->maps->fam, ps->maps->ref)
		: in->src[k] ? in->src[k]->bake : NULL;
	if (o->sharp_diffuse || ps->sss.on || !key_only(s) || s->skins[k].reflection)
		return NULL;
	return b;
}

/* The split (povsplit.h): the diffuse part gets the height map blurred by
 * the bake's Rd(r); alpha_sub is the relief the box filter took away, added
 * to the specular's alpha (povsplit_spec). */
static int load_split(const struct povexport_options *o, const struct scene *s, const char *base,
    int k, struct inputs *in, double alpha_sub, struct povexport_result *r, char **cause)
{
	struct pov_skin *ps = &in->ps[k];
	const char *sn = s->skins[k].name;
	const struct bake *b = split_bake(o, s, k, in);
	if (ps->height_png == NULL || b == NULL || !(in->hm[k].h_range_um > 0))
		return 0;	/* a flat relief: nothing to blur */
	struct povsplit_kernel kr;
	double ratio;
	char *err = NULL;
	if (povsplit_make(&in->hm[k], b, &in->blur[k], &kr, &ratio, &err) != 0) {
		msg(r, "skin '%s': the diffuse part keeps the sharp relief: %s", sn, err);
		free(err);
		return 0;
	}
	in->blurs[k] = xasprintf("%s_%s_height_diffuse.png", base, sn);
	ps->diffuse_png = in->blurs[k];
	double toksvig = sqrt(b->roughness * b->roughness + alpha_sub * alpha_sub);
	ps->spec_alpha = fmax(b->roughness, fmin(toksvig, POVSPLIT_ALPHA_WHOLE));
	ps->spec.alpha = ps->spec_alpha;
	if (alpha_sub > 0)
		msg(r, "skin '%s': the relief below the bump map's texels (RMS slope %.3g) widens "
		    "the specular's GGX alpha %.3g -> %.3g (Toksvig's %.3g, capped at the "
		    "measured whole-face lobe %.2f)", sn, alpha_sub,
		    b->roughness, ps->spec_alpha, toksvig, POVSPLIT_ALPHA_WHOLE);
	const struct bumpmap *bl = &in->blur[k];
	ps->diffuse_bump_size = bumpmap_size(bl->h_range_um, bl->size_px, bl->tile_mm);
	msg(r, "skin '%s': the diffuse part sees the height map blurred by Rd(r)%s (mean radius "
	    "%.3g mm, %.0f %% of it within half a texel), its RMS slope %.0f %% of the relief's; "
	    "the surface specular sees the relief", sn,
	    ps->maps ? " of the maps' median member" : "", kr.mean_um * 1e-3, 100 * kr.w0,
	    100 * ratio);
	(void)cause;
	return 0;
}

static int load_bumps(const struct povexport_options *o, const struct scene *s, const char *base,
    int k, struct inputs *in, struct povexport_result *r, char **cause)
{
	const struct scene_skin *sk = &s->skins[k];
	struct bumpmap *h = &in->hm[k];
	const char *tdir = bind_find(o->texs, o->n_texs, sk->name);
	if (tdir == NULL)
		tdir = sk->textures;
	if (tdir == NULL || !sk->bumps)
		return 0;
	if (in->ps[k].sss.on && in->ps[k].maps) {
		/* The maps' texture_map of layered members is the object's whole texture. */
		msg(r, "skin '%s': translucent maps are written without the bump map", sk->name);
		return 0;
	}
	for (int i = 0; i < s->n_objects && in->ps[k].sss.on; i++)
		if (s->objects[i].shape == SCENE_MESH && s->objects[i].material == SCENE_MAT_SKIN &&
		    s->objects[i].skin == k) {
			/* A mesh's bump map is a texture per triangle, which cannot be layered. */
			msg(r, "skin '%s': translucent meshes are written without the bump map",
			    sk->name);
			return 0;
		}
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *ob = &s->objects[i];
		if (ob->shape == SCENE_MESH && ob->material == SCENE_MAT_SKIN && ob->skin == k &&
		    ob->mesh->uv == NULL)
			return *cause = xasprintf("[object %s]: the mesh (%s) has no UV "
			    "coordinates, so the bump map of skin '%s' cannot follow it: give the "
			    "model UVs, or set bumps = off in [skin %s]",
				   ob->name, ob->mesh->source, sk->name, sk->name),
			       -1;
	}
	if (bumpmap_load(tdir, h, cause) != 0)
		return -1;
	in->heights[k] = xasprintf("%s_%s_height.png", base, sk->name);
	in->ps[k].height_png = in->heights[k];
	in->ps[k].tile_units = h->tile_mm / s->unit_mm;
	/* With the split the specular takes the relief below the map's texels as
	 * roughness (maps: load_far does not apply). */
	double texel = in->ps[k].tile_units / h->size_px, px = pixel_footprint(s, k), s2 = 0;
	int split = split_bake(o, s, k, in) != NULL && in->ps[k].maps;
	int f = o->bump_filter ? bumpmap_filter_factor(h->size_px, texel, px) : 1;
	if (f > 1 && split)
		s2 = povsplit_slope2(h);
	if (f > 1) {
		msg(r, "skin '%s': height map box-filtered %d -> %d px (texel %.3g mm, image pixel "
		    "%.3g mm on the nearest object; --bump-filter off keeps it)",
		    sk->name, h->size_px, h->size_px / f, h->tile_mm / h->size_px,
		    pixel_footprint(s, k) * s->unit_mm);
		bumpmap_reduce(h, f);
	}
	double alpha_sub = split && f > 1 ? sqrt(fmax(0, s2 - povsplit_slope2(h))) : 0;
	in->ps[k].bump_size = bumpmap_size(h->h_range_um, h->size_px, h->tile_mm);
	/* --bump-filter off keeps the bump map as it is, also below a pixel. */
	if (o->bump_filter && load_far(s, base, k, tdir, in, r, cause) != 0)
		return -1;
	/* The cavity map (texture directories of issue 24's relief7 round on)
	 * darkens furrows and pores where the bump map is drawn, on meshes
	 * (mesh2.h); SKINBAKE_CAVITY=off leaves it out. */
	char *cp = xasprintf("%s/cavity.png", tdir);
	const char *env = getenv("SKINBAKE_CAVITY");
	if (in->ps[k].height_png != NULL && access(cp, R_OK) == 0
	    && !(env != NULL && strcmp(env, "off") == 0)) {
		in->cav_src[k] = cp;
		in->cavs[k] = xasprintf("%s_%s_cavity.png", base, sk->name);
		in->ps[k].cavity_png = in->cavs[k];
	} else
		free(cp);
	return load_split(o, s, base, k, in, alpha_sub, r, cause);
}

/* The cavity map box-filtered by f like the height map (the mean of its
 * blocks: a pixel's average darkening, without aliasing). */
static int write_cavity(const char *src, int f, const char *dst, char **cause)
{
	int n, h, ch, bits;
	uint16_t *px = pngio_read(src, &n, &h, &ch, &bits, cause);
	if (px == NULL)
		return -1;
	if (n != h || ch != 1 || bits != 16 || n % f != 0) {
		free(px);
		return povfiles_copy(src, dst, cause);
	}
	double lo, hi;
	uint16_t *q = bumpmap_filter(px, n, 0, 1, f, &lo, &hi);
	for (size_t i = 0; i < (size_t)(n / f) * (size_t)(n / f); i++)
		q[i] = (uint16_t)nearbyint((lo + q[i] / 65535.0 * (hi - lo)) * 65535);
	int e = pngio_write(dst, n / f, n / f, 1, 16, q, 0, 0, NULL, cause);
	free(px);
	free(q);
	return e;
}

/* The height maps, far roughness maps and the shape macros next to the written scene. */
static int write_extras(const struct scene *s, const char *out, const char *base,
    const struct inputs *in, char **cause)
{
	for (int k = 0; k < s->n_skins; k++)
		if (in->heights[k]) {
			char *dst = xasprintf("%s/%s", out, in->heights[k]);
			int e = in->hm[k].filter > 1 ? bumpmap_write_png(&in->hm[k], dst, cause)
						     : povfiles_copy(in->hm[k].src, dst, cause);
			free(dst);
			if (e != 0)
				return -1;
		}
	for (int k = 0; k < s->n_skins; k++)
		if (in->blurs[k]) {
			char *dst = xasprintf("%s/%s", out, in->blurs[k]);
			int e = bumpmap_write_png(&in->blur[k], dst, cause);
			free(dst);
			if (e != 0)
				return -1;
		}
	for (int k = 0; k < s->n_skins; k++)
		if (in->cavs[k]) {
			char *dst = xasprintf("%s/%s", out, in->cavs[k]);
			int f = in->hm[k].filter;
			int e = f > 1 ? write_cavity(in->cav_src[k], f, dst, cause)
				      : povfiles_copy(in->cav_src[k], dst, cause);
			free(dst);
			if (e != 0)
				return -1;
		}
	for (int k = 0; k < s->n_skins; k++)
		if (in->fars[k]) {
			char *dst = xasprintf("%s/%s", out, in->fars[k]);
			int e = pngio_write(dst, in->far_m[k], in->far_m[k], 1, 16, in->far_px[k],
			    0, 0, NULL, cause);
			free(dst);
			if (e != 0)
				return -1;
		}
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *ob = &s->objects[i];
		char *name = ob->material == SCENE_MAT_MODEL ? povmodel_texture_file(ob, base)
		    : NULL;
		if (name == NULL)
			continue;
		char *dst = xasprintf("%s/%s", out, name);
		int e = ob->mesh->texture
		    ? povfiles_write_bytes(dst, ob->mesh->texture, ob->mesh->texture_size, cause)
					  : povfiles_copy(ob->mesh->texture_file, dst, cause);
		free(dst);
		free(name);
		if (e != 0)
			return -1;
	}
	for (int k = 0; k < s->n_skins; k++)
		if (in->maps[k] && pov_maps_write_images(in->maps[k], out, cause) != 0)
			return -1;
	if (in->shapes) {
		char *dst = xasprintf("%s/skinbake_shapes.inc", out);
		int e = povfiles_copy(in->shapes, dst, cause);
		free(dst);
		if (e != 0)
			return -1;
	}
	return 0;
}

static void report(const struct povexport_options *o, const struct scene *s,
    const struct pov_report *rep, double seconds, struct povexport_result *r)
{
	char tab[64] = "", gam[64] = "", mix[64] = "";
	if (rep->strategy == SCENE_LIGHTS_KEY || rep->strategy == SCENE_LIGHTS_PASSES)
		snprintf(tab, sizeof tab, ", %dx%d table", o->n_theta, o->n_theta);
	if (rep->n_gamma_used > 1)
		snprintf(gam, sizeof gam, " x %d light-view angles", rep->n_gamma_used);
	if (rep->strategy == SCENE_LIGHTS_MIXTURE)
		snprintf(mix, sizeof mix, ", %d^3 mixture table", o->n_mix);
	msg(r, "%s: lights %s%s%s%s (%.2f s)", o->out, scene_strategy_name(rep->strategy), tab, gam,
	    mix, seconds);
	if (rep->strategy == SCENE_LIGHTS_KEY && s->n_lights > 1)
		msg(r,
		    "warning: lights = key with %d lights: the table is exact only for light '%s'",
		    s->n_lights, s->lights[0].name);
	if (rep->mix_error >= 0)
		msg(r, "lights auto: the one-pass mixture table would be %.2f %% off for these "
		    "lights and camera (estimated; the limit is %.1f %%), so %s",
		    100 * rep->mix_error, 100 * STRATEGY_MIX_MAX,
		    rep->strategy == SCENE_LIGHTS_MIXTURE ? "mixture"
		    : "passes (exact: one table per light)");
	else if (rep->strategy == SCENE_LIGHTS_MIXTURE && rep->mix_gamma_spread > 0.05 * M_PI / 180)
		msg(r, "note: the mixture table takes each light-view angle at the objects' "
		    "centre; it varies by %.1f deg over them (use --lights passes to be exact)",
		    rep->mix_gamma_spread * 180 / M_PI);
	if (rep->strategy == SCENE_LIGHTS_SEPARABLE ||
	    (rep->strategy == SCENE_LIGHTS_PASSES && !rep->layered))
		msg(r,
		    "separable fit%s: mean error %.1f %%, rms error %.1f %% of pi*f*cos(theta_i) "
		    "for angles up to 80 deg",
		    rep->strategy == SCENE_LIGHTS_PASSES ? " (used without animation)" : "",
		    100 * rep->sep_mean, 100 * rep->sep_rms);
	for (int i = 0; i < rep->n_files && r->n_files < 16; i++)
		r->files[r->n_files++] = xasprintf("%s/%s", o->out, rep->files[i]);
}

static int write_all(const struct povexport_options *o, const struct scene *s, const char *base,
    struct inputs *in, struct povexport_result *r, char **cause)
{
	struct pov_report rep = { 0 };
	struct outdir od;
	if (outdir_begin(&od, o->out, &povfiles_outdir_kind, cause) != 0)
		return -1;
	const char *stage = outdir_path(&od);
	struct pov_options po = {
		.base = base,
		.n_theta = o->n_theta,
		.n_gamma = o->n_gamma,
		.n_mix = o->n_mix,
		.write_scene = o->scene_path != NULL,
		.shapes_inc = in->shapes ? "skinbake_shapes.inc" : NULL,
		.sss_samples = any_sss(s, in) ? o->sss_samples : 0,
	};
	double t0 = util_now();
	struct povao_stats ao = { 0 };
	if (povfiles_write(s, in->ps, &po, stage, &rep, cause) != 0 ||
	    write_extras(s, stage, base, in, cause) != 0 ||
	    (rep.strategy == SCENE_LIGHTS_KEY && povao_write(s, stage, base, &ao, cause) != 0) ||
	    povfiles_write_index(stage, cause) != 0) {
		povfiles_report_free(&rep);
		outdir_fail(&od, cause);
		return -2;
	}
	if (outdir_commit(&od, cause) != 0) {
		povfiles_report_free(&rep);
		return -2;
	}
	report(o, s, &rep, util_now() - t0, r);
	if (ao.n_vertices > 0)
		msg(r, "fill occlusion: %d rays at each of %d mesh vertices in view, "
		    "mean visibility %.3f (%.2f s)", ao.n_rays, ao.n_vertices, ao.mean_v,
		    ao.seconds);
	povfiles_report_free(&rep);
	return 0;
}

/* --out may be replaced by an export, and is none of the inputs. */
static int check_out(const struct povexport_options *o, char **cause)
{
	const char *in[2 * POVEXPORT_MAX_BIND + 5] = { NULL },
	    *more[] = { o->scene_path, o->family, o->maps, o->data_dir };
	int n = 0;
	for (int i = 0; i < o->n_bakes + o->n_texs + 4; i++) {
		const char *b = i < o->n_bakes ? o->bakes[i] : i < o->n_bakes + o->n_texs
		    ? o->texs[i - o->n_bakes]
		    : more[i - o->n_bakes - o->n_texs], *eq = b ? strchr(b, '=') : NULL;
		if (b)
			in[n++] = i < o->n_bakes + o->n_texs && eq ? eq + 1 : b;
	}
	return outdir_check(o->out, &povfiles_outdir_kind, in, cause);
}

int povexport_run(const struct povexport_options *o, struct povexport_result *r, char **cause)
{
	struct inputs in = { 0 };
	char *base = NULL;
	int rc = -1;
	struct scene *s = make_scene(o, cause);
	if (s == NULL)
		return -1;
	if (o->plan) {
		print_plan(o->plan_out, s);
		scene_free(s);
		return 0;
	}
	if (o->out == NULL) {
		*cause = xstrdup("--out DIR is required");
		goto done;
	}
	if (check_out(o, cause) != 0)
		goto done;
	base = o->name ? xstrdup(o->name) : o->scene_path ? base_from_scene(o->scene_path)
	    : xstrdup("skin");
	if (!*base || strspn(base,
	    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") != strlen(base)) {
		*cause = xasprintf("--name = '%s' must be letters, digits, '_', '.' or '-'", base);
		goto done;
	}
	for (int k = 0; k < s->n_skins; k++)
		if (load_brdf(o, s, k, &in, r, cause) != 0 ||
		    (o->family && load_maps(o, s, base, k, &in, cause) != 0) ||
		    load_sss(o, s, k, &in, r, cause) != 0 ||
		    load_bumps(o, s, base, k, &in, r, cause) != 0)
			goto done;
	for (int k = 0; k < s->n_skins; k++)
		set_fill(s, k, &in, r);
	int need_shapes = 0;
	for (int i = 0; i < s->n_objects; i++)
		need_shapes |= s->objects[i].shape == SCENE_HAND ||
		    s->objects[i].shape == SCENE_HEAD;
	if (need_shapes && (in.shapes = find_shapes(o->data_dir, o->scene_path)) == NULL) {
		*cause = xstrdup("skinbake_shapes.inc not found (give --data-dir DIR)");
		goto done;
	}
	rc = write_all(o, s, base, &in, r, cause);
done:
	inputs_free(&in);
	free(base);
	scene_free(s);
	return rc;
}
