/* blender_options: what an image set is made with (blender.h writes it,
 * blender_manifest.h records it), and the manifest's format version. */
#ifndef SKINBAKE_BLENDER_OPTIONS_H
#define SKINBAKE_BLENDER_OPTIONS_H

#define BLENDER_FORMAT_VERSION 1	/* manifest "format_version"; the importer checks it */

struct blender_options {
	int lut_cos;		/* cosine nodes per LUT axis [BLENDER_LUT_COS_MIN, MAX] */
	int lut_phi;		/* delta_phi nodes over [0, pi] [BLENDER_LUT_PHI_MIN, MAX] */
	double sun_elevation;	/* sun above the horizon of a +Z-up world [rad], (0, pi/2] */
	double sun_azimuth;	/* sun azimuth from +X toward +Y [rad] */
	double sun_strength;	/* irradiance normal to the sun [W/m^2], > 0 */
	double view_elevation;	/* reference camera above the horizon [rad], (0, pi/2] */
	double view_azimuth;	/* reference camera azimuth from +X toward +Y [rad] */
	int map_size;		/* side of the albedo, roughness and flat detail maps [px] */
	const char *generator;	/* program name and version for the manifest */
};

#define BLENDER_LUT_COS_MIN 8
#define BLENDER_LUT_COS_MAX 1024
#define BLENDER_LUT_PHI_MIN 2
#define BLENDER_LUT_PHI_MAX 361
#define BLENDER_MAP_MIN 1
#define BLENDER_MAP_MAX 4096
#endif
