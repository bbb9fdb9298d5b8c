/* opt: the option tables of the commands: parsing by one set of rules,
 * the generated --help text, and the messages about bad values (opt.h). */
#include "config.h"
#include "cli/opt.h"

#include <assert.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "base/util.h"

#define HELP_COL 25	/* column of the option texts in --help */
#define HELP_WIDTH 79
#define NBSP '\001'	/* a space the help wrapper does not break at */
#define KEYS_MAX 32

int opt_error(const struct opt_ctx *x, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	cli_vusage_error(x->cmd->name, fmt, ap);
	va_end(ap);
	return CLI_EXIT_USAGE;
}

/* ---- numbers ---------------------------------------------------------- */

/* [+-]digits[.digits][(e|E)[+-]digits] with a digit in the mantissa: what
 * strtod would read as a decimal number, without hexadecimal, inf, nan,
 * blanks or anything after it. */
static int decimal(const char *s, int *integer)
{
	int digits = 0;
	*integer = 1;
	if (*s == '+' || *s == '-')
		s++;
	for (; *s >= '0' && *s <= '9'; s++)
		digits++;
	if (*s == '.') {
		*integer = 0;
		for (s++; *s >= '0' && *s <= '9'; s++)
			digits++;
	}
	if (digits == 0)
		return 0;
	if (*s == 'e' || *s == 'E') {
		*integer = 0;
		s++;
		if (*s == '+' || *s == '-')
			s++;
		if (!(*s >= '0' && *s <= '9'))
			return 0;
		while (*s >= '0' && *s <= '9')
			s++;
	}
	return *s == '\0';
}

/* Shortest text that reads back as V: 5, 0.005, 1e12, 2^63-1, inf. */
static void fmt_num(char *b, size_t n, double v)
{
	if (isinf(v)) {
		snprintf(b, n, "%sinf", v < 0 ? "-" : "");
		return;
	}
	if (v == (double)LONG_MAX) {
		snprintf(b, n, "2^63-1");
		return;
	}
	if (v == floor(v) && fabs(v) < 1e6) {
		snprintf(b, n, "%.0f", v);
		return;
	}
	for (int p = 1; p <= 17; p++) {
		snprintf(b, n, "%.*g", p, v);
		if (strtod(b, NULL) == v)
			break;
	}
	char *e = strchr(b, 'e');
	if (e != NULL) {	/* 1e+12 -> 1e12, 1e-07 -> 1e-7 */
		char *d = e + 1, *s = e + 1;
		if (*s == '+')
			s++;
		else if (*s == '-')
			*d++ = *s++;
		while (*s == '0' && s[1] != '\0')
			s++;
		memmove(d, s, strlen(s) + 1);
	}
}

/* "[0, 90) deg" */
static void fmt_range(char *b, size_t n, double lo, double hi, unsigned flags, const char *unit)
{
	char l[40], h[40];
	fmt_num(l, sizeof l, lo);
	fmt_num(h, sizeof h, hi);
	snprintf(b, n, "%c%s, %s%c%s%s", flags & OPT_LO_OPEN ? '(' : '[', l, h, flags & OPT_HI_OPEN ? ')' : ']',
	    unit ? " " : "", unit ? unit : "");
}

static int in_range(double v, double lo, double hi, unsigned flags)
{
	if (isinf(v) && (flags & OPT_INF))
		return 1;
	return (flags & OPT_LO_OPEN ? v > lo : v >= lo) && (flags & OPT_HI_OPEN ? v < hi : v <= hi);
}

/* Reads S by the rules; *integer tells whether it had neither '.' nor an
 * exponent.  -1 after reporting. */
static int number(const struct opt_ctx *x, const char *label, const char *s, double lo, double hi,
    unsigned flags, const char *unit, const char *what, double *out, int *integer)
{
	char r[96];
	fmt_range(r, sizeof r, lo, hi, flags, unit);
	*integer = 0;
	if ((flags & OPT_INF) && strcasecmp(s, "inf") == 0) {
		*out = INFINITY;
		return 0;
	}
	if (!decimal(s, integer))
		return opt_error(x, "%s = '%s' is not a %s in %s", label, s, what, r), -1;
	errno = 0;
	double v = strtod(s, NULL);
	if (!isfinite(v) || !in_range(v, lo, hi, flags))
		return opt_error(x, "%s = %s is out of range %s", label, s, r), -1;
	*out = v;
	return 0;
}

int opt_double(const struct opt_ctx *x, const char *label, const char *s, double lo, double hi,
    unsigned flags, const char *unit, double *out)
{
	int integer;
	return number(x, label, s, lo, hi, flags, unit, "decimal number", out, &integer);
}

int opt_long(const struct opt_ctx *x, const char *label, const char *s, double lo, double hi,
    unsigned flags, const char *unit, long *out)
{
	double v;
	int integer;
	char r[96];
	if (number(x, label, s, lo, hi, flags & ~OPT_INF, unit, "whole decimal number", &v, &integer) != 0)
		return -1;
	fmt_range(r, sizeof r, lo, hi, flags, unit);
	if (v != floor(v))
		return opt_error(x, "%s = %s is not a whole number in %s", label, s, r), -1;
	if (integer) {	/* exact beyond 2^53, e.g. seeds */
		errno = 0;
		long l = strtol(s, NULL, 10);
		if (errno == ERANGE)
			return opt_error(x, "%s = %s is out of range %s", label, s, r), -1;
		*out = l;
	} else {
		if (fabs(v) >= 9.2e18)
			return opt_error(x, "%s = %s is out of range %s", label, s, r), -1;
		*out = (long)v;
	}
	return 0;
}

/* ---- paths -------------------------------------------------------------- */

/* HINT (the option's help) says what was expected. */
static int path_in(const struct opt_ctx *x, const char *label, const char *path, unsigned flags,
    const char *hint)
{
	struct stat st;
	const char *why = NULL;
	if (*path == '\0')
		return opt_error(x, "%s: empty path", label), -1;
	if (stat(path, &st) != 0)
		why = strerror(errno);
	else if ((flags & OPT_DIR) && !S_ISDIR(st.st_mode))
		why = "not a directory";
	else if ((flags & OPT_FILE) && S_ISDIR(st.st_mode))
		why = "a directory, not a file";
	else if (access(path, S_ISDIR(st.st_mode) ? R_OK | X_OK : R_OK) != 0)
		why = "not readable";
	if (why == NULL)
		return 0;
	if (hint != NULL && strlen(hint) > 60)	/* a short help says what was expected */
		hint = NULL;
	return opt_error(x, "%s = '%s': %s%s%s%s", label, path, why, hint ? " (expected: " : "", hint ? hint : "",
	    hint ? ")" : ""), -1;
}

int opt_path_in(const struct opt_ctx *x, const char *label, const char *path, unsigned flags)
{
	return path_in(x, label, path, flags, NULL);
}

int opt_path_out(const struct opt_ctx *x, const char *label, const char *path)
{
	struct stat st;
	if (*path == '\0')
		return opt_error(x, "%s: empty path (give a directory)", label), -1;
	if (stat(path, &st) == 0) {
		if (!S_ISDIR(st.st_mode))
			return opt_error(x, "%s = '%s' exists and is not a directory", label, path), -1;
		if (access(path, W_OK | X_OK) != 0)
			return opt_error(x, "%s = '%s' is not writable: %s", label, path, strerror(errno)), -1;
		return 0;
	}
	if (errno != ENOENT)
		return opt_error(x, "%s = '%s': %s", label, path, strerror(errno)), -1;
	char *parent = xstrdup(path);
	size_t n = strlen(parent);
	while (n > 1 && parent[n - 1] == '/')
		parent[--n] = '\0';
	char *slash = strrchr(parent, '/');
	if (slash == NULL)
		strcpy(parent, ".");
	else
		slash[slash == parent] = '\0';	/* "/x" -> "/" */
	int rc = 0;
	if (stat(parent, &st) != 0 || !S_ISDIR(st.st_mode))
		rc = opt_error(x, "%s = '%s': its parent directory '%s' does not exist", label, path, parent);
	else if (access(parent, W_OK | X_OK) != 0)
		rc = opt_error(x, "%s = '%s': its parent directory '%s' is not writable: %s", label, path, parent,
		    strerror(errno));
	free(parent);
	return rc ? -1 : 0;
}

/* ---- values ------------------------------------------------------------- */

/* Index of S in "a|b|c", or -1. */
static int choice(const char *choices, const char *s)
{
	size_t n = strlen(s);
	int i = 0;
	for (const char *p = choices; ; i++) {
		const char *bar = strchr(p, '|');
		size_t k = bar ? (size_t)(bar - p) : strlen(p);
		if (k == n && strncmp(p, s, n) == 0)
			return i;
		if (bar == NULL)
			return -1;
		p = bar + 1;
	}
}

static int bad_choice(const struct opt_ctx *x, const char *label, const char *s, const char *choices)
{
	char list[256];
	size_t k = 0;
	for (const char *p = choices; *p && k + 3 < sizeof list; p++) {
		if (*p == '|') {
			list[k++] = ',';
			list[k++] = ' ';
		} else
			list[k++] = *p;
	}
	list[k] = '\0';
	return opt_error(x, "%s = '%s' is not one of %s", label, s, list), -1;
}

static int cmp_double(const void *a, const void *b)
{
	double p = *(const double *)a, q = *(const double *)b;
	return (p > q) - (p < q);
}

static int parse_list(const struct opt_ctx *x, const char *label, const struct opt *o, const char *v,
    struct opt_list *l)
{
	int max = o->max > 0 && o->max < OPT_LIST_MAX ? o->max : OPT_LIST_MAX;
	char *s = xstrdup(v), *p = s;
	int rc = -1;
	l->n = 0;
	for (;;) {
		char *comma = strchr(p, ',');
		if (comma != NULL)
			*comma = '\0';
		if (*p == '\0') {
			opt_error(x, "%s = '%s' has an empty element (a comma list: 30,45,60)", label, v);
			goto out;
		}
		if (l->n == max) {
			opt_error(x, "%s = '%s' has more than %d values", label, v, max);
			goto out;
		}
		double d;
		long w;
		if (o->flags & OPT_WHOLE) {
			if (opt_long(x, label, p, o->lo, o->hi, o->flags, o->unit, &w) != 0)
				goto out;
			d = (double)w;
		} else if (opt_double(x, label, p, o->lo, o->hi, o->flags, o->unit, &d) != 0)
			goto out;
		for (int i = 0; (o->flags & OPT_UNIQUE) && i < l->n; i++)
			if (l->v[i] == d) {
				opt_error(x, "%s: %s is listed twice", label, p);
				goto out;
			}
		l->v[l->n++] = d;
		if (comma == NULL)
			break;
		p = comma + 1;
	}
	if (o->flags & OPT_SORT)
		qsort(l->v, (size_t)l->n, sizeof l->v[0], cmp_double);
	rc = 0;
out:
	free(s);
	return rc;
}

/* Parse V for option O into its destination. */
static int apply(struct opt_ctx *x, const struct opt *o, const char *v)
{
	char label[80];
	snprintf(label, sizeof label, "--%s", o->name);
	double d;
	long l;
	int i;
	switch (o->type) {
	case OPT_FLAG:
		i = 1;
		break;
	case OPT_DOUBLE:
		if (opt_double(x, label, v, o->lo, o->hi, o->flags, o->unit, &d) != 0)
			return -1;
		if (o->dest)
			*(double *)o->dest = d;
		return 0;
	case OPT_LONG:
	case OPT_INT:
		if (opt_long(x, label, v, o->lo, o->hi, o->flags, o->unit, &l) != 0)
			return -1;
		if (o->dest && o->type == OPT_LONG)
			*(long *)o->dest = l;
		else if (o->dest)
			*(int *)o->dest = (int)l;
		return 0;
	case OPT_ENUM:
		if ((i = choice(o->choices, v)) < 0)
			return bad_choice(x, label, v, o->choices);
		break;
	case OPT_LIST:
		return parse_list(x, label, o, v, o->dest);
	case OPT_PATH_IN:
		if (path_in(x, label, v, o->flags, o->help) != 0)
			return -1;
		goto text;
	case OPT_PATH_OUT:
		if (opt_path_out(x, label, v) != 0)
			return -1;
		goto text;
	case OPT_STRING:
		if (*v == '\0')
			return opt_error(x, "%s: empty value", label), -1;
text:
		if (o->dest)
			*(const char **)o->dest = v;
		return 0;
	case OPT_CUSTOM:
		return o->fn(x, o, v);
	default:
		assert(!"option type not usable in struct opt");
		return -1;
	}
	if (o->dest)
		*(int *)o->dest = i;
	return 0;
}

/* ---- KEY=VALUE,... ------------------------------------------------------ */

static void key_names(const struct opt_key *keys, unsigned need, char *b, size_t n)
{
	size_t k = 0;
	b[0] = '\0';
	for (int i = 0; keys[i].name && k < n; i++)
		if (!need || (keys[i].flags & need))
			k += (size_t)snprintf(b + k, n - k, "%s%s", k ? ", " : "", keys[i].name);
}

static int key_value(const struct opt_ctx *x, const char *label, const struct opt_key *k, const char *v,
    void *base)
{
	char kl[128];
	snprintf(kl, sizeof kl, "%s: %s", label, k->name);
	char *dest = (char *)base + k->offset;
	long l;
	int i;
	switch (k->type) {
	case OPT_DOUBLE:
		return opt_double(x, kl, v, k->lo, k->hi, k->flags, k->unit, (double *)(void *)dest);
	case OPT_LONG:
		return opt_long(x, kl, v, k->lo, k->hi, k->flags, k->unit, (long *)(void *)dest);
	case OPT_INT:
		if (opt_long(x, kl, v, k->lo, k->hi, k->flags, k->unit, &l) != 0)
			return -1;
		*(int *)(void *)dest = (int)l;
		return 0;
	case OPT_ENUM:
		if ((i = choice(k->choices, v)) < 0)
			return bad_choice(x, kl, v, k->choices);
		*(int *)(void *)dest = i;
		return 0;
	case OPT_STRING:
		if (*v == '\0' || strlen(v) >= k->size)
			return opt_error(x, "%s = '%s' must have 1 to %zu characters", kl, v, k->size - 1), -1;
		memcpy(dest, v, strlen(v) + 1);
		return 0;
	case OPT_VEC3: {
		double *out = (double *)(void *)dest, w[3];
		char *s = xstrdup(v), *p = s;
		int rc = 0;
		for (int c = 0; c < 3 && rc == 0; c++) {
			char *colon = strchr(p, ':');
			if ((c < 2) != (colon != NULL))
				rc = opt_error(x, "%s = '%s' is not X:Y:Z", kl, v);
			else {
				if (colon)
					*colon = '\0';
				rc = opt_double(x, kl, p, k->lo, k->hi, k->flags, k->unit, &w[c]) != 0;
				p = colon ? colon + 1 : p;
			}
		}
		free(s);
		if (rc != 0)
			return -1;
		memcpy(out, w, sizeof w);
		return 0;
	}
	default:
		assert(!"key type not usable in struct opt_key");
		return -1;
	}
}

int opt_keys(const struct opt_ctx *x, const char *label, const char *spec, const struct opt_key *keys,
    void *base)
{
	int nk = 0, seen[KEYS_MAX] = { 0 }, rc = -1;
	char names[256];
	while (keys[nk].name)
		nk++;
	assert(nk <= KEYS_MAX);
	key_names(keys, 0, names, sizeof names);
	char *s = xstrdup(spec), *p = s;
	for (;;) {
		char *comma = strchr(p, ','), *eq;
		if (comma != NULL)
			*comma = '\0';
		if ((eq = strchr(p, '=')) == NULL) {
			opt_error(x, "%s: '%s' is not KEY=VALUE (keys %s)", label, p, names);
			goto out;
		}
		*eq = '\0';
		int i = 0;
		while (i < nk && strcmp(keys[i].name, p) != 0)
			i++;
		if (i == nk) {
			opt_error(x, "%s: unknown key '%s' (keys %s)", label, p, names);
			goto out;
		}
		if (seen[i]++) {
			opt_error(x, "%s: key %s is given twice", label, p);
			goto out;
		}
		if (key_value(x, label, &keys[i], eq + 1, base) != 0)
			goto out;
		if (comma == NULL)
			break;
		p = comma + 1;
	}
	for (int i = 0; i < nk; i++) {
		if (seen[i])
			continue;
		if (keys[i].flags & OPT_REQUIRED) {
			key_names(keys, OPT_REQUIRED, names, sizeof names);
			opt_error(x, "%s: '%s' lacks %s (required keys %s)", label, spec, keys[i].name, names);
			goto out;
		}
		if (keys[i].def && key_value(x, label, &keys[i], keys[i].def, base) != 0)
			goto out;
	}
	rc = 0;
out:
	free(s);
	return rc;
}

/* ---- the command line ----------------------------------------------------- */

static int find(const struct opt *opts, const char *name, size_t len)
{
	for (int i = 0; opts[i].name; i++)
		if (strlen(opts[i].name) == len && strncmp(opts[i].name, name, len) == 0)
			return i;
	return -1;
}

int opt_given(const struct opt_ctx *x, const char *name)
{
	int i = find(x->cmd->opts, name, strlen(name));
	assert(i >= 0);
	return x->count[i];
}

const char *opt_text(const struct opt_ctx *x, const char *name)
{
	int i = find(x->cmd->opts, name, strlen(name));
	assert(i >= 0);
	return x->text[i];
}

/* Is NAME (without --) in the "a|b" list? */
static int listed(const char *list, const char *name)
{
	return list != NULL && choice(list, name) >= 0;
}

/* Exclusions and required options.  0 or -1 after reporting. */
static int check_groups(struct opt_ctx *x, const struct opt *opts)
{
	for (int i = 0; opts[i].name; i++) {
		const struct opt *o = &opts[i];
		int other = 0;
		for (int j = 0; opts[j].name; j++)
			if (j != i && listed(o->excl, opts[j].name) && x->count[j]) {
				if (x->count[i])
					return opt_error(x, "--%s and --%s exclude each other", o->name, opts[j].name), -1;
				other = 1;
			}
		if ((o->flags & OPT_REQUIRED) && !x->count[i] && !other) {
			if (o->excl == NULL)
				return opt_error(x, "--%s is required (see skinbake %s --help)", o->name, x->cmd->name), -1;
			char alt[160];
			size_t k = 0;
			for (const char *p = o->excl; *p && k + 4 < sizeof alt; p++)
				k += (size_t)snprintf(alt + k, sizeof alt - k, "%s", *p == '|' ? ", --" : (char[2]){ *p, 0 });
			return opt_error(x, "give one of --%s, --%s (see skinbake %s --help)", o->name, alt, x->cmd->name), -1;
		}
	}
	return 0;
}

/* Split argv into occurrences (option index, value) and positionals; -1
 * after reporting, 1 for --help. */
static int scan(struct opt_ctx *x, const struct opt *opts, int argc, char **argv, int *occ, const char **val,
    int *n_occ)
{
	int only_args = 0;
	*n_occ = 0;
	for (int a = 1; a < argc; a++) {
		const char *s = argv[a];
		if (only_args || s[0] != '-' || s[1] == '\0') {
			if (x->n_args == x->cmd->max_args)
				return opt_error(x, "unexpected argument '%s' (see skinbake %s --help)", s, x->cmd->name), -1;
			x->args[x->n_args++] = s;
			continue;
		}
		if (strcmp(s, "--") == 0) {
			only_args = 1;
			continue;
		}
		if (strcmp(s, "--help") == 0 || strcmp(s, "-h") == 0)
			return 1;
		const char *eq = strchr(s, '=');
		size_t len = eq ? (size_t)(eq - s - 2) : strlen(s + 2);
		int i = s[1] == '-' ? find(opts, s + 2, len) : -1;
		if (i < 0)
			return opt_error(x, "unknown option '%.*s' (see skinbake %s --help)", (int)(eq ? eq - s : (long)strlen(s)),
			    s, x->cmd->name), -1;
		const char *v = NULL;
		if (opts[i].type == OPT_FLAG) {
			if (eq)
				return opt_error(x, "--%s takes no value", opts[i].name), -1;
		} else if (eq)
			v = eq + 1;
		else if (a + 1 < argc && !(argv[a + 1][0] == '-' && argv[a + 1][1] == '-' &&
		    (find(opts, argv[a + 1] + 2, strlen(argv[a + 1] + 2)) >= 0 || strcmp(argv[a + 1], "--help") == 0)))
			v = argv[++a];
		else
			return opt_error(x, "--%s needs a value (see skinbake %s --help)", opts[i].name, x->cmd->name), -1;
		occ[*n_occ] = i;
		val[(*n_occ)++] = v;
	}
	return 0;
}

int opt_parse(struct opt_ctx *x, const struct opt_cmd *c, int argc, char **argv)
{
	const struct opt *opts = c->opts;
	int n = 0;
	memset(x, 0, sizeof *x);
	x->cmd = c;
	x->exit = CLI_EXIT_USAGE;
	while (opts[n].name)
		n++;
	assert(n <= OPT_MAX && c->max_args <= OPT_MAX_ARGS);
	int *occ = xcalloc((size_t)argc + 1, sizeof *occ), n_occ, rc;
	const char **val = xcalloc((size_t)argc + 1, sizeof *val);
	if ((rc = scan(x, opts, argc, argv, occ, val, &n_occ)) != 0) {
		if (rc > 0) {
			opt_help(c, stdout);
			x->exit = CLI_EXIT_OK;
		}
		goto out;
	}
	rc = -1;
	for (int k = 0; k < n_occ; k++) {
		const struct opt *o = &opts[occ[k]];
		if (x->count[occ[k]] && !(o->flags & OPT_REPEAT)) {
			if (o->type == OPT_FLAG)
				opt_error(x, "--%s is given twice; give it once", o->name);
			else
				opt_error(x, "--%s is given twice ('%s' and '%s'); give it once", o->name, x->text[occ[k]], val[k]);
			goto out;
		}
		if (o->max > 0 && o->type != OPT_LIST && x->count[occ[k]] == o->max) {
			opt_error(x, "--%s is given more than %d times; at most %d are allowed", o->name, o->max, o->max);
			goto out;
		}
		x->count[occ[k]]++;
		x->text[occ[k]] = val[k];
	}
	if (check_groups(x, opts) != 0)
		goto out;
	for (int k = 0; k < n_occ; k++)
		if (apply(x, &opts[occ[k]], val[k] ? val[k] : "") != 0)
			goto out;
	for (int i = 0; i < n; i++)
		if (!x->count[i] && opts[i].def && apply(x, &opts[i], opts[i].def) != 0)
			goto out;
	if (x->n_args < c->min_args) {
		opt_error(x, "missing argument (usage: skinbake %s %s)", c->name, c->usage);
		goto out;
	}
	rc = 0;
out:
	free(occ);
	free(val);
	return rc == 0 ? 0 : -1;
}

/* ---- help ---------------------------------------------------------------- */

/* Print TEXT from column COL (the cursor is at column AT), wrapped at
 * HELP_WIDTH; continuation lines start at column COL. */
static void wrap(FILE *fp, const char *text, int at, int col)
{
	const char *p = text;
	if (at >= col) {
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
			fmt_range(r, sizeof r, k->lo, k->hi, k->flags, k->unit);
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

static void describe(FILE *fp, const struct opt *o)
{
	char head[64], t[1024] = "", r[96], req[160] = "", rep[48] = "", d[160];
	const char *meta = o->meta ? o->meta : o->type == OPT_ENUM ? o->choices
	    : o->type == OPT_FLAG ? NULL : o->type == OPT_PATH_IN || o->type == OPT_PATH_OUT ? "PATH" : "X";
	snprintf(head, sizeof head, "  --%s%s%s", o->name, meta ? " " : "", meta ? meta : "");
	cat(t, sizeof t, o->help);
	if (o->type == OPT_DOUBLE || o->type == OPT_LONG || o->type == OPT_INT || o->type == OPT_LIST) {
		fmt_range(r, sizeof r, o->lo, o->hi, o->flags, o->unit);
		cat(t, sizeof t, o->type == OPT_LIST ? ", comma-separated, each in " : " in ");
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
		cat(req, sizeof req, (o->flags & OPT_REQUIRED) ? "required: this or --" : "not with --");
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
	wrap(fp, t, at, HELP_COL);
	if (o->keys)
		describe_keys(fp, o->keys);
}

void opt_help(const struct opt_cmd *c, FILE *fp)
{
	fprintf(fp, "usage: skinbake %s %s\n", c->name, c->usage);
	if (c->about)
		fprintf(fp, "\n%s\n", c->about);
	fputc('\n', fp);
	for (int i = 0; c->opts[i].name; i++)
		describe(fp, &c->opts[i]);
	fprintf(fp, "%-*s this text\n", HELP_COL - 1, "  --help");
	if (c->notes)
		fprintf(fp, "\n%s\n", c->notes);
}

/* ---- actions ------------------------------------------------------------- */

int opt_dispatch(const char *cmd, const struct opt_sub *subs, int argc, char **argv)
{
	char names[128] = "";
	for (int i = 0; subs[i].name; i++)
		snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "", subs[i].name);
	if (argc < 2)
		return cli_usage_error(cmd, "missing action: %s (see skinbake %s --help)", names, cmd);
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
