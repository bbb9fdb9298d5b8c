/* family_radial: the Rd(r) of a family's members by one white Monte Carlo
 * run per wavelength (engine/wmc.h) instead of one run per member and
 * wavelength, where the members differ only in absorption (a family over
 * melanin and blood).  Each wavelength: a pilot of FAMILY_RADIAL_PILOT
 * photons gives every member's mean exit radius with its relative error
 * e_m; a member needing more than the photon cap (pilot x (e_m / target)^2
 * x 1.2, bake.h's rule) is left to its own run in bake_run; the run is
 * then repeated with the largest need of the rest (other random streams),
 * which replaces the pilot.  Under MPI (spec's n_ranks and allreduce) the
 * ranks share the wavelengths and sum the profiles: every rank ends with
 * the same numbers as one process.  The walks play far roulette beyond
 * the bins (engine/transport.h), as bake/radial.h. */
#ifndef SKINBAKE_FAMILY_RADIAL_H
#define SKINBAKE_FAMILY_RADIAL_H
#include "bake/bake.h"

#define FAMILY_RADIAL_PILOT 4000	/* photons of a group's pilot */
#define FAMILY_RADIAL_GROUPS 4		/* groups per wavelength at most */

struct family_radial {
	int n_members, n_wl, n_r;
	double *rd_r;		/* [n_wl][n_members][n_r] [1/cm^2] */
	double *rd_r_err;	/* [n_wl][n_members][n_r] */
	unsigned char *ok;	/* [n_wl][n_members] 1: shared profile there,
				 * 0: the member runs its own */
	long photons;		/* photons of all the shared runs */
	double seconds;		/* their wall time [s] */
};

/* The shared profiles for spec s (its n_wl, theta_i[0], bins, radial_error,
 * radial_photons, seed, threads) of the members' prepared slabs
 * slabs[m * s->n_wl + w].  0 when none is shared (an all-Monte Carlo bake,
 * no bins, or no wavelength where the members share their scattering), 1
 * with fr filled (caller frees with family_radial_free). */
int family_radial_run(const struct bake_spec *s, const struct slab *slabs, int n_members,
    struct family_radial *fr);
/* Member m's given profiles for bake_spec.radial_given. */
void family_radial_given(const struct family_radial *fr, int m, struct bake_radial_given *g);
void family_radial_free(struct family_radial *fr);
#endif
