/* json: numbers with the non-finite policy of json.h, text and files. */
#include "config.h"

#include "io/json.h"

#include <math.h>
#include <stdio.h>
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

struct json_object *json_num_g(double v, int digits)
{
	if (!isfinite(v))
		return NULL;
	char buf[48];
	snprintf(buf, sizeof buf, "%.*g", digits, v);
	return json_object_new_double_s(v, buf);
}

struct json_object *json_num_g_array(const double *v, int n, int digits)
{
	struct json_object *a = json_object_new_array_ext(n);
	for (int i = 0; i < n; i++)
		json_object_array_add(a, json_num_g(v[i], digits));
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

struct json_object *json_load(const char *path)
{
	return json_object_from_file(path);
}

struct json_object *json_parse(const char *text)
{
	return json_tokener_parse(text);
}

int json_to_num(struct json_object *v, double *out)
{
	enum json_type t = json_object_get_type(v);
	if (t == json_type_null) {
		*out = NAN;
		return 1;
	}
	if (t != json_type_double && t != json_type_int)
		return -1;
	double x = json_object_get_double(v);
	if (!isfinite(x))
		return -1;
	*out = x;
	return 0;
}

int json_get_num(struct json_object *o, const char *key, double *out)
{
	struct json_object *v;
	if (!json_object_object_get_ex(o, key, &v))
		return -1;
	return json_to_num(v, out);
}
