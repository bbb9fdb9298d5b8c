/* blender_manifest: manifest.json of an image set (blender_manifest.h). */
#include "config.h"

#include "export/blender/blender_manifest.h"

#include <json-c/json.h>
#include <math.h>
#include <stddef.h>

#include "base/util.h"
#include "io/json.h"

/* Nine significant digits: plenty for the data, readable in the manifest. */
static json_object *jd(double v)
{
	return json_num_g(v, 9);
}

static json_object *jvec(const double *v, int n)
{
	return json_num_g_array(v, n, 9);
}

static json_object *jfile(const char *path, int w, int h, const char *channels,
    const char *encoding,
    const char *colorspace, const char *role)
{
	json_object *f = json_object_new_object();
	json_object_object_add(f, "path", json_object_new_string(path));
	json_object_object_add(f, "width", json_object_new_int(w));
	json_object_object_add(f, "height", json_object_new_int(h));
	json_object_object_add(f, "channels", json_object_new_string(channels));
	json_object_object_add(f, "encoding", json_object_new_string(encoding));
	json_object_object_add(f, "blender_colorspace", json_object_new_string(colorspace));
	json_object_object_add(f, "role", json_object_new_string(role));
	return f;
}

static json_object *jnum_or_null(const char *s)
{
	double v;
	if (s == NULL || util_parse_double(s, &v) != 0)
		return NULL;
	return jd(v);
}

/* The files of the set: path, size, channels, encoding, colour space, role. */
static json_object *files_info(const struct blender_options *o, const struct blender_maps *d)
{
	int lw = o->lut_cos * o->lut_phi, lh = o->lut_cos;
	json_object *x = json_object_new_object();
	json_object_object_add(x, "albedo", jfile("albedo.exr", o->map_size, o->map_size, "R,G,B",
	    "float32",
	    "default (scene linear)",
	    "Principled Base Color (and Subsurface Color in Blender 3.x)"));
	json_object_object_add(x, "brdf_lut", jfile("brdf_lut.exr", lw, lh, "R,G,B", "float32",
	    "Non-Color",
	    "exact mode: Diffuse BSDF colour = pi * f_r, layout in brdf_lut"));
	json_object_object_add(x, "roughness", jfile("roughness.png", o->map_size, o->map_size,
	    "gray",
	    "16-bit PNG", "Non-Color", "Principled Roughness = sqrt(GGX alpha)"));
	json_object_object_add(x, "height", jfile("height.png", d->w, d->h, "gray", "16-bit PNG",
	    "Non-Color",
	    "height, 0 lowest .. 65535 highest (for a Bump node or displacement)"));
	json_object_object_add(x, "normal", jfile("normal.png", d->w, d->h, "RGB", "16-bit PNG",
	    "Non-Color",
	    "tangent-space normal, OpenGL (+Y) convention, for a Normal Map node"));
	if (d->far != NULL)
		json_object_object_add(x, "roughness_far", jfile("roughness_far.png", d->far_n,
		    d->far_n, "gray",
		    "16-bit PNG", "Non-Color",
		    "alpha_relief = value / 65535 per block of the tile (docs/relief.md): "
		    "GGX alpha^2 = alpha_skin^2 + alpha_relief^2 where the relief is below a "
		    "pixel"));
	if (d->cavity != NULL) {
		json_object *c = jfile("cavity.png", d->cavity_n, d->cavity_n, "gray", "16-bit PNG",
		    "Non-Color",
		    "cavity = value / 65535, the relief's ambient occlusion tiled "
		    "like normal.png (docs/relief.md): multiplies the skin's shading");
		double sum = 0;
		size_t np = (size_t)d->cavity_n * (size_t)d->cavity_n;
		for (size_t i = 0; i < np; i++)
			sum += d->cavity[i] / 65535.0;
		json_object_object_add(c, "mean", jd(sum / (double)np));
		json_object_object_add(x, "cavity", c);
	}
	return x;
}

/* Exact mode: the sun of the demo scene and the reference plane's values. */
static json_object *exact_info(const struct blender_options *o, const struct blender_reference *r)
{
	json_object *x = json_object_new_object();
	json_object_object_add(x, "sun_direction", jvec(r->sun, 3));
	json_object_object_add(x, "sun_elevation_deg", jd(o->sun_elevation * 180 / M_PI));
	json_object_object_add(x, "sun_azimuth_deg", jd(o->sun_azimuth * 180 / M_PI));
	json_object_object_add(x, "sun_strength_w_m2", jd(o->sun_strength));
	json_object_object_add(x, "convention", json_object_new_string(
	    "world +Z up; sun_direction points toward the sun; azimuth from +X toward +Y"));
	json_object_object_add(x, "exact_for", json_object_new_string(
	    "every sun, point and spot lamp, one view layer each (import_skin.py), any geometry "
	    "and camera: "
	    "the node tree computes cos_view, cos_light and delta_phi per shading point; "
	    "sun_direction is the "
	    "demo scene's sun. World light and area lamps are shaded by the general material."));
	json_object *ref = json_object_new_object();
	json_object_object_add(ref, "geometry", json_object_new_string("plane with normal +Z, "
	    "orthographic camera looking along -view_direction, black world"));
	json_object_object_add(ref, "view_direction", jvec(r->view, 3));
	json_object_object_add(ref, "view_elevation_deg", jd(o->view_elevation * 180 / M_PI));
	json_object_object_add(ref, "view_azimuth_deg", jd(o->view_azimuth * 180 / M_PI));
	json_object_object_add(ref, "cos_light", jd(r->cos_l));
	json_object_object_add(ref, "cos_view", jd(r->cos_v));
	json_object_object_add(ref, "delta_phi_deg", jd(r->dphi * 180 / M_PI));
	json_object_object_add(ref, "pi_fr_rgb", jvec(r->pi_fr, 3));
	json_object_object_add(ref, "pi_fr_lut_rgb", jvec(r->pi_fr_lut, 3));
	json_object_object_add(ref, "radiance_rgb", jvec(r->radiance, 3));
	json_object_object_add(x, "reference", ref);
	return x;
}

json_object *blender_manifest_build(const struct brdf_source *m, const struct blender_options *o,
    const struct blender_maps *d, const double albedo[3], const struct blender_reference *r)
{
	json_object *j = json_object_new_object(), *x;
	double sss_m[3];
	for (int c = 0; c < 3; c++)
		sss_m[c] = m->sss_radius_cm[c] * 0.01;

	json_object_object_add(j, "format", json_object_new_string("skinbake-blender-image-set"));
	json_object_object_add(j, "format_version", json_object_new_int(BLENDER_FORMAT_VERSION));
	json_object_object_add(j, "generator", json_object_new_string(o->generator));
	x = json_object_new_object();
	json_object_object_add(x, "brdf", json_object_new_string(m->source ? m->source : ""));
	json_object_object_add(x, "preset", m->preset ? json_object_new_string(m->preset) : NULL);
	json_object_object_add(x, "textures", m->detail ? json_object_new_string(m->detail->dir)
	    : NULL);
	json_object_object_add(j, "source", x);
	x = json_object_new_object();
	json_object_object_add(x, "length", json_object_new_string("m"));
	json_object_object_add(x, "angle", json_object_new_string("deg"));
	json_object_object_add(x, "irradiance", json_object_new_string("W/m^2"));
	json_object_object_add(x, "brdf", json_object_new_string("1/sr"));
	json_object_object_add(x, "colour",
	    json_object_new_string("linear Rec.709 (sRGB primaries, D65)"));
	json_object_object_add(j, "units", x);

	/* Material parameters for the general (Principled BSDF) mode. */
	json_object_object_add(j, "ior", jd(m->ior));
	json_object_object_add(j, "roughness_alpha", jd(m->roughness));
	json_object_object_add(j, "roughness", jd(sqrt(m->roughness)));
	json_object_object_add(j, "sss_radius_m", jvec(sss_m, 3));
	json_object_object_add(j, "albedo_rgb", jvec(albedo, 3));
	json_object_object_add(j, "albedo_definition", json_object_new_string(
	    "bihemispherical (white-sky) diffuse albedo: 2 * integral of the "
	    "directional-hemispherical "
	    "albedo a(theta_i) cos(theta_i) d(cos theta_i); the specular reflection is not "
	    "included"));
	x = json_object_new_object();
	json_object_object_add(x, "theta_i_deg", json_object_new_array());
	for (int i = 0; i < m->n_albedo; i++)
		json_object_array_add(json_object_object_get(x, "theta_i_deg"),
		    jd(m->theta_albedo[i] * 180.0 / M_PI));
	for (int c = 0; c < 3; c++) {
		static const char *const key[3] = { "R", "G", "B" };
		json_object_object_add(x, key[c],
		    jvec(m->albedo_rgb + (size_t)c * (size_t)m->n_albedo, m->n_albedo));
	}
	json_object_object_add(j, "albedo_curve", x);

	json_object_object_add(j, "files", files_info(o, d));

	x = json_object_new_object();
	json_object_object_add(x, "flat", json_object_new_boolean(d->flat));
	json_object_object_add(x, "note", json_object_new_string(d->flat ?
	    "no --textures given: constant height and normal (0.5, 0.5, 1) maps" :
	    "height.png and normal.png copied from the textures directory"));
	json_object_object_add(x, "tile_mm", jnum_or_null(d->tile_mm));
	json_object_object_add(x, "height_min_um", jnum_or_null(d->hmin_um));
	json_object_object_add(x, "height_max_um", jnum_or_null(d->hmax_um));
	json_object_object_add(j, "detail", x);

	x = json_object_new_object();
	json_object_object_add(x, "value", json_object_new_string(
	    "pi * f_r, the total BRDF (diffuse + surface specular) times pi, linear RGB"));
	json_object_object_add(x, "cos_nodes", json_object_new_int(o->lut_cos));
	json_object_object_add(x, "phi_nodes", json_object_new_int(o->lut_phi));
	json_object_object_add(x, "tiles", json_object_new_string(
	    "phi_nodes tiles side by side, each cos_nodes x cos_nodes; tile k is delta_phi = "
	    "k * 180 / (phi_nodes - 1) deg, 0 = view back toward the light, 180 = mirror side"));
	json_object_object_add(x, "u", json_object_new_string(
	    "inside a tile, column j is cos_view = j / (cos_nodes - 1); texture u = (k * "
	    "cos_nodes + j + 0.5) / width"));
	json_object_object_add(x, "v", json_object_new_string(
	    "file row r from the top is cos_light = 1 - r / (cos_nodes - 1): the bottom row "
	    "(Blender v = 0) "
	    "is cos_light = 0; texture v = (cos_light * (cos_nodes - 1) + 0.5) / cos_nodes"));
	json_object_object_add(x, "interpolation", json_object_new_string(
	    "bilinear inside the two neighbouring delta_phi tiles, then linear in delta_phi"));
	json_object_object_add(j, "brdf_lut", x);

	json_object_object_add(j, "exact", exact_info(o, r));
	return j;
}

