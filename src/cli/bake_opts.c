/* bake_opts: the transport options of `skinbake bake` (bake_opts.h). */
#include "config.h"

#include "cli/bake_opts.h"

#include <string.h>

int bake_opts_transport(struct opt *o, struct bake_opts *b)
{
	struct bake_spec *s = b->s;
	const struct opt t[] = {
		{ "solver", OPT_ENUM, &b->solver, .def = "auto", .choices = bake_method_choices(),
		  .help = "adding-doubling (ad), Monte Carlo (mc), or ad with mc, said on stderr, "
		  "for the wavelengths where ad cannot meet --ad-tol (auto)" },
		{ "ad-tol", OPT_DOUBLE, &s->ad_tol, "E", "0.001", .lo = 1e-6, .hi = 0.1,
		  .help = "ad: estimated RMS relative error of the table to reach "
		  "(or --target-error when smaller)" },
		{ "ad-quad", OPT_INT, &s->ad_quad, "N", .lo = 4, .hi = 1024,
		  .help = "ad: quadrature nodes per unit cosine",
		  .def_note = "the fewest from 16 up, doubling, that meet --ad-tol" },
		{ "ad-quad-max", OPT_INT, &s->ad_quad_max, "N", .lo = 16, .hi = 1024,
		  .def_note = "256",
		  .help = "ad: the most nodes per unit cosine the automatic search tries "
		  "before refusing (its cost bound)" },
		{ "radial-error", OPT_DOUBLE, &s->radial_error, "E", "0.02", .lo = 1e-4, .hi = 1,
		  .help = "ad: relative error of each mean exit radius (Rd(r) by Monte Carlo: "
		  "1024 photons per wavelength, more as E asks, up to --radial-photons)" },
		{ "radial-photons", OPT_LONG, &s->radial_photons, "N", "1e6", .lo = 100, .hi = 1e10,
		  .help = "ad: Rd(r) photons cap" },
		{ "target-error", OPT_DOUBLE, &s->target_error, "E", "0.02", .lo = 0, .hi = 1,
		  .help = "mc: add photons until the solid-angle-weighted RMS relative error "
		  "of the table is below E (at least 0.001; 0 = spend --max-photons); "
		  "without --batch-photons a pilot of 8 x 250 photons per (wavelength, angle) "
		  "measures the error E_p, then the first round is 32 batches of N/32 photons, "
		  "N = 2000 (E_p/E)^2 x 1.1," },
		{ "max-photons", OPT_LONG, &s->max_photons, "N", "2e8", .lo = 1e3, .hi = 1e13,
		  .help = "mc: photon budget" },
		{ "batch-photons", OPT_LONG, &s->batch_photons, "N", .lo = 100, .hi = 1e9,
		  .help = "mc: photons per batch, 8 batches in the first round",
		  .def_note = "sized from --target-error; 4000 with --target-error 0" },
		{ "r-step", OPT_DOUBLE, &s->dr, "CM", "0.002", .lo = 1e-6, .hi = 10, .unit = "cm",
		  .help = "radial bin of Rd(r)" },
		{ "r-bins", OPT_INT, &s->n_r, "N", "250", .lo = 1, .hi = 100000,
		  .help = "radial bins of Rd(r)" },
		{ "fresnel", OPT_ENUM, &b->fresnel, .def = "exact", .choices = "exact|schlick",
		  .help = "boundary reflectance model" },
		{ "estimator", OPT_ENUM, &b->estimator, .def = "nee", .choices = "nee|bins",
		  .help = "mc: how the table is scored: next-event estimation toward every bin "
		  "(nee), or binning the escaping photons (bins), both unbiased" },
		{ "seed", OPT_U64, &b->seed, "N", "1", .help = "mc: random seed (exact)" },
	};
	memcpy(o, t, sizeof t);
	return (int)(sizeof t / sizeof t[0]);
}
