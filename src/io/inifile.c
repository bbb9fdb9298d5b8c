/* inifile: INI text through libinih with line numbers and whole lines
 * (see inifile.h). */
#include "config.h"
#include "io/inifile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

/* libinih reader: one line per call, stripped of its end of line. */
static char *reader(char *str, int num, void *stream)
{
	struct inifile *f = stream;
	if (f->too_long || *f->pos == '\0')
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
	return str;
}

int inifile_parse(struct inifile *f, const char *origin, const char *text, ini_handler handler, void *user)
{
	f->origin = origin;
	f->pos = text;
	f->cur = text;
	f->line = 0;
	f->too_long = 0;
	f->max_line = INI_MAX_LINE - 1;
	int rc = ini_parse_stream(reader, f, handler, user);
	return f->too_long ? f->too_long : rc;
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
