/* Fuzz target: the OpenEXR reader (src/io/exrio.c): size, channels and
 * string attributes, as the bake and Blender readers call them. */
#include "config.h"
#include "fuzz.h"

#include <stdlib.h>

#include "io/exrio.h"

/* Channel names skinbake's files use (the dictionary has more). */
static const char *const channels[] = { "R", "G", "B", "A", "Y", "fr.550nm", "fr_err.550nm", "albedo.550nm" };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *path = fuzz_file(data, size);
	char *cause = NULL;
	int w, h;
	if (exrio_size(path, &w, &h, &cause) != 0) {
		fuzz_refused(cause);
		return 0;
	}
	if (w < 1 || h < 1)
		fuzz_fail("exrio_size accepted a %d x %d image", w, h);
	/* Callers check the size against their own before they allocate; the
	 * target stops at a size no skinbake file has. */
	if ((long)w * h > 1L << 22)
		return 0;
	float *px = malloc(sizeof(float) * (size_t)w * (size_t)h);
	for (size_t i = 0; i < sizeof channels / sizeof channels[0]; i++) {
		cause = NULL;
		if (exrio_read_channel(path, channels[i], w, h, px, &cause) != 0)
			fuzz_refused(cause);
	}
	free(px);
	cause = NULL;
	char *v = exrio_read_string_attr(path, "skinbake:format", &cause);
	free(v);
	free(cause);
	return 0;
}
