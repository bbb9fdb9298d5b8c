/* povfiles: the POV-Ray files the exporter writes, and only this module
 * writes them: BASE.inc (lights, lit-table pigments, finishes, bump maps,
 * stand-in textures; #declared, guarded, #version 3.7 inside), BASE.pov (the
 * scene), BASE.ini (size, antialiasing, output) and for per-light passes
 * BASE_combine.pov/.ini (POV-Ray's own sum of the .hdr passes). */
#ifndef SKINBAKE_POVFILES_H
#define SKINBAKE_POVFILES_H
#include "base/outdir.h"
#include <stddef.h>

#include "export/pov/littable.h"
#include "export/pov/povtypes.h"
#include "scene/scene.h"

void povfiles_report_free(struct pov_report *r);

/* Write BASE.inc (and with write_scene BASE.pov and BASE.ini; for passes
 * also BASE_combine.pov and BASE_combine.ini) into outdir.  Every file goes
 * through a temporary name and all are renamed into place only when all
 * were written.  -1 and *cause on failure. */
int povfiles_write(const struct scene *s, const struct pov_skin *skins, const struct pov_options *o,
    const char *outdir, struct pov_report *r, char **cause);

/* An export's directory, for base/outdir.h: manifest.json of format
 * "skinbake-pov" listing the files (written by povfiles_write_index). */
extern const struct outdir_kind povfiles_outdir_kind;
/* manifest.json in DIR listing every other entry of DIR (call it last). */
int povfiles_write_index(const char *dir, char **cause);

/* Copy a file, or write bytes to one (through a temporary name). */
int povfiles_copy(const char *src, const char *dst, char **cause);
int povfiles_write_bytes(const char *dst, const unsigned char *data, size_t size, char **cause);
#endif
