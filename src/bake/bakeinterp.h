/* bakeinterp: the baked diffuse BRDF between a bake table's entries, with
 * an error that covers the interpolation (bakefile.h's bake_eval_diffuse).
 *
 * Point values (adding-doubling wavelengths, table.values "points"):
 *  - Delta-phi: the trigonometric interpolant through the n_phi nodes
 *    j pi / (n_phi - 1), a cosine series of n_phi terms (the Fourier series
 *    in the azimuth that adding-doubling computes, cut there).
 *  - theta_o (and theta_i at the default nodes): the polynomial interpolant
 *    in theta through the Chebyshev-Lobatto nodes (bake_nodes_theta), as a
 *    Chebyshev series sum c_k cos(k u), u = acos(1 - 4 theta / pi).  With the
 *    default incidence nodes (the exit nodes below 90 deg) the table is
 *    completed by theta_i = 90 deg to a square grid, f(90, b) = f(b, 90)
 *    by reciprocity from the grazing-exit column (0 under a smooth top;
 *    under a rough top the BRDF's finite limit; the corner f(90, 90) from
 *    the quadratic through that column's last three nodes), and the
 *    coefficients are made symmetric in (theta_i, theta_o): eval is
 *    reciprocal exactly (f(a, b) = f(b, a)); half the table's asymmetry
 *    goes to the error.  Other incidence nodes: linear in theta_i between
 *    the nodes and to f(90, theta_o) = f(theta_o, 90) at 90 deg (the
 *    grazing-exit column linear in theta_i, held past the last node).
 *  - Error: the table's error (its fr_err through the same interpolant, in
 *    absolute value) + the interpolation error estimate |f - f_half|, f_half
 *    the series cut to the first half of its terms in every axis (the table
 *    at half resolution), + the asymmetry; with other incidence nodes the
 *    linear step's t (1 - t) |f(a0) - f(a1)|.
 *
 * Bin means (Monte Carlo wavelengths, and bakes written before issue 26):
 * linear between the bin centres and the incidence nodes, and from the last
 * centre or node linear to 0 at 90 deg (the limit of the BRDF at grazing
 * under a smooth top; before issue 26 the last value was held).  Under a
 * rough top (b->rough_top), whose BRDF keeps a finite value at grazing, the
 * last theta_o centre is held and theta_i goes from the last node linearly
 * to f(90, theta_o) = f(theta_o, 90) by reciprocity (the last exit bin at
 * incidence min(theta_o, last node)); the error adds that step's
 * t (1 - t) |f(a) - f_end|, f_end's own error, its hold in incidence (the
 * last two exit bins' slope, by reciprocity, over the distance held) and,
 * past the last theta_o centre, |f'| times the distance.  This reads bin means as if
 * they were point values (no deconvolution); the error is the standard
 * error (interpolated the same way) + what that reading costs: per axis the
 * curvature |f''| from the neighbouring values (divided differences, with
 * 0 at 90 deg) times h^2 / 24 (a bin mean's offset from its centre value,
 * theta_o and delta_phi) + the linear step's (x - a)(b - x) / 2 (all three
 * axes; a held end: its distance^2 / 2, and |f'| times it in theta_o), the
 * sum times 2 for the higher orders (tests/test_grazing: it covers the
 * actual error at 99.8 % of a dense grid, at 91 % without the factor). */
#ifndef SKINBAKE_BAKEINTERP_H
#define SKINBAKE_BAKEINTERP_H
#include <stddef.h>

struct bake;

/* The series of b's point-value wavelengths (b->points); b->interp. */
void bake_interp_build(struct bake *b);
void bake_interp_free(struct bake *b);

/* Wavelength w's diffuse BRDF [1/sr] at (theta_i, theta_o) [rad] in
 * [0, pi/2], dphi [rad] in [0, pi]; its error into *err (may be NULL). */
double bake_interp_eval(const struct bake *b, int w, double theta_i, double theta_o, double dphi, double *err);
/* The same for RGB channel c of the linear sRGB plane: -1 when that plane
 * cannot be interpolated as one (wavelengths of both kinds): then sum the
 * wavelengths. */
int bake_interp_rgb(const struct bake *b, int c, double theta_i, double theta_o, double dphi, double *v);
#endif
