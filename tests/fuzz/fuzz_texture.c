/* Fuzz target: the [texture] section of texture preset files
 * (src/geom/sites.c, `skinbake texture --preset-file`). */
#include "config.h"
#include "fuzz.h"

#include <stdlib.h>

#include "geom/sites.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct texture_config cfg;
	char *cause = NULL;
	if (sites_load("face", &cfg, &cause) != 0)
		fuzz_fail("built-in site 'face' does not load: %s", cause);
	if (sites_read_ini(fuzz_file(data, size), &cfg, &cause) != 0) {
		if (cause == NULL || *cause == '\0')
			fuzz_fail("texture file refused without a message");
		fuzz_refused(cause);
		return 0;
	}
	/* Every parameter must be within its published range after a good file. */
	int n;
	const struct texture_param *p = sites_params(&n);
	for (int i = 0; i < n; i++) {
		double v = sites_get(&cfg, &p[i]);
		if (!(v >= p[i].lo && v <= p[i].hi))
			fuzz_fail("%s = %g after a good file, outside [%g, %g]", p[i].key, v, p[i].lo, p[i].hi);
	}
	return 0;
}
