/* Helpers shared by the fuzz targets: inputs as files without disk I/O. */
#define _GNU_SOURCE
#include "config.h"
#include "fuzz.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

const char *fuzz_file(const uint8_t *data, size_t size)
{
	static int fd = -1;
	static char path[64];
	if (fd < 0) {
		fd = memfd_create("skinbake-fuzz", 0);
		if (fd < 0)
			fuzz_fail("memfd_create failed");
		snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
	}
	if (ftruncate(fd, 0) != 0 || (size > 0 && pwrite(fd, data, size, 0) != (ssize_t)size))
		fuzz_fail("cannot write the input to the memfd");
	return path;
}

char *fuzz_text(const uint8_t *data, size_t size)
{
	char *s = malloc(size + 1);
	if (s == NULL)
		fuzz_fail("out of memory");
	if (size > 0)
		memcpy(s, data, size);
	s[size] = '\0';
	return s;
}

void fuzz_fail(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fputs("fuzz: ", stderr);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
	abort();
}

const char *fuzz_datadir(void)
{
	const char *d = getenv("SKINBAKE_FUZZ_DATA");
	return d != NULL && *d != '\0' ? d : FUZZ_DATADIR;
}

void fuzz_refused(char *cause)
{
	static int verbose = -1;
	if (verbose < 0)
		verbose = getenv("SKINBAKE_FUZZ_VERBOSE") != NULL;
	if (verbose)
		fprintf(stderr, "refused: %s\n", cause ? cause : "(no message)");
	free(cause);
}
