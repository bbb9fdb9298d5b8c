/* relief_impl: the placed features of a relief, shared by placing
 * (relief.c) and rendering (relief_render.c); not for other modules. */
#ifndef SKINBAKE_RELIEF_IMPL_H
#define SKINBAKE_RELIEF_IMPL_H
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
	double depth1;	/* at (x1, y1) [cm]; linear in between, so a furrow fades in and out */
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

struct relief {
	struct relief_params p;
	int n_waves;
	struct wave *waves;
	int n_pores;
	struct pore *pores;
	struct bbox *pore_box;
	int n_levels;
	struct level level[RELIEF_MAX_LEVELS];
};
#endif
