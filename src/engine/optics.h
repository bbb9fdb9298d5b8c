/* optics: reflection and refraction at a smooth dielectric interface, in
 * cosines (no trigonometry).  Pure functions.  References: Born & Wolf
 * (Fresnel equations); Schlick, Computer Graphics Forum 13(3), 1994. */
#ifndef SKINBAKE_OPTICS_H
#define SKINBAKE_OPTICS_H

enum optics_fresnel {
	OPTICS_FRESNEL_EXACT,	/* unpolarized average of s and p */
	OPTICS_FRESNEL_SCHLICK	/* R0 + (1-R0)(1-cos)^5, cos in the optically thinner medium */
};

/* Cosine of the refraction angle for light going from index n1 to n2 with
 * incidence cosine cos_i in [0, 1]; -1 on total internal reflection.
 * Snell in cosines: cos_t^2 = 1 - (n1/n2)^2 (1 - cos_i^2). */
double optics_cos_t(double n1, double n2, double cos_i);

/* Cosine of the critical angle going from n1 into n2 (0 when n1 <= n2). */
double optics_cos_critical(double n1, double n2);

/* Reflectance for unpolarized light from n1 into n2 at incidence cosine cos_i
 * in [0, 1].  Stores the refraction cosine in *cos_t (0 on total internal
 * reflection, which returns 1).  n1 == n2 gives exactly 0. */
double optics_fresnel(enum optics_fresnel model, double n1, double n2, double cos_i, double *cos_t);
/* Reflectance of a stack of lossless interfaces n[0] | n[1] | ... | n[count-1]
 * (clear layers between them, crossed incoherently) for light arriving from
 * n[0] at cosine cos_i.  Adding: R' = R + (1-R)^2 r / (1 - R r), valid
 * because a lossless stack reflects alike from both sides.  Stores the
 * cosine in the last medium in *cos_t (0 on total internal reflection). */
double optics_stack_reflectance(enum optics_fresnel model, const double *n, int count, double cos_i, double *cos_t);
#endif
