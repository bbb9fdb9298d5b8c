/* skinbake maps new: uniform parameter maps for a family (each map at a
 * --set value or the middle of the family's range), to paint or edit. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "cli/cli.h"
#include "cli/cmd_maps.h"

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
	if (rc == 0) {
		wh[0] = (int)a;
		wh[1] = (int)b;
	}
	return rc;
}

int cmd_maps_new(int argc, char **argv)
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
		{ "set", OPT_CUSTOM, &sets, "KEY=V", .fn = cmd_maps_parse_set, .flags = OPT_REPEAT,
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
	if ((like && cmd_maps_image_arg(&x, "like", like, &wh[0], &wh[1])) || cmd_maps_check_out_dir(&x, out, fam, like))
		return CLI_EXIT_USAGE;
	struct family *f = cmd_maps_load_family(&x, fam);
	if (f == NULL)
		return CLI_EXIT_USAGE;
	double texels = (double)wh[0] * wh[1];
	char what[64];
	snprintf(what, sizeof what, "maps new of %d x %d texels", wh[0], wh[1]);
	double per = MAPS_MEM_PER_TEXEL_MAP * f->n_axes + MAPS_NEW_MEM_PER_TEXEL;
	double disk = (exr ? 4.0 : 2.0) * f->n_axes * texels;
	if (cmd_maps_budget(&x, what, per * texels + MAPS_MEM_FIXED, disk, out,
		"use a smaller --size or --like image")) {
		family_free(f);
		return CLI_EXIT_USAGE;
	}
	struct mapset *m = mapset_new(f, wh[0], wh[1], NULL);
	struct maps_op ops[64];
	long clamped[FAMILY_MAX_AXES];
	char *cause = NULL, *cl = mapset_command_line("new", argc, argv);
	int rc = cmd_maps_resolve_ops(&x, &sets, m, ops) ? CLI_EXIT_USAGE : CLI_EXIT_OK;
	if (rc == CLI_EXIT_OK) {
		maps_edit(m, ops, sets.n, NULL, 0, clamped, &cause);
		m->exr = exr;
		mapset_add_history(m, cl);
		rc = cmd_maps_write(&x, out, m);
	}
	if (rc == CLI_EXIT_OK && !quiet)
		printf("skinbake maps new: %d x %d maps of %d parameters -> %s\n", m->w, m->h, m->n, out);
	free(cl);
	mapset_free(m);
	family_free(f);
	return rc;
}
