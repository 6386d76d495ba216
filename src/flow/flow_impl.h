/* The driver logic shared by the double and the Arb Taylor integrators:
 * order from the tolerance, and the step from the coefficient norms
 * N_k = max_i |z_i^[k]|.
 *
 * Jorba & Zou (2005, section 3.2) take the step at which the terms of the
 * last two orders are eps:  h = min_{k=p-1,p} (eps/N_k)^(1/k) e^(-0.7/(p-1)).
 * NOTE: that reads the tail of the series from two coefficients, and at
 * points of symmetry whole orders vanish: from q = 0 in the well q^4/4, q(t)
 * has terms only at the orders 1 mod 4 and p(t) at 0 mod 4, so N_{p-1} and
 * N_p can both be 0 (an unbounded step), or tiny near q = 0 (a step far too
 * long).  So the step also keeps the terms of the orders below, back to
 * p - HL_FLOW_WINDOW + 1, under eps e^(3 (p-1-k)): at Jorba & Zou's step a
 * converging series falls by about e^2 an order, so this binds only where
 * an order below is out of line with the last two (an ordinary orbit keeps
 * its step), and then the terms past p, which repeat the pattern, are under
 * eps.  If every order of the window is 0, the coefficients say nothing of
 * the tail (q^10/10 from q = 0, or a series that terminates: a free fall):
 * the driver then checks the step itself (hl_flow_shrink). */
#ifndef HAMLIE_FLOW_IMPL_H
#define HAMLIE_FLOW_IMPL_H

#include <math.h>

#define HL_FLOW_MAX_ORDER 1000

/* The orders the step reads: the last HL_FLOW_WINDOW.  Six see a pattern
 * of up to five vanishing orders (q^6/6 from q = 0 has four). */
#define HL_FLOW_WINDOW 6

/* p = ceil(-ln(tol)/2) + 1 from ln(tol) < 0; at least 2. */
static inline int hl_flow_order_for(double ln_tol)
{
    double p = ceil(-ln_tol / 2) + 1;
    return p < 2 ? 2 : p > HL_FLOW_MAX_ORDER + 1 ? HL_FLOW_MAX_ORDER + 1 : (int)p;
}

/* The lowest order of the window. */
static inline int hl_flow_window_lo(int p)
{
    return p - HL_FLOW_WINDOW + 1 < 1 ? 1 : p - HL_FLOW_WINDOW + 1;
}

/* x^k for k >= 0 by squaring */
static inline double hl_flow_powi(double x, int k)
{
    double r = 1;
    for (; k > 0; k >>= 1, x *= x)
        if (k & 1)
            r *= x;
    return r;
}

/* The step from norm[k] = N_k, k = hl_flow_window_lo(p)..p, for the
 * tolerance eps and ln_eps = ln(eps) (eps may underflow where ln_eps does
 * not: then the test below fails and the log domain decides): > 0; +inf
 * when every N_k of the window is 0 (then see hl_flow_shrink); NaN when
 * one is not finite. */
static inline double hl_flow_step_for(double eps, double ln_eps, const double *norm, int p)
{
    const int lo = hl_flow_window_lo(p);
    double sum = 0;
    for (int k = lo; k <= p; k++)
        sum += norm[k]; /* NaN or inf if a norm is */
    if (!isfinite(sum))
        return NAN;
    if (sum == 0)
        return INFINITY;
    /* Jorba & Zou, in the log domain so that one exp gives the step */
    double e = INFINITY;
    for (int k = p - 1; k <= p; k++)
        if (norm[k] > 0)
            e = fmin(e, (ln_eps - log(norm[k])) / k);
    const double fudge = -0.7 / (p - 1);
    double h = exp(e + fudge);
    /* the orders below: N_k h^k <= eps e^(3 (p-1-k)), tested without logs
     * (h = inf makes any nonzero N_k h^k inf) and solved where it fails */
    double bound = eps * exp(3.0), hk = hl_flow_powi(h, p - 2);
    for (int k = p - 2; k >= lo; k--, bound *= exp(3.0), hk /= h) {
        if (norm[k] > 0 && !(norm[k] * hk <= bound)) { /* NaN (inf/inf) fails too */
            double ek = (ln_eps + 3.0 * (p - 1 - k) - log(norm[k])) / k;
            if (ek < e) {
                e = ek;
                h = exp(e + fudge);
                hk = hl_flow_powi(h, k);
            }
        }
    }
    return h;
}

/* A step chosen without the window (every order of it 0) is checked by
 * its defect, d = P'(h) - f(P(h)) for the step's polynomial P: the tail
 * past p is about h |d|_inf / (p+1) (its first term's derivative
 * dominates).  Returns 0 to take h, else the next, shorter h to try. */
static inline double hl_flow_shrink(double h, double defect, double eps, int p)
{
    double err = h * defect / (p + 1);
    if (err <= eps)
        return 0;
    double f = isfinite(err) ? 0.9 * pow(eps / err, 1.0 / (p + 1)) : 0.1;
    return h * (f < 0.1 ? 0.1 : f > 0.9 ? 0.9 : f);
}

#endif
