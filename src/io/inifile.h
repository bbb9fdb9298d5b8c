/* inifile: INI text through libinih with line numbers, whole lines only.
 * libinih cuts lines at 200 characters and parses the pieces silently
 * (../shared/notes/dependencies.md section 6); here a longer line stops the
 * parse and is reported.  Used by presets, scene files and texture files. */
#ifndef SKINBAKE_INIFILE_H
#define SKINBAKE_INIFILE_H
#include <ini.h>
#include <stdarg.h>

struct inifile {
	const char *origin;	/* a path, or a description of the text, for messages */
	const char *pos;	/* next unread character of the text */
	const char *cur;	/* start of the line last handed to libinih */
	int line;		/* its number, 1-based */
	int too_long;		/* number of the first over-long line, 0 if none */
	int max_line;		/* longest line accepted [characters] */
};

/* Parse text line by line with handler(user, ...); handlers may read
 * f->line.  Returns ini_parse_stream's result (0, or the first line with a
 * syntax error or a handler returning 0), or f->too_long when a line is
 * longer than f->max_line characters. */
int inifile_parse(struct inifile *f, const char *origin, const char *text, ini_handler handler, void *user);
/* "ORIGIN:LINE: message" (caller frees): how every INI error is worded. */
char *inifile_vmsg(const char *origin, int line, const char *fmt, va_list ap) __attribute__((format(printf, 3, 0)));

/* The whole file (caller frees), or NULL with *cause "PATH: reason". */
char *inifile_read(const char *path, char **cause);
#endif
