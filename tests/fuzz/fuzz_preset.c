/* Fuzz target: the preset INI reader (src/skin/preset.c).  A preset that
 * loads must also survive its own round trip: preset_to_ini's text loads
 * back and prints the same. */
#include "config.h"
#include "fuzz.h"

#include <stdlib.h>
#include <string.h>

#include "skin/preset.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *text = fuzz_text(data, size), *cause = NULL;
	struct skin_params *p = preset_load_string(text, "fuzz.ini", &cause);
	free(text);
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
