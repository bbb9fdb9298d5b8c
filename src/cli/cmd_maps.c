/* skinbake maps: parameter maps of a family (src/maps): new, fit, edit,
 * render-albedo, one file each (cmd_maps_*.c); here the dispatch and what
 * they share.  Options and calls only; every input is checked before any
 * work or output. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "cli/cli.h"
#include "cli/cmd_maps.h"
#include "maps/image.h"

struct family *cmd_maps_load_family(const struct opt_ctx *x, const char *dir)
{
	char *cause = NULL;
	struct family *f = family_load(dir, &cause);
	if (f == NULL) {
		opt_error(x, "--family %s: %s", dir, cause);
		free(cause);
	}
	return f;
}

struct mapset *cmd_maps_load_maps(const struct opt_ctx *x, const char *dir)
{
	char *cause = NULL;
	struct mapset *m = mapset_read(dir, &cause);
	if (m == NULL) {
		opt_error(x, "--maps %s: %s", dir, cause);
		free(cause);
	}
	return m;
}

/* Print "--OPT" SEP CAUSE (only CAUSE when opt is NULL), free cause; -1. */
static int opt_cause(const struct opt_ctx *x, const char *opt, const char *sep, char *cause)
{
	opt_error(x, "%s%s%s%s", opt ? "--" : "", opt ? opt : "", sep, cause);
	free(cause);
	return -1;
}

int cmd_maps_image_arg(const struct opt_ctx *x, const char *opt, const char *path, int *w, int *h)
{
	char *cause = NULL;
	return image_size(path, w, h, &cause) != 0 ? opt_cause(x, opt, " ", cause) : 0;
}

int cmd_maps_budget(const struct opt_ctx *x, const char *what, double mem, double disk,
    const char *out, const char *lower)
{
	char *cause = NULL;
	if (budget_check(what, mem, disk, out, lower, &cause) != 0)
		return opt_cause(x, NULL, "", cause);
	return 0;
}

int cmd_maps_check_out_dir(const struct opt_ctx *x, const char *out, const char *in1, const char *in2)
{
	const char *in[] = { in1, in2 };
	return opt_out_check(x, out, &mapset_outdir_kind, in, 2);
}

int cmd_maps_check_out_file(const struct opt_ctx *x, const char *opt, const char *path, int *exr)
{
	char *cause = NULL;
	return image_check_out(path, exr, &cause) != 0 ? opt_cause(x, opt, " = ", cause) : 0;
}

static int kv_parse(struct opt_ctx *x, const struct opt *o, const char *v, enum maps_op_kind kind)
{
	struct kv_list *l = o->dest;
	const char *eq = strchr(v, '=');
	if (eq == NULL || eq == v || (size_t)(eq - v) >= sizeof l->op[0].key) {
		opt_error(x, "--%s = '%s' is not KEY=VALUE", o->name, v);
		return -1;
	}
	if (l->n == (int)(sizeof l->op / sizeof l->op[0])) {
		opt_error(x, "more than %d edits", l->n);
		return -1;
	}
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

int cmd_maps_parse_scale(struct opt_ctx *x, const struct opt *o, const char *v)
{
	return kv_parse(x, o, v, MAPS_SCALE);
}

int cmd_maps_parse_add(struct opt_ctx *x, const struct opt *o, const char *v)
{
	return kv_parse(x, o, v, MAPS_ADD);
}

int cmd_maps_parse_set(struct opt_ctx *x, const struct opt *o, const char *v)
{
	return kv_parse(x, o, v, MAPS_SET);
}

int cmd_maps_resolve_ops(const struct opt_ctx *x, const struct kv_list *l, const struct mapset *m,
    struct maps_op *ops)
{
	char *cause = NULL;
	return maps_ops_resolve(m, l->op, l->n, ops, &cause) != 0 ? opt_cause(x, NULL, "", cause) : 0;
}

int cmd_maps_write(const struct opt_ctx *x, const char *out, const struct mapset *m)
{
	char *cause = NULL;
	if (mapset_write(out, m, &cause) != 0) {
		fprintf(stderr, "skinbake %s: %s\n", x->cmd->name, cause);
		free(cause);
		return CLI_EXIT_FAIL;
	}
	return CLI_EXIT_OK;
}

static const struct opt_sub actions[] = {
	{ "new", "uniform maps for a family, to paint or edit", cmd_maps_new },
	{ "fit", "maps whose albedo matches an albedo texture, with an error and a status map", cmd_maps_fit },
	{ "edit", "scale, add or set maps under a mask, clamped to the family's range", cmd_maps_edit },
	{ "render-albedo", "the family's albedo (and subsurface radius) per texel from maps", cmd_maps_render },
	{ NULL, NULL, NULL },
};

int cmd_maps(int argc, char **argv)
{
	return opt_dispatch("maps", actions, argc, argv);
}
