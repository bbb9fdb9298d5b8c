/* skinbake texture: grow the micro-relief of a skin site (pores and
 * Delaunay furrows) as seamless maps: a 16-bit height PNG with its physical
 * range in tEXt chunks, the components, a tangent-space normal map (16-bit
 * PNG and float EXR, OpenGL +Y), a float height EXR, an 8-bit preview and
 * manifest.json.  Everything is validated before any file is written. */
#include "config.h"

#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/opt.h"
#include "cli/cmd_texture.h"
#include "geom/relief.h"
#include "geom/relief_ranges.h"
#include "geom/sites.h"
#include "geom/texdir.h"

static const char *CMD = "texture";

static void list_sites(void)
{
	for (int i = 0; i < sites_count(); i++)
		printf("%-10s %s\n", sites_name(i), sites_summary(i));
}

/* After the options: place, render and write (texdir_make), then the notes
 * and the summary. */
static int run(const struct texture_config *cfg, const char *out, int quiet)
{
	char *cause = NULL;
	struct texdir_made s;
	int rc = texdir_make(out, cfg, &s, &cause);
	for (char *line = quiet ? NULL : s.notes, *nl; line; line = nl ? nl + 1 : NULL) {
		nl = strchr(line, '\n');
		fprintf(stderr, "skinbake texture: note: %.*s\n", nl ? (int)(nl - line) : (int)strlen(line), line);
	}
	free(s.notes);
	if (rc != 0) {
		rc = s.refused ? cli_usage_error(CMD, "%s", cause) : cli_fail(CMD, "%s", cause);
		free(cause);
		return rc;
	}
	if (!quiet)
		fprintf(stderr, "skinbake texture: %s, %ld px over %.4g mm, seed %llu: %d pores, "
		    "relief %.4g to %.4g um; place %.2f s, render %.2f s, write %.2f s -> %s\n",
		    cfg->site, cfg->size, cfg->relief.tile * 10, (unsigned long long)cfg->seed,
		    s.n_pores, s.h_min * 1e4, s.h_max * 1e4, s.t_place, s.t_render, s.t_write, out);
	int outside = 0;
	char *text = s.have_stats ? relief_ranges_report(&s.stats, cfg->site, &outside) : NULL;
	if (text != NULL && outside < 0)
		printf("%s# not compared with measured ranges\n", text);
	else if (text != NULL)
		printf("%s# %d outside their measured range\n", text, outside);
	free(text);
	return CLI_EXIT_OK;
}

int cmd_texture(int argc, char **argv)
{
	int np;
	const struct texture_param *params = sites_params(&np);
	const char *site = "face", *preset = NULL, *out = NULL, *dirmap = NULL;
	float *dir = NULL;
	int quiet = 0, dump = 0, list = 0, stats = 0, rc = CLI_EXIT_USAGE;
	struct opt opts[OPT_MAX] = {
		{ "site", OPT_STRING, &site, "NAME", "face", .help = "start from a body site (see --list-sites)" },
		{ "preset-file", OPT_PATH_IN, &preset, "FILE", .flags = OPT_FILE, .help = "start from the [texture] "
		  "section of an INI file (keys as below with '_' for '-'; 'site = NAME' first resets to that site); "
		  "applied after --site" },
		{ "out", OPT_PATH_OUT, &out, "DIR", .help = "output directory (created if missing), required unless "
		  "--list-sites or --dump-config" },
		{ "list-sites", OPT_FLAG, &list, .help = "list the sites and exit" },
		{ "dump-config", OPT_FLAG, &dump, .help = "print the resolved [texture] section and exit" },
		{ "quiet", OPT_FLAG, &quiet, .help = "no summary on stderr" },
		{ "stats", OPT_FLAG, &stats, .help = "measure the map into manifest.json and print it against the site's "
		  "measured ranges (data/relief_sites.tsv)" },
		{ "direction-map", OPT_PATH_IN, &dirmap, "PNG", .flags = OPT_FILE,
		  .help = "preferred furrow direction per pixel in UV, a PNG of --size x --size px "
		  "(encoding in docs/relief.md); replaces --orientation" },
	};
	/* One option per texture parameter, from the table in geom/sites.c. */
	enum { N_FIXED = 8 };
	char defs[OPT_MAX][32];
	struct texture_config cfg;
	char *cause = NULL;
	sites_load("face", &cfg, &cause);
	for (int i = 0; i < np && N_FIXED + i < OPT_MAX - 1; i++) {
		const struct texture_param *p = &params[i];
		snprintf(defs[i], sizeof defs[i], "%.10g", sites_get(&cfg, p));
		opts[N_FIXED + i] = (struct opt){ p->key, p->type == SITES_REAL ? OPT_DOUBLE : p->type == SITES_SEED ? OPT_U64
			: OPT_LONG, NULL,
			p->type == SITES_REAL ? "X" : "N", .def_note = defs[i], .lo = p->lo, .hi = p->hi,
			.unit = strcmp(p->unit, "1") ? p->unit : NULL, .help = p->help };
	}
	const struct opt_cmd cmd = { "texture", "[--site NAME | --preset-file FILE] [options] --out DIR",
		"Grow the micro-relief of skin (pores, primary furrows, secondary ones that\n"
		"split the primary triangles, finer nets, plateau texture) as seamless maps:\n"
		"DIR/height.png (16-bit, physical range in its tEXt chunks), pores_height.png,\n"
		"furrows_height.png, normal.png (16-bit RGB) and normal.exr (float) in tangent\n"
		"space with the OpenGL +Y convention, height.exr (float, um), preview.png and\n"
		"manifest.json.  The parameters after --direction-map override the site; the\n"
		"defaults shown are site 'face'.", opts,
		"Furrow level k (k = 0 primary) has cell furrow-cell * level-scale^k (level 2\n"
		"with --hierarchy 1: a star in each primary triangle), depth furrow-depth *\n"
		"level-gain^k, dome ridge-height * level-gain^k and width furrow-width *\n"
		"level-scale^(k/2) (at most half its cell).\n\n"
		"Heights are relative to the undisturbed surface; 0 in height.png is the\n"
		"lowest point of the map and 65535 the highest (skinbake:height_min_um and\n"
		"skinbake:height_max_um).  POV-Ray: bump_size = (max - min) * size / tile.\n"
		"Details: docs/texture.md; measured data and sources: docs/relief.md.", 0, 0 };
	struct opt_ctx x;
	if (opt_parse(&x, &cmd, argc, argv) != 0)
		return x.exit;
	if (list) {
		list_sites();
		return CLI_EXIT_OK;
	}

	/* Site, then preset file, then the options in command-line order. */
	const struct texture_sources src = { site, preset, dirmap };
	if (cmd_texture_resolve(&cfg, &x, &src, &dir) != 0)
		goto done;
	if (dump) {
		char *ini = sites_ini_text(&cfg);
		fputs(ini, stdout);
		free(ini);
		rc = CLI_EXIT_OK;
		goto done;
	}
	if (out == NULL) {
		cli_usage_error(CMD, "--out DIR is required");
		goto done;
	}

	cfg.with_stats = stats;
	rc = run(&cfg, out, quiet);
done:
	free(dir);
	free(cause);
	return rc;
}
