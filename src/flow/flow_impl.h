/* The driver logic shared by the double and the Arb Taylor integrators:
 * order from the tolerance and step from the last two coefficient norms
 * (Jorba & Zou 2005, section 3.2). */
#ifndef HAMLIE_FLOW_IMPL_H
#define HAMLIE_FLOW_IMPL_H

#include <math.h>

#define HL_FLOW_MAX_ORDER 1000

/* p = ceil(-ln(tol)/2) + 1 from ln(tol) < 0; at least 2. */
static inline int hl_flow_order_for(double ln_tol)
{
    double p = ceil(-ln_tol / 2) + 1;
    return p < 2 ? 2 : p > HL_FLOW_MAX_ORDER + 1 ? HL_FLOW_MAX_ORDER + 1 : (int)p;
}

/* h = min_{k=p-1,p} (eps/|z^[k]|)^(1/k) * exp(-0.7/(p-1)) with ln_eps =
 * ln(eps); +inf when both norms are 0 (the series terminates), NaN when a
 * norm is not finite. */
static inline double hl_flow_step_for(double ln_eps, double norm_pm1, double norm_p, int p)
{
    if (!isfinite(norm_pm1) || !isfinite(norm_p))
        return NAN;
    /* in the log domain, so that one exp gives the step */
    double e = INFINITY;
    if (norm_pm1 > 0)
        e = (ln_eps - log(norm_pm1)) / (p - 1);
    if (norm_p > 0) {
        double e2 = (ln_eps - log(norm_p)) / p;
        e = e2 < e ? e2 : e;
    }
    return e == INFINITY ? INFINITY : exp(e - 0.7 / (p - 1));
}

#endif
