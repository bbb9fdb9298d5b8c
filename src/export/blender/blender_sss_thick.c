/* blender_sss_thick: the thickness weight of the translucent node (see
 * blender_sss_thick.h). */
#include "config.h"
#include "export/blender/blender_sss_thick.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bakedir.h"
#include "base/util.h"
#include "export/sss_tt.h"

const double blender_thick_d_mm[BLENDER_THICK_N] = { 0.25, 0.5, 0.75, 1, 1.5, 2, 3, 4, 6,
	BLENDER_THICK_AO_MM };

/* The same major.minor? */
static int same_series(const char *a, const char *b)
{
	int a1 = -1, a2 = -1, b1 = -2, b2 = -2;
	return sscanf(a, "%d.%d", &a1, &a2) == 2 && sscanf(b, "%d.%d", &b1, &b2) == 2 && a1 == b1 &&
	    a2 == b2;
}

const struct sss_trans_table *blender_thick_table(const struct sss_table *t)
{
	for (int k = 0; blender_sss_trans_tables[k] != NULL; k++)
		if (same_series(t->version, blender_sss_trans_tables[k]->version))
			return blender_sss_trans_tables[k];
	return NULL;
}

/* ln T of colour row i at x [mm], ln-linear between the nodes and beyond. */
static double ln_row(const struct sss_trans_table *t, int i, double x)
{
	const double *row = t->t + (size_t)i * (size_t)t->n_x;
	int j = 0;
	while (j < t->n_x - 2 && x > t->x_mm[j + 1])
		j++;
	double a = log(fmax(row[j], 1e-12)), b = log(fmax(row[j + 1], 1e-12));
	return a + (b - a) * (x - t->x_mm[j]) / (t->x_mm[j + 1] - t->x_mm[j]);
}

double blender_thick_walk(const struct sss_trans_table *t, double colour, double x_mm)
{
	int i = 0;
	while (i < t->n_colour - 2 && colour > t->colour[i + 1])
		i++;
	double u = (colour - t->colour[i]) / (t->colour[i + 1] - t->colour[i]);
	u = fmin(fmax(u, 0.0), 1.0);
	double v = (1 - u) * exp(ln_row(t, i, x_mm)) + u * exp(ln_row(t, i + 1, x_mm));
	return fmin(v, 1.0);
}

int blender_thick_stack(const struct bake *b, double tt[BLENDER_THICK_N][3], char **cause)
{
	return sss_stack_tt(b, blender_thick_d_mm, BLENDER_THICK_N, tt, cause);
}

void blender_thick_weights(const struct sss_fit *f, const double tt[BLENDER_THICK_N][3],
    struct blender_thick *out)
{
	*out = (struct blender_thick){ 0 };
	const struct sss_trans_table *t = blender_thick_table(f->table);
	if (t == NULL)
		return;
	out->has = 1;
	for (int k = 0; k < BLENDER_THICK_N; k++)
		for (int c = 0; c < 3; c++) {
			double wk = f->scale * blender_thick_walk(t, f->colour[c],
			    blender_thick_d_mm[k] / f->length_mm[c]);
			out->tt[k][c] = tt[k][c];
			out->walk[k][c] = wk;
			/* Where the walk lets nothing through there is nothing to correct: the
			 * previous node's weight (a jump to 1 there would leak into thinner
			 * slabs through the AO's noise), 1 at the AO distance. */
			double x = wk > 1e-4 ? fmin(fmax(tt[k][c], 0.0) / wk, 1.0)
			    : k ? out->weight[k - 1][c] : 1.0;
			out->weight[k][c] = k == BLENDER_THICK_N - 1 ? 1.0 : x;
		}
}

static char *rows(const double v[BLENDER_THICK_N][3])
{
	char *s = xstrdup("[");
	for (int k = 0; k < BLENDER_THICK_N; k++) {
		char *t = xasprintf("%s%s[%.6g, %.6g, %.6g]", s, k ? ", " : "", v[k][0], v[k][1],
		    v[k][2]);
		free(s);
		s = t;
	}
	char *t = xasprintf("%s]", s);
	free(s);
	return t;
}

char *blender_thick_json(const struct blender_thick *t)
{
	if (!t->has)
		return xstrdup("");
	char *d = xstrdup("[");
	for (int k = 0; k < BLENDER_THICK_N; k++) {
		char *x = xasprintf("%s%s%.6g", d, k ? ", " : "", blender_thick_d_mm[k] * 1e-3);
		free(d);
		d = x;
	}
	char *tt = rows(t->tt), *wk = rows(t->walk), *w = rows(t->weight);
	char *j = xasprintf(", \"thickness\": {\"ao_distance_m\": %g, \"ao_near_m\": %g, "
	    "\"d_m\": %s], "
	    "\"tt_stack\": %s, \"t_walk\": %s, \"weight\": %s, \"how\": \"the node per channel "
	    "times weight (linear in d between d_m; d = ao_distance_m sqrt(AO), Cycles' Ambient "
	    "Occlusion with Inside), and a Diffuse BSDF of (1 - weight) times its far field: "
	    "weight = min(1, tt_stack / t_walk), the bake's stack cut to d lit from behind "
	    "(adding-doubling) over the walk's measured transmittance (the previous node's where "
	    "the walk passes below 1e-4, 1 at ao_distance_m); d from an AO within ao_near_m, "
	    "or beyond it one within ao_distance_m\"}", BLENDER_THICK_AO_MM * 1e-3,
	    BLENDER_THICK_NEAR_MM * 1e-3, d, tt, wk, w);
	free(d);
	free(tt);
	free(wk);
	free(w);
	return j;
}
