/* The JSON module's policy for numbers JSON cannot hold (src/io/json.h):
 * non-finite values are written as null, null reads back as NaN marked
 * apart, and the NaN/Infinity tokens json-c's parser takes are refused. */
#include "config.h"

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "io/json.h"

static void nonfinite_written_as_null(void **state)
{
	(void)state;
	double v[4] = { 1.5, NAN, INFINITY, -INFINITY };
	struct json_object *o = json_object_new_object();
	json_put(o, "a", json_num_array(v, 4));
	json_put(o, "x", json_num(NAN));
	char *t = json_text(o, JSON_PLAIN);
	assert_string_equal(t, "{\"a\":[1.5,null,null,null],\"x\":null}");
	free(t);
	json_object_put(o);
}

static void null_reads_as_nan_apart(void **state)
{
	(void)state;
	struct json_object *o = json_parse("{\"x\":null,\"y\":2,\"s\":\"2\",\"n\":NaN,\"i\":-Infinity}");
	assert_non_null(o);
	double x = 0;
	assert_int_equal(json_get_num(o, "x", &x), 1);
	assert_true(isnan(x));
	assert_int_equal(json_get_num(o, "y", &x), 0);
	assert_true(x == 2);
	assert_int_equal(json_get_num(o, "s", &x), -1);
	assert_int_equal(json_get_num(o, "n", &x), -1);
	assert_int_equal(json_get_num(o, "i", &x), -1);
	assert_int_equal(json_get_num(o, "missing", &x), -1);
	json_object_put(o);
}

static void slashes_not_escaped(void **state)
{
	(void)state;
	struct json_object *o = json_object_new_string("a/b");
	char *t = json_text(o, JSON_PRETTY);
	assert_string_equal(t, "\"a/b\"");
	free(t);
	json_object_put(o);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(nonfinite_written_as_null),
		cmocka_unit_test(null_reads_as_nan_apart),
		cmocka_unit_test(slashes_not_escaped),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
