/* cmd_maps: what the maps subcommands (cmd_maps_*.c) share: loading a
 * family or maps with a message naming the option, checking images and
 * outputs, the KEY=VALUE edit options, writing the maps. */
#ifndef SKINBAKE_CMD_MAPS_H
#define SKINBAKE_CMD_MAPS_H
#include "cli/opt.h"
#include "maps/edit.h"
#include "maps/mapset.h"

/* The KEY=VALUE options of edit and new, in the order given. */
struct kv_list {
	int n;
	struct maps_edit_arg op[64];
};

/* Option parsers (struct opt .fn) of --scale, --add and --set into a kv_list. */
int cmd_maps_parse_scale(struct opt_ctx *x, const struct opt *o, const char *v);
int cmd_maps_parse_add(struct opt_ctx *x, const struct opt *o, const char *v);
int cmd_maps_parse_set(struct opt_ctx *x, const struct opt *o, const char *v);

/* These print the message (naming the option) and return NULL or -1. */
struct family *cmd_maps_load_family(const struct opt_ctx *x, const char *dir);
struct mapset *cmd_maps_load_maps(const struct opt_ctx *x, const char *dir);
/* An image option: a PNG or EXR, its size into w, h. */
int cmd_maps_image_arg(const struct opt_ctx *x, const char *opt, const char *path, int *w, int *h);
int cmd_maps_check_out_dir(const struct opt_ctx *x, const char *out, const char *in1, const char *in2);
/* Output file: .png or .exr (*exr), its directory writable, not a directory itself. */
int cmd_maps_check_out_file(const struct opt_ctx *x, const char *opt, const char *path, int *exr);
/* The edits as map operations: keys known, set values in the family's range. */
int cmd_maps_resolve_ops(const struct opt_ctx *x, const struct kv_list *l, const struct mapset *m,
    struct maps_op *ops);
/* The memory and disk WHAT needs, checked before work (base/budget.h; the
 * message names LOWER, the option that lowers them); -1 with the message. */
int cmd_maps_budget(const struct opt_ctx *x, const char *what, double mem, double disk,
    const char *out, const char *lower);
/* Write the maps; CLI_EXIT_OK, or CLI_EXIT_FAIL with the message printed. */
int cmd_maps_write(const struct opt_ctx *x, const char *out, const struct mapset *m);

/* The subcommands. */
int cmd_maps_new(int argc, char **argv);
int cmd_maps_fit(int argc, char **argv);
int cmd_maps_edit(int argc, char **argv);
int cmd_maps_render(int argc, char **argv);
#endif
