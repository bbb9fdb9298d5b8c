/* json: numbers with the non-finite policy of json.h, text and files. */
#include "config.h"

#include "io/json.h"

#include <math.h>
#include <stdlib.h>

#include "base/util.h"

struct json_object *json_num(double v)
{
	if (!isfinite(v))
		return NULL;
	return json_object_new_double(v);
}

struct json_object *json_num_array(const double *v, int n)
{
	struct json_object *a = json_object_new_array();
	for (int i = 0; i < n; i++)
		json_object_array_add(a, json_num(v[i]));
	return a;
}

void json_put(struct json_object *o, const char *key, struct json_object *val)
{
	json_object_object_add(o, key, val);
}

char *json_text(struct json_object *o, enum json_layout layout)
{
	int flags = JSON_C_TO_STRING_NOSLASHESCAPE;
	if (layout == JSON_PRETTY)
		flags |= JSON_C_TO_STRING_PRETTY;
	else
		flags |= JSON_C_TO_STRING_PLAIN;
	return xstrdup(json_object_to_json_string_ext(o, flags));
}

int json_save(const char *path, struct json_object *o, enum json_layout layout, char **cause)
{
	char *text = json_text(o, layout);
	int rc = outfile_write_text(path, text, cause);
	free(text);
	return rc;
}

int json_get_num(struct json_object *o, const char *key, const char *what, double *out, char **cause)
{
	struct json_object *v;
	if (!json_object_object_get_ex(o, key, &v)) {
		*cause = xasprintf("%s: no \"%s\"", what, key);
		return -1;
	}
	if (v == NULL) {
		*out = NAN;
		return 0;
	}
	enum json_type t = json_object_get_type(v);
	if (t != json_type_double && t != json_type_int) {
		*cause = xasprintf("%s: \"%s\" is not a number", what, key);
		return -1;
	}
	*out = json_object_get_double(v);
	return 0;
}
