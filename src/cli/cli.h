/* cli: the command-line layer.  Only files of this layer (cli.c, cmd_*.c)
 * print errors and choose exit codes.  Exit status: 0 success, 2 bad input
 * (usage, flag, preset, file), 1 runtime failure (I/O). */
#ifndef SKINBAKE_CLI_H
#define SKINBAKE_CLI_H
#include <stdarg.h>
#include <stdio.h>

#include "cli/msg.h"

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
int cmd_export_mitsuba(int argc, char **argv);
int cmd_maps(int argc, char **argv);
int cmd_verify(int argc, char **argv);
int cmd_scene(int argc, char **argv);
#endif
