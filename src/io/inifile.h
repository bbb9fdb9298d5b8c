/* inifile: INI text through libinih with line numbers, whole lines only.
 * libinih cuts lines at 200 characters and parses the pieces silently
 * (../shared/notes/dependencies.md section 6); here a longer line stops the
 * parse and is reported.  libinih also ignores whatever follows the ']' of
 * a section header and never reports a section without keys; here text
 * after a header (other than a ';' or '#' comment) stops the parse, and a
 * reader may check every header's name with a section callback, so that
 * `[dermis] thickness = 0.1` and a misspelt empty `[surfce]` are errors.
 * Used by presets, scene files and texture files. */
#ifndef SKINBAKE_INIFILE_H
#define SKINBAKE_INIFILE_H
#include <ini.h>
#include <stdarg.h>

/* Called for every section header before the keys under it: 1 to go on, 0
 * to stop the parse (the reader keeps its own message; f->line is the
 * header's line). */
typedef int (*inifile_section_fn)(void *user, const char *section);

struct inifile {
	const char *origin;	/* a path, or a description of the text, for messages */
	const char *pos;	/* next unread character of the text */
	const char *cur;	/* start of the line last handed to libinih */
	int line;		/* its number, 1-based */
	int filled;		/* size of libinih's buffer if that line filled it, else 0 */
	int too_long;		/* number of the first over-long line, 0 if none */
	int max_line;		/* longest line accepted [characters] */
	int bad_header;		/* number of the first header line with text after ']',
				 * 0 if none */
	char *error;		/* "ORIGIN:LINE: ..." for bad_header (caller frees),
				 * else NULL */
	int refused;		/* line of a header the section callback refused, 0 if none */
	inifile_section_fn section;	/* may be NULL */
	void *user;
};

/* Parse text line by line with handler(user, ...) and section(user, ...)
 * (NULL: no check of headers); handlers may read f->line.  Returns
 * ini_parse_stream's result (0, or the first line with a syntax error or a
 * handler returning 0), or the line of an over-long line (f->too_long), of
 * a header with trailing text (f->bad_header, message in f->error) or of a
 * header the section callback refused (f->refused). */
int inifile_parse(struct inifile *f, const char *origin, const char *text, ini_handler handler,
    inifile_section_fn section, void *user);
/* "ORIGIN:LINE: message" (caller frees): how every INI error is worded. */
char *inifile_vmsg(const char *origin, int line, const char *fmt, va_list ap)
    __attribute__((format(printf, 3, 0)));

/* The whole file (caller frees), or NULL with *cause "PATH: reason". */
char *inifile_read(const char *path, char **cause);
#endif
