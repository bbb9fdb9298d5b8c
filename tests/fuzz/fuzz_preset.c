/* Fuzz target: the preset INI reader (src/skin/preset.c).  A preset that
 * loads must also survive its own round trip: preset_to_ini's text loads
 * back and prints the same.  A first line "#origin:NAME" (a comment to the
 * reader) makes NAME the file name, from which a preset without name and
 * description takes both. */
#include "config.h"
#include "fuzz.h"

#include <stdlib.h>
#include <string.h>

#include "skin/preset.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *text = fuzz_text(data, size), *cause = NULL, *origin = NULL;
	if (strncmp(text, "#origin:", 8) == 0) {
		size_t n = strcspn(text + 8, "\n");
		origin = fuzz_text((const uint8_t *)text + 8, n);
	}
	struct skin_params *p = preset_load_string(text, origin ? origin : "fuzz.ini", &cause);
	free(text);
	free(origin);
	if (p == NULL) {
		if (cause == NULL || *cause == '\0')
			fuzz_fail("preset refused without a message");
		fuzz_refused(cause);
		return 0;
	}
	char *ini = preset_to_ini(p);
	struct skin_params *q = preset_load_string(ini, "round-trip.ini", &cause);
	if (q == NULL)
		fuzz_fail("preset_to_ini output does not load back: %s\n%s", cause, ini);
	char *ini2 = preset_to_ini(q);
	if (strcmp(ini, ini2) != 0)
		fuzz_fail("preset round trip changes the text:\n%s\n---\n%s", ini, ini2);
	free(ini);
	free(ini2);
	preset_free(p);
	preset_free(q);
	return 0;
}
