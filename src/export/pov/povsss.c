/* povsss: POV-Ray's subsurface closure under the remainder of the baked
 * table (translucent mode; see povsss.h). */
#include "config.h"
#include "export/pov/povsss.h"

#include <math.h>

#include "export/pov/sdl.h"

void povsss_remainder(void *ctx, double ti, double to, double dphi, double rgb[3])
{
	const struct pov_sss *s = ctx;
	s->table.f_rgb(s->table.ctx, ti, to, dphi, rgb);
	for (int c = 0; c < 3; c++) {
		double far = POVSSS_WEIGHT * sss_far_pi_f(s->fit.table, c, s->fit.colour[c], ti, to) / M_PI;
		rgb[c] = fmax(rgb[c] - far, 0.0);
	}
}

/* The largest share of the table the remainder clips, over a grid to 80
 * degrees (the far field's own nodes end at 85). */
static double clipped_share(const struct pov_sss *s)
{
	double worst = 0.0;
	for (int i = 0; i <= 16; i++)
		for (int j = 0; j <= 16; j++) {
			double ti = i * (80.0 / 16) * M_PI / 180, to = j * (80.0 / 16) * M_PI / 180, t[3];
			s->table.f_rgb(s->table.ctx, ti, to, 0.5 * M_PI, t);
			for (int c = 0; c < 3; c++) {
				double far = POVSSS_WEIGHT * sss_far_pi_f(s->fit.table, c, s->fit.colour[c], ti, to) / M_PI;
				if (t[c] > 0 && far > t[c])
					worst = fmax(worst, (far - t[c]) / t[c]);
			}
		}
	return worst;
}

int povsss_setup(struct pov_sss *sss, struct pov_brdf *brdf, double *ior, const struct bake *b,
    char **cause)
{
	if (sss_fit_bake(&sss_pov_table, b, POVSSS_WEIGHT, &sss->fit, cause) != 0)
		return -1;
	sss->on = 1;
	sss->table = *brdf;
	*ior = sss->fit.table->ior;	/* the object's interior: the calibration's (its dipole depends on it) */
	brdf->f_rgb = povsss_remainder;
	brdf->ctx = sss;
	sss->clipped = clipped_share(sss);
	povback_setup(&sss->back, b, &sss->fit);
	return 0;
}

void povsss_write(FILE *fp, const char *skin, const struct pov_sss *sss, int reflection)
{
	const struct sss_fit *f = &sss->fit;
	fprintf(fp, "// Translucent (docs/translucency.md): POV-Ray's subsurface closure fitted to the bake's Rd(r)\n"
	    "// from the calibration of %s %s (%s), weight %g; the lit table above it is the\n"
	    "// bake's BRDF minus the closure's far field (clipped at 0: at most %.1f %% of the table).\n",
	    f->table->renderer, f->table->version, f->table->closure, f->scale, 100 * sss->clipped);
	fprintf(fp, "//   within %g mm        R          G          B\n", f->r_max_mm);
	fprintf(fp, "//   power bake   %10.5f %10.5f %10.5f\n", f->integral_bake[0], f->integral_bake[1], f->integral_bake[2]);
	fprintf(fp, "//   power fit    %10.5f %10.5f %10.5f (of it local, left in the table)\n", f->integral_fit[0],
	    f->integral_fit[1], f->integral_fit[2]);
	fprintf(fp, "//   local        %10.5f %10.5f %10.5f\n", f->local[0], f->local[1], f->local[2]);
	fprintf(fp, "//   mean r bake  %10.5f %10.5f %10.5f mm\n", f->mean_bake_mm[0], f->mean_bake_mm[1], f->mean_bake_mm[2]);
	fprintf(fp, "//   mean r fit   %10.5f %10.5f %10.5f mm\n", f->mean_fit_mm[0], f->mean_fit_mm[1], f->mean_fit_mm[2]);
	fprintf(fp, "//   RMS ln R(r)  %10.5f %10.5f %10.5f (predicted, rings holding 95 %%)\n", f->rms_log[0],
	    f->rms_log[1], f->rms_log[2]);
	fprintf(fp, "#declare SKIN_%s_Subsurface = texture { pigment { ", skin);
	sdl_rgb(fp, f->colour);
	fputs(" }\n  finish { diffuse 1 brilliance 1 ambient 0 emission 0 specular 0 subsurface { translucency ", fp);
	sdl_rgb(fp, f->length_mm);
	fputs(" }", fp);
	if (reflection)
		fputs(" reflection { 0, 1 fresnel on } conserve_energy", fp);
	fputs(" } }\n", fp);
}

void povsss_write_global(FILE *fp, double unit_mm, int samples)
{
	fprintf(fp, " mm_per_unit " SDL_G " subsurface { samples %d, 1 }", unit_mm, samples);
}
