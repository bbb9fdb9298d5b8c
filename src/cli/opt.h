/* opt: commands described by tables.  Each option is declared once, in an
 * array of struct opt: name, type, destination, default, unit, range and
 * help.  From that one table come the parsing, the --help text and every
 * message about a bad value.  The rules, the same for every command:
 *
 *   - numbers are decimal: [+-]digits[.digits][e[+-]digits]; hexadecimal,
 *     inf and nan (unless OPT_INF), blanks and trailing junk are refused,
 *     also inside compound values (opt_keys, opt_double, opt_long);
 *   - every range message names the option, the value and the range:
 *     "skinbake bake: --r-bins = 0 is out of range [1, 100000]";
 *   - an option given twice is an error unless declared OPT_REPEAT;
 *   - paths are checked while parsing, before any work: OPT_PATH_IN must
 *     exist and be readable; OPT_PATH_OUT (a directory to be created or
 *     replaced) must not be empty or an existing non-directory, and it or
 *     its parent must be a writable directory;
 *   - messages go to stderr as "skinbake CMD: ..."; --help (or -h) prints
 *     the generated help on stdout and ends with status 0; misuse ends
 *     with status 2 (CLI_EXIT_USAGE).
 *
 * Converting a command (cmd_eval.c is a short example):
 *
 *     double ti;
 *     const char *dir;
 *     int json;
 *     const struct opt opts[] = {
 *         { "bake", OPT_PATH_IN, &dir, "DIR", .flags = OPT_REQUIRED | OPT_DIR,
 *           .help = "a directory written by skinbake bake" },
 *         { "theta-in", OPT_DOUBLE, &ti, "DEG", .lo = 0, .hi = 90, .unit = "deg",
 *           .flags = OPT_REQUIRED, .help = "incidence angle" },
 *         { "json", OPT_FLAG, &json, .help = "one JSON object" },
 *         OPT_END
 *     };
 *     const struct opt_cmd cmd = { .name = "eval", .usage = "--bake DIR --theta-in DEG [--json]",
 *         .about = "Print the baked BRDF ...", .opts = opts };
 *     struct opt_ctx x;
 *     if (opt_parse(&x, &cmd, argc, argv) != 0)
 *         return x.exit;
 *
 * The table is a local array, so destinations may be locals or fields of a
 * library struct.  A default (.def) is text applied through the same parser
 * when the option is absent, so --help shows exactly what is used.  Checks
 * that tie options together beyond .excl (A needs B, a step that must
 * divide 90) follow opt_parse and report with opt_error().  Compound values
 * (--layer d=..,mua=.., --light type=..,position=X:Y:Z) are OPT_CUSTOM with a
 * callback (OPT_REPEAT if it may be given again, e.g. one --light each);
 * with a struct opt_key table, opt_keys() parses them by the same rules and
 * --help documents every key.  An OPT_ENUM key writes an int: give
 * opt_keys a staging struct when the field is of an enum type.
 *
 * Implemented in opt.c (the table and the command line), opt_value.c
 * (numbers, paths, range texts) and opt_help.c (--help, opt_dispatch). */
#ifndef SKINBAKE_OPT_H
#define SKINBAKE_OPT_H
#include <stddef.h>
#include <stdio.h>

enum opt_type {
	OPT_FLAG,	/* no value; dest int, set to 1 */
	OPT_DOUBLE,	/* decimal number in the range; dest double */
	OPT_LONG,	/* whole number (1e6 allowed) in the range; dest long */
	OPT_INT,	/* as OPT_LONG; dest int */
	/* whole number in [0, 2^64-1], exact (seeds); dest uint64_t; .lo, .hi unused */
	OPT_U64,
	OPT_STRING,	/* any non-empty text; dest const char * (points into argv) */
	OPT_ENUM,	/* one of .choices "a|b|c"; dest int, the index of the choice */
	OPT_LIST,	/* comma list of numbers, each in the range; dest struct opt_list */
	OPT_PATH_IN,	/* existing readable file or directory; dest const char * */
	OPT_PATH_OUT,	/* output directory, see above; dest const char * */
	OPT_CUSTOM,	/* .fn(x, o, value) parses; dest is the callback's */
	OPT_VEC3,	/* opt_key only: X:Y:Z, each in the range; dest double[3] */
};

/* Flags (.flags of struct opt and struct opt_key). */
#define OPT_REQUIRED 0x001u	/* must be given (with .excl: exactly one of the group) */
#define OPT_REPEAT 0x002u	/* may be given again (OPT_CUSTOM only); .max caps the count */
#define OPT_LO_OPEN 0x004u	/* range excludes .lo */
#define OPT_HI_OPEN 0x008u	/* range excludes .hi */
#define OPT_INF 0x010u	/* "inf" is a value (+infinity) beyond the range */
#define OPT_WHOLE 0x020u	/* OPT_LIST: whole numbers only */
#define OPT_UNIQUE 0x040u	/* OPT_LIST: no value twice */
#define OPT_SORT 0x080u	/* OPT_LIST: sorted ascending after parsing */
#define OPT_DIR 0x100u	/* OPT_PATH_IN: must be a directory */
#define OPT_FILE 0x200u	/* OPT_PATH_IN: must not be a directory */
#define OPT_STEPS 0x400u	/* OPT_LIST: an element may be START:STOP:STEP */

#define OPT_MAX 96	/* options per command */
#define OPT_MAX_ARGS 4	/* positional arguments per command */
#define OPT_LIST_MAX 256	/* values per OPT_LIST */

struct opt_list {
	int n;
	double v[OPT_LIST_MAX];
};

struct opt_ctx;
struct opt;

/* One key of a compound KEY=VALUE,... value (see opt_keys). */
struct opt_key {
	const char *name;
	/* OPT_DOUBLE, OPT_LONG, OPT_INT, OPT_ENUM, OPT_STRING or OPT_VEC3 */
	enum opt_type type;
	size_t offset;	/* of the destination in the struct given to opt_keys */
	const char *def;	/* applied when the key is absent; NULL: left as it was */
	const char *unit;
	double lo, hi;
	unsigned flags;	/* OPT_REQUIRED, OPT_LO_OPEN, OPT_HI_OPEN, OPT_INF */
	const char *choices;	/* OPT_ENUM: "a|b" */
	size_t size;	/* OPT_STRING: dest is char[size], the value shorter */
	const char *help;	/* one phrase */
};

struct opt {
	const char *name;	/* long name without "--" */
	enum opt_type type;
	void *dest;	/* where the value goes (by type, above) */
	const char *meta;	/* placeholder in --help ("DEG", "DIR"); NULL: from the type */
	/* default as typed by a user, parsed like a given value; NULL: none */
	const char *def;
	const char *def_note;	/* shown as "(default ...)" when .def is NULL ("the preset's") */
	const char *unit;	/* "deg", "cm", "1/cm", "nm"; NULL for pure numbers */
	double lo, hi;	/* range of numbers and list values, closed unless OPT_*_OPEN */
	unsigned flags;
	int max;	/* OPT_LIST: most values; OPT_REPEAT: most occurrences (0: no limit) */
	const char *choices;	/* OPT_ENUM: "exact|schlick" */
	/* options this one excludes, "a" or "a|b" (list it on both sides) */
	const char *excl;
	/* OPT_CUSTOM: documents KEY=VALUE keys, ends with { NULL } */
	const struct opt_key *keys;
	/* OPT_CUSTOM: parse VALUE into o->dest; on failure report with opt_error and return -1. */
	int (*fn)(struct opt_ctx *x, const struct opt *o, const char *value);
	const char *help;	/* one phrase; range, unit and default are appended */
};
#define OPT_END { .name = NULL }

struct opt_cmd {
	const char *name;	/* "bake", "export blender": message prefix and help */
	const char *usage;	/* synopsis after "usage: skinbake NAME " */
	const char *about;	/* paragraph(s) before the options, or NULL */
	const struct opt *opts;	/* ends with OPT_END */
	const char *notes;	/* paragraph(s) after the options, or NULL */
	int min_args, max_args;	/* positional arguments (default none) */
};

/* Filled by opt_parse; no allocation, nothing to free. */
struct opt_ctx {
	const struct opt_cmd *cmd;
	const char *text[OPT_MAX];	/* value given, the last one if repeated; NULL if absent */
	int count[OPT_MAX];	/* times given */
	const char *args[OPT_MAX_ARGS];	/* positional arguments in order */
	int n_args;
	int exit;	/* when opt_parse returns -1: 0 after --help, 2 after an error */
};

/* Parse argv[1..argc-1] (argv[0] is the command name).  0: go on; -1: stop
 * and return x->exit (help printed, or an error reported). */
int opt_parse(struct opt_ctx *x, const struct opt_cmd *c, int argc, char **argv);
/* The generated help text. */
void opt_help(const struct opt_cmd *c, FILE *fp);
/* Times option NAME was given (0: absent; the default applies). */
int opt_given(const struct opt_ctx *x, const char *name);
/* The text given for NAME (the last one if repeated), or NULL. */
const char *opt_text(const struct opt_ctx *x, const char *name);
/* Print "skinbake CMD: message" on stderr; returns CLI_EXIT_USAGE (2). */
int opt_error(const struct opt_ctx *x, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The rules above for parts of compound values; LABEL names the value in
 * messages ("--layer 2: d").  0, or -1 after reporting. */
int opt_double(const struct opt_ctx *x, const char *label, const char *s, double lo, double hi,
    unsigned flags, const char *unit, double *out);
int opt_long(const struct opt_ctx *x, const char *label, const char *s, double lo, double hi,
    unsigned flags, const char *unit, long *out);
/* A whole number in [0, 2^64-1] exactly (digits are read as an integer, not
 * through a double; 9.2e18 and 1e6 forms are taken when whole). */
int opt_u64(const struct opt_ctx *x, const char *label, const char *s, unsigned long long *out);
int opt_path_in(const struct opt_ctx *x, const char *label, const char *path, unsigned flags);
/* As opt_path_in; a short HINT (what was expected) ends the message. */
int opt_path_in_hint(const struct opt_ctx *x, const char *label, const char *path, unsigned flags,
    const char *hint);
int opt_path_out(const struct opt_ctx *x, const char *label, const char *path);
/* After opt_parse, before any work: may --out PATH be replaced by an output
 * of KIND (base/outdir.h outdir_check, with the command's INPUTS, a
 * NULL-terminated list whose NULL entries before the end are skipped:
 * pass optional inputs as they are, the list ends at index N)?  0, or -1
 * after reporting (exit 2). */
struct outdir_kind;
int opt_out_check(const struct opt_ctx *x, const char *path, const struct outdir_kind *kind,
    const char *const *inputs, int n);
/* The range as messages and --help show it, e.g. "[0, 90) deg", "(0, inf) cm". */
void opt_range_text(char *b, size_t n, double lo, double hi, unsigned flags, const char *unit);
/* Parse "KEY=VALUE,KEY=VALUE" into the struct at BASE by KEYS (ends with
 * { NULL }): unknown, repeated, missing required keys and bad values are
 * reported with LABEL; absent keys get their .def. */
int opt_keys(const struct opt_ctx *x, const char *label, const char *spec,
    const struct opt_key *keys, void *base);

/* Commands with actions (export pov|blender, preset show|cat|keys). */
struct opt_sub {
	const char *name;
	const char *summary;
	int (*exec)(int argc, char **argv);	/* argv[0] is the action's name */
};
/* Run the action named by argv[1] (table ends with { NULL }); --help lists them. */
int opt_dispatch(const char *cmd, const struct opt_sub *subs, int argc, char **argv);
#endif
