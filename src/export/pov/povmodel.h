/* povmodel: the model file's own material of a mesh object (material
 * model): its diffuse texture through the UVs or its colour, its specular
 * as a Phong highlight, and the fill with its occlusion map (povao.h). */
#ifndef SKINBAKE_POVMODEL_H
#define SKINBAKE_POVMODEL_H
#include <stdio.h>

#include "export/pov/povtypes.h"

/* The finish of a surface lit by the lights alone. */
#define POVMODEL_FINISH_LIT "diffuse 1 brilliance 1 ambient 0 emission 0 specular 0"

/* The file name of a model-material mesh's texture in the output (the
 * exporter writes it there), or NULL when it has none POV-Ray reads. */
char *povmodel_texture_file(const struct scene_object *o, const char *base);
/* The texture block of model-material object o: fill (NULL: none) is the
 * fill's colour, ao (NULL: none) the occlusion map multiplying it. */
void povmodel_write_texture(FILE *fp, const struct scene_object *o, const char *base,
    const double *fill, const char *ao);
#endif
