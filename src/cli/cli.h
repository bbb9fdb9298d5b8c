/* cli: the command-line layer.  Only files of this layer (cli.c, cmd_*.c)
 * print errors and choose exit codes.  Exit status: 0 success, 2 bad input
 * (usage, flag, preset, file), 1 runtime failure (I/O). */
#ifndef SKINBAKE_CLI_H
#define SKINBAKE_CLI_H
#include <stdarg.h>
#include <stdio.h>

#define CLI_EXIT_OK 0
#define CLI_EXIT_FAIL 1
#define CLI_EXIT_USAGE 2

/* Print "skinbake CMD: message" to stderr; returns CLI_EXIT_USAGE.  Under
 * MPI only rank 0 prints: every rank sees the same bad input. */
int cli_usage_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int cli_vusage_error(const char *cmd, const char *fmt, va_list ap) __attribute__((format(printf, 2, 0)));
/* Print "skinbake CMD: message" to stderr; returns CLI_EXIT_FAIL. */
int cli_fail(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Progress bar on stderr, shown only when stderr is a terminal (and on MPI rank 0). */
struct cli_progress {
	const char *label;
	double t0;	/* start [s] */
	int shown;	/* last permille drawn */
	int tty;
};
void cli_progress_start(struct cli_progress *p, const char *label);
/* Usable as a sim_run progress callback: user = struct cli_progress *. */
void cli_progress_update(void *user, long done, long total);
void cli_progress_end(struct cli_progress *p);

/* "skinbake ARGV[0] ARGV[1] ...", for a manifest.  Caller frees. */
char *cli_command_line(int argc, char **argv);

/* Option values by the rules of opt.h (decimal only, message with the
 * range); -1 after reporting.  For commands not yet described by an opt
 * table (cmd_export_pov.c); new code uses opt.h. */
int cli_double(const char *cmd, const char *opt, const char *s, double lo, double hi, double *out);
int cli_long(const char *cmd, const char *opt, const char *s, long lo, long hi, long *out);

/* Process layout for bakes split over MPI ranks: {0, 1, NULL} in the plain
 * build; skinbake-mpi fills it after MPI_Init.  Only rank 0 prints and writes. */
struct cli_parallel {
	int rank;				/* this process */
	int size;				/* processes */
	void (*allreduce)(double *v, long n);	/* in-place sum over ranks */
};
extern struct cli_parallel cli_par;

/* Subcommands (each in its own cmd_*.c). */
int cmd_simulate(int argc, char **argv);
int cmd_presets(int argc, char **argv);
int cmd_preset(int argc, char **argv);
int cmd_bake(int argc, char **argv);
int cmd_eval(int argc, char **argv);
int cmd_texture(int argc, char **argv);
int cmd_export(int argc, char **argv);
int cmd_export_pov(int argc, char **argv);
int cmd_export_blender(int argc, char **argv);
int cmd_maps(int argc, char **argv);
int cmd_verify(int argc, char **argv);
int cmd_scene(int argc, char **argv);
#endif
