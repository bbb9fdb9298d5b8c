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
/* A fresh temporary name beside PATH for writers that open files themselves
 * (libpng, OpenEXR); caller frees.  Pair with util_commit_tmp. */
char *util_tmp_name(const char *path);
int util_commit_tmp(const char *tmp, const char *path, char **cause);
/* mkdir -p; -1 and *cause on failure. */
int util_mkdirs(const char *dir, char **cause);
/* Output directories written as a whole (a family, maps): built in
 * util_stage_name(DIR) = "DIR.staging" (caller frees) and swapped into
 * place by util_replace_dir, which replaces an earlier DIR.
 * util_dir_replaceable: 0 when DIR is absent, empty, or holds MARKER (an
 * earlier output of the kind WHAT); -1 and *cause otherwise.  util_rm_tree
 * removes a directory tree this program made. */
char *util_stage_name(const char *dir);
int util_replace_dir(const char *stage, const char *dir, char **cause);
int util_dir_replaceable(const char *dir, const char *marker, const char *what, char **cause);
void util_rm_tree(const char *path);
/* Monotonic wall clock [s]. */
double util_now(void);
/* Parse a double/long from the whole string (no trailing junk); 0 on success. */
int util_parse_double(const char *s, double *out);
int util_parse_long(const char *s, long *out);
#endif
