/* povao: the fill's occlusion on meshes (`fill_occlusion = N` in [scene]).
 * A uniform sky of radiance L seen past occluders gives a Lambert surface
 * the radiance albedo x L x V, V the cosine-weighted fraction of the
 * hemisphere that reaches the sky; the exporter's fill (albedo(theta_o) x
 * fill, povinc.c) is multiplied by V.  V is traced per mesh vertex with N
 * stratified cosine-distributed rays against every mesh of the scene (a
 * uniform grid, any hit), interpolated over each triangle into the mesh's
 * UV space and written as a 16-bit grey PNG by which BASE.pov blends the
 * fill pigment (V = 1) toward the fill bounced once off the skin (V = 0,
 * povsplit_bounce_curve).  Left out: the key's light bounced between
 * surfaces, more than one bounce, the BRDF weighting of the directions
 * (cosine only), and non-mesh shapes as occluders. */
#ifndef SKINBAKE_POVAO_H
#define SKINBAKE_POVAO_H
#include "scene/scene.h"

#define POVAO_SIZE 2048	/* texels per side of the UV map */

/* Object o gets an occlusion map: the scene asks for it, has a fill, o is a
 * mesh with UVs. */
int povao_wanted(const struct scene *s, const struct scene_object *o);
/* Its file name: BASE_ao_NAME.png (caller frees). */
char *povao_name(const char *base, const struct scene_object *o);

struct povao_stats {
	int n_rays;		/* per vertex: fill_occlusion rounded down to a square */
	int n_vertices;		/* traced (in the camera's view), over the objects */
	double mean_v;		/* mean visibility over those vertices [-] */
	double seconds;		/* tracing and rasterising */
};

/* Trace and write every wanted object's map into DIR; 0, or -1 with *cause. */
int povao_write(const struct scene *s, const char *dir, const char *base, struct povao_stats *st,
    char **cause);
#endif
