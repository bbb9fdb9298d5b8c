/* opt_help: the --help text generated from a command's option table, and
 * the dispatcher of commands with actions (opt.h). */
#include "config.h"
#include "cli/opt.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/msg.h"
#include "base/util.h"

#define HELP_COL 25	/* column of the option texts */
#define HELP_WIDTH 79
#define NBSP '\001'	/* a space the wrapper does not break at */

/* ---- help ---------------------------------------------------------------- */

/* Print TEXT from column COL (the cursor is at column AT), wrapped at
 * HELP_WIDTH; continuation lines start at column COL. */
static void wrap(FILE *fp, const char *text, int at, int col)
{
	const char *p = text;
	if (at > col) {
		fputc('\n', fp);
		at = 0;
	}
	fprintf(fp, "%*s", col - at, "");
	at = col;
	int first = 1;
	while (*p) {
		while (*p == ' ')
			p++;
		size_t w = strcspn(p, " ");
		if (w == 0)
			break;
		if (!first && at + 1 + (int)w > HELP_WIDTH) {
			fprintf(fp, "\n%*s", col, "");
			at = col;
		} else if (!first) {
			fputc(' ', fp);
			at++;
		}
		for (size_t i = 0; i < w; i++)
			fputc(p[i] == NBSP ? ' ' : p[i], fp);
		at += (int)w;
		p += w;
		first = 0;
	}
	fputc('\n', fp);
}

/* Append to B (size N): S with its spaces made unbreakable. */
static void cat_nb(char *b, size_t n, const char *s)
{
	size_t k = strlen(b);
	for (; *s && k + 1 < n; s++)
		b[k++] = *s == ' ' ? NBSP : *s;
	b[k] = '\0';
}

static void cat(char *b, size_t n, const char *s)
{
	size_t k = strlen(b);
	snprintf(b + k, n - k, "%s", s);
}

/* Append " (A; B; C)" of the non-empty parts. */
static void cat_parts(char *t, size_t n, const char *const *parts, int np)
{
	int k = 0;
	for (int i = 0; i < np; i++) {
		if (parts[i] == NULL || *parts[i] == '\0')
			continue;
		cat(t, n, k++ ? "; " : " (");
		cat(t, n, parts[i]);
	}
	if (k)
		cat(t, n, ")");
}

/* "default X" with X unbreakable when short. */
static void fmt_default(char *b, size_t n, const char *def)
{
	snprintf(b, n, "default");
	if (def == NULL) {
		b[0] = '\0';
		return;
	}
	if (strlen(def) <= 24)
		cat_nb(b, n, " ");
	else
		cat(b, n, " ");
	(strlen(def) <= 24 ? cat_nb : cat)(b, n, def);
}

static void describe_keys(FILE *fp, const struct opt_key *keys)
{
	int w = 0;
	for (int i = 0; keys[i].name; i++)
		w = (int)strlen(keys[i].name) > w ? (int)strlen(keys[i].name) : w;
	for (int i = 0; keys[i].name; i++) {
		const struct opt_key *k = &keys[i];
		char t[512] = "", r[96], d[96];
		cat(t, sizeof t, k->help);
		if (k->type == OPT_ENUM) {
			cat(t, sizeof t, ": ");
			cat(t, sizeof t, k->choices);
		} else if (k->type != OPT_STRING) {
			opt_range_text(r, sizeof r, k->lo, k->hi, k->flags, k->unit);
			cat(t, sizeof t, k->type == OPT_VEC3 ? " X:Y:Z, each in " : " in ");
			cat_nb(t, sizeof t, r);
		}
		fmt_default(d, sizeof d, k->def);
		const char *parts[] = { k->flags & OPT_REQUIRED ? "required" : NULL, d };
		cat_parts(t, sizeof t, parts, 2);
		int at = fprintf(fp, "%*s%-*s", HELP_COL + 2, "", w, k->name);
		wrap(fp, t, at, HELP_COL + 2 + w + 2);
	}
}

/* The placeholder of o's value in --help: its .meta, else from its type
 * (NULL for a flag). */
static const char *meta_of(const struct opt *o)
{
	if (o->meta)
		return o->meta;
	if (o->type == OPT_ENUM)
		return o->choices;
	if (o->type == OPT_FLAG)
		return NULL;
	if (o->type == OPT_PATH_IN || o->type == OPT_PATH_OUT)
		return "PATH";
	return "X";
}

static void describe(FILE *fp, const struct opt *o)
{
	char head[64], t[1024] = "", r[96], req[160] = "", rep[48] = "", d[160];
	const char *meta = meta_of(o);
	snprintf(head, sizeof head, "  --%s%s%s", o->name, meta ? " " : "", meta ? meta : "");
	cat(t, sizeof t, o->help);
	if (o->type == OPT_DOUBLE || o->type == OPT_LONG || o->type == OPT_INT ||
	    o->type == OPT_LIST || o->type == OPT_U64) {
		opt_range_text(r, sizeof r, o->type == OPT_U64 ? 0 : o->lo,
		    o->type == OPT_U64 ? 18446744073709551616.0 : o->hi,
		    o->type == OPT_U64 ? 0 : o->flags, o->unit);
		cat(t, sizeof t,
		    o->type != OPT_LIST ? " in " : o->flags & OPT_STEPS ? ", comma-separated, "
		    "START:STOP:STEP for a range, each in " : ", comma-separated, each in ");
		cat_nb(t, sizeof t, r);
		if (o->type == OPT_LIST && o->max > 0) {
			snprintf(r, sizeof r, ", at most %d", o->max);
			cat(t, sizeof t, r);
		}
	} else if (o->type != OPT_ENUM && o->unit) {
		cat(t, sizeof t, " [");
		cat(t, sizeof t, o->unit);
		cat(t, sizeof t, "]");
	}
	if (o->excl) {
		cat(req, sizeof req,
		    (o->flags & OPT_REQUIRED) ? "required: this or --" : "not with --");
		for (const char *p = o->excl; *p; p++)
			cat(req, sizeof req, *p == '|' ? " or --" : (char[2]){ *p, 0 });
	} else if (o->flags & OPT_REQUIRED)
		cat(req, sizeof req, "required");
	if (o->flags & OPT_REPEAT) {
		snprintf(rep, sizeof rep, "repeat");
		if (o->max > 0)
			snprintf(rep, sizeof rep, "repeat, at most %d times", o->max);
	}
	fmt_default(d, sizeof d, o->def ? o->def : o->def_note);
	const char *parts[] = { req, rep, d };
	cat_parts(t, sizeof t, parts, 3);
	int at = fprintf(fp, "%-*s", HELP_COL - 1, head);
	if (at >= HELP_COL) {	/* a long head: the text goes below it */
		fputc('\n', fp);
		at = 0;
	}
	wrap(fp, t, at, HELP_COL);
	if (o->keys)
		describe_keys(fp, o->keys);
}

/* Paragraphs (separated by an empty line) refilled to HELP_WIDTH, except
 * those with indented lines, which keep their layout. */
static void paragraphs(FILE *fp, const char *text)
{
	char *s = xstrdup(text), *p = s;
	while (p != NULL) {
		char *end = strstr(p, "\n\n");
		if (end != NULL)
			*end = '\0';
		if (*p == ' ' || strstr(p, "\n ") != NULL)
			fprintf(fp, "%s\n", p);
		else {
			for (char *q = p; *q; q++)
				*q = *q == '\n' ? ' ' : *q;
			wrap(fp, p, 0, 0);
		}
		if (end != NULL)
			fputc('\n', fp);
		p = end ? end + 2 : NULL;
	}
	free(s);
}

void opt_help(const struct opt_cmd *c, FILE *fp)
{
	int at = fprintf(fp, "usage: skinbake %s%s", c->name, *c->usage ? " " : "");
	wrap(fp, c->usage, at, at);
	if (c->about) {
		fputc('\n', fp);
		paragraphs(fp, c->about);
	}
	fputc('\n', fp);
	for (int i = 0; c->opts[i].name; i++)
		describe(fp, &c->opts[i]);
	fprintf(fp, "%-*s this text\n", HELP_COL - 1, "  --help");
	if (c->notes) {
		fputc('\n', fp);
		paragraphs(fp, c->notes);
	}
}

/* ---- actions ------------------------------------------------------------- */

int opt_dispatch(const char *cmd, const struct opt_sub *subs, int argc, char **argv)
{
	char names[128] = "";
	for (int i = 0; subs[i].name; i++)
		snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s",
		    i ? ", " : "", subs[i].name);
	if (argc < 2)
		return cli_usage_error(cmd, "missing action: %s (see skinbake %s --help)",
		    names, cmd);
	const char *a = argv[1];
	if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0 || strcmp(a, "help") == 0) {
		printf("usage: skinbake %s ACTION [options]\n\nactions:\n", cmd);
		for (int i = 0; subs[i].name; i++)
			printf("  %-10s %s\n", subs[i].name, subs[i].summary);
		printf("\n  skinbake %s ACTION --help shows the options of each.\n", cmd);
		return CLI_EXIT_OK;
	}
	for (int i = 0; subs[i].name; i++)
		if (strcmp(subs[i].name, a) == 0)
			return subs[i].exec(argc - 1, argv + 1);
	return cli_usage_error(cmd, "unknown action '%s' (%s)", a, names);
}
