/* blender: the image set that exporters/blender/import_skin.py turns into
 * Blender materials.  Blender's shader nodes see the view direction but not
 * the light's, and its EXR reader takes only R,G,B[,A] channels (see
 * docs/blender.md and the measured notes behind it), so everything here is
 * plain RGB images plus manifest.json:
 *
 *   albedo.exr      RGB float, linear Rec.709: bihemispherical diffuse albedo
 *   brdf_lut.exr    RGB float atlas of pi * f_r (total BRDF) for the exact mode
 *   roughness.png   16-bit gray: Blender roughness = sqrt(GGX alpha)
 *   height.png      16-bit gray height (copied from `skinbake texture`, or flat)
 *   normal.png      16-bit RGB tangent-space normal, OpenGL +Y (or flat)
 *   manifest.json   format version, parameters, axes, units, light set-up
 *
 * brdf_lut.exr layout: n_phi tiles side by side, each n_cos x n_cos.  Tile k
 * holds delta_phi_k = k pi / (n_phi - 1) (0 = view back toward the light);
 * inside a tile column j is cos_view = j / (n_cos - 1) and file row r (row 0
 * at the top) is cos_light = 1 - r / (n_cos - 1), so Blender's v = 0 (the
 * bottom row) is cos_light = 0.  Texture coordinates of a node sit at texel
 * centres: u = (k n_cos + j + 0.5) / width, v = (i + 0.5) / n_cos with
 * cos_light = i / (n_cos - 1).
 *
 * The BRDF, albedo, specular parameters, subsurface radius and detail maps
 * come from a struct brdf_source (export/source.h): a bake or an analytic
 * test model; the height and normal maps are the source's detail maps, or
 * flat ones when it has none. */
#ifndef SKINBAKE_BLENDER_H
#define SKINBAKE_BLENDER_H

#include "base/outdir.h"
#include "export/blender/blender_options.h"
#include "export/source.h"


void blender_options_default(struct blender_options *o);

/* The pi * f_r atlas described above: three planes (R, G, B), each
 * n_cos rows by n_phi * n_cos columns, row 0 at the top.  Caller frees the
 * returned block (planes at offsets 0, w*h, 2*w*h). */
float *blender_lut(const struct brdf_source *m, int n_cos, int n_phi);
/* Bihemispherical (white-sky) albedo 2 * int a(mu) mu dmu per channel, with
 * a(theta) linear between the model's nodes and clamped beyond them. */
void blender_albedo_mean(const struct brdf_source *m, double rgb[3]);
/* Unit vector toward a direction at elevation/azimuth [rad] in a +Z-up world. */
void blender_direction(double elevation, double azimuth, double v[3]);

/* o and m within the ranges above; -1 and *cause (caller frees) otherwise. */
int blender_check(const struct brdf_source *m, const struct blender_options *o, char **cause);

/* An image set, for base/outdir.h: manifest.json of format
 * "skinbake-blender-image-set" and the images. */
extern const struct outdir_kind blender_outdir_kind;

/* The image set in memory.  blender_prepare validates o and m (blender_check)
 * and computes every file; NULL and *cause (caller frees) on bad
 * input.  blender_write writes it into DIR through base/outdir.h (all or
 * nothing, one swap): -1 and *cause when DIR is refused (not an image set,
 * or being written), -2 on an I/O failure.  blender_write_files writes the
 * files into the existing directory DIR (a staging directory), manifest.json
 * last; -1 on an I/O failure.  blender_set_free(NULL) is a no-op. */
struct blender_set;
struct blender_set *blender_prepare(const struct brdf_source *m, const struct blender_options *o, char **cause);
int blender_write(const struct blender_set *s, const char *dir, char **cause);
int blender_write_files(const struct blender_set *s, const char *dir, char **cause);
void blender_set_free(struct blender_set *s);
/* Add a section KEY (JSON object text) to the manifest s will write. */
void blender_set_add_section(struct blender_set *s, const char *key, const char *json);
/* prepare + write: nothing is written when an option or a texture is bad. */
int blender_export(const struct brdf_source *m, const struct blender_options *o, const char *dir,
    char **cause);
#endif
