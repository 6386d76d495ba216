/* a^(3/2): Kepler's r^3 (the tape compiler writes w^(3/2), sqrt(w) w and
 * sqrt(w)^3 as this op).  A power whose exponent the rule knows, so that no
 * back end calls pow(): a fixed-step Kepler run costs what the loop written
 * by hand does (bench/run-fixed-process.sh), not twice as much.
 *
 * Point value a sqrt(a), the hand loop's: two roundings, so under 2 ulp;
 * at most 1.27 ulp seen and 0.34 ulp on average, correctly rounded three
 * times in four (bench/pow3h_ulp.py against mpmath; glibc's pow: 0.505 ulp,
 * 0.25 on average).  Nothing as cheap is better everywhere:
 *   - sqrt(a a a): 1.17 ulp at most, 0.30 on average in [1, 4), but a^3
 *     overflows from a ~ 5.6e102 and loses its digits below a ~ 1e-103;
 *   - fma(a, r, -(fma(r, r, -a) (r/2))), r = sqrt(a) (a sqrt(a) is
 *     a r - (r^2 - a) r/2 up to u^2): 0.50 ulp, for two fma and a product
 *     more, but where the result overflows, the correction (u times the
 *     result) does too from a ~ 2^720, and about half of those a then give
 *     -inf; +inf gives NaN.  Safe only with a select the emitters lack.
 * Out of the finite positives as pow: a < 0 gives NaN, +-0 gives +0, +inf
 * gives +inf; only -inf differs (NaN here, +inf from pow).
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
