/* inifile: INI text through libinih with line numbers and whole lines
 * (see inifile.h). */
#include "config.h"
#include "io/inifile.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

static char *msg(const char *origin, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static char *msg(const char *origin, int line, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	char *m = inifile_vmsg(origin, line, fmt, ap);
	va_end(ap);
	return m;
}

/* A section header line (after blanks and, on line 1, a UTF-8 byte-order
 * mark, as libinih skips them): 1 when it is "[NAME]" with at most blanks
 * and a ';' or '#' comment after it, and NAME into name[size] as libinih
 * takes it; 0 for other lines; -1 (message in f->error) for a header with
 * other text after ']' or without ']'. */
static int header(struct inifile *f, const char *s, char *name, size_t size)
{
	if (f->line == 1 && strncmp(s, "\xEF\xBB\xBF", 3) == 0)
		s += 3;
	while (*s == ' ' || *s == '\t')
		s++;
	if (*s != '[')
		return 0;
	const char *end = strchr(s + 1, ']');
	if (end == NULL) {
		/* Said here: libinih would carry on under the previous section
		 * and a later key would be reported instead (given twice). */
		f->bad_header = f->line;
		f->error = msg(f->origin, f->line,
		    "the section header '%s' is not closed (']' missing)", s);
		return -1;
	}
	snprintf(name, size, "%.*s", (int)(end - s - 1), s + 1);
	const char *t = end + 1;
	while (*t == ' ' || *t == '\t')
		t++;
	if (*t == '\0' || *t == ';' || *t == '#')
		return 1;
	f->bad_header = f->line;
	f->error = msg(f->origin, f->line, "text after the section header [%s]: '%s' (a header "
	    "line holds only [NAME] and an optional ; comment; put keys on lines of their own)",
	    name, t);
	return -1;
}

/* libinih reader: one line per call, stripped of its end of line. */
static char *reader(char *str, int num, void *stream)
{
	struct inifile *f = stream;
	/* libinih r56 and later (Debian 13) read on into a smaller buffer after
	 * a line that filled theirs, to discard the rest of an over-long line;
	 * r55 (Debian 12) goes on to the next line with the same buffer.  The
	 * line was whole (its end of line stripped): there is no rest. */
	int rest = f->filled && num < f->filled;
	f->filled = 0;
	if (rest)
		return NULL;
	if (f->too_long || f->bad_header || f->refused || *f->pos == '\0')
		return NULL;
	const char *eol = strchr(f->pos, '\n');
	size_t len = eol ? (size_t)(eol - f->pos) : strlen(f->pos);
	size_t content = len;
	if (content > 0 && f->pos[content - 1] == '\r')
		content--;
	f->line++;
	f->cur = f->pos;
	f->pos += eol ? len + 1 : len;
	if (content > (size_t)f->max_line || content > (size_t)num - 1) {
		f->too_long = f->line;
		return NULL;
	}
	memcpy(str, f->cur, content);
	str[content] = '\0';
	if (content == (size_t)num - 1)
		f->filled = num;
	char name[INI_MAX_LINE];
	int h = header(f, str, name, sizeof name);
	if (h < 0)
		return NULL;
	if (h > 0 && f->section != NULL && !f->section(f->user, name)) {
		f->refused = f->line;
		return NULL;
	}
	return str;
}

int inifile_parse(struct inifile *f, const char *origin, const char *text, ini_handler handler,
    inifile_section_fn section, void *user)
{
	*f = (struct inifile){ .origin = origin, .pos = text, .cur = text,
		.max_line = INI_MAX_LINE - 1, .section = section, .user = user };
	int rc = ini_parse_stream(reader, f, handler, user);
	if (f->too_long)
		return f->too_long;
	if (f->bad_header)
		return f->bad_header;
	return f->refused ? f->refused : rc;
}

char *inifile_read(const char *path, char **cause)
{
	FILE *fp = fopen(path, "rb");
	if (fp == NULL) {
		*cause = xasprintf("%s: cannot open: %s", path, strerror(errno));
		return NULL;
	}
	size_t cap = 4096, n = 0;
	char *buf = xmalloc(cap);
	size_t k;
	while ((k = fread(buf + n, 1, cap - n - 1, fp)) > 0) {
		n += k;
		if (n + 1 >= cap)
			buf = xreallocarray(buf, cap *= 2, 1);
	}
	int bad = ferror(fp);
	fclose(fp);
	if (bad) {
		*cause = xasprintf("%s: read error", path);
		free(buf);
		return NULL;
	}
	if (memchr(buf, '\0', n) != NULL) {
		*cause = xasprintf("%s: not a text file (contains NUL bytes)", path);
		free(buf);
		return NULL;
	}
	buf[n] = '\0';
	return buf;
}

char *inifile_vmsg(const char *origin, int line, const char *fmt, va_list ap)
{
	char *m;
	if (vasprintf(&m, fmt, ap) < 0)
		fatalx("out of memory formatting a message");
	char *r = xasprintf("%s:%d: %s", origin, line, m);
	free(m);
	return r;
}
