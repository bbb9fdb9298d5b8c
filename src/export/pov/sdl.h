/* sdl: small writers of POV-Ray scene language (SDL) text shared by the
 * exporter's modules: numbers, vectors, colours, blend-map entries,
 * identifiers and orientation matrices. */
#ifndef SKINBAKE_SDL_H
#define SKINBAKE_SDL_H
#include <stdio.h>

/* Numbers in SDL: 7 significant digits keep values well past 16-bit output
 * precision. */
#define SDL_G "%.7g"

void sdl_vec(FILE *fp, const double v[3]);		/* <x,y,z> */
void sdl_rgb(FILE *fp, const double c[3]);		/* rgb <r,g,b> */
/* One `aoi color_map` entry for exit angle theta_o [rad]; the first entry of
 * a map (first = 1) also pins the value at aoi 0, below grazing. */
void sdl_aoi_entry(FILE *fp, int first, double theta_o, const double rgb[3]);
/* "Skinbake_BASE" with every character outside [A-Za-z0-9] replaced by '_'
 * (SDL identifiers need a leading letter); caller frees. */
char *sdl_ident(const char *base);
/* " matrix <...>" taking z to the unit vector d (and x, y to a frame around
 * it): planar bump maps project along z. */
void sdl_align(FILE *fp, const double d[3]);
/* `pigment { aoi color_map { ... } }\n`: a(theta_o) at the n nodes th
 * (ascending [rad]) of curves a ([3][n], linear sRGB), flat beyond them. */
void sdl_albedo_pigment(FILE *fp, int n, const double *th, const double *a);
#endif
