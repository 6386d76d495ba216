/* The driver logic shared by the double and the Arb Taylor integrators:
 * order from the tolerance, and the step from the coefficient norms
 * N_k = max_i |z_i^[k]|.
 *
 * Jorba & Zou (2005, section 3.2) estimate the radius of convergence from
 * the last two orders and step a fixed fraction of it:
 *   rho = min_{k=p-1,p} (s/N_k)^(1/k),  h = rho e^-2 e^(-0.7/(p-1)),
 * s = max(1, |z|) (s = eps/tol; the tolerance picked the order).
 * NOTE: that reads the tail of the series from two coefficients, and at
 * points of symmetry whole orders vanish: from q = 0 in the well q^4/4, q(t)
 * has terms only at the orders 1 mod 4 and p(t) at 0 mod 4, so N_{p-1} and
 * N_p can both be 0 (an unbounded step), or tiny near q = 0 (a step far too
 * long).  So the step also keeps the terms of the orders below, back to
 * p - HL_FLOW_WINDOW + 1, under eps e^(3.5 (p-1-k)): at Jorba & Zou's step a
 * converging series falls by e^2 an order (N_k h^k ~ eps e^(2 (p-1-k))),
 * so this binds only where
 * an order below is out of line with the last two (an ordinary orbit keeps
 * its step), and then the terms past p, which repeat the pattern, stay
 * near eps.  Where the orders below do bind, and where every order of the
 * window is 0 (q^10/10 from q = 0, or a series that terminates: a free
 * fall), the coefficients are not trusted alone: the driver checks the
 * step itself by its defect (hl_flow_shrink).
 * NOTE: a pattern of vanishing orders longer than the window, near (not
 * at) its point of symmetry, is not seen: q^10/10 near q = 0, where the
 * orders 12..19 are tiny.  The driver checks the first step of a run
 * always, since runs start at such points; an orbit that passes within
 * 1e-6 of one later may lose accuracy there. */
#ifndef HAMLIE_FLOW_IMPL_H
#define HAMLIE_FLOW_IMPL_H

#include <float.h>
#include <math.h>

#include "flow/lnexp.h"
#include "hamlie/error.h"
#include "hamlie/flow.h"
#include "hamlie/tape.h"

#define HL_FLOW_MAX_ORDER 1000

/* The orders the step reads: the last HL_FLOW_WINDOW, p-5..p.  Six see a
 * pattern of up to five vanishing orders (q^6/6 from q = 0 has four). */
#define HL_FLOW_WINDOW 6

/* The orders below p-1 may exceed eps by e^HL_FLOW_SLACK an order (see
 * above): 3.5 leaves the steps of the pendulum, Henon-Heiles and Kepler as
 * Jorba & Zou chose them, and the quartic from q = 0 within its tolerance. */
#define HL_FLOW_SLACK 3.5

/* p = ceil(-ln(tol)/2) + 1 from ln(tol) < 0; at least 2.  NOTE: not at
 * least the window: an order above Jorba & Zou's takes steps nearer the
 * radius of convergence, where the slack below is too loose (order 10 at
 * tol 1e-3 lost the energy of the sextic from q = 0). */
static inline int hl_flow_order_for(double ln_tol)
{
    double p = ceil(-ln_tol / 2) + 1;
    return p < 2 ? 2 : p > HL_FLOW_MAX_ORDER + 1 ? HL_FLOW_MAX_ORDER + 1 : (int)p;
}

/* Below this order every step is checked by its defect (hl_flow_shrink):
 * a low order's window sees too little of the series (at order 4, tol
 * 1e-2, the sextic and octic wells took steps that lost all their energy,
 * from any point).  Tolerances above 1.5e-8 only. */
#define HL_FLOW_CHECK_BELOW 10

/* The lowest order of the window (order 0, the state, is not in it). */
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

/* Jorba & Zou's factor on the radius of convergence: e^-2 so that order p
 * = -ln(tol)/2 + 1 makes the last term (h/rho)^p about tol e^-2, and
 * e^(-0.7/(p-1)) for the tail past it.  heyoka (taylor_00.cpp,
 * taylor_determine_h_rhofac) uses the same; an earlier rule here read eps
 * into the radius itself, h = (eps/N_k)^(1/k), which is eps^(1/p) ~ e^-1.8
 * of the radius instead of e^-2: 8-11 % longer steps and up to 10x the
 * error of heyoka at the same tol (issue 17). */
static inline double hl_flow_ln_safety(int p)
{
    return -2 - 0.7 / (p - 1);
}

/* The order and the step of a flow: h = rho e^ln_ratio, rho the radius
 * of convergence read from the orders p-1 and p (hl_flow_step_for). */
typedef struct hl_flow_rule {
    int p;
    double ln_tol;   /* the tolerance (its log) */
    double ln_ratio; /* ln(h / rho) < 0 */
} hl_flow_rule;

/* Jorba & Zou's rule: p = hl_flow_order_for, ln_ratio = hl_flow_ln_safety
 * (heyoka's order and steps; the Arb integrator's rule). */
void hl_flow_rule_jz(hl_flow_rule *rule, double ln_tol);

/* hl_flow_rule_for raises the order while the step it allows stays under
 * e^-1.5 of the radius: the series still falls by e^1.5 an order (as it
 * falls by e^2 at Jorba & Zou's), so the window's slack (e^3.5 an order)
 * still tells a vanishing order from a falling one, and the tail past the
 * order stays a few times its first term. */
#define HL_FLOW_MAX_LN_RATIO (-1.5)

/* The rule at order p whose step leaves the tail past p a tenth of Jorba
 * & Zou's at their order (at their order their rule).  A tenth, not the
 * same: at the same tail the errors of a run at a raised order were
 * smaller than heyoka's on average (0.45 geometric mean over the four
 * systems of docs/work-precision.md, tol 1e-9 .. 1e-13, t = 1e4) but
 * larger at 3 points of 20 (Henon-Heiles at 1e-13: 6.6e-12 against
 * 4.3e-12), for the orbit's errors scatter by factors of 2 to 5 from one
 * order to the next.  A tenth costs ln(10)/(p+1), about 9 %, of the step. */
#define HL_FLOW_RAISED_MARGIN 2.302585092994046 /* ln 10 */
void hl_flow_rule_at(hl_flow_rule *rule, double ln_tol, int p);

/* hl_flow_new at a given order (0: the rule's) with hl_flow_rule_at's
 * step: for the benches that measure the cost of a step against the order
 * (bench/work_precision.c order=P) and for tests.  HL_EINVAL outside
 * 2 .. HL_FLOW_MAX_ORDER. */
hl_status hl_flow_new_order(hl_flow **out, hl_tape *f, double atol, double rtol, int order,
                            hl_error *err);

/* The double integrator's rule for the field f: the order that costs
 * least per unit time by the tape's cost model (hl_tape_taylor_step_cost),
 * with the step at that order whose tail is Jorba & Zou's (rule.c). */
void hl_flow_rule_for(hl_flow_rule *rule, double ln_tol, const hl_tape *f);

/* The step's ln and exp are lnexp.h's, not libm's, and the step is taken
 * e^-HL_FLOW_LNEXP_DELTA shorter, which covers their errors and the
 * roundings of the formula: the step is never longer than the rule's exact
 * value.  ln h = min_k (ln s - ln N_k) (1/k) + ln_ratio; the errors in
 * ln h: ln s 2e-16 + 2.5e-16 |ln s| (|ln s| <= 709.8), ln N_k as much
 * (|ln N_k| <= 708.4; libm's 1.1e-16 |ln N_k| for a subnormal N_k, <= 744.4),
 * their difference L 1.1e-16 |L| (|L| <= 1455), the product by the rounded
 * 1/k 2.2e-16 |L| / k (k >= 2; exact for k = 1), ln_ratio - delta 2.2e-16,
 * the sum 1.1e-16 |ln h|, the exp 4e-16 (|ln h| <= 708; beyond, libm's exp:
 * the step is 0 or huge, and clipped).  At most 7.7e-13 in all. */
#define HL_FLOW_LNEXP_DELTA 1e-12

/* hl_flow_step_for's body for a window of nw orders, inlined twice: with
 * nw the constant HL_FLOW_WINDOW (every order from 6 on) its loops unroll,
 * the same operations in the same order (the same bits), where the loops'
 * counting was a fifth of the rule's instructions. */
static inline __attribute__((always_inline)) double hl_flow_step_window(int *check, double eps,
                                                                        double s,
                                                                        const hl_flow_rule *rule,
                                                                        const double *win, int nw)
{
    const int p = rule->p, lo = p - nw + 1;
    double sum = 0;
    for (int j = 0; j < nw; j++)
        sum += win[j]; /* NaN or inf if a norm is */
    *check = 1; /* unless the window vouches for the step */
    if (!isfinite(sum))
        return NAN;
    if (sum == 0)
        return INFINITY;
    /* Jorba & Zou: the radius rho = min_{k=p-1,p} (s / N_k)^(1/k) and h = rho
     * times the safety factor, h = e^(min_k ln(s / N_k) / k + ln_ratio).  Both
     * orders, side by side, without a branch: the step is one chain of
     * dependences (state, recursion, step, state), and order p first, p-1
     * only where h broke its bound (a third of Kepler's steps; one log fewer
     * on average) made that chain longer, the pendulum's steps 4 % slower.
     * For the same reason ln s - ln N_k and the product by 1/k, not the log
     * of a quotient and a division: s is known before the recursion ends,
     * 1/k from the order, so no division waits on N_k (a third log, 40
     * instructions, but 2-4 % faster steps on the pendulum and Henon-Heiles,
     * the same on Kepler); lnexp.h's ln and exp (HL_FLOW_LNEXP_DELTA). */
    const double Np = win[nw - 1], Nq = win[nw - 2];
    const double ln_s = hl_flow_ln(s); /* libm's where s is not normal: s = inf */
    double lp = Np > 0 ? (ln_s - hl_flow_ln(Np)) * (1.0 / p) : INFINITY;
    double lq = Nq > 0 ? (ln_s - hl_flow_ln(Nq)) * (1.0 / (p - 1)) : INFINITY;
    double h = hl_flow_exp((lq < lp ? lq : lp) + (rule->ln_ratio - HL_FLOW_LNEXP_DELTA));
    /* the orders below: N_k h^k <= eps e^(3.5 (p-1-k)).  First all at once,
     * without logs or branches (most steps end here)... */
    double worst = 0, pw = hl_flow_powi(h, lo);
    double c = lo > 1 ? exp(-HL_FLOW_SLACK * (HL_FLOW_WINDOW - 2)) : exp(-HL_FLOW_SLACK * (p - 2));
    for (int j = 0; j < nw - 2; j++, pw *= h, c *= exp(HL_FLOW_SLACK)) {
        double t = win[j] * pw * c; /* NaN if N_k = 0 and h^k = inf: no bound */
        worst = t > worst ? t : worst;
    }
    *check = p < HL_FLOW_CHECK_BELOW;
    if (worst <= eps && h < INFINITY)
        return h;
    /* ...else one by one, solved where it fails; a shorter h keeps the
     * orders already passed.  The step an order below allows keeps only the
     * tail's factor e^(-0.7/(p-1)): its bound already says how far below
     * eps that order must be, and the defect check (hl_flow_shrink) has the
     * last word on such a step.  In the log domain: eps may underflow. */
    double ln_eps = rule->ln_tol + ln_s, lh = log(h);
    double bound = eps * exp(HL_FLOW_SLACK), hk = hl_flow_powi(h, p - 2), inv_h = 1 / h;
    for (int k = p - 2; k >= lo; k--, bound *= exp(HL_FLOW_SLACK), hk *= inv_h) {
        if (win[k - lo] > 0 && !(win[k - lo] * hk <= bound)) { /* NaN (h = inf) fails too */
            double lk =
                (ln_eps + HL_FLOW_SLACK * (p - 1 - k) - log(win[k - lo])) / k - 0.7 / (p - 1);
            if (lk < lh) { /* not if eps underflowed: the test failed wrongly */
                *check = 1;
                lh = lk;
                h = exp(lh);
                hk = hl_flow_powi(h, k);
                inv_h = 1 / h;
            }
        }
    }
    return h;
}

/* The step from win[k - lo] = N_k, k = lo..p (lo = hl_flow_window_lo), for
 * the tolerance eps of this step, the scale s = eps / tol of the state (1
 * in absolute mode, |z| in relative; > 0 and normal) and the rule's order
 * p, tolerance ln_tol and step ratio (eps = tol max(1, |z|) when atol =
 * rtol = tol).  eps may underflow where s does not (the Arb integrator at
 * many digits): then the test of the window below fails and the log domain
 * decides.  Returns > 0; +inf when every N_k of the window is 0; NaN when
 * one is not finite.  *check = 1 if the step is to be checked
 * (hl_flow_shrink), else 0. */
static inline double hl_flow_step_for(int *check, double eps, double s, const hl_flow_rule *rule,
                                      const double *win)
{
    const int nw = rule->p - hl_flow_window_lo(rule->p) + 1;
    return nw == HL_FLOW_WINDOW ? hl_flow_step_window(check, eps, s, rule, win, HL_FLOW_WINDOW)
                                : hl_flow_step_window(check, eps, s, rule, win, nw);
}

/* The tolerances of a double flow (flow.c, batch.c): atol, rtol, and
 * their quotients by tol = min(atol, rtol) (not below HL_FLOW_MIN_RTOL),
 * so that the scale s = eps / tol of a step needs no log. */
typedef struct hl_flow_tols {
    double atol, rtol, s_atol, s_rtol;
} hl_flow_tols;

/* Returns ln(tol), the rule's tolerance: an atol far below rtol only says
 * that the relative error counts near 0; an order from it would not be
 * reached in double. */
static inline double hl_flow_tols_set(hl_flow_tols *t, double atol, double rtol)
{
    double tol = fmax(fmin(atol, rtol), HL_FLOW_MIN_RTOL);
    *t = (hl_flow_tols){atol, rtol, atol / tol, rtol / tol};
    return log(tol);
}

/* The tolerance eps of a step from the state's norm n0 = |z|_inf, and its
 * scale s = eps / tol: relative where rtol n0 > atol, else absolute. */
static inline double hl_flow_scale(const hl_flow_tols *t, double n0, double *eps)
{
    int relative = t->rtol * n0 > t->atol;
    *eps = relative ? t->rtol * n0 : t->atol;
    return relative ? t->s_rtol * n0 : t->s_atol;
}

/* win[j] = max(win[j], |cw[j L]|) for j < nw, and their sum (the maxima
 * drop NaN; a sum keeps it).  Inlined: with nw the constant window (any
 * order from 6 on, one step of the hot loop) it unrolls. */
static inline __attribute__((always_inline)) double hl_flow_add_norms(double *win, const double *cw,
                                                                      int nw, int L)
{
    double sum = 0;
    for (int j = 0; j < nw; j++) {
        double a = fabs(cw[(size_t)j * L]);
        win[j] = a > win[j] ? a : win[j];
        sum += a;
    }
    return sum;
}

/* The norms a step reads off its coefficients: N_0 = max_i |z_i| (the
 * return) and win[k - lo] = N_k = max_i |z_i^[k]| for k = lo..p (lo =
 * hl_flow_window_lo), win[p - lo] NaN if a coefficient of the window is
 * not finite.  Component i's order k at c[(i S + k) L] (S = p + 1): L = 1
 * for flow.c's layout, the lanes' count for batch.c's. */
static inline __attribute__((always_inline)) double hl_flow_norms(double *win, const double *c,
                                                                  int n, int p, int L)
{
    const int S = p + 1, lo = hl_flow_window_lo(p), nw = p - lo + 1;
    double n0 = 0, sum = 0;
    for (int j = 0; j < HL_FLOW_WINDOW; j++)
        win[j] = 0;
    for (int i = 0; i < n; i++) {
        const double *ci = c + (size_t)i * S * L;
        double a0 = fabs(ci[0]);
        n0 = a0 > n0 ? a0 : n0;
        sum += nw == HL_FLOW_WINDOW ? hl_flow_add_norms(win, ci + (size_t)lo * L, HL_FLOW_WINDOW, L)
                                    : hl_flow_add_norms(win, ci + (size_t)lo * L, nw, L);
    }
    if (!isfinite(sum))
        win[nw - 1] = NAN;
    return n0;
}

/* NOTE: where the field has an essential singularity (sin(1/p) at p = 0,
 * reached at a finite time t*) the steps shrink like (t* - t)^2, not like
 * t* - t as at a pole (1/p): t creeps towards t* and the step falls below
 * the rounding of t only after some 1e8 steps, so the run took minutes (the
 * zoo's N7).  The driver therefore measures its pace, the time covered by
 * each block of HL_FLOW_BLOCK steps, and stops, with "no progress", a flow
 * whose pace has fallen below 1/HL_FLOW_SLOWDOWN of its fastest: an orbit
 * that only passes near a singularity (Kepler's pericentre) takes a few
 * hundred short steps there, not thousands. */
#define HL_FLOW_BLOCK 4096
#define HL_FLOW_SLOWDOWN 1e6

typedef struct {
    long n;      /* steps taken in the current block */
    double done; /* the time they covered */
    double best; /* the most a block of the flow covered */
} hl_flow_pace; /* zero to start */

/* After a step of length h > 0: 1 if the block it ends went too slowly
 * (see above), with *done the time that block covered. */
static inline int hl_flow_stalled(hl_flow_pace *pace, double h, double *done)
{
    pace->done += h;
    if (++pace->n < HL_FLOW_BLOCK)
        return 0;
    *done = pace->done;
    pace->n = 0;
    pace->done = 0;
    pace->best = *done > pace->best ? *done : pace->best;
    return *done * HL_FLOW_SLOWDOWN < pace->best;
}

static inline int hl_flow_no_progress(hl_error *err, double done, double t)
{
    return hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                        "no progress: %d steps covered %g only, at t = %.17g "
                        "(a singularity of the field?)",
                        HL_FLOW_BLOCK, done, t);
}

/* A step that the window does not vouch for is checked by its defect,
 * d = P'(h) - f(P(h)) for the step's polynomial P: the tail past p is
 * about h |d|_inf / (p+1) (its first term's derivative dominates).
 * Returns 0 to take h, else the next, shorter h to try. */
static inline double hl_flow_shrink(double h, double defect, double eps, int p)
{
    double err = h * defect / (p + 1);
    if (err <= eps)
        return 0;
    double f = isfinite(err) ? 0.9 * pow(eps / err, 1.0 / (p + 1)) : 0.1;
    return h * (f < 0.1 ? 0.1 : f > 0.9 ? 0.9 : f);
}

#endif
