/* msg: the command line's messages and exit status, and the process
 * layout under MPI (only rank 0 speaks): what the option parser (opt.c)
 * and the commands share, below cli.h. */
#ifndef SKINBAKE_MSG_H
#define SKINBAKE_MSG_H
#include <stdarg.h>

#define CLI_EXIT_OK 0
#define CLI_EXIT_FAIL 1
#define CLI_EXIT_USAGE 2

/* Print "skinbake CMD: message" to stderr; returns CLI_EXIT_USAGE.  Under
 * MPI only rank 0 prints: every rank sees the same bad input. */
int cli_usage_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int cli_vusage_error(const char *cmd, const char *fmt, va_list ap) __attribute__((format(printf, 2, 0)));
/* Print "skinbake CMD: message" to stderr; returns CLI_EXIT_FAIL. */
int cli_fail(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Process layout for bakes split over MPI ranks: {0, 1, NULL} in the plain
 * build; skinbake-mpi fills it after MPI_Init.  Only rank 0 prints and writes. */
struct cli_parallel {
	int rank;				/* this process */
	int size;				/* processes */
	void (*allreduce)(double *v, long n);	/* in-place sum over ranks */
};
extern struct cli_parallel cli_par;
#endif
