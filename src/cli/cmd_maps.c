/* skinbake maps: parameter maps of a family (src/maps): new, fit, edit,
 * render-albedo.  Options and calls only; every input is checked before
 * any work or output. */
#include "config.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/srgb.h"
#include "base/util.h"
#include "cli/cli.h"
#include "cli/opt.h"
#include "maps/edit.h"
#include "maps/fit.h"
#include "maps/image.h"
#include "maps/mapset.h"
#include "maps/render.h"

/* "skinbake maps ACTION ARGS...", for maps.json's history.  Caller frees. */
static char *command_line(const char *action, int argc, char **argv)
{
	char *s = xasprintf("skinbake maps %s", action);
	for (int i = 1; i < argc; i++) {
		char *t = xasprintf("%s %s", s, argv[i]);
		free(s);
		s = t;
	}
	return s;
}

static struct family *load_family(const struct opt_ctx *x, const char *dir)
{
	char *cause = NULL;
	struct family *f = family_load(dir, &cause);
	if (f == NULL) {
		opt_error(x, "--family %s: %s", dir, cause);
		free(cause);
	}
	return f;
}

static struct mapset *load_maps(const struct opt_ctx *x, const char *dir)
{
	char *cause = NULL;
	struct mapset *m = mapset_read(dir, &cause);
	if (m == NULL) {
		opt_error(x, "--maps %s: %s", dir, cause);
		free(cause);
	}
	return m;
}

/* An image option: a PNG or EXR, its size into w, h. */
static int image_arg(const struct opt_ctx *x, const char *opt, const char *path, int *w, int *h)
{
	char *cause = NULL;
	if (image_size(path, w, h, &cause) != 0) {
		opt_error(x, "--%s %s", opt, cause);
		free(cause);
		return -1;
	}
	return 0;
}

static int check_out_dir(const struct opt_ctx *x, const char *out)
{
	char *cause = NULL;
	if (mapset_check_out(out, &cause) != 0) {
		opt_error(x, "--out %s", cause);
		free(cause);
		return -1;
	}
	return 0;
}

/* Output file: .png or .exr, its directory writable, not a directory itself. */
static int check_out_file(const struct opt_ctx *x, const char *opt, const char *path, int *exr)
{
	size_t n = strlen(path);
	struct stat st;
	*exr = n > 4 && strcmp(path + n - 4, ".exr") == 0;
	if (!(*exr || (n > 4 && strcmp(path + n - 4, ".png") == 0)))
		return opt_error(x, "--%s = '%s' does not end with .png or .exr", opt, path), -1;
	if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
		return opt_error(x, "--%s = '%s' is a directory, expected a file name", opt, path), -1;
	char *dir = xstrdup(path), *sl = strrchr(dir, '/');
	if (sl)
		*(sl == dir ? sl + 1 : sl) = '\0';
	int ok = access(sl ? dir : ".", W_OK) == 0;
	if (!ok)
		opt_error(x, "--%s = '%s': its directory '%s' is missing or not writable", opt, path, sl ? dir : ".");
	free(dir);
	return ok ? 0 : -1;
}

/* ---- KEY=VALUE options of edit and new ---- */

struct kv_list {
	int n;
	struct {
		enum maps_op_kind kind;
		char key[64];
		double value;
	} op[64];
};

static int kv_parse(struct opt_ctx *x, const struct opt *o, const char *v, enum maps_op_kind kind)
{
	struct kv_list *l = o->dest;
	const char *eq = strchr(v, '=');
	if (eq == NULL || eq == v || (size_t)(eq - v) >= sizeof l->op[0].key)
		return opt_error(x, "--%s = '%s' is not KEY=VALUE", o->name, v), -1;
	if (l->n == (int)(sizeof l->op / sizeof l->op[0]))
		return opt_error(x, "more than %d edits", l->n), -1;
	char label[96];
	snprintf(label, sizeof label, "--%s %.*s", o->name, (int)(eq - v), v);
	double lo = kind == MAPS_SCALE ? 0 : -1e300, hi = kind == MAPS_SCALE ? 100 : 1e300;
	if (opt_double(x, label, eq + 1, lo, hi, 0, NULL, &l->op[l->n].value) != 0)
		return -1;
	memcpy(l->op[l->n].key, v, (size_t)(eq - v));
	l->op[l->n].key[eq - v] = '\0';
	l->op[l->n].kind = kind;
	l->n++;
	return 0;
}

static int parse_scale(struct opt_ctx *x, const struct opt *o, const char *v)
{
	return kv_parse(x, o, v, MAPS_SCALE);
}

static int parse_add(struct opt_ctx *x, const struct opt *o, const char *v)
{
	return kv_parse(x, o, v, MAPS_ADD);
}

static int parse_set(struct opt_ctx *x, const struct opt *o, const char *v)
{
	return kv_parse(x, o, v, MAPS_SET);
}

/* The edits as map operations: keys known, set values in the family's range. */
static int resolve_ops(const struct opt_ctx *x, const struct kv_list *l, const struct mapset *m, struct maps_op *ops)
{
	for (int k = 0; k < l->n; k++) {
		int a = mapset_find(m, l->op[k].key);
		if (a < 0) {
			char names[256] = "";
			for (int b = 0; b < m->n; b++)
				snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", b ? ", " : "", m->p[b].key);
			return opt_error(x, "%s: not one of the maps (%s)", l->op[k].key, names), -1;
		}
		if (l->op[k].kind == MAPS_SET && !(l->op[k].value >= m->p[a].fam_lo && l->op[k].value <= m->p[a].fam_hi))
			return opt_error(x, "--set %s = %g is outside the family's range [%g, %g]", l->op[k].key, l->op[k].value,
			    m->p[a].fam_lo, m->p[a].fam_hi), -1;
		ops[k] = (struct maps_op){ l->op[k].kind, a, l->op[k].value };
	}
	return 0;
}

static int write_maps(const struct opt_ctx *x, const char *out, const struct mapset *m)
{
	char *cause = NULL;
	if (mapset_write(out, m, &cause) != 0) {
		fprintf(stderr, "skinbake %s: %s\n", x->cmd->name, cause);
		free(cause);
		return CLI_EXIT_FAIL;
	}
	return CLI_EXIT_OK;
}

/* ---- maps new ---- */

static int parse_size(struct opt_ctx *x, const struct opt *o, const char *v)
{
	int *wh = o->dest;
	long a, b;
	char *c = xstrdup(v), *p = strchr(c, 'x');
	int rc = -1;
	if (p == NULL)
		opt_error(x, "--size = '%s' is not WxH", v);
	else {
		*p = '\0';
		rc = opt_long(x, "--size: W", c, 1, 16384, 0, NULL, &a) || opt_long(x, "--size: H", p + 1, 1, 16384, 0, NULL, &b)
		    ? -1 : 0;
	}
	free(c);
	if (rc == 0)
		wh[0] = (int)a, wh[1] = (int)b;
	return rc;
}

static int maps_new(int argc, char **argv)
{
	const char *fam = NULL, *like = NULL, *out = NULL;
	static struct kv_list sets;
	int wh[2] = { 0, 0 }, exr = 0, quiet = 0;
	sets.n = 0;
	const struct opt opts[] = {
		{ "family", OPT_PATH_IN, &fam, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "a family directory (bake --vary)" },
		{ "size", OPT_CUSTOM, wh, "WxH", .fn = parse_size, .flags = OPT_REQUIRED, .excl = "like",
		  .help = "map size in texels, each in [1, 16384]" },
		{ "like", OPT_PATH_IN, &like, "IMAGE", .flags = OPT_REQUIRED | OPT_FILE, .excl = "size",
		  .help = "the size of this PNG or EXR image" },
		{ "set", OPT_CUSTOM, &sets, "KEY=V", .fn = parse_set, .flags = OPT_REPEAT,
		  .help = "a map's value everywhere (default: the middle of the family's range)" },
		{ "format", OPT_ENUM, &exr, .def = "png", .choices = "png|exr", .help = "16-bit PNG or float EXR maps" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED, .help = "maps directory (created or replaced)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		OPT_END
	};
	const struct opt_cmd cmd = { "maps new", "--family DIR (--size WxH | --like IMAGE) --out DIR [--set KEY=V ...]",
		"Uniform parameter maps for a family, to paint or edit (skinbake maps edit).", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if ((like && image_arg(&x, "like", like, &wh[0], &wh[1])) || check_out_dir(&x, out))
		return CLI_EXIT_USAGE;
	struct family *f = load_family(&x, fam);
	if (f == NULL)
		return CLI_EXIT_USAGE;
	struct mapset *m = mapset_new(f, wh[0], wh[1], NULL);
	struct maps_op ops[64];
	long clamped[FAMILY_MAX_AXES];
	char *cause = NULL, *cl = command_line("new", argc, argv);
	int rc = resolve_ops(&x, &sets, m, ops) ? CLI_EXIT_USAGE : CLI_EXIT_OK;
	if (rc == CLI_EXIT_OK) {
		maps_edit(m, ops, sets.n, NULL, 0, clamped, &cause);
		m->exr = exr;
		mapset_add_history(m, cl);
		rc = write_maps(&x, out, m);
	}
	if (rc == CLI_EXIT_OK && !quiet)
		printf("skinbake maps new: %d x %d maps of %d parameters -> %s\n", m->w, m->h, m->n, out);
	free(cl);
	mapset_free(m);
	family_free(f);
	return rc;
}

/* ---- maps fit ---- */

static int maps_fit_cmd(int argc, char **argv)
{
	const char *fam = NULL, *alb = NULL, *mask = NULL, *out = NULL;
	int input = 0, exr = 0, quiet = 0;
	struct maps_fit_opts fo = { 0 };
	const struct opt opts[] = {
		{ "family", OPT_PATH_IN, &fam, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "a family directory (bake --vary)" },
		{ "albedo", OPT_PATH_IN, &alb, "IMAGE", .flags = OPT_REQUIRED | OPT_FILE,
		  .help = "the albedo texture: PNG (8 or 16 bit) or EXR, RGB or grey, alpha < 0.5 not fitted" },
		{ "input", OPT_ENUM, &input, .def = "auto", .choices = "auto|srgb|linear",
		  .help = "how the albedo's values are encoded: auto = sRGB for PNG, linear for EXR" },
		{ "mask", OPT_PATH_IN, &mask, "IMAGE", .flags = OPT_FILE,
		  .help = "fit only where this grey image is >= 0.5 (the albedo's size)" },
		{ "max-de", OPT_DOUBLE, &fo.max_de, "E", "2.5", .lo = 0, .hi = 100, .flags = OPT_LO_OPEN,
		  .help = "CIEDE2000 beyond which a texel is flagged unmatched (status 255)" },
		{ "format", OPT_ENUM, &exr, .def = "png", .choices = "png|exr", .help = "16-bit PNG or float EXR maps" },
		{ "threads", OPT_INT, &fo.threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED, .help = "maps directory (created or replaced)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		OPT_END
	};
	const struct opt_cmd cmd = { "maps fit", "--family DIR --albedo IMAGE --out DIR [options]",
		"Per texel, the family parameters whose diffuse albedo matches the texture's colour\n"
		"(CIELAB D65, CIEDE2000 reported), with an error map and a status map (docs/maps.md).", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	int w, h, mw, mh;
	if (image_arg(&x, "albedo", alb, &w, &h) || (mask && image_arg(&x, "mask", mask, &mw, &mh)) || check_out_dir(&x, out))
		return CLI_EXIT_USAGE;
	if (mask && (mw != w || mh != h))
		return opt_error(&x, "--mask %s is %d x %d texels, but --albedo %s is %d x %d", mask, mw, mh, alb, w, h);
	struct family *f = load_family(&x, fam);
	if (f == NULL)
		return CLI_EXIT_USAGE;
	char *cause = NULL;
	struct image *a = image_read(alb, &cause), *mk = NULL;
	if (a && mask)
		mk = image_read(mask, &cause);
	int rc = CLI_EXIT_OK;
	if (a == NULL || (mask && mk == NULL)) {
		rc = opt_error(&x, "%s", cause);
		free(cause);
		family_free(f);
		image_free(a);
		return rc;
	}
	fo.input_linear = input == 2 || (input == 0 && a->bits == 32);
	struct mapset *m = NULL;
	struct maps_fit_summary s;
	if (maps_fit(f, a, mk, &fo, &m, &s, &cause) != 0) {
		rc = opt_error(&x, "%s", cause);
		free(cause);
	} else {
		char *cl = command_line("fit", argc, argv);
		m->fit = maps_fit_summary_json(&s, &fo, alb);
		m->exr = exr;
		mapset_add_history(m, cl);
		free(cl);
		rc = write_maps(&x, out, m);
		if (rc == CLI_EXIT_OK && !quiet)
			printf("skinbake maps fit: %s (%d x %d, %s) with %s -> %s\n"
			    "  %ld texels fitted (%ld distinct colours), %ld not fitted; %ld matched, %ld unmatched "
			    "(CIEDE2000 > %g, %.2f %%)\n  CIEDE2000 median %.3f, 95th percentile %.3f, max %.3f; %.2f s\n", alb, w,
			    h, fo.input_linear ? "linear" : "sRGB", fam, out, s.fitted, s.unique, s.texels - s.fitted, s.matched,
			    s.unmatched, fo.max_de, s.fitted ? 100.0 * s.unmatched / s.fitted : 0.0, s.de_median, s.de_p95,
			    s.de_max, s.seconds);
	}
	mapset_free(m);
	image_free(a);
	image_free(mk);
	family_free(f);
	return rc;
}

/* ---- maps edit ---- */

static int maps_edit_cmd(int argc, char **argv)
{
	const char *in = NULL, *mask = NULL, *out = NULL;
	static struct kv_list ops_l;
	int invert = 0, quiet = 0;
	ops_l.n = 0;
	const struct opt opts[] = {
		{ "maps", OPT_PATH_IN, &in, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "a maps directory" },
		{ "scale", OPT_CUSTOM, &ops_l, "KEY=F", .fn = parse_scale, .flags = OPT_REPEAT,
		  .help = "multiply map KEY by F in [0, 100] (e.g. epidermis.melanin=1.3: tanning)" },
		{ "add", OPT_CUSTOM, &ops_l, "KEY=D", .fn = parse_add, .flags = OPT_REPEAT,
		  .help = "add D (the key's unit) to map KEY" },
		{ "set", OPT_CUSTOM, &ops_l, "KEY=V", .fn = parse_set, .flags = OPT_REPEAT,
		  .help = "set map KEY to V, within the family's range" },
		{ "mask", OPT_PATH_IN, &mask, "IMAGE", .flags = OPT_FILE,
		  .help = "blend every edit by this grey image's value w in [0, 1]: new = old + w (edited - old)" },
		{ "invert-mask", OPT_FLAG, &invert, .help = "use 1 - w" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .flags = OPT_REQUIRED,
		  .help = "maps directory (created or replaced; may be --maps)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		OPT_END
	};
	const struct opt_cmd cmd = { "maps edit", "--maps DIR (--scale|--add|--set KEY=V) ... [--mask IMAGE] --out DIR",
		"Edit parameter maps (tanning, flushing, pallor), in the order given, blended by a mask and\n"
		"clamped to the family's range (a message counts the clamped texels).", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (ops_l.n == 0)
		return opt_error(&x, "no edit given (--scale, --add or --set)");
	int mw, mh;
	if ((mask && image_arg(&x, "mask", mask, &mw, &mh)) || check_out_dir(&x, out))
		return CLI_EXIT_USAGE;
	struct mapset *m = load_maps(&x, in);
	if (m == NULL)
		return CLI_EXIT_USAGE;
	struct maps_op ops[64];
	struct image *mk = NULL;
	char *cause = NULL;
	int rc = CLI_EXIT_OK;
	if (resolve_ops(&x, &ops_l, m, ops) != 0)
		rc = CLI_EXIT_USAGE;
	else if (mask && (mw != m->w || mh != m->h))
		rc = opt_error(&x, "--mask %s is %d x %d texels, but the maps %s are %d x %d", mask, mw, mh, in, m->w, m->h);
	else if (mask && (mk = image_read(mask, &cause)) == NULL) {
		rc = opt_error(&x, "%s", cause);
		free(cause);
	}
	long clamped[FAMILY_MAX_AXES];
	if (rc == CLI_EXIT_OK && maps_edit(m, ops, ops_l.n, mk, invert, clamped, &cause) != 0) {
		rc = opt_error(&x, "%s", cause);
		free(cause);
	}
	if (rc == CLI_EXIT_OK) {
		for (int a = 0; a < m->n; a++)
			if (clamped[a] > 0)
				fprintf(stderr, "skinbake maps edit: %s: %ld texels (%.2f %%) clamped to the family's range [%g, %g]\n",
				    m->p[a].key, clamped[a], 100.0 * clamped[a] / ((double)m->w * m->h), m->p[a].fam_lo,
				    m->p[a].fam_hi);
		char *cl = command_line("edit", argc, argv);
		mapset_add_history(m, cl);
		free(cl);
		rc = write_maps(&x, out, m);
		if (rc == CLI_EXIT_OK && !quiet)
			printf("skinbake maps edit: %s -> %s (%d edits)\n", in, out, ops_l.n);
	}
	image_free(mk);
	mapset_free(m);
	return rc;
}

/* ---- maps render-albedo ---- */

static int maps_render_cmd(int argc, char **argv)
{
	const char *fam = NULL, *in = NULL, *out = NULL, *radius = NULL;
	int bits = 16, enc = 0, threads = 0, quiet = 0, exr, rexr;
	const struct opt opts[] = {
		{ "family", OPT_PATH_IN, &fam, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "a family directory (bake --vary)" },
		{ "maps", OPT_PATH_IN, &in, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "its parameter maps" },
		{ "out", OPT_STRING, &out, "FILE", .flags = OPT_REQUIRED,
		  .help = "the albedo: FILE.png (sRGB-encoded unless --encoding linear) or FILE.exr (linear float)" },
		{ "bits", OPT_INT, &bits, "N", "16", .lo = 8, .hi = 16, .help = "PNG bits, 8 or 16" },
		{ "encoding", OPT_ENUM, &enc, .def = "srgb", .choices = "srgb|linear", .help = "PNG encoding" },
		{ "radius", OPT_STRING, &radius, "FILE.exr",
		  .help = "also the subsurface radius per R, G, B [cm] as a float EXR" },
		{ "threads", OPT_INT, &threads, "N", "0", .lo = 0, .hi = 1024, .help = "OpenMP threads (0 = all cores)" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stdout" },
		OPT_END
	};
	const struct opt_cmd cmd = { "maps render-albedo", "--family DIR --maps DIR --out FILE [options]",
		"The family's diffuse albedo per texel from parameter maps (the fit's forward direction).", opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (bits != 8 && bits != 16)
		return opt_error(&x, "--bits = %d is not 8 or 16", bits);
	if (check_out_file(&x, "out", out, &exr) || (radius && check_out_file(&x, "radius", radius, &rexr)))
		return CLI_EXIT_USAGE;
	if (radius && !rexr)
		return opt_error(&x, "--radius = '%s' must be an .exr file (radii in cm)", radius);
	struct family *f = load_family(&x, fam);
	struct mapset *m = f ? load_maps(&x, in) : NULL;
	char *cause = NULL;
	int rc = CLI_EXIT_OK;
	if (f == NULL || m == NULL)
		rc = CLI_EXIT_USAGE;
	else if (mapset_check_family(m, in, f, &cause) != 0) {
		rc = opt_error(&x, "%s", cause);
		free(cause);
	}
	if (rc == CLI_EXIT_OK) {
		struct image *rad = NULL, *im = maps_render_albedo(f, m, radius ? &rad : NULL, threads);
		static const char *names[] = { "R", "G", "B" };
		const char *kv[] = { "skinbake:content", "diffuse albedo, linear sRGB (D65)" };
		if (exr)
			rc = image_write_exr(out, im, names, 1, kv, &cause);
		else {
			if (enc == 0)
				for (size_t i = 0; i < (size_t)im->w * im->h * 3; i++)
					im->v[i] = (float)srgb_encode(im->v[i]);
			struct png_text_kv tx[] = { { "Software", PACKAGE_STRING }, { "Comment", enc == 0
				? "diffuse albedo, sRGB-encoded" : "diffuse albedo, linear sRGB values (no transfer function)" } };
			rc = image_write_png(out, im, bits, enc == 0 && bits == 8, 2, tx, &cause);
		}
		const char *rkv[] = { "skinbake:content", "subsurface radius (mean exit radius) per R, G, B [cm]" };
		if (rc == 0 && rad)
			rc = image_write_exr(radius, rad, names, 1, rkv, &cause);
		if (rc != 0) {
			fprintf(stderr, "skinbake maps render-albedo: %s\n", cause);
			free(cause);
			rc = CLI_EXIT_FAIL;
		} else if (!quiet)
			printf("skinbake maps render-albedo: %s with %s -> %s%s%s\n", in, fam, out, rad ? " and " : "",
			    rad ? radius : "");
		image_free(im);
		image_free(rad);
	}
	mapset_free(m);
	family_free(f);
	return rc;
}

static const struct opt_sub actions[] = {
	{ "new", "uniform maps for a family, to paint or edit", maps_new },
	{ "fit", "maps whose albedo matches an albedo texture, with an error and a status map", maps_fit_cmd },
	{ "edit", "scale, add or set maps under a mask, clamped to the family's range", maps_edit_cmd },
	{ "render-albedo", "the family's albedo (and subsurface radius) per texel from maps", maps_render_cmd },
	{ NULL, NULL, NULL },
};

int cmd_maps(int argc, char **argv)
{
	return opt_dispatch("maps", actions, argc, argv);
}
