/* skinbake's entry point: the command table, error printing and the
 * progress bar (options are parsed by opt.c). */
#include "config.h"
#include "cli/cli.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <errno.h>
#include <string.h>
#include <unistd.h>

#include "cli/opt.h"
#include "base/util.h"
#include "engine/ad.h"

/* What went to stdout is output too: a write error there (a full disk,
 * /dev/full) is a failure with its cause, never exit status 0. */
static int close_stdout(int rc)
{
	errno = 0;
	if (fflush(stdout) != 0 || ferror(stdout)) {
		fprintf(stderr, "skinbake: writing the standard output failed: %s\n",
		    errno ? strerror(errno) : "I/O error");
		return rc == CLI_EXIT_OK ? CLI_EXIT_FAIL : rc;
	}
	return rc;
}

#ifdef SKINBAKE_MPI
#include <mpi.h>
#endif

static const struct opt_sub commands[] = {
	{ "simulate", "Monte Carlo transport in a layered slab: totals, BRDF, Rd(r)",
	  cmd_simulate },
	{ "presets", "list the shipped skin presets", cmd_presets },
	{ "preset", "preset show NAME: print a preset's layers per wavelength", cmd_preset },
	{ "bake", "bake a skin preset's BRDF into OpenEXR lookup tables", cmd_bake },
	{ "eval", "evaluate a baked BRDF at given angles", cmd_eval },
	{ "verify", "check a bake's table against an independent Monte Carlo run", cmd_verify },
	{ "texture", "grow pores and furrows as seamless height and normal maps", cmd_texture },
	{ "scene", "write a scene file as renderer-neutral scene.json", cmd_scene },
	{ "export", "export pov|blender: scenes and image sets for renderers", cmd_export },
	{ "maps", "maps new|fit|edit|render-albedo: parameter maps of a family", cmd_maps },
	{ NULL, NULL, NULL },
};

static void usage(FILE *fp)
{
	fprintf(fp, "usage: skinbake COMMAND [options]\n\ncommands:\n");
	for (size_t i = 0; commands[i].name; i++)
		fprintf(fp, "  %-10s %s\n", commands[i].name, commands[i].summary);
	fprintf(fp,
	    "\n  skinbake COMMAND --help   shows every option with its default, unit and range.\n"
	    "  skinbake --version        prints the version.\n");
}

static int cli_main(int argc, char **argv)
{
	ad_blas_init();
	if (argc < 2) {
		usage(stderr);
		return CLI_EXIT_USAGE;
	}
	if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
	    strcmp(argv[1], "help") == 0) {
		if (argc > 2 && strcmp(argv[1], "help") == 0) {
			char *hv[] = { argv[2], (char *)"--help", NULL };
			for (size_t i = 0; commands[i].name; i++)
				if (strcmp(commands[i].name, argv[2]) == 0)
					return commands[i].exec(2, hv);
		}
		usage(stdout);
		return CLI_EXIT_OK;
	}
	if (strcmp(argv[1], "--version") == 0) {
		printf("%s\n", PACKAGE_STRING);
		return CLI_EXIT_OK;
	}
	for (size_t i = 0; commands[i].name; i++)
		if (strcmp(commands[i].name, argv[1]) == 0)
			return commands[i].exec(argc - 1, argv + 1);
	fprintf(stderr, "skinbake: unknown command '%s'\n", argv[1]);
	usage(stderr);
	return CLI_EXIT_USAGE;
}

#ifdef SKINBAKE_MPI
/* Read by AddressSanitizer, when linked in (./configure --enable-asan): Open
 * MPI never frees its own allocations, partly in plug-ins it unloads (beyond
 * suppression by name), so skinbake-mpi runs without LeakSanitizer; the same
 * code is leak-checked in skinbake. */
const char *__asan_default_options(void);
const char *__asan_default_options(void)
{
	return "detect_leaks=0";
}

/* Every value belongs to one rank and is zero on the others, so the sum is
 * exact whatever order MPI adds in. */
static void mpi_allreduce(double *v, long n)
{
	for (long off = 0; off < n; off += 1L << 28) {
		int k = (int)(n - off < (1L << 28) ? n - off : (1L << 28));
		MPI_Allreduce(MPI_IN_PLACE, v + off, k, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
	}
}

int main(int argc, char **argv)
{
	MPI_Init(&argc, &argv);
	MPI_Comm_rank(MPI_COMM_WORLD, &cli_par.rank);
	MPI_Comm_size(MPI_COMM_WORLD, &cli_par.size);
	cli_par.allreduce = mpi_allreduce;
	if (cli_par.rank != 0 && freopen("/dev/null", "w", stdout) == NULL)
		fatalx("cannot silence stdout on rank %d", cli_par.rank);
	int rc = close_stdout(cli_main(argc, argv));
	/* A rank that failed on bad input must not leave the others waiting. */
	int worst = rc;
	MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
	MPI_Finalize();
	return worst;
}
#else
int main(int argc, char **argv)
{
	return close_stdout(cli_main(argc, argv));
}
#endif

int cli_double(const char *cmd, const char *opt, const char *s, double lo, double hi, double *out)
{
	struct opt_cmd c = { .name = cmd };
	struct opt_ctx x = { .cmd = &c };
	return opt_double(&x, opt, s, lo, hi, 0, NULL, out);
}

int cli_long(const char *cmd, const char *opt, const char *s, long lo, long hi, long *out)
{
	struct opt_cmd c = { .name = cmd };
	struct opt_ctx x = { .cmd = &c };
	return opt_long(&x, opt, s, (double)lo, (double)hi, 0, NULL, out);
}

void cli_progress_start(struct cli_progress *p, const char *label)
{
	p->label = label;
	p->t0 = util_now();
	p->shown = -1;
	p->tty = isatty(2) && cli_par.rank == 0;	/* under MPI rank 0 shows it */
}

void cli_progress_update(void *user, long done, long total)
{
	struct cli_progress *p = user;
	if (!p->tty || total <= 0)
		return;
	int pm = (int)(1000.0 * (double)done / (double)total);
	if (pm == p->shown)
		return;
	p->shown = pm;
	double el = util_now() - p->t0;
	double eta = done > 0 ? el * (double)(total - done) / (double)done : 0.0;
	int bar = pm * 30 / 1000;
	char b[31];
	for (int i = 0; i < 30; i++)
		b[i] = i < bar ? '#' : '.';
	b[30] = '\0';
	fprintf(stderr, "\r%s [%s] %5.1f%%  %.1fs elapsed, %.1fs left ",
	    p->label, b, pm / 10.0, el, eta);
	fflush(stderr);
}

void cli_progress_end(struct cli_progress *p)
{
	if (p->tty && p->shown >= 0)
		fputc('\n', stderr);
}

char *cli_command_line(int argc, char **argv)
{
	char *line = xstrdup("skinbake");
	for (int i = 0; i < argc; i++) {
		char *t = xasprintf("%s %s", line, argv[i]);
		free(line);
		line = t;
	}
	return line;
}
