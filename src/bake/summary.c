/* summary: what a bake made, with which method, at what error and cost. */
#include "config.h"
#include "bake/summary.h"

#include <string.h>

#include "engine/solvers.h"

void bake_summary(FILE *fp, const struct bake_spec *s, const struct bake_result *r, const char *label, const char *dir)
{
	const struct brdf_table *t = &r->table;
	fprintf(fp, "skinbake bake: %s -> %s\n  %d wavelengths x %d incidence angles, table %d x %d\n", label, dir, s->n_wl,
	    s->n_ti, s->n_to, s->n_phi);
	const struct solver_ops *ops = solvers_find(r->solver);
	if (ops && (ops->traits & SOLVER_SAMPLED)) {
		fprintf(fp, "  photons %ld, %.2f s, RMS relative error %.4f (target %g: %s)\n", t->photons, t->seconds,
		    t->rms_rel_err, s->target_error, s->target_error <= 0 ? "none"
		    : t->target_met ? "met" : "NOT met, photon budget spent");
		return;
	}
	fprintf(fp, "  solver %s, %.2f s, RMS relative error %.2g (estimate; tolerance %g: %s)\n", r->solver, t->seconds,
	    t->rms_rel_err, r->tol, t->target_met ? "met" : "NOT met");
	if (t->photons > 0)
		fprintf(fp, "  Monte Carlo for the wavelengths adding-doubling refused: %ld photons\n", t->photons);
	if (r->radial_photons > 0)
		fprintf(fp, "  Rd(r) by Monte Carlo: %ld photons, %.2f s\n", r->radial_photons, r->radial_seconds);
}

void bake_summary_notes(FILE *fp, const struct bake_result *r)
{
	for (const char *l = r->notes; l && *l;) {
		const char *e = strchr(l, '\n');
		int n = e ? (int)(e - l) : (int)strlen(l);
		fprintf(fp, "skinbake bake: %.*s\n", n, l);
		l += n + (e != NULL);
	}
}
