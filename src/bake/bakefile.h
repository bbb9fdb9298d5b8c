/* bakefile: read a bake directory written by `skinbake bake` and evaluate
 * the baked BRDF.  Exporters (POV-Ray, Blender) and `skinbake eval` use only
 * this interface.
 *
 * Directory layout (see README "Bake outputs"):
 *   manifest.json   everything below, plus preset, layers per wavelength, settings
 *   brdf.exr        float32, width n_phi, height n_ti * n_to, row = ti * n_to + to,
 *                   column = phi; channels "fr.<WL>nm" (diffuse BRDF [1/sr]) and
 *                   "fr_err.<WL>nm" (its standard error) per integer wavelength WL
 *   brdf_rgb.exr    same layout, channels R, G, B: linear sRGB (D65) diffuse BRDF
 *   albedo.exr      width n_ti, height 1: "albedo.<WL>nm" and R, G, B
 *   albedo.png      8-bit sRGB preview
 *
 * Angles: theta_i at nodes (the incidence angles simulated); theta_o and
 * delta_phi per wavelength either at bin centres (Monte Carlo: uniform bins
 * over [0, 90] and [0, 180] degrees, each value the bin mean) or, for
 * adding-doubling wavelengths of a bake with point values (manifest
 * table.values "points", since issue 26), the BRDF at the nodes
 * theta_o_nodes (Chebyshev-Lobatto in theta over [0, 90] deg) and
 * phi_nodes (uniform over [0, 180] deg, both ends).  delta_phi = 0 is back
 * toward the light, pi the mirror side.  All angles here are radians.
 *
 * The surface specular part (rough Fresnel reflection at the top surface) is
 * not in the tables: it is analytic, from `ior` and `roughness`.
 *
 * A bake with a mm-scale relief (manifest specular.macro_slope > 0, preset
 * key [surface] macro_slope) keeps the facets' own table and lobe in its
 * files; bake_eval_diffuse, bake_eval_specular and bake_eval_rgb return them
 * integrated over the tilted facets (engine/macro.h), so eval and the C
 * exporters' tables (POV-Ray, Blender's LUT: export/source.h reads through
 * these) see the relief.  The albedo curve, the analytic GGX parameters the
 * renderers' general modes use, and the Mitsuba table plugin (which reads
 * brdf.exr itself and says so on stderr) stay the facets' (the relief's
 * single-scattering loss, 0.5-7 % for m 0.1-0.4, is not in the albedo). */
#ifndef SKINBAKE_BAKEFILE_H
#define SKINBAKE_BAKEFILE_H
#include "bake/bakedir.h"
#include "base/outdir.h"

/* A bake directory, for base/outdir.h: manifest.json of format
 * "skinbake-bake" and the tables. */
extern const struct outdir_kind bake_outdir_kind;

/* Write the bake directory DIR (created if needed) through base/outdir.h:
 * the complete new set replaces the old one in one swap, or nothing
 * changes; -1 and *cause (also when DIR is not a bake directory, or is
 * being written by another process). */
int bake_write(const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m, char **cause);
/* The files of a bake, written straight into the existing directory DIR
 * (a staging directory: outdir_path, or a family member's in the family's
 * staging); -1 and *cause. */
int bake_write_files(const char *dir, const struct bake_spec *s, const struct bake_result *r,
    const struct bake_meta *m, char **cause);

struct skin_params;

/* The single bake of preset p (label names it in the manifest) into the
 * directory out: bake_run with its checkpoint beside out, then on rank 0
 * the directory (bakefile.h) and the checkpoint removed.  0; -1 and *cause
 * when the bake is refused (r zeroed); -2 and *cause when out cannot be
 * written (r holds the result).  Caller frees r with bake_result_free. */
int bake_preset_to_dir(struct bake_spec *s, const struct skin_params *p, const char *label, const char *out,
    const char *command, struct bake_result *r, char **cause);

/* Load DIR; NULL with *cause (caller frees) when a file is missing or corrupt. */
struct bake *bake_load(const char *dir, char **cause);

/* Ready b for evaluation (the series through its point values) after its
 * arrays were filled other than by bake_load (family_bake_at). */
void bake_prepare(struct bake *b);

/* Diffuse BRDF per wavelength [1/sr] and its error, interpolated at
 * theta_i, theta_o in [0, pi/2] and delta_phi in [0, pi] (values outside
 * are folded/clamped) as bakeinterp.h says: point values by series in every
 * angle with an error that includes the interpolation's; bin means linearly,
 * with their standard error.  f and err have n_wl entries; err may be NULL. */
void bake_eval_diffuse(const struct bake *b, double theta_i, double theta_o, double dphi, double *f, double *err);
/* Analytic surface specular BRDF per wavelength [1/sr]. */
void bake_eval_specular(const struct bake *b, double theta_i, double theta_o, double dphi, double *f);
/* Analytic surface specular BRDF in linear sRGB [1/sr] (the part of
 * bake_eval_rgb that is not the diffuse table). */
void bake_eval_specular_rgb(const struct bake *b, double theta_i, double theta_o, double dphi, double rgb[3]);
/* The diffuse table's part of bake_eval_rgb in linear sRGB [1/sr]. */
void bake_eval_diffuse_rgb(const struct bake *b, double theta_i, double theta_o, double dphi, double rgb[3]);
/* Total (diffuse + specular) BRDF in linear sRGB [1/sr]. */
void bake_eval_rgb(const struct bake *b, double theta_i, double theta_o, double dphi, double rgb[3]);
#endif
