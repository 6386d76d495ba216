/* sqrt(a).  From d^2 = a: d[k] = (a[k] - sum_{j=1..k-1} d[j] d[k-j]) / (2 d[0]),
 * the sum by symmetry, 1/(2 d[0]) kept from k = 0. */
#include "rules/rules_impl.h"

static void sqrt_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_SQRT, EV_COEF(E, A, 0))); }

static void sqrt_taylor(hl_em *E, int k)
{
    if (k == 0) {
        sqrt_point(E);
        rule_keep_inverse(E, EV_MUL(E, EV_NUM(E, 2, 1), EV_COEF(E, D, 0)));
        return;
    }
    int has;
    hl_ev s = rule_sqr(E, D, 1, k, &has);
    EV_STORE(E, D, k, EV_MUL(E, rule_minus(E, EV_COEF(E, A, k), s, has), EV_KEPT(E, KEEP_INV)));
}
const hl_rule hl_rule_sqrt = {"sqrt", sqrt_point, sqrt_taylor};
