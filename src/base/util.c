/* util: allocation that never fails, messages, and atomic file output
 * (see util.h). */
#include "config.h"
#include "base/util.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

void fatalx(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fputs("skinbake: fatal: ", stderr);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
	abort();
}

void *xmalloc(size_t size)
{
	void *p = malloc(size ? size : 1);
	if (p == NULL)
		fatalx("out of memory allocating %zu bytes", size);
	return p;
}

void *xcalloc(size_t n, size_t size)
{
	void *p = calloc(n ? n : 1, size ? size : 1);
	if (p == NULL)
		fatalx("out of memory allocating %zu x %zu bytes", n, size);
	return p;
}

void *xreallocarray(void *p, size_t n, size_t size)
{
	if (size && n > SIZE_MAX / size)
		fatalx("allocation overflow: %zu x %zu", n, size);
	void *q = realloc(p, (n * size) != 0 ? n * size : 1);
	if (q == NULL)
		fatalx("out of memory reallocating %zu x %zu bytes", n, size);
	return q;
}

char *xstrdup(const char *s)
{
	char *p = strdup(s);
	if (p == NULL)
		fatalx("out of memory duplicating a string");
	return p;
}

char *xasprintf(const char *fmt, ...)
{
	va_list ap;
	char *s;
	va_start(ap, fmt);
	if (vasprintf(&s, fmt, ap) < 0)
		fatalx("out of memory formatting a message");
	va_end(ap);
	return s;
}

char *util_tmp_name(const char *path)
{
	static unsigned long counter;
	unsigned long c;
#pragma omp atomic capture
	c = counter++;
	return xasprintf("%s.tmp.%ld.%lu", path, (long)getpid(), c);
}

int util_commit_tmp(const char *tmp, const char *path, char **cause)
{
	if (rename(tmp, path) != 0) {
		*cause = xasprintf("%s: cannot rename into place: %s", path, strerror(errno));
		unlink(tmp);
		return -1;
	}
	return 0;
}

int outfile_open(struct outfile *o, const char *path, char **cause)
{
	o->path = xstrdup(path);
	o->tmp = util_tmp_name(path);
	o->fp = fopen(o->tmp, "w");
	if (o->fp == NULL) {
		*cause = xasprintf("%s: cannot write: %s", path, strerror(errno));
		free(o->path);
		free(o->tmp);
		o->path = o->tmp = NULL;
		return -1;
	}
	return 0;
}

int outfile_write_text(const char *path, const char *text, char **cause)
{
	struct outfile of;
	if (outfile_open(&of, path, cause) != 0)
		return -1;
	size_t n = strlen(text);
	fputs(text, of.fp);
	if (n == 0 || text[n - 1] != '\n')
		fputc('\n', of.fp);
	return outfile_commit(&of, cause);
}

int outfile_commit(struct outfile *o, char **cause)
{
	int rc = 0;
	if (ferror(o->fp) | (fclose(o->fp) != 0)) {
		*cause = xasprintf("%s: write failed: %s", o->path, strerror(errno));
		unlink(o->tmp);
		rc = -1;
	} else
		rc = util_commit_tmp(o->tmp, o->path, cause);
	free(o->path);
	free(o->tmp);
	o->fp = NULL;
	o->path = o->tmp = NULL;
	return rc;
}

void outfile_abort(struct outfile *o)
{
	if (o->fp != NULL)
		fclose(o->fp);
	if (o->tmp != NULL)
		unlink(o->tmp);
	free(o->path);
	free(o->tmp);
	o->fp = NULL;
	o->path = o->tmp = NULL;
}

int util_mkdirs(const char *dir, char **cause)
{
	if (*dir == '\0') {	/* the loop below starts after the first character */
		*cause = xstrdup("the directory name is empty");
		return -1;
	}
	char *p = xstrdup(dir);
	for (char *s = p + 1; ; s++) {
		char c = *s;
		if (c == '/' || c == '\0') {
			*s = '\0';
			if (mkdir(p, 0777) != 0 && errno != EEXIST) {
				*cause = xasprintf("%s: cannot create directory: %s", p, strerror(errno));
				free(p);
				return -1;
			}
			*s = c;
			if (c == '\0')
				break;
		}
	}
	struct stat st;
	if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
		*cause = xasprintf("%s: not a directory", dir);
		free(p);
		return -1;
	}
	free(p);
	return 0;
}

double util_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int util_parse_double(const char *s, double *out)
{
	char *end;
	if (s == NULL || *s == '\0')
		return -1;
	errno = 0;
	double v = strtod(s, &end);
	if (*end != '\0' || errno == ERANGE)
		return -1;
	*out = v;
	return 0;
}

int util_parse_decimal(const char *s, double *out)
{
	const char *p = s;
	int digits = 0;
	if (s == NULL)
		return -1;
	if (*p == '+' || *p == '-')
		p++;
	for (; *p >= '0' && *p <= '9'; p++)
		digits++;
	if (*p == '.')
		for (p++; *p >= '0' && *p <= '9'; p++)
			digits++;
	if (digits == 0)
		return -1;
	if (*p == 'e' || *p == 'E') {
		p++;
		if (*p == '+' || *p == '-')
			p++;
		if (!(*p >= '0' && *p <= '9'))
			return -1;
		while (*p >= '0' && *p <= '9')
			p++;
	}
	if (*p != '\0' || util_parse_double(s, out) != 0 || !isfinite(*out))
		return -1;
	return 0;
}

int util_parse_long(const char *s, long *out)
{
	double v;
	/* Accept 1e6 as well as 1000000: photon counts are written both ways. */
	if (util_parse_double(s, &v) != 0 || !isfinite(v) || v != floor(v) || fabs(v) > 9.2e18)
		return -1;
	*out = (long)v;
	return 0;
}
