/* opt: parse a command line by the command's option table (opt.h); the
 * rules for single values are in opt_value.c, the help text in opt_help.c. */
#include "config.h"
#include "cli/opt.h"

#include <assert.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli/msg.h"
#include "base/util.h"

#define KEYS_MAX 32

int opt_error(const struct opt_ctx *x, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	cli_vusage_error(x->cmd->name, fmt, ap);
	va_end(ap);
	return CLI_EXIT_USAGE;
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

/* One number of list O (LABEL names it in messages). */
static int list_number(const struct opt_ctx *x, const char *label, const struct opt *o, const char *p, double *d)
{
	long w;
	if (!(o->flags & OPT_WHOLE))
		return opt_double(x, label, p, o->lo, o->hi, o->flags, o->unit, d);
	if (opt_long(x, label, p, o->lo, o->hi, o->flags, o->unit, &w) != 0)
		return -1;
	*d = (double)w;
	return 0;
}

/* Append D to L unless it breaks OPT_UNIQUE or the length. */
static int list_add(const struct opt_ctx *x, const char *label, const struct opt *o, const char *v, double d,
    struct opt_list *l)
{
	int max = o->max > 0 && o->max < OPT_LIST_MAX ? o->max : OPT_LIST_MAX;
	for (int i = 0; (o->flags & OPT_UNIQUE) && i < l->n; i++)
		if (l->v[i] == d)
			return opt_error(x, "%s: %.15g is listed twice", label, d), -1;
	if (l->n == max)
		return opt_error(x, "%s = '%s' has more than %d values", label, v, max), -1;
	l->v[l->n++] = d;
	return 0;
}

/* START:STOP:STEP of an OPT_STEPS list: START, START + STEP, ... <= STOP. */
static int list_steps(const struct opt_ctx *x, const char *label, const struct opt *o, const char *v, char *p,
    struct opt_list *l)
{
	char *c1 = strchr(p, ':'), *c2 = strchr(c1 + 1, ':'), sl[96];
	double a, b, st;
	long w;
	if (c2 == NULL || strchr(c2 + 1, ':') != NULL)
		return opt_error(x, "%s: '%s' is not START:STOP:STEP", label, p), -1;
	*c1 = *c2 = '\0';
	snprintf(sl, sizeof sl, "%s: STEP", label);
	if (list_number(x, label, o, p, &a) || list_number(x, label, o, c1 + 1, &b))
		return -1;
	if (o->flags & OPT_WHOLE) {
		if (opt_long(x, sl, c2 + 1, 1, 1e15, 0, o->unit, &w) != 0)
			return -1;
		st = (double)w;
	} else if (opt_double(x, sl, c2 + 1, 0, INFINITY, OPT_LO_OPEN | OPT_HI_OPEN, o->unit, &st) != 0)
		return -1;
	if (b < a)
		return opt_error(x, "%s: %s:%s:%s has STOP < START", label, p, c1 + 1, c2 + 1), -1;
	long cnt = (long)floor((b - a) / st + 1e-9) + 1;	/* as preset_parse_wavelengths */
	for (long i = 0; i < cnt; i++)
		if (list_add(x, label, o, v, a + st * (double)i, l) != 0)
			return -1;
	return 0;
}

static int parse_list(const struct opt_ctx *x, const char *label, const struct opt *o, const char *v,
    struct opt_list *l)
{
	char *s = xstrdup(v), *p = s;
	int rc = -1;
	l->n = 0;
	for (;;) {
		char *comma = strchr(p, ',');
		double d;
		if (comma != NULL)
			*comma = '\0';
		if (*p == '\0') {
			opt_error(x, "%s = '%s' has an empty element (a comma list: 30,45,60)", label, v);
			goto out;
		}
		if ((o->flags & OPT_STEPS) && strchr(p, ':') != NULL) {
			if (list_steps(x, label, o, v, p, l) != 0)
				goto out;
		} else if (list_number(x, label, o, p, &d) != 0 || list_add(x, label, o, v, d, l) != 0)
			goto out;
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
		if (opt_path_in_hint(x, label, v, o->flags, o->help) != 0)
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
