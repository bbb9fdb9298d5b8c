/* macro: the macro-scale roughness over a facet BRDF (see macro.h): a
 * product Gauss-Hermite rule over Gaussian slopes and the Beckmann surface's
 * height-correlated Smith term. */
#include "config.h"
#include "engine/macro.h"

#include <math.h>

#include "engine/microfacet.h"

/* The orthonormal Hermite polynomials of the standard normal density,
 * p_{k+1} = (x p_k - sqrt(k) p_{k-1}) / sqrt(k + 1): p_n(x) into *pn,
 * p_{n-1}(x) into *pm and sum_{k<n} p_k(x)^2 into *s2. */
static void hermite(int n, double x, double *pn, double *pm, double *s2)
{
	double a = 0.0, b = 1.0, s = 0.0;	/* p_{k-1}, p_k */
	for (int k = 0; k < n; k++) {
		s += b * b;
		double c = (x * b - sqrt((double)k) * a) / sqrt(k + 1.0);
		a = b;
		b = c;
	}
	*pn = b;
	*pm = a;
	*s2 = s;
}

/* Nodes x and weights w (summing to 1) of the n-point Gauss rule for the
 * standard normal density: the roots of p_n, bracketed by a scan and
 * polished by bisection; the weights are 1 / sum_{k<n} p_k(x)^2
 * (Christoffel numbers of an orthonormal family). */
static int gauss_hermite(int n, double *x, double *w)
{
	double lim = sqrt(4.0 * n + 2.0) + 1.0, h = lim / (40.0 * n), pn, pm, s2;
	int found = 0;
	hermite(n, -lim, &pn, &pm, &s2);
	double xa = -lim, fa = pn;
	for (double xb = -lim + h; xb <= lim + 0.5 * h && found < n; xb += h) {
		hermite(n, xb, &pn, &pm, &s2);
		double fb = pn;
		if ((fa < 0.0) != (fb < 0.0)) {
			double lo = xa, hi = xb, flo = fa;
			for (int it = 0; it < 80; it++) {
				double mid = 0.5 * (lo + hi);
				hermite(n, mid, &pn, &pm, &s2);
				if ((pn < 0.0) == (flo < 0.0)) {
					lo = mid;
					flo = pn;
				} else
					hi = mid;
			}
			x[found++] = 0.5 * (lo + hi);
		}
		xa = xb;
		fa = fb;
	}
	double sum = 0.0;
	for (int i = 0; i < found; i++) {
		hermite(n, x[i], &pn, &pm, &s2);
		w[i] = 1.0 / s2;
		sum += w[i];
	}
	for (int i = 0; i < found; i++)
		w[i] /= sum;	/* sums to 1 already up to rounding */
	return found;
}

void macro_rule_init(struct macro_rule *r, double m_rms, int nq)
{
	r->m_rms = fmin(fmax(m_rms, 0.0), MACRO_SLOPE_MAX);
	r->n = 0;
	if (!(r->m_rms > 0.0))
		return;
	nq = nq < 2 ? 2 : nq > MACRO_NQ_MAX ? MACRO_NQ_MAX : nq;
	double x[MACRO_NQ_MAX], w[MACRO_NQ_MAX];
	int k = gauss_hermite(nq, x, w);
	/* Each slope component is normal with standard deviation m / sqrt(2). */
	double s = r->m_rms / sqrt(2.0);
	for (int a = 0; a < k; a++)
		for (int b = 0; b < k; b++) {
			double p = s * x[a], q = s * x[b], l = sqrt(1.0 + p * p + q * q);
			double *m = r->m[r->n];
			m[0] = -p / l;
			m[1] = -q / l;
			m[2] = 1.0 / l;
			r->w[r->n++] = w[a] * w[b];
		}
}

double macro_g2(const struct macro_rule *r, double cos_i, double cos_o)
{
	if (!(r->m_rms > 0.0))
		return 1.0;
	struct microfacet b = { MICROFACET_BECKMANN, r->m_rms, OPTICS_FRESNEL_EXACT };
	return 1.0 / (1.0 + microfacet_lambda(&b, cos_i) + microfacet_lambda(&b, cos_o));
}

static double dot(const double *a, const double *b)
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The rule in the frame where wi (swap = 0) or wo (swap = 1) has azimuth
 * 0; f always gets the incoming and outgoing angles in their own roles. */
static void eval_one(const struct macro_rule *r, macro_fn f, void *ctx, int n, double ti, double to,
    double dphi, int swap, double *out)
{
	double v[MACRO_MAX_OUT], ta = swap ? to : ti, tb = swap ? ti : to;
	double u[3] = { sin(ta), 0.0, cos(ta) };
	double w[3] = { sin(tb) * cos(dphi), sin(tb) * sin(dphi), cos(tb) };
	const double *wi = swap ? w : u, *wo = swap ? u : w;
	double scale = macro_g2(r, wi[2], wo[2]) / (wi[2] * wo[2]);
	for (int j = 0; j < n; j++)
		out[j] = 0.0;
	for (int k = 0; k < r->n; k++) {
		const double *m = r->m[k];
		double ci = dot(wi, m), co = dot(wo, m);
		if (ci <= 0.0 || co <= 0.0)
			continue;
		/* The local azimuth: the angle between wi and wo projected on the facet. */
		double a[3], b[3];
		for (int j = 0; j < 3; j++) {
			a[j] = wi[j] - ci * m[j];
			b[j] = wo[j] - co * m[j];
		}
		double na = sqrt(dot(a, a)), nb = sqrt(dot(b, b));
		double cp = na > 1e-12 && nb > 1e-12 ? dot(a, b) / (na * nb) : 1.0;
		double ph = acos(fmin(fmax(cp, -1.0), 1.0));
		f(ctx, acos(fmin(ci, 1.0)), acos(fmin(co, 1.0)), ph, v);
		double wk = r->w[k] * ci * co / m[2] * scale;
		for (int j = 0; j < n; j++)
			out[j] += wk * v[j];
	}
}

void macro_eval(const struct macro_rule *r, macro_fn f, void *ctx, int n, double theta_i,
    double theta_o, double dphi, double *out)
{
	if (r->n == 0) {
		f(ctx, theta_i, theta_o, dphi, out);
		return;
	}
	/* The rule is fixed over the slopes, so swapping the directions (a
	 * rotation of the pair) moves its nodes: the mean over the two frames is
	 * reciprocal by construction for a reciprocal f, at twice the cost. */
	const double tmax = 89.95 * M_PI / 180.0;
	double ti = fmin(fmax(theta_i, 0.0), tmax), to = fmin(fmax(theta_o, 0.0), tmax);
	double b[MACRO_MAX_OUT];
	eval_one(r, f, ctx, n, ti, to, dphi, 0, out);
	eval_one(r, f, ctx, n, ti, to, dphi, 1, b);
	for (int j = 0; j < n; j++)
		out[j] = 0.5 * (out[j] + b[j]);
}
