/* povscene: BASE.pov, the scene of an export: camera, lights, objects and
 * their textures (part of the files povfiles.h writes).
 *
 * Per-light passes are summed in one POV-Ray run where every skin object
 * allows it (spheres, boxes, patches, planes, meshes): each light shades its
 * own copy of the skin with its own table (a `light_group` of that light
 * alone), the copies nested a hair's breadth inside each other; copy k is
 * averaged with a clear texture so that each copy shows with weight 1/N
 * through the ones outside it, and each light's colour is multiplied by N.
 * The sum equals the sum of the separate renders (0.09 % mean on the
 * two-lights test scene; on the MakeHuman head 0.13 % away from edges, about
 * 1 % over all skin pixels: shadow edges and silhouettes move by the
 * inset).  Only the innermost copy casts shadows.  Where a
 * skin object cannot be inset (hand, head), passes are animation frames
 * written as .hdr and summed by BASE_combine.pov. */
#ifndef SKINBAKE_POVSCENE_H
#define SKINBAKE_POVSCENE_H
#include <stdio.h>

#include "export/pov/povmodel.h"
#include "export/pov/povtypes.h"

#define POVSCENE_FINISH_LIT POVMODEL_FINISH_LIT

/* Whether passes can be layers (every skin object can be inset). */
int povscene_layers_ok(const struct scene *s);
/* The light of layer k (0 outermost): the lights from the weakest to the
 * strongest, so the strongest shades the innermost copy, the one that casts
 * the shadows (outer layers' shadow edges and terminators shift by the
 * inset; measured on the MakeHuman head: 0.50 -> 0.41 % inside edges). */
int povscene_layer_light(const struct scene *s, int k);
/* How far copy k of the layers sits inside copy 0 [units]. */
double povscene_inset(const struct scene *s, int k);

/* The skin textures a mesh object's triangles carry (bump maps follow the
 * UVs, so they live in the mesh2): pigment, finish and the layer wrapping of
 * pass or layer `layer` (-1: not layered). */
void povscene_mesh_texture(const struct scene *s, const struct pov_skin *skins,
    const struct scene_object *o, enum scene_strategy st, int layer, char **pre, char **mid,
    char **post, char **plain);
/* Whether skin ps is written as an average of entries (the split of
 * povsplit.h or the fill; lights key only). */
int povscene_averaged(const struct pov_skin *ps);

void povscene_write(FILE *fp, const struct scene *s, const struct pov_skin *skins,
    const struct pov_options *o, enum scene_strategy st, int layered);
/* Name of POV-Ray's frame k output of n: BASE_passK.hdr, K padded to the
 * digits of n. */
char *povscene_pass_name(const char *base, int k, int n);
/* BASE_combine.pov: the sum of the .hdr passes. */
void povscene_write_combine(FILE *fp, const struct scene *s, const char *base,
    const char *scene_name);
#endif
