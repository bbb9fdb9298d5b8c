/* povsss: the translucent mode of the POV-Ray export (issue 27,
 * docs/translucency.md).  The skin is two layers of one texture:
 *
 *   texture { SKIN_s_Subsurface }      POV-Ray's own subsurface closure
 *                                      (`subsurface { translucency }`, a
 *                                      dipole) fitted to the bake's Rd(r)
 *   texture { pigment { average pigment_map { [1 SKIN_s_Remainder]
 *                       [999 rgbt <0,0,0,1>] } }  finish { diffuse 1e6 } }
 *
 * The top layer lets 0.999 of the light through to the subsurface layer and
 * adds 0.001 x 1e6 x table / 1000 = the table: measured exact (0.7047 =
 * 0.999 x 0.5047 + 0.2000).  Its table is the remainder: the baked BRDF
 * (diffuse + surface specular) minus the closure's own far-field BRDF
 * times 0.999 (from the calibration, export/sss_fit.h), never negative, so a
 * flat surface under uniform light still shows the baked BRDF wherever the
 * closure's far field stays below it. */
#ifndef SKINBAKE_POVSSS_H
#define SKINBAKE_POVSSS_H
#include <stdio.h>

#include "export/pov/littable.h"
#include "export/pov/povback.h"
#include "export/sss_fit.h"

#define POVSSS_CLEAR 999		/* parts of clear in the top layer's pigment */
#define POVSSS_WEIGHT 0.999		/* the subsurface layer's weight [-] */
#define POVSSS_DIFFUSE 1e6		/* the top layer's diffuse: (1 + 999) / (1 - 0.999) */

struct pov_sss {
	int on;				/* the skin is written translucent */
	struct sss_fit fit;		/* the closure's parameters and residuals */
	struct pov_brdf table;		/* the whole baked BRDF the remainder is taken from */
	double clipped;			/* largest share of the table the remainder clipped at 0 */
	struct pov_back back;		/* the back light through thin meshes (povback.h) */
};

/* Fit POV-Ray's closure to bake B and make *brdf the remainder (it keeps
 * the whole table in sss->table; SSS must outlive *brdf); *ior becomes the
 * calibration's index (the object's interior, which POV-Ray's dipole reads:
 * at 1.43 instead of 1.4 the far field is 0.7 % lower).  -1 and *cause when
 * B has no radial profile or POV-Ray no calibration. */
int povsss_setup(struct pov_sss *sss, struct pov_brdf *brdf, double *ior, const struct bake *b,
    char **cause);

/* The remainder pi f: max(0, table - weight x closure far field) [1/sr]. */
void povsss_remainder(void *ctx, double theta_i, double theta_o, double dphi, double rgb[3]);

/* Declare SKIN_<skin>_Subsurface (with the reflection, when asked) and a
 * comment with the calibration: renderer, version, parameters, residuals. */
void povsss_write(FILE *fp, const char *skin, const struct pov_sss *sss, int reflection);

/* The global_settings items the subsurface needs (mm_per_unit, samples). */
void povsss_write_global(FILE *fp, double unit_mm, int samples);
#endif
