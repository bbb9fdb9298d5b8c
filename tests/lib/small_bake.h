/* small_bake.h: the bake spec of the grazing tests (test_grazing, test_grazing_rough): one
 * wavelength, 18 x 18 exit directions on the default incidence nodes, adding-doubling, and a
 * coarse Rd(r) (10 rings of 0.01 cm, 50 % error), which those tests do not look at.  A test
 * changes the fields it needs after the call.  Header-only: two cmocka tests share it. */
#ifndef SKINBAKE_TESTS_SMALL_BAKE_H
#define SKINBAKE_TESTS_SMALL_BAKE_H

#include <string.h>

#include "bake/bake.h"
#include "engine/solvers.h"

static void small_bake_spec(struct bake_spec *s, double wl_nm)
{
	memset(s, 0, sizeof *s);
	s->n_to = s->n_phi = 18;
	bake_spec_axes(s, &wl_nm, 1, NULL, 0, 0);
	s->n_r = 10;
	s->dr = 0.01;
	transport_opts_default(&s->opts);
	s->method = solvers_index("ad");
	s->radial_error = 0.5;
	s->radial_photons = 2000;
	s->seed = 1;
	s->min_batches = 8;
	s->max_photons = 1000000;
	s->n_ranks = 1;
}

#endif
