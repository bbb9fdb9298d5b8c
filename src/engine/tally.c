/* tally: the exit and absorption sums of a batch of photons and the
 * geometry of their bins. */
#include "config.h"
#include "engine/tally.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/util.h"

int tally_grid_steps(struct tally_grid *g, double theta_step_deg, double phi_step_deg, char **cause)
{
	double nt = 90.0 / theta_step_deg, np = 180.0 / phi_step_deg;
	if (fabs(nt - round(nt)) > 1e-9) {
		*cause = xasprintf("--theta-out-step = %g does not divide 90 degrees", theta_step_deg);
		return -1;
	}
	if (fabs(np - round(np)) > 1e-9) {
		*cause = xasprintf("--phi-step = %g does not divide 180 degrees", phi_step_deg);
		return -1;
	}
	if (round(nt) * round(np) > 1e6) {
		*cause = xasprintf("--theta-out-step %g and --phi-step %g give %ld bins; at most 1e6 are allowed",
		    theta_step_deg, phi_step_deg, (long)round(nt) * (long)round(np));
		return -1;
	}
	g->n_theta = (int)round(nt);
	g->n_phi = (int)round(np);
	return 0;
}

void tally_alloc(struct tally *t, const struct tally_grid *g)
{
	CHECK(g->n_theta >= 1 && g->n_phi >= 1 && g->n_r >= 0);
	memset(t, 0, sizeof *t);
	t->exit = xcalloc((size_t)g->n_theta * (size_t)g->n_phi, sizeof *t->exit);
	t->radial = xcalloc((size_t)(g->n_r > 0 ? g->n_r : 1), sizeof *t->radial);
	if (g->var && g->n_r > 0) {
		t->radial_var = xcalloc((size_t)g->var->n * (size_t)g->n_r, sizeof *t->radial_var);
		t->var_total = xcalloc((size_t)g->var->n, sizeof *t->var_total);
	}
}

void tally_free(struct tally *t)
{
	free(t->exit);
	free(t->radial);
	free(t->radial_var);
	free(t->var_total);
	t->exit = t->radial = t->radial_var = t->var_total = NULL;
}

void tally_zero(struct tally *t, const struct tally_grid *g)
{
	double *e = t->exit, *r = t->radial, *rv = t->radial_var, *vt = t->var_total;
	memset(t, 0, sizeof *t);
	t->exit = e;
	t->radial = r;
	t->radial_var = rv;
	t->var_total = vt;
	memset(e, 0, sizeof *e * (size_t)g->n_theta * (size_t)g->n_phi);
	memset(r, 0, sizeof *r * (size_t)(g->n_r > 0 ? g->n_r : 1));
	if (rv)
		memset(rv, 0, sizeof *rv * (size_t)g->var->n * (size_t)g->n_r);
	if (vt)
		memset(vt, 0, sizeof *vt * (size_t)g->var->n);
}

void tally_add(struct tally *dst, const struct tally *src, const struct tally_grid *g)
{
	dst->rd += src->rd;
	dst->rd_unscat += src->rd_unscat;
	dst->tt += src->tt;
	dst->tt_unscat += src->tt_unscat;
	dst->lost += src->lost;
	dst->rsp += src->rsp;
	dst->facet_loss += src->facet_loss;
	dst->events += src->events;
	for (int i = 0; i < SLAB_MAX_LAYERS + 2; i++)
		dst->a[i] += src->a[i];
	for (int i = 0; i < g->n_theta * g->n_phi; i++)
		dst->exit[i] += src->exit[i];
	for (int i = 0; i < g->n_r; i++)
		dst->radial[i] += src->radial[i];
	if (dst->radial_var && src->radial_var)
		for (long i = 0; i < (long)g->var->n * g->n_r; i++)
			dst->radial_var[i] += src->radial_var[i];
	if (dst->var_total && src->var_total)
		for (int i = 0; i < g->var->n; i++)
			dst->var_total[i] += src->var_total[i];
}

double tally_cos_omega(double t0, double t1, double dphi)
{
	double s0 = sin(t0), s1 = sin(t1);
	return 0.5 * (s1 * s1 - s0 * s0) * 2.0 * dphi;
}

double tally_bin_omega(const struct tally_grid *g, int it)
{
	double dth = 0.5 * M_PI / g->n_theta;
	return (cos(it * dth) - cos((it + 1) * dth)) * 2.0 * M_PI / g->n_phi;
}

double tally_annulus_area(double dr, int i)
{
	return M_PI * dr * dr * (2 * i + 1);
}

double tally_mean_radius(const double *rd_r, int n_r, double dr)
{
	double num = 0.0, den = 0.0;
	for (int i = 0; i < n_r; i++) {
		double rc = (i + 0.5) * dr, area = tally_annulus_area(dr, i);
		num += rc * rd_r[i] * area;
		den += rd_r[i] * area;
	}
	return den > 0.0 ? num / den : 0.0;
}

double tally_mean_radius_err(const double *rd_r, const double *rd_r_err, int n_r, double dr)
{
	double den = 0.0, rm = tally_mean_radius(rd_r, n_r, dr), v = 0.0;
	for (int i = 0; i < n_r; i++)
		den += rd_r[i] * tally_annulus_area(dr, i);
	if (den <= 0.0)
		return 0.0;
	/* R = sum r_i x_i / sum x_i: dR/dx_i = (r_i - R) / sum x. */
	for (int i = 0; i < n_r; i++) {
		double d = ((i + 0.5) * dr - rm) / den * rd_r_err[i] * tally_annulus_area(dr, i);
		v += d * d;
	}
	return sqrt(v);
}
