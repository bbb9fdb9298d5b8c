/* opt_value: the rules for one value on the command line (opt.h):
 * decimal numbers in a range, input and output paths, and the range text
 * that messages and --help show. */
#include "config.h"
#include "cli/opt.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/outdir.h"
#include "base/util.h"

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
	if (v == 18446744073709551616.0) {
		snprintf(b, n, "2^64-1");
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
void opt_range_text(char *b, size_t n, double lo, double hi, unsigned flags, const char *unit)
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
	opt_range_text(r, sizeof r, lo, hi, flags, unit);
	*integer = 0;
	if ((flags & OPT_INF) && strcasecmp(s, "inf") == 0) {
		*out = INFINITY;
		return 0;
	}
	if (!decimal(s, integer)) {
		opt_error(x, "%s = '%s' is not a %s in %s", label, s, what, r);
		return -1;
	}
	errno = 0;
	double v = strtod(s, NULL);
	if (!isfinite(v) || !in_range(v, lo, hi, flags)) {
		opt_error(x, "%s = %s is out of range %s", label, s, r);
		return -1;
	}
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
	opt_range_text(r, sizeof r, lo, hi, flags, unit);
	if (v != floor(v)) {
		opt_error(x, "%s = %s is not a whole number in %s", label, s, r);
		return -1;
	}
	if (integer) {	/* exact beyond 2^53, e.g. seeds */
		errno = 0;
		long l = strtol(s, NULL, 10);
		if (errno == ERANGE) {
			opt_error(x, "%s = %s is out of range %s", label, s, r);
			return -1;
		}
		*out = l;
	} else {
		if (fabs(v) >= 9223372036854775808.0) {	/* 2^63: (long)v would be undefined */
			opt_error(x, "%s = %s is out of range %s", label, s, r);
			return -1;
		}
		*out = (long)v;
	}
	return 0;
}

int opt_u64(const struct opt_ctx *x, const char *label, const char *s, unsigned long long *out)
{
	double v;
	int integer;
	const double two64 = 18446744073709551616.0;
	if (number(x, label, s, 0, two64, 0, NULL, "whole decimal number", &v, &integer) != 0)
		return -1;
	if (v != floor(v) || (!integer && v >= two64)) {
		opt_error(x, "%s = %s is not a whole number in [0, 2^64-1]", label, s);
		return -1;
	}
	if (!integer) {
		*out = (unsigned long long)v;	/* exact: a double below 2^64 that is whole */
		return 0;
	}
	errno = 0;
	unsigned long long u = strtoull(s, NULL, 10);
	if (errno == ERANGE || strchr(s, '-') != NULL) {
		opt_error(x, "%s = %s is out of range [0, 2^64-1]", label, s);
		return -1;
	}
	*out = u;
	return 0;
}

/* ---- paths -------------------------------------------------------------- */

int opt_path_in_hint(const struct opt_ctx *x, const char *label, const char *path, unsigned flags,
    const char *hint)
{
	struct stat st;
	const char *why = NULL;
	if (*path == '\0') {
		opt_error(x, "%s: empty path", label);
		return -1;
	}
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
	return opt_path_in_hint(x, label, path, flags, NULL);
}

int opt_path_out(const struct opt_ctx *x, const char *label, const char *path)
{
	struct stat st;
	if (*path == '\0') {
		opt_error(x, "%s: empty path (give a directory)", label);
		return -1;
	}
	if (stat(path, &st) == 0) {
		if (!S_ISDIR(st.st_mode)) {
			opt_error(x, "%s = '%s' exists and is not a directory", label, path);
			return -1;
		}
		if (access(path, W_OK | X_OK) != 0) {
			opt_error(x, "%s = '%s' is not writable: %s", label, path, strerror(errno));
			return -1;
		}
		return 0;
	}
	if (errno != ENOENT) {
		opt_error(x, "%s = '%s': %s", label, path, strerror(errno));
		return -1;
	}
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

int opt_out_check(const struct opt_ctx *x, const char *path, const struct outdir_kind *kind, const char *const *inputs,
    int n)
{
	const char **in = xcalloc((size_t)n + 1, sizeof *in);
	int k = 0;
	for (int i = 0; i < n; i++)
		if (inputs[i] != NULL)
			in[k++] = inputs[i];
	char *cause = NULL;
	int rc = outdir_check(path, kind, in, &cause);
	free(in);
	if (rc != 0) {
		opt_error(x, "--out: %s", cause);
		free(cause);
	}
	return rc;
}
