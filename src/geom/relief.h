/* relief: the micro-relief of skin as a periodic height field on a square
 * tile: pores (smooth dimples at Poisson-disk positions, optionally on the
 * furrow junctions) and furrows (grooves along the edges of a periodic
 * Delaunay triangulation, with curved plateaus inside the triangles), at one
 * or more levels (deep primary lines; secondary ones that split the primary
 * triangles, so that they end on primary lines; finer independent nets),
 * bent, deeper along a preferred direction (one angle, or a direction map in
 * UV) and optionally stretched along it as on the back of the hand, with a
 * fine corneocyte-scale texture on the plateaus.  Every feature
 * is evaluated with periodic distances, so the map tiles without a seam.
 * The furrow net follows Li & Ng (skin surface figures 8-10); dermatology
 * sources for the numbers are in sites.c and docs/texture.md.
 *
 * Coordinates: x to the right, y up (toward row 0 of an image), both in tile
 * units [0, 1) inside the library; physical sizes are in cm. */
#ifndef SKINBAKE_RELIEF_H
#define SKINBAKE_RELIEF_H
#include <stdint.h>

#define RELIEF_MAX_LEVELS 4

struct relief_params {
	double tile;	/* tile edge length [cm] */
	/* Pores. */
	double pore_density;	/* pores per area [1/cm^2] */
	double pore_radius;	/* median radius at the surface [cm] */
	double pore_radius_sd;	/* log-normal sigma of the radius [1] */
	double pore_depth;	/* median depth of a pore of median radius [cm] */
	double pore_depth_sd;	/* log-normal sigma of depth / radius [1] */
	double pore_aspect;	/* ratio of the long to the short axis [1] */
	double pore_junction;	/* fraction of pores put on primary furrow junctions [1] */
	double pore_regularity;	/* Poisson-disk distance / mean spacing [1] */
	/* Furrows. */
	int levels;	/* furrow levels, 0 = none [1] */
	double furrow_cell;	/* mean junction spacing of the primary net [cm] */
	double furrow_width;	/* full width of a primary furrow at the surface [cm] */
	double furrow_depth;	/* median depth of a primary furrow [cm] */
	double furrow_depth_sd;	/* log-normal sigma of the depth of each edge [1] */
	double ridge_height;	/* height of the plateau dome inside a primary triangle [cm] */
	double level_scale;	/* cell size ratio of each level to the previous one [1] */
	double level_gain;	/* depth and dome ratio of each level to the previous one [1] */
	double stretch;	/* elongation of the cells along `orientation` [1] */
	double orientation;	/* direction of elongation from +x toward +y [rad] */
	double furrow_regularity;	/* Poisson-disk distance / mean spacing of junctions [1] */
	/* Hierarchy, shape and fine texture. */
	int hierarchy;	/* 1: level 2 splits every primary triangle by a three-armed star of
			 * secondary furrows (from an interior point to its three sides), so
			 * secondary lines end on primary ones; 0: an independent net [1] */
	double bend;	/* largest sideways bend of a furrow / its length [1] */
	double region_sd;	/* log-normal sigma of a smooth depth factor over the tile
				 * (1-3 cycles per tile): regions of deeper lines [1] */
	double furrow_fade;	/* f: a furrow's depth at its inner joints is exp(-f |z|), z
				 * standard normal, times that at its ends [1] */
	double direction_gain;	/* depth of a furrow along the preferred direction over one
				 * across it, (gain)^(cos 2 angle / 2) in between [1] */
	double plateau_roughness;	/* RMS height of the fine plateau texture [cm] */
	double plateau_scale;	/* its wavelength [cm] */
	/* Preferred direction map (NULL: `orientation` everywhere): n*n angles
	 * [rad] from +x toward +y, row 0 on top, covering the tile. */
	const float *direction;
	int direction_n;	/* its edge [px] */
};

/* Per-level furrow geometry derived from the parameters. */
struct relief_level_info {
	int points;	/* junctions (Delaunay vertices, or the star centres and arm ends) */
	int furrows;	/* furrows before bending (Delaunay edges or star arms) */
	double cell;	/* mean junction spacing [cm] */
	double width;	/* furrow width [cm] */
	double depth;	/* median furrow depth [cm] */
	double ridge;	/* plateau dome height [cm] */
};

struct relief;

/* Check the parameters (ranges as in sites.c) and the number of features
 * they imply; -1 and *cause (caller frees) naming the parameter otherwise. */
int relief_params_check(const struct relief_params *p, char **cause);
/* Place every feature (serial, deterministic for a seed).  NULL and *cause
 * if the parameters are bad or a triangulation fails.  Caller frees. */
struct relief *relief_new(const struct relief_params *p, uint64_t seed, char **cause);
void relief_free(struct relief *r);
int relief_n_pores(const struct relief *r);
/* Geometry of furrow level k (0 = primary). */
struct relief_level_info relief_level(const struct relief *r, int k);

/* Render an n x n window of the (infinitely repeated) relief whose lower-left
 * corner is (x0, y0) [tiles]: pixel (row, col) samples the centre
 * x = x0 + (col + 0.5) / n, y = y0 + (n - row - 0.5) / n; row 0 is the top.
 * With (x0, y0) = (0, 0) this is one period.  pores and furrows (either may
 * be NULL) receive n*n heights [cm], 0 = the undisturbed surface.  Uses
 * OpenMP; the result does not depend on the thread count. */
void relief_render(const struct relief *r, int n, double x0, double y0, float *pores, float *furrows);

/* Tangent-space unit normals of a periodic height map h (n x n, row 0 on
 * top, heights [cm], pixel pitch [cm]) by central differences with
 * wrap-around: n = (-dh/dx, -dh/dy, 1) / norm, x right and y up (OpenGL).
 * nx, ny, nz receive one component each (n*n floats). */
void relief_normals(int n, double pitch, const float *h, float *nx, float *ny, float *nz);
#endif
