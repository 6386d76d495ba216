/* The order and the step of the double Taylor integrator (flow.h), one
 * rule for hl_flow and hl_flow_batch so that both take the same steps.
 *
 * Jorba & Zou's order p = ceil(-ln tol / 2) + 1 (heyoka's) is the cheapest
 * per unit time if a step costs as the square of its order (the products'
 * convolutions).  A step really costs c0 + c1 p + c2 p^2 (the step rule
 * and the loop, the driver's sums over the coefficients, the products),
 * more past a knee in the compiled code's size (hl_tape_taylor_step_ns),
 * so where c0 and c1 matter (small systems) a higher order with a longer
 * step is cheaper, up to the knee.
 * The step at the higher order leaves the same tail past the order as
 * Jorba & Zou's step at theirs: the same estimated error per step, in fewer
 * steps (docs/tolerance.md). */
#include <float.h>
#include <math.h>

#include "flow/flow_impl.h"

void hl_flow_rule_jz(hl_flow_rule *rule, double ln_tol)
{
    rule->p = hl_flow_order_for(ln_tol);
    rule->ln_tol = ln_tol;
    rule->ln_ratio = hl_flow_ln_safety(rule->p);
}

/* ln of the tail past order p, sum_{k>p} r^k = r^(p+1) / (1 - r), of a
 * series that falls by r = h/rho an order (in units of the scale s). */
static double ln_tail(int p, double ln_r)
{
    return (p + 1) * ln_r - log1p(-exp(ln_r));
}

/* The ln r < 0 at which ln_tail(p, ln r) = target, by fixed point: the map
 * contracts by r / (1 - r) / (p + 1) < 0.02 for r < e^-1.5 and p >= 10. */
static double ratio_for_tail(int p, double target)
{
    double ln_r = target / (p + 1);
    for (int i = 0; i < 8; i++)
        ln_r = (target + log1p(-exp(ln_r))) / (p + 1);
    return ln_r;
}

void hl_flow_rule_at(hl_flow_rule *rule, double ln_tol, int p)
{
    hl_flow_rule_jz(rule, ln_tol);
    if (p == rule->p)
        return;
    double target = ln_tail(rule->p, rule->ln_ratio) - HL_FLOW_RAISED_MARGIN;
    rule->p = p;
    rule->ln_ratio = ratio_for_tail(p, target);
}

/* A step's cost per unit time, in units of the radius of convergence:
 * the cost of a step at the rule's order over its fraction of the radius. */
static double cost_per_time(const hl_tape *f, const hl_flow_rule *rule)
{
    return hl_tape_taylor_step_ns(f, rule->p) * exp(-rule->ln_ratio);
}

/* What Jorba & Zou's order would cost per unit time with the raised
 * orders' tail (a tenth of theirs, HL_FLOW_RAISED_MARGIN): the orders are
 * compared at the same estimated error, not the raised ones at a tenth of
 * Jorba & Zou's.  NOTE: compared at their own tail, Jorba & Zou's order won
 * by the margin's 10^(1/(p+1)) where a raised one was as cheap, and the
 * error jumped up as the tolerance fell (Kepler, t = 1e3: 2.6e-11 at tol
 * 1e-11, order 18; 1.3e-10 at 1e-13, order 16; flow/t-tol).  If none is
 * cheaper, the steps stay theirs (heyoka's). */
static double cost_at_raised_tail(const hl_tape *f, const hl_flow_rule *jz)
{
    hl_flow_rule at = *jz;
    at.ln_ratio = ratio_for_tail(jz->p, ln_tail(jz->p, jz->ln_ratio) - HL_FLOW_RAISED_MARGIN);
    return cost_per_time(f, &at);
}

/* NOTE: where Jorba & Zou's tail is below double's rounding (tol under
 * about 1e-13: the tail is some tol/100) the order stays theirs: there a
 * longer step buys no accuracy, only larger terms to round (the
 * oscillator at order 26, tol 1e-15, erred 2-4 times more than at 19 over
 * t = 3e3 .. 5e4; Henon-Heiles and Kepler at raised orders, tol 1e-14 ..
 * 1e-16, up to 6 times heyoka's error at its order).  Those steps are
 * heyoka's, and the compensated state update keeps their errors below its
 * (docs/work-precision.md). */
void hl_flow_rule_for(hl_flow_rule *rule, double ln_tol, const hl_tape *f)
{
    hl_flow_rule_jz(rule, ln_tol);
    if (rule->p < HL_FLOW_CHECK_BELOW)
        return; /* below, every step is checked: the orders stay Jorba & Zou's */
    if (ln_tail(rule->p, rule->ln_ratio) < log(DBL_EPSILON))
        return;
    double best = cost_at_raised_tail(f, rule);
    for (int p = rule->p + 1; p <= HL_FLOW_MAX_ORDER; p++) {
        hl_flow_rule at;
        hl_flow_rule_at(&at, ln_tol, p);
        if (at.ln_ratio > HL_FLOW_MAX_LN_RATIO)
            break;
        double cost = cost_per_time(f, &at);
        if (cost < best) {
            best = cost;
            *rule = at;
        }
    }
}
