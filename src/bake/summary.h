/* summary: the few lines `skinbake bake` prints about a finished bake (the
 * printing itself stays with the command). */
#ifndef SKINBAKE_SUMMARY_H
#define SKINBAKE_SUMMARY_H
#include <stdio.h>
#include "bake/bake.h"

/* Write the summary of bake r of spec s (label: the preset; dir: where it
 * went) to fp. */
void bake_summary(FILE *fp, const struct bake_spec *s, const struct bake_result *r, const char *label, const char *dir);
/* The result's notes (fallbacks), each line as "skinbake bake: LINE". */
void bake_summary_notes(FILE *fp, const struct bake_result *r);
#endif
