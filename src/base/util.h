/* util: allocation that never returns NULL, formatted messages, and files
 * written through a temporary name and renamed into place (no partial
 * output).  Nothing else belongs here. */
#ifndef SKINBAKE_UTIL_H
#define SKINBAKE_UTIL_H
#include <stddef.h>
#include <stdio.h>

void *xmalloc(size_t size);
void *xcalloc(size_t n, size_t size);
void *xreallocarray(void *p, size_t n, size_t size);
char *xstrdup(const char *s);
/* Caller frees. */
char *xasprintf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Out of memory and other impossible states: print and abort the program. */
void fatalx(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));

/* Atomic output: open PATH.tmp.PID for writing; commit renames it onto PATH,
 * abort removes it.  Return -1 and set *cause (caller frees) on failure. */
struct outfile {
	char *path;	/* final name */
	char *tmp;	/* temporary name in the same directory */
	FILE *fp;
};
int outfile_open(struct outfile *o, const char *path, char **cause);
int outfile_commit(struct outfile *o, char **cause);
void outfile_abort(struct outfile *o);
/* PATH holds TEXT, ended by a newline when TEXT has none, written through an
 * outfile (all or nothing). */
int outfile_write_text(const char *path, const char *text, char **cause);
/* A fresh temporary name beside PATH for writers that open files themselves
 * (libpng, OpenEXR); caller frees.  Pair with util_commit_tmp. */
char *util_tmp_name(const char *path);
int util_commit_tmp(const char *tmp, const char *path, char **cause);
/* mkdir -p; -1 and *cause on failure. */
int util_mkdirs(const char *dir, char **cause);
/* Monotonic wall clock [s]. */
double util_now(void);
/* Parse a double/long from the whole string (no trailing junk); 0 on success. */
int util_parse_double(const char *s, double *out);
int util_parse_long(const char *s, long *out);
/* A finite number in decimal notation only ([+-]digits[.digits][e[+-]digits]:
 * no hexadecimal, inf, nan or blanks), as files read by skinbake write them;
 * 0 on success. */
int util_parse_decimal(const char *s, double *out);
#endif
