/* sdl: write numbers, vectors, colours and identifiers as POV-Ray SDL text. */
#include "config.h"

#include "export/pov/sdl.h"

#include <math.h>

#include "base/util.h"
#include "export/pov/vec3.h"

void sdl_rgb(FILE *fp, const double c[3])
{
	fprintf(fp, "rgb <" SDL_G "," SDL_G "," SDL_G ">", c[0], c[1], c[2]);
}

void sdl_aoi_entry(FILE *fp, int first, double to, const double rgb[3])
{
	if (first) {
		fputs(" [0 ", fp);
		sdl_rgb(fp, rgb);
		fputs("]", fp);
	}
	fprintf(fp, " [%.8f ", 1 - to / M_PI);
	sdl_rgb(fp, rgb);
	fputs("]", fp);
}

void sdl_vec(FILE *fp, const double v[3])
{
	fprintf(fp, "<" SDL_G "," SDL_G "," SDL_G ">", v[0], v[1], v[2]);
}

char *sdl_ident(const char *base)
{
	char *s = xasprintf("Skinbake_%s", base);
	for (char *c = s; *c; c++)
		if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9')))
			*c = '_';
	return s;
}

void sdl_align(FILE *fp, const double d[3])
{
	double up[3] = { 0, 1, 0 }, u[3], w[3], n;
	if (fabs(d[1]) > 0.99) {
		up[1] = 0;
		up[2] = 1;
	}
	u[0] = up[1] * d[2] - up[2] * d[1];
	u[1] = up[2] * d[0] - up[0] * d[2];
	u[2] = up[0] * d[1] - up[1] * d[0];
	n = sqrt(vec3_dot(u, u));
	for (int i = 0; i < 3; i++)
		u[i] /= n;
	w[0] = d[1] * u[2] - d[2] * u[1];
	w[1] = d[2] * u[0] - d[0] * u[2];
	w[2] = d[0] * u[1] - d[1] * u[0];
	fprintf(fp, " matrix <" SDL_G "," SDL_G "," SDL_G ", " SDL_G "," SDL_G "," SDL_G ", " SDL_G "," SDL_G "," SDL_G
		    ", 0,0,0>",
	    u[0], u[1], u[2], w[0], w[1], w[2], d[0], d[1], d[2]);
}

void sdl_albedo_pigment(FILE *fp, int n, const double *th, const double *a)
{
	fputs("pigment { aoi color_map {", fp);
	for (int i = n - 1; i >= 0; i--) {
		double rgb[3] = { a[i], a[n + i], a[2 * n + i] };
		sdl_aoi_entry(fp, i == n - 1, th[i], rgb);
	}
	if (th[0] > 0) {
		double rgb[3] = { a[0], a[n], a[2 * n] };
		fputs(" [1 ", fp);
		sdl_rgb(fp, rgb);
		fputs("]", fp);
	}
	fputs(" } }\n", fp);
}
