/* Fuzz target: the PNG reader (src/io/pngio.c): pixels and tEXt values, as
 * the exporters read height and normal maps. */
#include "config.h"
#include "fuzz.h"

#include <stdlib.h>

#include "io/pngio.h"

static volatile unsigned sink;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *path = fuzz_file(data, size);
	char *cause = NULL;
	int w, h, ch, bits;
	uint16_t *px = pngio_read(path, &w, &h, &ch, &bits, &cause);
	if (px == NULL) {
		if (cause == NULL)
			fuzz_fail("pngio_read refused without a message");
		fuzz_refused(cause);
	} else {
		if (w < 1 || h < 1 || ch < 1 || ch > 4 || (bits != 8 && bits != 16))
			fuzz_fail("pngio_read returned %d x %d, %d channels, %d bits", w, h, ch, bits);
		/* Touch every sample: the buffer must hold w * h * ch of them. */
		unsigned sum = 0;
		for (size_t i = 0; i < (size_t)w * (size_t)h * (size_t)ch; i++)
			sum += px[i];
		sink = sum;
		free(px);
	}
	free(pngio_read_text(path, "skinbake:tile_mm"));
	return 0;
}
