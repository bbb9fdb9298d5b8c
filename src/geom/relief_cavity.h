/* relief_cavity: how much of the sky each point of the relief sees, for
 * the darkening of furrows and pores that a normal map cannot give (a pore
 * is dark because light that enters it is trapped, not because its walls
 * face away).  The value is the ambient occlusion of the height field,
 * the cosine-weighted fraction of the hemisphere about the local normal
 * that is not hidden by the relief around the point, estimated from the
 * horizon in D directions (horizon-based ambient occlusion, Bavoil L,
 * Sainz M, Dimitrov R, "Image-space horizon-based ambient occlusion",
 * SIGGRAPH 2008 talk): in the vertical slice along direction phi, with the
 * tangent plane at elevation t and the highest point of the relief within
 * the radius seen at elevation h, the cosine-weighted part of the slice
 * hidden is sin^2(h - t) (h - t >= 0), and
 *
 *     cavity = 1 - (1/D) sum_phi sin^2(max(0, h_phi - t_phi)).
 *
 * A flat or tilted plane gives 1; the centre of the flat bottom of a round
 * hole of radius r and depth d gives r^2 / (r^2 + d^2). */
#ifndef SKINBAKE_RELIEF_CAVITY_H
#define SKINBAKE_RELIEF_CAVITY_H

/* Steps along each direction at most; beyond, the steps widen. */
enum { RELIEF_CAVITY_MAX_STEPS = 48, RELIEF_CAVITY_DIRS = 16 };

/* cavity [0..1] of the periodic n x n height map h [cm] (row 0 on top,
 * pixel pitch [cm]), looking radius [cm] around each pixel (at least one
 * pixel).  cav receives n*n values. */
void relief_cavity(int n, double pitch, const float *h, double radius, float *cav);

/* The map the texture writer makes: a pore is the mouth of a follicle, a
 * light trap deeper than its funnel, so its occlusion counts in full; a
 * furrow is a groove narrower (about 60 um) than the 0.3-1 mm that light
 * travels under the skin before it leaves, so most of the light missing
 * from its bottom is made up by light from under the plateaus beside it:
 * its occlusion counts with the weight (an exponent) below, an assumption
 * (docs/relief.md).  cav = AO(pores) * AO(furrows)^RELIEF_CAVITY_FURROW_WEIGHT. */
#define RELIEF_CAVITY_FURROW_WEIGHT 0.3
void relief_cavity_combined(int n, double pitch, const float *pores, const float *furrows,
    double radius, float *cav);

/* The radius the texture writer uses: the primary furrow cell (cell [cm]),
 * which holds a pore and the furrows around it, at most half the tile. */
double relief_cavity_radius(double cell, double tile);

/* Write cav (n x n) as a 16-bit gray PNG, value = cavity * 65535, with
 * tEXt keys for the radius [um], the site and the software. */
int relief_cavity_write(const char *path, int n, const float *cav, double radius_um,
    const char *site, const char *software, char **cause);
#endif
