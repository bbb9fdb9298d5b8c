/* scene_keys_table: print the scene reader's key table (scene/scene_keytab.h)
 * as tab-separated rows: section, key, type, unit, range, default, meaning;
 * scripts/doc_keys.py makes scenes/README.md's key tables from it. */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "scene/scene_keytab.h"

int main(void)
{
	for (const struct scene_key *k = scene_key_table; k->section != NULL; k++) {
		char range[128] = "";
		if (k->type == SCENE_KEY_NUMBER || k->type == SCENE_KEY_INTEGER)
			snprintf(range, sizeof range, "%g to %g", k->lo, k->hi);
		else if (k->type == SCENE_KEY_COLOUR)
			snprintf(range, sizeof range, "%g to %g each", k->lo, k->hi);
		else if (k->type == SCENE_KEY_CHOICE)
			snprintf(range, sizeof range, "%s", k->choices);
		printf("%s\t%s\t%s\t%s\t%s\t%s\t%s\n", k->section, k->name, scene_key_type_name(k->type), k->unit,
		    range, k->def, k->doc);
	}
	return 0;
}
