/* cmd_texture_cfg: the configuration of `skinbake texture` from its
 * options (cmd_texture.h): site, preset file, parameters, direction map. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "cli/cmd_texture.h"
#include "geom/dirmap.h"
#include "geom/relief.h"

static const char *CMD = "texture";

int cmd_texture_resolve(struct texture_config *cfg, const struct opt_ctx *x,
    const struct texture_sources *src, float **dir)
{
	int np;
	const struct texture_param *params = sites_params(&np);
	char *cause = NULL;
	int rc = -1;
	*dir = NULL;
	if (sites_load(src->site, cfg, &cause) != 0) {
		cli_usage_error(CMD, "--site: %s", cause);
		goto done;
	}
	if (src->preset && sites_read_ini(src->preset, cfg, &cause) != 0) {
		cli_usage_error(CMD, "--preset-file: %s", cause);
		goto done;
	}
	for (int i = 0; i < np; i++) {
		char label[64];
		snprintf(label, sizeof label, "--%s", params[i].key);
		const char *v = opt_given(x, params[i].key) ? opt_text(x, params[i].key) : NULL;
		if (v != NULL && sites_set(cfg, &params[i], label, v, &cause) != 0) {
			cli_usage_error(CMD, "%s", cause);
			goto done;
		}
	}
	/* The map's size is --size, so it is read after the parameters. */
	if (src->dirmap != NULL && (*dir = dirmap_apply(cfg, src->dirmap, &cause)) == NULL) {
		cli_usage_error(CMD, "--direction-map: %s", cause);
		goto done;
	}
	if (relief_params_check(&cfg->relief, &cause) != 0) {
		cli_usage_error(CMD, "%s", cause);
		goto done;
	}
	rc = 0;
done:
	free(cause);
	return rc;
}
