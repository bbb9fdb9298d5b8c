/* msg: "skinbake CMD: message" on stderr (rank 0 only under MPI) and the
 * exit status that goes with it (see msg.h). */
#include "config.h"

#include "cli/msg.h"

#include <stdio.h>

struct cli_parallel cli_par = { 0, 1, NULL };

static void vmsg(const char *cmd, const char *fmt, va_list ap)
{
	/* Under MPI every rank parses the same input and meets the same error:
	 * rank 0 speaks for all (main's MPI_Allreduce gives the exit status). */
	if (cli_par.rank != 0)
		return;
	fprintf(stderr, "skinbake %s: ", cmd);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
}

int cli_vusage_error(const char *cmd, const char *fmt, va_list ap)
{
	if (cli_par.rank == 0)
		vmsg(cmd, fmt, ap);
	return CLI_EXIT_USAGE;
}

int cli_usage_error(const char *cmd, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	cli_vusage_error(cmd, fmt, ap);
	va_end(ap);
	return CLI_EXIT_USAGE;
}

int cli_fail(const char *cmd, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vmsg(cmd, fmt, ap);
	va_end(ap);
	return CLI_EXIT_FAIL;
}
