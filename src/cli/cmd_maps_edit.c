/* skinbake maps edit: scale, add or set parameter maps under a mask,
 * clamped to the family's range (maps/edit.c). */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "cli/cmd_maps.h"
#include "maps/image.h"

int cmd_maps_edit(int argc, char **argv)
{
	const char *in = NULL, *mask = NULL, *out = NULL;
	static struct kv_list ops_l;
	int invert = 0, quiet = 0;
	ops_l.n = 0;
	const struct opt opts[] = {
		{ "maps", OPT_PATH_IN, &in, "DIR", .flags = OPT_REQUIRED | OPT_DIR, .help = "a maps directory" },
		{ "scale", OPT_CUSTOM, &ops_l, "KEY=F", .fn = cmd_maps_parse_scale, .flags = OPT_REPEAT,
		  .help = "multiply map KEY by F in [0, 100] (e.g. epidermis.melanin=1.3: tanning)" },
		{ "add", OPT_CUSTOM, &ops_l, "KEY=D", .fn = cmd_maps_parse_add, .flags = OPT_REPEAT,
		  .help = "add D (the key's unit) to map KEY" },
		{ "set", OPT_CUSTOM, &ops_l, "KEY=V", .fn = cmd_maps_parse_set, .flags = OPT_REPEAT,
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
	if ((mask && cmd_maps_image_arg(&x, "mask", mask, &mw, &mh)) || cmd_maps_check_out_dir(&x, out, mask, NULL))
		return CLI_EXIT_USAGE;
	/* Before the maps are read, from the size maps.json states (reading it
	 * says what is wrong with it).  Disk: the maps and the fit's de2000 at
	 * 4 bytes (EXR) at most, its status 1. */
	int w, h, n;
	char what[160], *cause = NULL;
	if (mapset_read_size(in, &w, &h, &n, &cause) == 0) {
		double texels = (double)w * h, disk = (4.0 * n + 5.0) * texels;
		double per = MAPS_MEM_PER_TEXEL_MAP * n + MAPS_EDIT_MEM_PER_TEXEL;
		per += mask ? MAPS_MASK_MEM_PER_TEXEL : 0.0;
		snprintf(what, sizeof what, "maps edit of %d x %d texels (--maps %s)", w, h, in);
		if (cmd_maps_budget(&x, what, per * texels + MAPS_MEM_FIXED, disk, out,
			"edit smaller maps (tiles one by one)"))
			return CLI_EXIT_USAGE;
	}
	free(cause);
	cause = NULL;
	struct mapset *m = cmd_maps_load_maps(&x, in);
	if (m == NULL)
		return CLI_EXIT_USAGE;
	struct maps_op ops[64];
	struct image *mk = NULL;
	int rc = CLI_EXIT_OK;
	if (cmd_maps_resolve_ops(&x, &ops_l, m, ops) != 0)
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
		char *cl = mapset_command_line("edit", argc, argv);
		mapset_add_history(m, cl);
		free(cl);
		rc = cmd_maps_write(&x, out, m);
		if (rc == CLI_EXIT_OK && !quiet)
			printf("skinbake maps edit: %s -> %s (%d edits)\n", in, out, ops_l.n);
	}
	image_free(mk);
	mapset_free(m);
	return rc;
}
