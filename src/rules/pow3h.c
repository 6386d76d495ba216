/* a^(3/2): Kepler's r^3 (the tape compiler writes w^(3/2) and sqrt(w) w as
 * this op).  A power whose exponent the rule knows, so that no back end
 * calls pow().
 *
 * Point value a sqrt(a): two roundings, at most about 1.25 ulp (measured
 * with mpmath over random and hard arguments by bench/pow3h_ulp.py; glibc's
 * pow is within 0.51 ulp) for a tenth of pow's time.  sqrt(a a a) is no more
 * accurate (three roundings, the first two halved by the root) and
 * overflows from a ~ 5.6e102; a correction by fma (p = a r, r = sqrt(a):
 * p + (fma(a, r, -p) - fma(r, r, -a) r / 2)) is within 0.5 ulp but turns an
 * overflowing p into NaN, and the emitters have no select.  Out of the
 * domain as pow: a < 0 gives NaN, +-0 gives +0, +inf gives +inf; only
 * -inf differs (NaN here, +inf from pow).
 *
 * Taylor recurrence: pow.c's with c = 3/2 as constants (weights 5/2 m - k),
 * one weighted convolution a coefficient; cheaper than sqrt's series times
 * a (a symmetric convolution and a product).  The kept ratio c d[0] / a[0]
 * is 3/2 sqrt(a[0]): two roundings instead of four.  Its derivative (d[1])
 * is then 3/2 sqrt(a[0]) a[1]. */
#include "rules/rules_impl.h"

static hl_ev pow3h_point_of(hl_em *E, hl_ev *root)
{
    hl_ev a0 = EV_COEF(E, A, 0);
    *root = EV_CALL(E, HL_PFN_SQRT, a0);
    return EV_MUL(E, a0, *root);
}

static void pow3h_point(hl_em *E)
{
    hl_ev root;
    EV_STORE(E, D, 0, pow3h_point_of(E, &root));
}

static void pow3h_taylor(hl_em *E, int k)
{
    if (k == 0) {
        hl_ev root;
        EV_STORE(E, D, 0, pow3h_point_of(E, &root));
        rule_keep_inverse(E, EV_COEF(E, A, 0));
        EV_KEEP(E, KEEP_RATIO, EV_MUL(E, EV_NUM(E, 3, 2), root));
        return;
    }
    rule_pow_step(E, k, EV_NUM(E, 5, 2));
}
const hl_rule hl_rule_pow3h = {"pow3h", pow3h_point, pow3h_taylor};
