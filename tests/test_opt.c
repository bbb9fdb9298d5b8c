/* The option tables (src/cli/opt.h): decimal numbers only, range messages
 * that name the field, the value and the range, repeated options refused
 * unless repeatable, KEY=VALUE specs, paths checked, and --help generated
 * with every option's default, unit and range. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/opt.h"

/* The messages opt.c would print, captured instead (cli.c is not linked). */
static char msg[1024];
static int n_msg;

int cli_vusage_error(const char *cmd, const char *fmt, va_list ap)
{
	int k = snprintf(msg, sizeof msg, "skinbake %s: ", cmd);
	vsnprintf(msg + k, sizeof msg - (size_t)k, fmt, ap);
	n_msg++;
	return CLI_EXIT_USAGE;
}

int cli_usage_error(const char *cmd, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	cli_vusage_error(cmd, fmt, ap);
	va_end(ap);
	return CLI_EXIT_USAGE;
}

static const struct opt_cmd test_cmd = { "test", "", NULL, NULL, NULL, 0, 0 };
static struct opt_ctx ctx = { .cmd = &test_cmd };

static void msg_has(const char *want)
{
	if (strstr(msg, want) == NULL)
		fail_msg("message '%s' lacks '%s'", msg, want);
}

static void test_decimal_accepted(void **state)
{
	(void)state;
	static const char *ok[] = { "0", "1", "-2.5", "+3", ".5", "5.", "1e6", "1E-3", "2.5e+2", "007", "-0" };
	for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
		double v = -99;
		n_msg = 0;
		assert_int_equal(opt_double(&ctx, "--x", ok[i], -1e9, 1e9, 0, NULL, &v), 0);
		assert_true(v == strtod(ok[i], NULL));
		assert_int_equal(n_msg, 0);
	}
}

static void test_decimal_refused(void **state)
{
	(void)state;
	static const char *bad[] = { "0x10", "0X1P3", "inf", "-inf", "nan", "NAN", "infinity", "", " 1", "1 ", "1e",
		"e5", "1.2.3", "--1", "1,5", "1e+", ".", "-", "+", "1x", "1_000", "1e5.0", "\t2", "0b101" };
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		double v = 42;
		n_msg = 0;
		assert_int_equal(opt_double(&ctx, "--x", bad[i], 0, 100, 0, "cm", &v), -1);
		assert_true(v == 42);
		assert_int_equal(n_msg, 1);
		msg_has("skinbake test: --x = '");
		msg_has("is not a decimal number in [0, 100] cm");
	}
}

static void test_range_messages(void **state)
{
	(void)state;
	double v;
	assert_int_equal(opt_double(&ctx, "--p", "0", 0, 1, OPT_LO_OPEN, NULL, &v), -1);
	msg_has("--p = 0 is out of range (0, 1]");
	assert_int_equal(opt_double(&ctx, "--p", "1", 0, 1, OPT_LO_OPEN, NULL, &v), 0);
	assert_int_equal(opt_double(&ctx, "--t", "90", 0, 90, OPT_HI_OPEN, "deg", &v), -1);
	msg_has("--t = 90 is out of range [0, 90) deg");
	assert_int_equal(opt_double(&ctx, "--t", "1e400", 0, 90, 0, NULL, &v), -1);
	msg_has("--t = 1e400 is out of range [0, 90]");
	assert_int_equal(opt_double(&ctx, "--t", "-1e-400", 0, 90, 0, NULL, &v), 0);	/* underflows to -0 */
	/* inf only where declared, and nan never. */
	assert_int_equal(opt_double(&ctx, "d", "inf", 0, INFINITY, OPT_LO_OPEN | OPT_HI_OPEN | OPT_INF, NULL, &v), 0);
	assert_true(isinf(v));
	assert_int_equal(opt_double(&ctx, "d", "nan", 0, INFINITY, OPT_LO_OPEN | OPT_HI_OPEN | OPT_INF, NULL, &v), -1);
	msg_has("d = 'nan' is not a decimal number in (0, inf)");
}

static void test_whole_numbers(void **state)
{
	(void)state;
	long l;
	assert_int_equal(opt_long(&ctx, "--n", "1e6", 1, 1e12, 0, NULL, &l), 0);
	assert_int_equal(l, 1000000);
	assert_int_equal(opt_long(&ctx, "--n", "1.5", 1, 1e12, 0, NULL, &l), -1);
	msg_has("--n = 1.5 is not a whole number in [1, 1e12]");
	assert_int_equal(opt_long(&ctx, "--n", "0x40", 16, 16384, 0, "px", &l), -1);
	msg_has("--n = '0x40' is not a whole decimal number in [16, 16384] px");
	/* Seeds beyond 2^53 are exact, up to 2^63-1. */
	assert_int_equal(opt_long(&ctx, "--seed", "9007199254740993", 0, (double)LONG_MAX, 0, NULL, &l), 0);
	assert_true(l == 9007199254740993L);
	assert_int_equal(opt_long(&ctx, "--seed", "9223372036854775807", 0, (double)LONG_MAX, 0, NULL, &l), 0);
	assert_true(l == LONG_MAX);
	assert_int_equal(opt_long(&ctx, "--seed", "9223372036854775808", 0, (double)LONG_MAX, 0, NULL, &l), -1);
	msg_has("out of range [0, 2^63-1]");
	assert_int_equal(opt_long(&ctx, "--seed", "1e19", 0, (double)LONG_MAX, 0, NULL, &l), -1);
	assert_int_equal(opt_long(&ctx, "--n", "inf", 0, INFINITY, OPT_INF, NULL, &l), -1);
}

static void test_range_text(void **state)
{
	(void)state;
	char b[96];
	opt_range_text(b, sizeof b, 1, 1e12, 0, NULL);
	assert_string_equal(b, "[1, 1e12]");
	opt_range_text(b, sizeof b, 1e-7, 0.005, OPT_LO_OPEN, "cm");
	assert_string_equal(b, "(1e-7, 0.005] cm");
	opt_range_text(b, sizeof b, 0, 9007199254740992.0, 0, NULL);
	assert_string_equal(b, "[0, 9007199254740992]");
	opt_range_text(b, sizeof b, -1, (double)LONG_MAX, OPT_LO_OPEN | OPT_HI_OPEN, NULL);
	assert_string_equal(b, "(-1, 2^63-1)");
	opt_range_text(b, sizeof b, 360, 16384, 0, "px");
	assert_string_equal(b, "[360, 16384] px");
	opt_range_text(b, sizeof b, 0.01, 2e8, 0, NULL);
	assert_string_equal(b, "[0.01, 2e8]");
}

/* A command with one option of each kind. */
static double d;
static long l;
static int i, flag, e, reps;
static const char *s, *out;
static struct opt_list lst;

static int add_rep(struct opt_ctx *x, const struct opt *o, const char *v)
{
	(void)x;
	(void)o;
	(void)v;
	reps++;
	return 0;
}

static const struct opt opts[] = {
	{ "d", OPT_DOUBLE, &d, "X", "2.5", .lo = 0, .hi = 10, .unit = "cm", .help = "a length" },
	{ "l", OPT_LONG, &l, "N", "1e6", .lo = 1, .hi = 1e12, .help = "a count" },
	{ "i", OPT_INT, &i, "N", "4", .lo = 1, .hi = 8, .excl = "l", .help = "a small count" },
	{ "flag", OPT_FLAG, &flag, .help = "a switch" },
	{ "e", OPT_ENUM, &e, .def = "two", .choices = "one|two|three", .help = "a choice" },
	{ "s", OPT_STRING, &s, "NAME", .flags = OPT_REQUIRED, .help = "a name" },
	{ "list", OPT_LIST, &lst, "LIST", .lo = 0, .hi = 90, .flags = OPT_HI_OPEN | OPT_UNIQUE | OPT_SORT, .max = 3,
	  .unit = "deg", .help = "angles" },
	{ "rep", OPT_CUSTOM, NULL, "SPEC", .fn = add_rep, .flags = OPT_REPEAT, .max = 2, .help = "repeatable" },
	{ "out", OPT_PATH_OUT, &out, "DIR", .help = "output directory" },
	OPT_END
};
static const struct opt_cmd cmd = { "t", "-s NAME [options]", "About.", opts, "Notes.", 0, 1 };

static int run(struct opt_ctx *x, ...)
{
	char *argv[32] = { (char *)"t" };
	int argc = 1;
	va_list ap;
	va_start(ap, x);
	for (char *a; (a = va_arg(ap, char *)) != NULL;)
		argv[argc++] = a;
	va_end(ap);
	d = -1, l = -1, i = -1, flag = 0, e = -1, reps = 0, s = NULL, out = NULL;
	n_msg = 0;
	msg[0] = '\0';
	return opt_parse(x, &cmd, argc, argv);
}

static void test_parse_defaults_and_values(void **state)
{
	(void)state;
	struct opt_ctx x;
	assert_int_equal(run(&x, "--s", "a", NULL), 0);
	assert_true(d == 2.5 && l == 1000000 && i == 4 && e == 1 && flag == 0);
	assert_string_equal(s, "a");
	assert_int_equal(opt_given(&x, "d"), 0);
	assert_int_equal(run(&x, "--s=b", "--d", "7", "--flag", "--e", "three", "--list", "60,0,30", "--rep", "x",
	    "--rep", "y", "arg", NULL), 0);
	assert_true(d == 7 && flag == 1 && e == 2 && reps == 2);
	assert_true(lst.n == 3 && lst.v[0] == 0 && lst.v[1] == 30 && lst.v[2] == 60);
	assert_string_equal(opt_text(&x, "d"), "7");
	assert_int_equal(opt_given(&x, "rep"), 2);
	assert_int_equal(x.n_args, 1);
	assert_string_equal(x.args[0], "arg");
	assert_int_equal(run(&x, "--s", "a", "--d", "-0.5e-1", NULL), -1);	/* a value may start with '-' */
	msg_has("--d = -0.5e-1 is out of range [0, 10] cm");
}

static void test_parse_errors(void **state)
{
	(void)state;
	struct opt_ctx x;
	static const struct {
		const char *a[6];
		const char *want;
	} cases[] = {
		{ { "--s", "a", "--d", "1", "--d", "2" }, "--d is given twice ('1' and '2'); give it once" },
		{ { "--s", "a", "--flag", "--flag" }, "--flag is given twice" },
		{ { "--s", "a", "--rep", "1", "--rep", "2" }, NULL },
		{ { "--s", "a", "--l", "5", "--i", "2" }, "--i and --l exclude each other" },
		{ { "--d", "1" }, "--s is required" },
		{ { "--s", "a", "--dd", "1" }, "unknown option '--dd'" },
		{ { "--s", "a", "-d", "1" }, "unknown option '-d'" },
		{ { "--s", "a", "--d" }, "--d needs a value" },
		{ { "--s", "--d", "1" }, "--s needs a value" },
		{ { "--s", "" }, "--s: empty value" },
		{ { "--s", "a", "--flag=1" }, "--flag takes no value" },
		{ { "--s", "a", "x", "y" }, "unexpected argument 'y'" },
		{ { "--s", "a", "--e", "four" }, "--e = 'four' is not one of one, two, three" },
		{ { "--s", "a", "--list", "1,,2" }, "empty element" },
		{ { "--s", "a", "--list", "1,2," }, "empty element" },
		{ { "--s", "a", "--list", "10,10.0" }, "--list: 10 is listed twice" },
		{ { "--s", "a", "--list", "1,2,3,4" }, "more than 3 values" },
		{ { "--s", "a", "--list", "0x1" }, "--list = '0x1' is not a decimal number in [0, 90) deg" },
		{ { "--s", "a", "--list", "90" }, "--list = 90 is out of range [0, 90) deg" },
		{ { "--s", "a", "--i", "9" }, "--i = 9 is out of range [1, 8]" },
		{ { "--s", "a", "--out", "" }, "--out: empty path" },
	};
	for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		const char *const *a = cases[k].a;
		int rc = run(&x, a[0], a[1], a[2], a[3], a[4], a[5], NULL);
		if (cases[k].want == NULL) {	/* --rep may be given twice (its .max) */
			assert_int_equal(rc, 0);
			continue;
		}
		assert_int_equal(rc, -1);
		assert_int_equal(x.exit, CLI_EXIT_USAGE);
		assert_int_equal(n_msg, 1);
		msg_has("skinbake t: ");
		msg_has(cases[k].want);
	}
	assert_int_equal(run(&x, "--s", "a", "--rep", "1", "--rep", "2", "--rep", "3", NULL), -1);
	msg_has("--rep is given more than 2 times");
}

/* --help anywhere wins, prints on stdout and ends with status 0. */
static void test_parse_help(void **state)
{
	(void)state;
	struct opt_ctx x;
	fflush(stdout);
	int saved = dup(1), null = open("/dev/null", O_WRONLY);
	dup2(null, 1);
	int rc1 = run(&x, "--d", "0x10", "--help", NULL), exit1 = x.exit;
	int rc2 = run(&x, "-h", NULL), exit2 = x.exit;
	fflush(stdout);
	dup2(saved, 1);
	close(null);
	close(saved);
	assert_int_equal(rc1, -1);
	assert_int_equal(exit1, CLI_EXIT_OK);
	assert_int_equal(rc2, -1);
	assert_int_equal(exit2, CLI_EXIT_OK);
	assert_int_equal(n_msg, 0);
}

static void test_help_text(void **state)
{
	(void)state;
	char buf[8192] = "";
	FILE *fp = fmemopen(buf, sizeof buf - 1, "w");
	opt_help(&cmd, fp);
	fclose(fp);
	/* Unfold the wrapped lines: one option per line. */
	char flat[8192];
	size_t k = 0;
	for (const char *p = buf; *p && k + 1 < sizeof flat; p++) {
		if (*p == '\n' && p[1] == ' ' && p[2] == ' ' && p[3] == ' ') {
			while (p[1] == ' ')
				p++;
			flat[k++] = ' ';
		} else
			flat[k++] = *p;
	}
	flat[k] = '\0';
	static const char *want[] = {
		"usage: skinbake t -s NAME [options]\n\nAbout.\n",
		"  --d X                  a length in [0, 10] cm (default 2.5)\n",
		"  --l N                  a count in [1, 1e12] (default 1e6)\n",
		"  --i N                  a small count in [1, 8] (not with --l; default 4)\n",
		"  --flag                 a switch\n",
		"  --e one|two|three      a choice (default two)\n",
		"  --s NAME               a name (required)\n",
		"  --list LIST            angles, comma-separated, each in [0, 90) deg, at most 3\n",
		"  --rep SPEC             repeatable (repeat, at most 2 times)\n",
		"  --out DIR              output directory\n",
		"  --help                 this text\n\nNotes.\n",
	};
	for (size_t j = 0; j < sizeof want / sizeof want[0]; j++)
		if (strstr(flat, want[j]) == NULL)
			fail_msg("help lacks '%s':\n%s", want[j], buf);
	for (const char *p = buf; *p; p += strcspn(p, "\n") + (p[strcspn(p, "\n")] != '\0'))
		assert_true(strcspn(p, "\n") <= 79);
}

struct thing {
	double len;
	int kind;
	long count;
	double pos[3];
	char name[8];
};

static const struct opt_key thing_keys[] = {
	{ "len", OPT_DOUBLE, offsetof(struct thing, len), .lo = 0, .hi = INFINITY, .unit = "cm",
	  .flags = OPT_REQUIRED | OPT_LO_OPEN | OPT_HI_OPEN | OPT_INF, .help = "length" },
	{ "kind", OPT_ENUM, offsetof(struct thing, kind), "b", .choices = "a|b", .help = "kind" },
	{ "count", OPT_LONG, offsetof(struct thing, count), "3", .lo = 1, .hi = 9, .help = "count" },
	{ "pos", OPT_VEC3, offsetof(struct thing, pos), "0:0:0", .lo = -10, .hi = 10, .help = "position" },
	{ "name", OPT_STRING, offsetof(struct thing, name), .size = 8, .help = "name" },
	{ NULL },
};

static void test_keys(void **state)
{
	(void)state;
	struct thing t = { 0 };
	assert_int_equal(opt_keys(&ctx, "--thing 1", "len=2", thing_keys, &t), 0);
	assert_true(t.len == 2 && t.kind == 1 && t.count == 3 && t.pos[0] == 0 && t.name[0] == '\0');
	assert_int_equal(opt_keys(&ctx, "--thing 1", "pos=1:-2:3.5,len=inf,kind=a,name=abc,count=9", thing_keys, &t), 0);
	assert_true(isinf(t.len) && t.kind == 0 && t.count == 9 && t.pos[1] == -2 && t.pos[2] == 3.5);
	assert_string_equal(t.name, "abc");
	static const struct {
		const char *spec, *want;
	} bad[] = {
		{ "len=1,len=2", "--thing 1: key len is given twice" },
		{ "len=1,x=2", "--thing 1: unknown key 'x' (keys len, kind, count, pos, name)" },
		{ "len", "--thing 1: 'len' is not KEY=VALUE" },
		{ "len=1,", "--thing 1: '' is not KEY=VALUE" },
		{ "", "--thing 1: '' is not KEY=VALUE" },
		{ "kind=a", "--thing 1: 'kind=a' lacks len (required keys len)" },
		{ "len=0x10", "--thing 1: len = '0x10' is not a decimal number in (0, inf) cm" },
		{ "len=0", "--thing 1: len = 0 is out of range (0, inf) cm" },
		{ "len=nan", "--thing 1: len = 'nan' is not a decimal number" },
		{ "len=1,count=2.5", "--thing 1: count = 2.5 is not a whole number in [1, 9]" },
		{ "len=1,kind=c", "--thing 1: kind = 'c' is not one of a, b" },
		{ "len=1,pos=1:2", "--thing 1: pos = '1:2' is not X:Y:Z" },
		{ "len=1,pos=1:2:3:4", "--thing 1: pos = '1:2:3:4' is not X:Y:Z" },
		{ "len=1,pos=1:2:11", "--thing 1: pos = 11 is out of range [-10, 10]" },
		{ "len=1,pos=1:0x2:1", "--thing 1: pos = '0x2' is not a decimal number" },
		{ "len=1,name=abcdefgh", "--thing 1: name = 'abcdefgh' must have 1 to 7 characters" },
	};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		struct thing u = { .len = 5 };
		n_msg = 0;
		assert_int_equal(opt_keys(&ctx, "--thing 1", bad[k].spec, thing_keys, &u), -1);
		assert_int_equal(n_msg, 1);
		msg_has(bad[k].want);
	}
}

static void test_list_steps(void **state)
{
	(void)state;
	static struct opt_list w;
	const struct opt o[] = {
		{ "wl", OPT_LIST, &w, "LIST", .lo = 380, .hi = 780, .unit = "nm", .max = 8,
		  .flags = OPT_WHOLE | OPT_UNIQUE | OPT_STEPS, .help = "wavelengths" },
		OPT_END
	};
	const struct opt_cmd c = { "w", "", NULL, o, NULL, 0, 0 };
	struct opt_ctx x;
	char *ok[] = { (char *)"w", (char *)"--wl", (char *)"400:430:10,500,600:600:5" };
	assert_int_equal(opt_parse(&x, &c, 3, ok), 0);
	assert_int_equal(w.n, 6);
	assert_true(w.v[0] == 400 && w.v[3] == 430 && w.v[4] == 500 && w.v[5] == 600);
	static const struct {
		const char *v, *want;
	} bad[] = {
		{ "500:400:10", "--wl: 500:400:10 has STOP < START" },
		{ "400:500", "--wl: '400:500' is not START:STOP:STEP" },
		{ "400:500:10:1", "is not START:STOP:STEP" },
		{ "400:500:0", "--wl: STEP = 0 is out of range [1, 1e15] nm" },
		{ "400:0x1f4:10", "--wl = '0x1f4' is not a whole decimal number in [380, 780] nm" },
		{ "400:800:10", "--wl = 800 is out of range [380, 780] nm" },
		{ "400:420:10,410", "--wl: 410 is listed twice" },
		{ "400:500:10", "--wl = '400:500:10' has more than 8 values" },
	};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		char *argv[] = { (char *)"w", (char *)"--wl", (char *)bad[k].v };
		n_msg = 0;
		assert_int_equal(opt_parse(&x, &c, 3, argv), -1);
		assert_int_equal(n_msg, 1);
		msg_has(bad[k].want);
	}
}

static void test_paths(void **state)
{
	(void)state;
	char dir[] = "/tmp/test_opt.XXXXXX", file[64], sub[64], deep[80], fileout[80];
	assert_non_null(mkdtemp(dir));
	snprintf(file, sizeof file, "%s/f", dir);
	snprintf(sub, sizeof sub, "%s/new", dir);
	snprintf(deep, sizeof deep, "%s/no/new", dir);
	snprintf(fileout, sizeof fileout, "%s/f/new", dir);
	FILE *fp = fopen(file, "w");
	fclose(fp);
	assert_int_equal(opt_path_in(&ctx, "--in", file, OPT_FILE), 0);
	assert_int_equal(opt_path_in(&ctx, "--in", dir, OPT_DIR), 0);
	assert_int_equal(opt_path_in(&ctx, "--in", file, OPT_DIR), -1);
	msg_has("--in = '");
	msg_has("': not a directory");
	assert_int_equal(opt_path_in(&ctx, "--in", dir, OPT_FILE), -1);
	msg_has("a directory, not a file");
	assert_int_equal(opt_path_in(&ctx, "--in", sub, 0), -1);
	msg_has("No such file or directory");
	assert_int_equal(opt_path_in(&ctx, "--in", "", 0), -1);
	msg_has("--in: empty path");
	assert_int_equal(opt_path_out(&ctx, "--out", dir), 0);
	assert_int_equal(opt_path_out(&ctx, "--out", sub), 0);
	assert_int_equal(opt_path_out(&ctx, "--out", "x-relative-new"), 0);
	assert_int_equal(opt_path_out(&ctx, "--out", file), -1);
	msg_has("exists and is not a directory");
	assert_int_equal(opt_path_out(&ctx, "--out", deep), -1);
	msg_has("its parent directory '");
	msg_has("/no' does not exist");
	assert_int_equal(opt_path_out(&ctx, "--out", fileout), -1);
	assert_int_equal(opt_path_out(&ctx, "--out", ""), -1);
	msg_has("--out: empty path");
	unlink(file);
	rmdir(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_decimal_accepted),
		cmocka_unit_test(test_decimal_refused),
		cmocka_unit_test(test_range_messages),
		cmocka_unit_test(test_whole_numbers),
		cmocka_unit_test(test_range_text),
		cmocka_unit_test(test_parse_defaults_and_values),
		cmocka_unit_test(test_parse_errors),
		cmocka_unit_test(test_parse_help),
		cmocka_unit_test(test_help_text),
		cmocka_unit_test(test_keys),
		cmocka_unit_test(test_list_steps),
		cmocka_unit_test(test_paths),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
