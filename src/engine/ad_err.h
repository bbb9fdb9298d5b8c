/* ad_err: the adding-doubling solver's values with their error estimates.
 * The values come from the solve at N nodes per unit cosine; the errors
 * from the solve at N/2:
 *   err = F |X_N - X_N/2| + (Fourier tail) + (transmittance dropped),
 * where |X_N - X_N/2| bounds the error of X_N when every doubling of the
 * nodes at least halves the error (exponential convergence, the usual case
 * here, overstates it by far), and F = q / (1 - q) > 1 corrects it where
 * the solves converge slower: q = |X_N - X_N/2| / |X_N/2 - X_N/4| from a
 * third solve (RMS over the table and sums over the totals; F <= 9; q is
 * kept as ad_result.conv_ratio).  The
 * Fourier tail is the size of the last two orders kept, extrapolated
 * geometrically with the orders' decay.
 *
 * The whole table's RMS estimate (ad_result.rms_rel_err, which decides the
 * node count) takes the same geometric tail Fs = q / (1 - q) below q = 1/2
 * too, with q at least 1/4 (Fs >= 1/3): where the solves converge fast
 * (q far below 1/4) the difference to the half solve is about the half
 * solve's own error, and overstates X_N's by 1/q.  Only while every node
 * count tried so far converged that fast (ad.c): a fall that was slow at
 * fewer nodes can look fast for one doubling (g = 0.99 at 256 nodes: q =
 * 0.07 after slow falls; it keeps F, and simulate's 1e-4 stays refused).
 * Paper's 470 nm table
 * at 16 nodes per unit cosine: estimated 1.37e-3 with F = 1 (so it went to
 * 32), 4.6e-4 with Fs, actual 2.4e-6 (against 128 nodes).  Every single
 * value's error (bins, bands, points, totals) keeps F >= 1: a difference
 * at one bin can vanish by chance where the two solves cross, which an RMS
 * over the table averages out (tests/test_ad test_bands_converged: a band
 * at 34 deg with |X_16 - X_8| only twice its actual error). */
#ifndef SKINBAKE_AD_ERR_H
#define SKINBAKE_AD_ERR_H
#include "engine/ad_eval.h"
#include "engine/ad_types.h"

/* Orders whose sum is the kept value (the rest estimate the tail). */
int ad_err_kept_orders(const struct ad_series *sr);
/* Multiplier of the last two orders' size for the tail beyond them. */
double ad_err_tail_factor(const struct ad_series *sr);
/* r's values from hi, errors from lo and lo2 (either may be NULL: no
 * quadrature error, or F = 1); sets r->conv_factor.  tail_ok: the table
 * RMS may take the geometric tail Fs (else F, as every single value). */
void ad_err_assemble(const struct ad_series *hi, const struct ad_series *lo, const struct ad_series *lo2,
    int tail_ok, struct ad_result *r);
/* Whether the estimates meet tol: table RMS, and Rd and Tt relative. */
int ad_err_meets(const struct ad_result *r, double tol);
#endif
