/* blender_detail: what a tangent-space detail normal map (16-bit RGB,
 * value = (n + 1) / 2 * 65535, OpenGL +Y) does to the mean brightness of a
 * plane, for the image set's manifest.  A normal map alone shades each
 * facet by n . L but keeps the plane's area, so it loses the light that
 * falls on the extra area of tilted facets: 1 / n_z per unit of plane.  The
 * importer's exact material multiplies by that area, and these functions
 * give the values its checks compare with. */
#ifndef SKINBAKE_BLENDER_DETAIL_H
#define SKINBAKE_BLENDER_DETAIL_H
#include <stddef.h>
#include <stdint.h>

/* What the importer's node tree reads from the exact-mode atlas
 * (blender_lut, blender.h) at cos_light, cos_view in [0, 1] and dphi in
 * [0, pi]: bilinear inside the two neighbouring delta_phi tiles, then
 * linear between them. */
void blender_lut_sample(const float *lut, int n_cos, int n_phi, double cos_l, double cos_v, double dphi,
    double rgb[3]);
/* Mean z of the unit normals of N texels (interleaved RGB) [-]. */
double blender_detail_mean_nz(const uint16_t *normal, size_t n);
/* Mean over the W x H tiling map of E cos_l pi f_r / pi / max(n_z, 0.2),
 * with the normal interpolated bilinearly between texels (four samples per
 * texel) and pi f_r read from the exact-mode atlas (blender_lut_sample), for
 * unit vectors sun and view and sun irradiance E [W/m^2]. */
void blender_detail_radiance(const uint16_t *normal, int w, int h, const double sun[3], const double view[3],
    double irradiance, const float *lut, int n_cos, int n_phi, double rgb[3]);
#endif
