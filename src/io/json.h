/* json: skinbake's one JSON module, on json-c.  Every JSON file or text the
 * program writes or reads goes through here, so that all of them follow one
 * policy for the numbers JSON cannot hold.
 *
 * Non-finite numbers: JSON (RFC 8259) has no NaN or infinity, and json-c
 * would print them as NaN/Infinity, which strict parsers refuse.  Writers
 * put every number through json_num(), which writes a non-finite value as
 * null.  Readers take numbers through json_to_num(): a finite number is
 * read, null is reported apart (1, and NaN) so that the reader accepts it
 * only for a member its schema says may be null, and anything else (a
 * string, or the NaN/Infinity tokens json-c's parser takes but JSON has
 * not) is refused.  Where infinity has a meaning of its own (a
 * semi-infinite layer's thickness) the writer says so with a string
 * ("inf"), never with null.  docs/json.md lists the members that may be
 * null.  */
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
/* V written with DIGITS significant digits ("%.*g"), or null when V is not
 * finite; and an array of N such numbers. */
struct json_object *json_num_g(double v, int digits);
struct json_object *json_num_g_array(const double *v, int n, int digits);
/* Add KEY = VAL to object O (VAL may be NULL: null). */
void json_put(struct json_object *o, const char *key, struct json_object *val);
/* O as text in LAYOUT, slashes not escaped; caller frees. */
char *json_text(struct json_object *o, enum json_layout layout);
/* Write O as text in LAYOUT to PATH, all or nothing (base/util.h outfile),
 * ended by a newline; -1 and *cause on failure. */
int json_save(const char *path, struct json_object *o, enum json_layout layout, char **cause);
/* The JSON file PATH parsed (json-c's parser), or NULL when it cannot be
 * read or is not JSON; the caller says which file it expected. */
struct json_object *json_load(const char *path);
/* TEXT parsed, or NULL. */
struct json_object *json_parse(const char *text);
/* V as a number: 0 and *out for a finite number, 1 and *out = NaN for null
 * (V NULL), -1 for anything else (not a number, or not finite). */
int json_to_num(struct json_object *v, double *out);
/* Member KEY of O through json_to_num; -1 also when it is missing. */
int json_get_num(struct json_object *o, const char *key, double *out);
#endif
