/* skinbake preset: show a preset's resolved layers per wavelength, print a
 * built-in preset's INI text, or list the preset file keys. */
#include "config.h"

#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "skin/preset.h"
#include "base/util.h"

static const char *CMD = "preset";

static void help(FILE *fp)
{
	fprintf(fp,
	    "usage: skinbake preset show NAME [--wavelengths LIST] [--ini]\n"
	    "       skinbake preset show --preset-file FILE [--wavelengths LIST] [--ini]\n"
	    "       skinbake preset cat NAME\n"
	    "       skinbake preset keys\n"
	    "\n"
	    "show   prints the layer stack the simulation gets, top first, one row per\n"
	    "       wavelength and layer: thickness d [cm], refractive index n, absorption\n"
	    "       mua [1/cm], scattering mus [1/cm], HG anisotropy g and the reduced\n"
	    "       scattering musp = mus (1 - g) [1/cm].  Air is above; below the deepest\n"
	    "       layer is a half space of its own index.\n"
	    "  --wavelengths LIST     wavelengths [nm] in [380, 780]: comma list and\n"
	    "                         START:STOP:STEP ranges, ascending (default: the preset's)\n"
	    "  --preset-file FILE     read the preset from FILE instead of a built-in one\n"
	    "  --ini                  print the fully resolved preset in the file format instead\n"
	    "cat    prints a built-in preset's INI text (a start for own preset files)\n"
	    "keys   lists every preset file key with unit, default and range\n"
	    "\n"
	    "Built-in presets: skinbake presets.  File format: docs/presets.md.\n");
}

static int show(int argc, char **argv)
{
	enum { O_WL = 256, O_FILE, O_INI, O_HELP };
	static const struct option opts[] = {
		{ "wavelengths", required_argument, 0, O_WL }, { "preset-file", required_argument, 0, O_FILE },
		{ "ini", no_argument, 0, O_INI }, { "help", no_argument, 0, O_HELP }, { 0, 0, 0, 0 }
	};
	const char *file = NULL, *wls = NULL;
	int ini = 0, ch;
	opterr = 0;
	optind = 1;
	while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (ch) {
		case O_WL: wls = optarg; break;
		case O_FILE: file = optarg; break;
		case O_INI: ini = 1; break;
		case 'h':
		case O_HELP: help(stdout); return CLI_EXIT_OK;
		default:
			return cli_usage_error(CMD, "unknown or incomplete option '%s' (see skinbake preset --help)",
			    argv[optind - 1]);
		}
	}
	const char *name = optind < argc ? argv[optind] : NULL;
	if (optind + 1 < argc)
		return cli_usage_error(CMD, "unexpected argument '%s'", argv[optind + 1]);
	if ((name == NULL) == (file == NULL))
		return cli_usage_error(CMD, "show needs either a preset NAME or --preset-file FILE "
		    "(see skinbake presets)");

	if (ini && wls)
		return cli_usage_error(CMD, "--wavelengths and --ini exclude each other (--ini prints the preset, "
		    "whose [skin] wavelengths are its defaults)");
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

int cmd_preset(int argc, char **argv)
{
	if (argc < 2)
		return cli_usage_error(CMD, "missing action: show, cat or keys (see skinbake preset --help)");
	const char *a = argv[1];
	if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0 || strcmp(a, "help") == 0) {
		help(stdout);
		return CLI_EXIT_OK;
	}
	if (strcmp(a, "show") == 0)
		return show(argc - 1, argv + 1);
	if (strcmp(a, "cat") == 0) {
		if (argc != 3)
			return cli_usage_error(CMD, "usage: skinbake preset cat NAME");
		int i = preset_find(argv[2]);
		if (i < 0) {
			char *cause = NULL;
			preset_load_builtin(argv[2], &cause);	/* for the message listing the names */
			int rc = cli_usage_error(CMD, "%s", cause);
			free(cause);
			return rc;
		}
		fputs(preset_builtin_text(i), stdout);
		return CLI_EXIT_OK;
	}
	if (strcmp(a, "keys") == 0) {
		if (argc != 2)
			return cli_usage_error(CMD, "unexpected argument '%s'", argv[2]);
		preset_print_keys(stdout);
		return CLI_EXIT_OK;
	}
	return cli_usage_error(CMD, "unknown action '%s' (show, cat, keys)", a);
}
