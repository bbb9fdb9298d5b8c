/* json: skinbake's one JSON module, on json-c.  Every JSON file or text the
 * program writes or reads goes through here, so that all of them follow one
 * policy for the numbers JSON cannot hold.
 *
 * Non-finite numbers: JSON (RFC 8259) has no NaN or infinity, and json-c
 * would print them as NaN/Infinity, which strict parsers refuse.  The writer
 * json_num() turns a non-finite value into null; a reader taking a number
 * (json_get_num) gives NaN for null.  A field that may be null says so in
 * the schema of its file (docs/json.md lists them).  Where infinity has a
 * meaning of its own (a semi-infinite layer) the writer says so with a
 * string ("inf"), never with null. */
#ifndef SKINBAKE_JSON_H
#define SKINBAKE_JSON_H
#include <json-c/json.h>

/* Output layouts: indented (files people read) or on one line. */
enum json_layout { JSON_PRETTY, JSON_PLAIN };

/* V as a JSON number, or null (NULL, which json-c stores as null) when V is
 * not finite. */
struct json_object *json_num(double v);
/* An array of the N numbers V (each through json_num). */
struct json_object *json_num_array(const double *v, int n);
/* Add KEY = VAL to object O (VAL may be NULL: null). */
void json_put(struct json_object *o, const char *key, struct json_object *val);
/* O as text in LAYOUT, slashes not escaped; caller frees. */
char *json_text(struct json_object *o, enum json_layout layout);
/* Write O as text in LAYOUT to PATH, all or nothing (base/util.h outfile),
 * ended by a newline; -1 and *cause on failure. */
int json_save(const char *path, struct json_object *o, enum json_layout layout, char **cause);
/* A number member KEY of O: its value, NaN for null; -1 and *cause naming
 * WHAT (the file) and KEY when it is missing or not a number. */
int json_get_num(struct json_object *o, const char *key, const char *what, double *out, char **cause);
#endif
