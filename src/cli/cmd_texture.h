/* cmd_texture: what `skinbake texture` (cmd_texture.c) shares with its
 * configuration step (cmd_texture_cfg.c). */
#ifndef SKINBAKE_CMD_TEXTURE_H
#define SKINBAKE_CMD_TEXTURE_H
#include "cli/opt.h"
#include "geom/sites.h"

/* The options that choose where the configuration starts. */
struct texture_sources {
	const char *site;	/* --site */
	const char *preset;	/* --preset-file, or NULL */
	const char *dirmap;	/* --direction-map, or NULL */
};

/* Resolve cfg: the site, then the preset file, then the parameter options
 * in command-line order, then the direction map (*dir receives its angles,
 * the caller frees them), and check the result.  On bad input it prints
 * the message (naming the option, the value and the allowed range) and
 * returns -1 (exit status 2). */
int cmd_texture_resolve(struct texture_config *cfg, const struct opt_ctx *x,
    const struct texture_sources *src, float **dir);
#endif
