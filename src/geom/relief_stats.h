/* relief_stats: areal statistics of a periodic height map, as skin
 * topography papers report them, so a generated relief can be compared with
 * replica profilometry (docs/texture.md, "Measured statistics"):
 *
 * - Sa: mean |h - mean h| (the areal Ra, ISO 25178) [cm];
 * - Sz: highest minus lowest point (peak to valley; not the ISO five-point
 *   mean) [cm];
 * - furrow density: downward crossings of the level mean - t (t = the
 *   furrow threshold), per length, along every row, column and both
 *   diagonals (wrap-around lines), averaged over these four directions;
 *   each crossing starts a furrow excursion, and the mean depth below the
 *   mean of the deepest point of each excursion is the furrow depth;
 * - anisotropy 1 - lambda_min / lambda_max of the mean gradient structure
 *   tensor (central differences, periodic); 0 isotropic, 1 all gradients
 *   along one axis; the furrow direction is the eigenvector of lambda_min
 *   (along which the height varies least), in [0, pi) from +x toward +y;
 * - pores: 4-connected regions (periodic) of the pore map deeper than the
 *   pore threshold; density per area and mean equivalent diameter
 *   2 sqrt(area / pi) at the threshold level, and mean depth (the deepest
 *   point of each region of the pore map below 0: a pore's own depth, not
 *   counting the furrows it sits in);
 * - Sdr: the developed area ratio (ISO 25178), mean of
 *   sqrt(1 + |grad h|^2) - 1 over the pixels (the same central differences),
 *   how much larger the true surface is than its projection.
 *
 * Maps are n x n, row 0 at the top (+y end), pixel pitch in cm. */
#ifndef SKINBAKE_RELIEF_STATS_H
#define SKINBAKE_RELIEF_STATS_H

#include "geom/relief.h"

struct relief_stats {
	double sa;	/* mean absolute deviation from the mean [cm] */
	double sz;	/* peak to valley [cm] */
	double furrow_density;	/* furrow crossings per length, mean of 4 directions [1/cm] */
	double furrow_depth;	/* mean depth of the furrow excursions below the mean [cm] */
	double anisotropy;	/* 1 - lambda_min / lambda_max [1] */
	double direction;	/* furrow direction from +x toward +y, [0, pi) [rad] */
	int pores;	/* pore regions found */
	double pore_density;	/* pores per area [1/cm^2] */
	double pore_diameter;	/* mean equivalent diameter, 0 without pores [cm] */
	double sdr;	/* developed area / projected area - 1 [1] */
	double pore_depth;	/* mean deepest point of the pore regions, 0 without pores [cm] */
};

struct relief_stats_spec {
	double pitch;	/* pixel pitch [cm] */
	double furrow_threshold;	/* t: crossing level below the mean [cm], > 0 */
	double pore_threshold;	/* pore pixels are deeper than this below 0 [cm], > 0 */
};

/* The spec for an n-pixel map of relief p: furrows counted below half the
 * median primary furrow depth, pores deeper than a tenth of the median
 * pore depth (each threshold at least 0.1 um). */
struct relief_stats_spec relief_stats_spec_for(const struct relief_params *p, int n);
/* relief_stats_compute with that spec. */
int relief_stats_for(const struct relief_params *p, int n, const float *h, const float *furrows,
    const float *pores, struct relief_stats *st);

/* Statistics of h (height for Sa, Sz and the anisotropy), furrows (the
 * furrow density and depth; h when NULL) and pores (pore regions; none when
 * NULL), each n x n [cm].  -1 and *cause (caller frees; cause may be NULL) for n < 3 or a
 * non-positive pitch or threshold. */
int relief_stats_compute(int n, const float *h, const float *furrows, const float *pores,
    const struct relief_stats_spec *spec, struct relief_stats *st, char **cause);
/* The statistics in user units, in report order: key (with its unit) and
 * value. */
enum { RELIEF_STATS_KEYS = 10 };
const char *relief_stats_key(int i);
double relief_stats_value(const struct relief_stats *st, int i);

/* The statistics as a JSON object: every key above, and "pores_found". */
struct json_object *relief_stats_json(const struct relief_stats *st);

#endif
