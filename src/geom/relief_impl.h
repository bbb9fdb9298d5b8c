/* relief_impl: the placed features of a relief, shared by placing
 * (relief.c) and rendering (relief_render.c); not for other modules. */
#ifndef SKINBAKE_RELIEF_IMPL_H
#define SKINBAKE_RELIEF_IMPL_H
#include <math.h>
#include <stdint.h>

#include "base/rng.h"
#include "geom/delaunay.h"
#include "geom/relief.h"

struct bbox {
	double x0, x1, y0, y1;	/* extent [tiles] */
};

struct pore {
	double x, y;	/* centre [tiles] */
	double a, b;	/* semi-axes [cm] */
	double c, s;	/* cosine, sine of the long axis angle [1] */
	double depth;	/* [cm] */
};

struct furrow {
	double x0, y0, x1, y1;	/* ends [tiles]; (x1, y1) may lie in a neighbour tile */
	double half;	/* half width [cm] */
	double depth;	/* at (x0, y0) [cm] */
	double depth1;	/* at (x1, y1) [cm]; linear in between: a furrow fades */
};

struct plateau {
	double x[3], y[3];	/* vertices [tiles], counter-clockwise */
	double inv2a;	/* 1 / twice the area [1/tiles^2] */
	double ridge;	/* dome height [cm] */
};

struct level {
	struct relief_level_info info;
	struct delaunay *del;
	double *xy;	/* junctions [tiles] */
	int n_furrows, n_plateaus;
	struct furrow *furrows;
	struct plateau *plateaus;
	struct bbox *fbox, *pbox;
};

/* One plane wave of the plateau texture: amp cos(2 pi (kx x + ky y) + phase)
 * with x, y in tiles, so the texture is periodic with the tile. */
#define RELIEF_WAVES 48

struct wave {
	int kx, ky;	/* cycles per tile */
	double amp;	/* [cm] */
	double phase;	/* [rad] */
};

#define RELIEF_REGION_WAVES 8

/* The meander of the furrow net (relief_waves.c, relief_render.c): furrows
 * and plateaus are drawn at the pixel's position moved by a smooth periodic
 * displacement of RELIEF_WARP_WAVES plane waves per component, wavelengths
 * about half the primary cell and RMS bend x the primary width, so that
 * edges wander and widths vary instead of running as ruled lines. */
#define RELIEF_WARP_WAVES 8

/* Profiles (relief_render.c): the rounded bottom of a pore's funnel and of
 * a furrow's V, and the rounded rim of the V, as fractions of the radius or
 * half width. */
#define RELIEF_PORE_BOTTOM 0.2
#define RELIEF_GROOVE_BOTTOM 0.25
#define RELIEF_GROOVE_RIM 0.35

struct relief {
	struct relief_params p;
	struct wave region[RELIEF_REGION_WAVES];	/* the regional depth field (relief.c) */
	int n_warp;	/* RELIEF_WARP_WAVES when the net meanders, else 0 */
	struct wave warp[2][RELIEF_WARP_WAVES];	/* its x and y displacement [cm] */
	int n_waves;
	struct wave *waves;
	int n_pores;
	struct pore *pores;
	struct bbox *pore_box;
	int n_levels;
	struct level level[RELIEF_MAX_LEVELS];
};

/* A standard normal deviate (Box-Muller), clamped to +-2.5 sigma so that
 * one draw cannot make a pore or furrow absurdly large. */
static inline double relief_normal(struct rng *r)
{
	double u1 = rng_uniform(r), u2 = rng_uniform(r);
	double z = sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
	return fmax(-2.5, fmin(2.5, z));
}

/* A groove's shoulder (relief_render.c): a broad shallow valley of
 * RELIEF_SHOULDER_WIDTH times the groove's half width and RELIEF_SHOULDER_DEPTH of
 * its depth around the narrow groove, so that the plateaus between deep lines
 * are domed cushions rather than flat tiles cut by hairlines. */
#define RELIEF_SHOULDER_WIDTH 3.0
#define RELIEF_SHOULDER_DEPTH 0.25
/* Shoulders add where lines cross, saturating smoothly at this many times
 * one shoulder's depth of the level's median furrow. */
#define RELIEF_SHOULDER_CAP 2.0

/* relief_lines.c: depth factors of the primary net's edges as long lines:
 * factor[2e] at edge e's point i, factor[2e + 1] at its point j: the line's
 * log-normal factor exp(sd z), times end_factor where the line ends. */
void relief_lines_factors(const struct delaunay *d, const double *xy, double sd, double end_factor,
    struct rng *rg, double *factor);

/* relief_waves.c: the regional depth field and the plateau texture. */
void relief_region_place(struct relief *r, uint64_t seed, uint32_t stream);
double relief_region_at(const struct relief *r, double x, double y);
void relief_waves_place(struct relief *r, uint64_t seed, uint32_t stream);
void relief_warp_place(struct relief *r, uint64_t seed, uint32_t stream);
#endif
