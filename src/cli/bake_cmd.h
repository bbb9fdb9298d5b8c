/* bake_cmd: `skinbake bake` after its options are read (cmd_bake.c). */
#ifndef SKINBAKE_BAKE_CMD_H
#define SKINBAKE_BAKE_CMD_H
#include "bake/bake.h"
#include "cli/cmd_bake_family.h"

/* Read preset PRESET (or the file PFILE) into s, then bake it into OUT,
 * or the family of VARY; ARGV for the manifest's command line.  Returns
 * the exit status (messages printed). */
int bake_cmd_run(struct bake_spec *s, const char *preset, const char *pfile, const char *out, int quiet,
    const struct bake_vary *vary, int argc, char **argv);
#endif
