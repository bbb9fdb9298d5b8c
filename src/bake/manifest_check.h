/* manifest_check: a bake directory's manifest.json checked before any of it
 * is used (issue 23 item 4), so that a tampered or damaged bake is refused
 * with the file, the key, the value and what is allowed, instead of giving
 * wrong numbers: every number a number (not text), finite and in its
 * range; the axes ascending (theta_i, theta_o, delta_phi); the wavelengths
 * unique to the nanometre (they name the EXR channels); the sizes of the
 * rgb, specular and radial tables matching the axes; the EXR tables of the
 * size the manifest gives; and the checksum of each data file
 * (base/checksum.h).  bake_load calls it; manifest.c only parses. */
#ifndef SKINBAKE_MANIFEST_CHECK_H
#define SKINBAKE_MANIFEST_CHECK_H

/* 0 when DIR's manifest and tables may be read; -1 and *cause otherwise. */
int manifest_check_bake(const char *dir, char **cause);
/* Every value of the tables b holds finite (bake_load, after reading);
 * -1 and *cause naming the file and the first bad entry. */
struct bake;
int manifest_check_values(const struct bake *b, char **cause);
#endif
