/* skinbake export pov: a bake (and micro-geometry maps) plus a scene file,
 * or lights and a camera given on the command line, to a POV-Ray 3.7
 * include file of lit-table textures and, with a scene, a complete .pov. */
#include "config.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bake/bakefile.h"
#include "cli/cli.h"
#include "io/pngio.h"
#include "export/pov/pov.h"
#include "export/pov/scene.h"
#include "base/util.h"

static const char *CMD = "export pov";

static void help(FILE *fp)
{
	fprintf(fp,
	    "usage: skinbake export pov --bake [SKIN=]DIR [--textures [SKIN=]DIR]\n"
	    "                           (--scene FILE | --light SPEC [--light SPEC ...] --camera SPEC)\n"
	    "                           --out DIR [options]\n"
	    "\n"
	    "Write POV-Ray 3.7 SDL that evaluates a baked skin BRDF as 'lit tables'\n"
	    "(pigment = pi*f_r over slope/aoi blend maps, finish diffuse 1 brilliance 1):\n"
	    "shadows, area lights and bump maps stay right.  See docs/pov.md.\n"
	    "\n"
	    "  --scene FILE           scene file (format: scenes/README.md); writes BASE.inc,\n"
	    "                         BASE.pov and BASE.ini (+ BASE_combine.* for passes)\n"
	    "  --light SPEC           without --scene (repeat, 1 to %d): comma-separated\n"
	    "                         type=parallel|point (default parallel), position=X:Y:Z\n"
	    "                         (required), point_at=X:Y:Z (default 0:0:0),\n"
	    "                         color=R:G:B (default 1:1:1, each in [0, 1e6]), name=NAME\n"
	    "  --camera SPEC          without --scene: type=orthographic|perspective,\n"
	    "                         location=X:Y:Z, look_at=X:Y:Z (default 0:0:0),\n"
	    "                         angle=DEG (perspective, [1, 170], default 40),\n"
	    "                         width=UNITS (orthographic, default 2.4); only the include\n"
	    "                         file is written\n"
	    "  --bake [SKIN=]DIR      bake directory from `skinbake bake` (repeat per skin; a bare\n"
	    "                         DIR serves every skin without one; default: the scene\n"
	    "                         skin's bake = DIR)\n"
	    "  --textures [SKIN=]DIR  micro-geometry directory from `skinbake texture`\n"
	    "                         (height.png, 16-bit); default: the skin's textures = DIR;\n"
	    "                         none: no bump map\n"
	    "  --out DIR              output directory, created if missing (required)\n"
	    "  --name BASE            base name of the output files (default: the scene file\n"
	    "                         name without .scene; 'skin' without a scene)\n"
	    "  --lights auto|key|mixture|passes|separable\n"
	    "                         light strategy (default: the scene's, else auto = key for\n"
	    "                         1 light, mixture for 2, passes for more)\n"
	    "  --nodes N              key-table nodes in theta_i and theta_o [2, 255] (default 65)\n"
	    "  --gamma-nodes N        light-view angle nodes where it varies [1, 256] (default 17)\n"
	    "  --mix-nodes N          two-light mixture nodes per axis [2, 255] (default 25)\n"
	    "  --data-dir DIR         where skinbake_shapes.inc is (default: $SKINBAKE_DATADIR,\n"
	    "                         then %s, then ../exporters/pov next to the scene)\n"
	    "  --bump-filter auto|off box-filter the height map so its texels are at most half\n"
	    "                         an image pixel on the nearest skin object (default auto)\n"
	    "  --analytic             use an analytic skin-like BRDF instead of a bake (tests)\n"
	    "  --plan                 print the incidence angles and wavelengths the scene\n"
	    "                         needs from a bake, write nothing\n"
	    "  --help                 this text\n"
	    "\n"
	    "Renders are linear (assumed_gamma 1): a white Lambertian under a light of colour 1\n"
	    "at normal incidence shows 1, so pixel = pi * radiance.\n",
	    SCENE_MAX_LIGHTS, PKGDATADIR);
}

/* "SKIN=DIR" or "DIR" options, bound to skins after the scene is known. */
struct binding {
	char *skin;	/* NULL: every skin without its own */
	char *dir;
};

static void bind_parse(const char *arg, struct binding *b)
{
	const char *eq = strchr(arg, '=');
	if (eq != NULL && eq != arg && strcspn(arg, "/") > (size_t)(eq - arg)) {
		b->skin = xasprintf("%.*s", (int)(eq - arg), arg);
		b->dir = xstrdup(eq + 1);
	} else {
		b->skin = NULL;
		b->dir = xstrdup(arg);
	}
}

static const char *bind_find(const struct binding *b, int n, const char *skin)
{
	for (int i = 0; i < n; i++)
		if (b[i].skin != NULL && !strcmp(b[i].skin, skin))
			return b[i].dir;
	for (int i = 0; i < n; i++)
		if (b[i].skin == NULL)
			return b[i].dir;
	return NULL;
}

static int parse_vec(const char *opt, const char *key, const char *v, double out[3])
{
	char *end;
	const char *s = v;
	for (int i = 0; i < 3; i++) {
		errno = 0;
		out[i] = strtod(s, &end);
		if (end == s || errno || !isfinite(out[i]) || (i < 2 && *end != ':') || (i == 2 && *end != '\0'))
			return cli_usage_error(CMD, "%s %s = '%s' is not X:Y:Z", opt, key, v), -1;
		s = end + 1;
	}
	return 0;
}

/* --light and --camera specs into the synthetic scene. */
static int parse_light(const char *spec, struct scene *s)
{
	if (s->n_lights == SCENE_MAX_LIGHTS)
		return cli_usage_error(CMD, "--light: at most %d lights", SCENE_MAX_LIGHTS), -1;
	struct scene_light *l = &s->lights[s->n_lights];
	*l = (struct scene_light){ .type = SCENE_LIGHT_PARALLEL, .color = { 1, 1, 1 }, .area_samples = 5 };
	snprintf(l->name, sizeof l->name, "L%d", s->n_lights + 1);
	char *buf = xstrdup(spec), *save = NULL;
	int have_pos = 0, rc = -1;
	for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		char *eq = strchr(t, '=');
		if (eq == NULL) {
			cli_usage_error(CMD, "--light: '%s' is not key=value (keys type, position, point_at, color, name)", t);
			goto out;
		}
		*eq = '\0';
		const char *k = t, *v = eq + 1;
		if (!strcmp(k, "type")) {
			if (!strcmp(v, "parallel"))
				l->type = SCENE_LIGHT_PARALLEL;
			else if (!strcmp(v, "point"))
				l->type = SCENE_LIGHT_POINT;
			else {
				cli_usage_error(CMD, "--light type = '%s' is not parallel or point", v);
				goto out;
			}
		} else if (!strcmp(k, "position")) {
			if (parse_vec("--light", k, v, l->position) != 0)
				goto out;
			have_pos = 1;
		} else if (!strcmp(k, "point_at")) {
			if (parse_vec("--light", k, v, l->point_at) != 0)
				goto out;
		} else if (!strcmp(k, "color")) {
			if (parse_vec("--light", k, v, l->color) != 0)
				goto out;
			for (int i = 0; i < 3; i++)
				if (l->color[i] < 0 || l->color[i] > 1e6) {
					cli_usage_error(CMD, "--light color = '%s': components must be in [0, 1e6]", v);
					goto out;
				}
		} else if (!strcmp(k, "name")) {
			size_t n = strlen(v), ok = n > 0 && n < sizeof l->name;
			for (size_t i = 0; ok && i < n; i++)
				ok = (v[i] >= 'a' && v[i] <= 'z') || (v[i] >= 'A' && v[i] <= 'Z') || (v[i] >= '0' && v[i] <= '9')
				    || v[i] == '_';
			if (!ok) {
				cli_usage_error(CMD, "--light name = '%s' is not a name (letters, digits, _)", v);
				goto out;
			}
			memcpy(l->name, v, n + 1);
		} else {
			cli_usage_error(CMD, "--light: unknown key '%s' (keys type, position, point_at, color, name)", k);
			goto out;
		}
	}
	if (!have_pos) {
		cli_usage_error(CMD, "--light '%s' lacks position=X:Y:Z", spec);
		goto out;
	}
	s->n_lights++;
	rc = 0;
out:
	free(buf);
	return rc;
}

static int parse_camera(const char *spec, struct scene *s)
{
	struct scene_camera *c = &s->camera;
	char *buf = xstrdup(spec), *save = NULL;
	int have_type = 0, have_loc = 0, rc = -1;
	*c = (struct scene_camera){ .angle = 40 * M_PI / 180, .width = 2.4 };
	for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		char *eq = strchr(t, '=');
		double x;
		if (eq == NULL) {
			cli_usage_error(CMD, "--camera: '%s' is not key=value (keys type, location, look_at, angle, width)", t);
			goto out;
		}
		*eq = '\0';
		const char *k = t, *v = eq + 1;
		if (!strcmp(k, "type")) {
			if (strcmp(v, "orthographic") && strcmp(v, "perspective")) {
				cli_usage_error(CMD, "--camera type = '%s' is not orthographic or perspective", v);
				goto out;
			}
			c->ortho = !strcmp(v, "orthographic");
			have_type = 1;
		} else if (!strcmp(k, "location")) {
			if (parse_vec("--camera", k, v, c->location) != 0)
				goto out;
			have_loc = 1;
		} else if (!strcmp(k, "look_at")) {
			if (parse_vec("--camera", k, v, c->look_at) != 0)
				goto out;
		} else if (!strcmp(k, "angle")) {
			if (cli_double(CMD, "--camera angle", v, 1, 170, &x) != 0)
				goto out;
			c->angle = x * M_PI / 180;
		} else if (!strcmp(k, "width")) {
			if (cli_double(CMD, "--camera width", v, 1e-6, 1e9, &c->width) != 0)
				goto out;
		} else {
			cli_usage_error(CMD, "--camera: unknown key '%s' (keys type, location, look_at, angle, width)", k);
			goto out;
		}
	}
	if (!have_type || !have_loc) {
		cli_usage_error(CMD, "--camera '%s' lacks %s", spec, !have_type ? "type=orthographic|perspective" : "location=X:Y:Z");
		goto out;
	}
	rc = 0;
out:
	free(buf);
	return rc;
}

static void bake_fn(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	bake_eval_rgb(ctx, ti, to, dphi, rgb);
}

/* The height map of a `skinbake texture` directory: its numbers. */
struct heightmap {
	char *src;		/* DIR/height.png */
	int size_px;		/* tile edge [px] */
	double tile_mm;		/* tile edge [mm] */
	double h_min_um;	/* height of value 0 [um] */
	double h_range_um;	/* max - min height [um] */
	uint16_t *px;		/* size_px^2 samples */
	int filter;		/* box-filter factor for the image's pixel footprint */
};

static int load_heightmap(const char *dir, struct heightmap *h)
{
	int w, hh, ch, bits;
	char *cause = NULL;
	h->src = xasprintf("%s/height.png", dir);
	uint16_t *px = pngio_read(h->src, &w, &hh, &ch, &bits, &cause);
	if (px == NULL) {
		cli_usage_error(CMD, "--textures %s: %s", dir, cause);
		free(cause);
		return -1;
	}
	h->px = px;
	if (ch != 1 || bits != 16 || w != hh)
		return cli_usage_error(CMD, "%s: expected a square 16-bit grayscale PNG, got %dx%d, %d channel(s), %d bit",
		    h->src, w, hh, ch, bits), -1;
	static const char *keys[] = { "skinbake:tile_mm", "skinbake:height_min_um", "skinbake:height_max_um" };
	double v[3];
	for (int i = 0; i < 3; i++) {
		char *t = pngio_read_text(h->src, keys[i]);
		int bad = t == NULL || util_parse_double(t, &v[i]) != 0 || !isfinite(v[i]);
		if (bad) {
			cli_usage_error(CMD, "%s: tEXt key %s is %s", h->src, keys[i], t ? "not a number" : "missing");
			free(t);
			return -1;
		}
		free(t);
	}
	if (v[0] <= 0 || v[2] < v[1])
		return cli_usage_error(CMD, "%s: tile_mm = %g must be > 0 and height_max_um = %g >= height_min_um = %g",
		    h->src, v[0], v[2], v[1]), -1;
	h->size_px = w;
	h->tile_mm = v[0];
	h->h_min_um = v[1];
	h->h_range_um = v[2] - v[1];
	return 0;
}

static int copy_file(const char *src, const char *dst, char **cause)
{
	FILE *in = fopen(src, "rb");
	if (in == NULL)
		return *cause = xasprintf("%s: %s", src, strerror(errno)), -1;
	struct outfile o;
	if (outfile_open(&o, dst, cause) != 0) {
		fclose(in);
		return -1;
	}
	char buf[65536];
	size_t n;
	while ((n = fread(buf, 1, sizeof buf, in)) > 0)
		fwrite(buf, 1, n, o.fp);
	int err = ferror(in);
	fclose(in);
	if (err) {
		outfile_abort(&o);
		return *cause = xasprintf("%s: read error", src), -1;
	}
	return outfile_commit(&o, cause);
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
		cand[n++] = sl ? xasprintf("%.*s/../exporters/pov/skinbake_shapes.inc", (int)(sl - scene_path), scene_path)
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

/* --plan: which incidence angles the scene's lights meet on skin.  Curved
 * shapes see every angle; flat ones (patch, box, plane) only the angles
 * between their face normals and the lights. */
static void print_plan(const struct scene *s)
{
	int curved = 0, n_ang = 0;
	double ang[SCENE_MAX_OBJECTS * SCENE_MAX_LIGHTS];
	printf("scene %s: lights strategy %s\n", s->path, scene_strategy_name(pov_strategy(s)));
	for (int i = 0; i < s->n_objects; i++) {
		const struct scene_object *o = &s->objects[i];
		if (o->material == SCENE_MAT_PLAIN)
			continue;
		if (o->shape == SCENE_SPHERE || o->shape == SCENE_HAND || o->shape == SCENE_HEAD) {
			curved = 1;
			continue;
		}
		for (int l = 0; l < s->n_lights; l++) {
			double n[3] = { 0, 0, -1 }, d[3], p[3] = { o->center[0] + o->translate[0], o->center[1] + o->translate[1],
				o->center[2] + o->translate[2] };
			if (o->shape == SCENE_PLANE)
				memcpy(n, o->normal, sizeof n);
			else {
				/* rotate (x, then y, then z) the face normal -z */
				double a = o->rotate[0], b = o->rotate[1], c = o->rotate[2], t[3];
				t[0] = n[0], t[1] = n[1] * cos(a) - n[2] * sin(a), t[2] = n[1] * sin(a) + n[2] * cos(a);
				n[0] = t[0] * cos(b) + t[2] * sin(b), n[1] = t[1], n[2] = -t[0] * sin(b) + t[2] * cos(b);
				t[0] = n[0] * cos(c) - n[1] * sin(c), t[1] = n[0] * sin(c) + n[1] * cos(c), t[2] = n[2];
				memcpy(n, t, sizeof n);
			}
			scene_light_dir(&s->lights[l], p, d);
			double ct = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
			double a = acos(fmax(-1, fmin(1, ct))) * 180 / M_PI;
			printf("object %s, light %s: theta_in %.2f deg%s\n", o->name, s->lights[l].name, a,
			    a >= 90 ? " (unlit)" : "");
			if (a < 90)
				ang[n_ang++] = a;
		}
	}
	if (curved)
		printf("curved skin objects: theta_in over [0, 90] deg (the table nodes are uniform in angle)\n");
	printf("wavelengths: the visible range (the tables are linear sRGB from the spectral bake)\n");
	for (int k = 0; k < s->n_skins; k++) {
		printf("skin %s: skinbake bake --preset %s ", s->skins[k].name, s->skins[k].preset);
		if (curved || n_ang == 0)
			printf("--theta-nodes 10");
		else
			for (int i = 0; i < n_ang; i++)
				printf("%s%.2f", i ? "," : "--theta-in ", ang[i]);
		printf(" --out %s\n", s->skins[k].bake ? s->skins[k].bake : "DIR");
	}
	if (!curved && n_ang > 0)
		printf("(bump maps tilt the normal: add neighbouring angles if the skin has relief)\n");
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
		scene_object_bounds(o, lo, hi);
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
		if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_'
		    || *c == '-'))
			*c = '_';
	return r;
}

int cmd_export_pov(int argc, char **argv)
{
	enum { O_SCENE = 1, O_LIGHT, O_CAMERA, O_BAKE, O_TEXTURES, O_OUT, O_NAME, O_LIGHTS, O_NODES, O_GNODES, O_MNODES,
		O_DATA, O_ANALYTIC, O_PLAN, O_FILTER, O_HELP };
	static const struct option opts[] = {
		{ "scene", required_argument, NULL, O_SCENE }, { "light", required_argument, NULL, O_LIGHT },
		{ "camera", required_argument, NULL, O_CAMERA }, { "bake", required_argument, NULL, O_BAKE },
		{ "textures", required_argument, NULL, O_TEXTURES }, { "out", required_argument, NULL, O_OUT },
		{ "name", required_argument, NULL, O_NAME }, { "lights", required_argument, NULL, O_LIGHTS },
		{ "nodes", required_argument, NULL, O_NODES }, { "gamma-nodes", required_argument, NULL, O_GNODES },
		{ "mix-nodes", required_argument, NULL, O_MNODES }, { "data-dir", required_argument, NULL, O_DATA },
		{ "analytic", no_argument, NULL, O_ANALYTIC }, { "plan", no_argument, NULL, O_PLAN },
		{ "bump-filter", required_argument, NULL, O_FILTER },
		{ "help", no_argument, NULL, O_HELP }, { NULL, 0, NULL, 0 } };
	const char *scene_path = NULL, *out = NULL, *name = NULL, *data_dir = NULL, *lights = NULL;
	struct binding bakes[SCENE_MAX_SKINS + 1], texs[SCENE_MAX_SKINS + 1];
	int n_bakes = 0, n_texs = 0, analytic = 0, plan = 0, rc = CLI_EXIT_USAGE, have_camera = 0, bump_filter = 1;
	long nodes = 65, gnodes = 17, mnodes = 25;
	struct scene cl = { 0 };	/* lights and camera from the command line */
	struct scene *s = NULL;
	struct bake *bk[SCENE_MAX_SKINS] = { 0 };
	struct heightmap hm[SCENE_MAX_SKINS] = { 0 };
	struct pov_skin ps[SCENE_MAX_SKINS];
	char *heights[SCENE_MAX_SKINS] = { 0 }, *shapes = NULL, *base = NULL, *cause = NULL;
	struct pov_report rep = { 0 };
	int c;

	optind = 1;
	while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (c) {
		case O_SCENE:
			scene_path = optarg;
			break;
		case O_LIGHT:
			if (parse_light(optarg, &cl) != 0)
				goto done;
			break;
		case O_CAMERA:
			if (parse_camera(optarg, &cl) != 0)
				goto done;
			have_camera = 1;
			break;
		case O_BAKE:
		case O_TEXTURES:
			if ((c == O_BAKE ? n_bakes : n_texs) > SCENE_MAX_SKINS) {
				cli_usage_error(CMD, "too many --%s options", c == O_BAKE ? "bake" : "textures");
				goto done;
			}
			if (c == O_BAKE)
				bind_parse(optarg, &bakes[n_bakes++]);
			else
				bind_parse(optarg, &texs[n_texs++]);
			break;
		case O_OUT:
			out = optarg;
			break;
		case O_NAME:
			name = optarg;
			break;
		case O_LIGHTS:
			lights = optarg;
			break;
		case O_NODES:
			if (cli_long(CMD, "--nodes", optarg, 2, POV_MAX_NODES, &nodes) != 0)
				goto done;
			break;
		case O_GNODES:
			if (cli_long(CMD, "--gamma-nodes", optarg, 1, 256, &gnodes) != 0)
				goto done;
			break;
		case O_MNODES:
			if (cli_long(CMD, "--mix-nodes", optarg, 2, POV_MAX_NODES, &mnodes) != 0)
				goto done;
			break;
		case O_DATA:
			data_dir = optarg;
			break;
		case O_ANALYTIC:
			analytic = 1;
			break;
		case O_PLAN:
			plan = 1;
			break;
		case O_FILTER:
			if (strcmp(optarg, "auto") && strcmp(optarg, "off")) {
				cli_usage_error(CMD, "--bump-filter = '%s' is not auto or off", optarg);
				goto done;
			}
			bump_filter = !strcmp(optarg, "auto");
			break;
		case O_HELP:
		case 'h':
			help(stdout);
			rc = CLI_EXIT_OK;
			goto done;
		default:
			help(stderr);
			goto done;
		}
	}
	if (optind < argc) {
		cli_usage_error(CMD, "unexpected argument '%s'", argv[optind]);
		goto done;
	}

	/* The scene: from the file, or synthetic from --light/--camera. */
	if (scene_path != NULL) {
		if (cl.n_lights > 0 || have_camera) {
			cli_usage_error(CMD, "--scene and --light/--camera exclude each other");
			goto done;
		}
		s = scene_load(scene_path, &cause);
		if (s == NULL) {
			cli_usage_error(CMD, "%s", cause);
			goto done;
		}
	} else {
		if (cl.n_lights == 0 || !have_camera) {
			cli_usage_error(CMD, "give --scene FILE, or --light SPEC and --camera SPEC (see --help)");
			goto done;
		}
		s = xcalloc(1, sizeof *s);
		*s = cl;
		s->path = xstrdup("the command line");
		s->width = 320, s->height = 240, s->unit_mm = 10;
		s->n_skins = 1;
		snprintf(s->skins[0].name, sizeof s->skins[0].name, "skin");
		s->skins[0].preset = xstrdup("(from the bake)");
		s->skins[0].bumps = 1;
	}
	if (lights != NULL) {
		static const char *names[] = { "auto", "key", "mixture", "passes", "separable" };
		int i;
		for (i = 0; i < 5 && strcmp(lights, names[i]); i++)
			;
		if (i == 5) {
			cli_usage_error(CMD, "--lights = '%s' is not one of auto, key, mixture, passes, separable", lights);
			goto done;
		}
		s->lights_strategy = (enum scene_strategy)i;
	}
	if (pov_strategy(s) == SCENE_LIGHTS_MIXTURE && s->n_lights != 2) {
		cli_usage_error(CMD, "lights = mixture needs exactly 2 lights, %s has %d", s->path, s->n_lights);
		goto done;
	}
	for (int i = 0; i < n_bakes; i++)
		if (bakes[i].skin && scene_find_skin(s, bakes[i].skin) < 0) {
			cli_usage_error(CMD, "--bake %s=...: the scene has no skin '%s'", bakes[i].skin, bakes[i].skin);
			goto done;
		}
	for (int i = 0; i < n_texs; i++)
		if (texs[i].skin && scene_find_skin(s, texs[i].skin) < 0) {
			cli_usage_error(CMD, "--textures %s=...: the scene has no skin '%s'", texs[i].skin, texs[i].skin);
			goto done;
		}
	if (plan) {
		print_plan(s);
		rc = CLI_EXIT_OK;
		goto done;
	}
	if (out == NULL) {
		cli_usage_error(CMD, "--out DIR is required");
		goto done;
	}
	base = name ? xstrdup(name) : scene_path ? base_from_scene(scene_path) : xstrdup("skin");
	if (!*base || strspn(base, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") != strlen(base)) {
		cli_usage_error(CMD, "--name = '%s' must be letters, digits, '_', '.' or '-'", base);
		goto done;
	}

	/* Load every input before writing anything. */
	for (int k = 0; k < s->n_skins; k++) {
		struct scene_skin *sk = &s->skins[k];
		ps[k] = (struct pov_skin){ .ior = 1.5, .albedo_rgb = { 0.62, 0.42, 0.33 } };
		if (analytic) {
			ps[k].brdf = (struct pov_brdf){ .f_rgb = pov_brdf_analytic };
		} else {
			const char *dir = bind_find(bakes, n_bakes, sk->name);
			if (dir == NULL)
				dir = sk->bake;
			if (dir == NULL) {
				cli_usage_error(CMD, "skin '%s': no bake (give --bake DIR or bake = DIR in [skin %s])", sk->name,
				    sk->name);
				goto done;
			}
			bk[k] = bake_load(dir, &cause);
			if (bk[k] == NULL) {
				cli_usage_error(CMD, "skin '%s': bake %s: %s", sk->name, dir, cause);
				goto done;
			}
			if (scene_path && bk[k]->preset && strcmp(bk[k]->preset, sk->preset))
				fprintf(stderr, "skinbake %s: note: skin '%s' asks for preset '%s', the bake %s has '%s'\n", CMD,
				    sk->name, sk->preset, dir, bk[k]->preset);
			if (scene_path == NULL && bk[k]->preset) {
				free(sk->preset);
				sk->preset = xstrdup(bk[k]->preset);
			}
			ps[k].brdf = (struct pov_brdf){ bake_fn, bk[k], bk[k]->n_ti, bk[k]->n_to, bk[k]->theta_i,
				bk[k]->theta_o };
			ps[k].ior = bk[k]->ior;
			for (int ch = 0; ch < 3; ch++)
				ps[k].albedo_rgb[ch] = bk[k]->albedo_rgb[ch * bk[k]->n_ti];
		}
		const char *tdir = bind_find(texs, n_texs, sk->name);
		if (tdir == NULL)
			tdir = sk->textures;
		if (tdir != NULL && sk->bumps) {
			if (load_heightmap(tdir, &hm[k]) != 0)
				goto done;
			heights[k] = xasprintf("%s_%s_height.png", base, sk->name);
			ps[k].height_png = heights[k];
			ps[k].tile_units = hm[k].tile_mm / s->unit_mm;
			hm[k].filter = bump_filter ? pov_filter_factor(hm[k].size_px, ps[k].tile_units / hm[k].size_px,
							 pixel_footprint(s, k))
						   : 1;
			if (hm[k].filter > 1) {
				double lo, hi;
				uint16_t *f = pov_filter_height(hm[k].px, hm[k].size_px, hm[k].h_min_um,
				    hm[k].h_min_um + hm[k].h_range_um, hm[k].filter, &lo, &hi);
				fprintf(stderr, "skinbake %s: skin '%s': height map box-filtered %d -> %d px (texel %.3g mm, "
				    "image pixel %.3g mm on the nearest object; --bump-filter off keeps it)\n", CMD, sk->name,
				    hm[k].size_px, hm[k].size_px / hm[k].filter, hm[k].tile_mm / hm[k].size_px,
				    pixel_footprint(s, k) * s->unit_mm);
				free(hm[k].px);
				hm[k].px = f;
				hm[k].size_px /= hm[k].filter;
				hm[k].h_min_um = lo;
				hm[k].h_range_um = hi - lo;
			}
			ps[k].bump_size = pov_bump_size(hm[k].h_range_um, hm[k].size_px, hm[k].tile_mm);
		}
	}
	int need_shapes = 0;
	for (int i = 0; i < s->n_objects; i++)
		need_shapes |= s->objects[i].shape == SCENE_HAND || s->objects[i].shape == SCENE_HEAD;
	if (need_shapes) {
		shapes = find_shapes(data_dir, scene_path);
		if (shapes == NULL) {
			cli_usage_error(CMD, "skinbake_shapes.inc not found (give --data-dir DIR)");
			goto done;
		}
	}

	/* Write. */
	rc = CLI_EXIT_FAIL;
	if (util_mkdirs(out, &cause) != 0) {
		cli_fail(CMD, "%s", cause);
		goto done;
	}
	struct pov_options po = { .base = base, .n_theta = (int)nodes, .n_gamma = (int)gnodes, .n_mix = (int)mnodes,
		.write_scene = scene_path != NULL, .shapes_inc = shapes ? "skinbake_shapes.inc" : NULL };
	double t0 = util_now();
	if (pov_export(s, ps, &po, out, &rep, &cause) != 0) {
		cli_fail(CMD, "%s", cause);
		goto done;
	}
	for (int k = 0; k < s->n_skins; k++)
		if (heights[k]) {
			char *dst = xasprintf("%s/%s", out, heights[k]);
			int e;
			if (hm[k].filter > 1) {
				char v[3][32];
				snprintf(v[0], sizeof v[0], "%.9g", hm[k].tile_mm);
				snprintf(v[1], sizeof v[1], "%.9g", hm[k].h_min_um);
				snprintf(v[2], sizeof v[2], "%.9g", hm[k].h_min_um + hm[k].h_range_um);
				struct png_text_kv kv[3] = { { "skinbake:tile_mm", v[0] }, { "skinbake:height_min_um", v[1] },
					{ "skinbake:height_max_um", v[2] } };
				e = pngio_write(dst, hm[k].size_px, hm[k].size_px, 1, 16, hm[k].px, 0, 3, kv, &cause);
			} else
				e = copy_file(hm[k].src, dst, &cause);
			free(dst);
			if (e != 0) {
				cli_fail(CMD, "%s", cause);
				goto done;
			}
		}
	if (shapes) {
		char *dst = xasprintf("%s/skinbake_shapes.inc", out);
		int e = copy_file(shapes, dst, &cause);
		free(dst);
		if (e != 0) {
			cli_fail(CMD, "%s", cause);
			goto done;
		}
	}
	fprintf(stderr, "skinbake %s: %s: lights %s", CMD, out, scene_strategy_name(rep.strategy));
	if (rep.strategy == SCENE_LIGHTS_KEY || rep.strategy == SCENE_LIGHTS_PASSES)
		fprintf(stderr, ", %ldx%ld table", nodes, nodes);
	if (rep.n_gamma_used > 1)
		fprintf(stderr, " x %d light-view angles", rep.n_gamma_used);
	if (rep.strategy == SCENE_LIGHTS_MIXTURE)
		fprintf(stderr, ", %ld^3 mixture table", mnodes);
	fprintf(stderr, " (%.2f s)\n", util_now() - t0);
	if (rep.strategy == SCENE_LIGHTS_KEY && s->n_lights > 1)
		fprintf(stderr, "skinbake %s: warning: lights = key with %d lights: the table is exact only for light '%s'\n",
		    CMD, s->n_lights, s->lights[0].name);
	if (rep.strategy == SCENE_LIGHTS_MIXTURE && rep.mix_gamma_spread > 0.05 * M_PI / 180)
		fprintf(stderr, "skinbake %s: note: the mixture table takes each light-view angle at the objects' centre; "
		    "it varies by %.1f deg over them (use --lights passes to be exact)\n", CMD,
		    rep.mix_gamma_spread * 180 / M_PI);
	if (rep.strategy == SCENE_LIGHTS_SEPARABLE || rep.strategy == SCENE_LIGHTS_PASSES)
		fprintf(stderr, "skinbake %s: separable fit%s: mean error %.1f %%, rms error %.1f %% of pi*f*cos(theta_i) "
		    "for angles up to 80 deg\n", CMD,
		    rep.strategy == SCENE_LIGHTS_PASSES ? " (used without animation)" : "", 100 * rep.sep_mean,
		    100 * rep.sep_rms);
	for (int i = 0; i < rep.n_files; i++)
		printf("%s/%s\n", out, rep.files[i]);
	rc = CLI_EXIT_OK;
done:
	pov_report_free(&rep);
	for (int k = 0; k < SCENE_MAX_SKINS; k++) {
		bake_free(bk[k]);
		free(hm[k].src);
		free(hm[k].px);
		free(heights[k]);
	}
	for (int i = 0; i < n_bakes; i++)
		free(bakes[i].skin), free(bakes[i].dir);
	for (int i = 0; i < n_texs; i++)
		free(texs[i].skin), free(texs[i].dir);
	free(shapes);
	free(base);
	free(cause);
	scene_free(s);
	return rc;
}
