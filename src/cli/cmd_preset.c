/* skinbake preset: show a preset's resolved layers per wavelength, print a
 * built-in preset's INI text, or list the preset file keys. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "skin/preset.h"
#include "base/util.h"

static int show(int argc, char **argv)
{
	const char *file = NULL;
	static struct opt_list wlist;	/* checked here, read again by preset_parse_wavelengths */
	int ini = 0;
	const struct opt opts[] = {
		{ "wavelengths", OPT_LIST, &wlist, "LIST", .lo = 380, .hi = 780, .unit = "nm", .max = SKIN_MAX_WL,
		  .flags = OPT_STEPS, .excl = "ini", .def_note = "the preset's", .help = "wavelengths, ascending" },
		{ "preset-file", OPT_PATH_IN, &file, "FILE", .flags = OPT_FILE,
		  .help = "read the preset from FILE instead of a built-in one" },
		{ "ini", OPT_FLAG, &ini, .excl = "wavelengths",
		  .help = "print the fully resolved preset in the file format instead" },
		OPT_END
	};
	const struct opt_cmd cmd = { "preset show", "(NAME | --preset-file FILE) [--wavelengths LIST] [--ini]",
		"Print the layer stack the simulation gets, top first, one row per wavelength\n"
		"and layer: thickness d [cm], refractive index n, absorption mua [1/cm],\n"
		"scattering mus [1/cm], HG anisotropy g and the reduced scattering\n"
		"musp = mus (1 - g) [1/cm].  Air is above; below the deepest layer is a half\n"
		"space of its own index.", opts,
		"Built-in presets: skinbake presets.  File format: docs/presets.md.", 0, 1 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	const char *name = x.n_args ? x.args[0] : NULL, *CMD = cmd.name, *wls = opt_text(&x, "wavelengths");
	if ((name == NULL) == (file == NULL))
		return opt_error(&x, "give either a preset NAME or --preset-file FILE (see skinbake presets)");
	char *cause = NULL;
	struct skin_params *p = file ? preset_load_file(file, &cause) : preset_load_builtin(name, &cause);
	if (p == NULL) {
		int rc = cli_usage_error(CMD, "%s", cause);
		free(cause);
		return rc;
	}
	if (ini) {
		char *s = preset_to_ini(p);
		fputs(s, stdout);
		free(s);
		preset_free(p);
		return CLI_EXIT_OK;
	}
	double wl[SKIN_MAX_WL];
	int n = p->n_wl;
	if (wls) {
		n = preset_parse_wavelengths(wls, wl, &cause);
		if (n < 0) {
			int rc = cli_usage_error(CMD, "--wavelengths = '%s': %s", wls, cause);
			free(cause);
			preset_free(p);
			return rc;
		}
	} else
		preset_default_wavelengths(p, wl, SKIN_MAX_WL);

	/* Resolve every wavelength before printing, so an error prints nothing. */
	struct slab *s = xmalloc(sizeof *s * (size_t)n);
	for (int i = 0; i < n; i++) {
		if (tissue_slab(p, wl[i], &s[i], &cause) != 0) {
			int rc = cli_usage_error(CMD, "%s", cause);
			free(cause);
			free(s);
			preset_free(p);
			return rc;
		}
	}
	printf("# preset %s: %s\n", p->name, p->description);
	printf("# origin %s; model %s; surface n %.4g, GGX alpha %.3g\n", p->origin,
	    p->model == SKIN_MODEL_TABLES ? "tables" : "chromophores", preset_surface_ior(p),
	    preset_surface_roughness(p));
	printf("# air above (n 1); layers top first; below the last layer a half space of its n\n");
	printf("%-7s %-10s %-9s %-7s %-11s %-11s %-6s %s\n", "wl_nm", "layer", "d_cm", "n", "mua_1/cm",
	    "mus_1/cm", "g", "musp_1/cm");
	for (int i = 0; i < n; i++) {
		int k = 0;
		for (int id = 0; id < SKIN_N_LAYERS; id++) {
			if (!tissue_layer_present(p, id))
				continue;
			const struct layer *l = &s[i].layer[++k];
			printf("%-7g %-10s %-9g %-7.4f %-11.5g %-11.5g %-6.4f %.5g\n", wl[i], tissue_layer_name(id),
			    l->d, l->n, l->mu_a, l->mu_s, l->g, l->mu_s * (1.0 - l->g));
		}
	}
	free(s);
	preset_free(p);
	return CLI_EXIT_OK;
}

static int cat(int argc, char **argv)
{
	const struct opt opts[] = { OPT_END };
	const struct opt_cmd cmd = { "preset cat", "NAME", "Print a built-in preset's INI text (a start for own "
		"preset files).", opts, NULL, 1, 1 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	int i = preset_find(x.args[0]);
	if (i < 0) {
		char *cause = NULL;
		preset_load_builtin(x.args[0], &cause);	/* for the message listing the names */
		int rc = opt_error(&x, "%s", cause);
		free(cause);
		return rc;
	}
	fputs(preset_builtin_text(i), stdout);
	return CLI_EXIT_OK;
}

static int keys(int argc, char **argv)
{
	const struct opt opts[] = { OPT_END };
	const struct opt_cmd cmd = { "preset keys", "", "List every preset file key with unit, default and range.",
		opts, NULL, 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	preset_print_keys(stdout);
	return CLI_EXIT_OK;
}

static const struct opt_sub actions[] = {
	{ "show", "print a preset's resolved layers per wavelength", show },
	{ "cat", "print a built-in preset's INI text", cat },
	{ "keys", "list every preset file key with unit, default and range", keys },
	{ NULL, NULL, NULL },
};

int cmd_preset(int argc, char **argv)
{
	return opt_dispatch("preset", actions, argc, argv);
}
