/* ad_err: the adding-doubling solver's values with their error estimates.
 * The values come from the solve at N nodes per unit cosine; the errors
 * from the solve at N/2:
 *   err = F |X_N - X_N/2| + (Fourier tail) + (transmittance dropped),
 * where |X_N - X_N/2| bounds the error of X_N when every doubling of the
 * nodes at least halves the error (exponential convergence, the usual case
 * here, overstates it by far), and F = q / (1 - q) > 1 corrects it where
 * the solves converge slower: q = |X_N - X_N/2| / |X_N/2 - X_N/4| from a
 * third solve (RMS over the table and sums over the totals; F <= 9).  The
 * Fourier tail is the size of the last two orders kept, extrapolated
 * geometrically with the orders' decay. */
#ifndef SKINBAKE_AD_ERR_H
#define SKINBAKE_AD_ERR_H
#include "engine/ad_eval.h"
#include "engine/ad_types.h"

/* Orders whose sum is the kept value (the rest estimate the tail). */
int ad_err_kept_orders(const struct ad_series *sr);
/* Multiplier of the last two orders' size for the tail beyond them. */
double ad_err_tail_factor(const struct ad_series *sr);
/* r's values from hi, errors from lo and lo2 (either may be NULL: no
 * quadrature error, or F = 1); sets r->conv_factor. */
void ad_err_assemble(const struct ad_series *hi, const struct ad_series *lo, const struct ad_series *lo2,
    struct ad_result *r);
/* Whether the estimates meet tol: table RMS, and Rd and Tt relative. */
int ad_err_meets(const struct ad_result *r, double tol);
#endif
