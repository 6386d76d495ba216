/* asinh(a), with X = sqrt(1 + a^2).  From x d' = a':
 *   x[k] = ((a*a)[k] - sum_{j=1..k-1} x[j] x[k-j]) / (2 x[0])   (the sqrt rule on 1 + a^2),
 *   d[k] = (k a[k] - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]). */
#include "rules/rules_impl.h"

static void asinh_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_ASINH, EV_COEF(E, A, 0))); }

static void asinh_taylor(hl_em *E, int k)
{
    int has;
    if (k == 0) {
        hl_ev a0 = EV_COEF(E, A, 0);
        EV_STORE(E, X, 0, EV_CALL(E, HL_PFN_SQRT, EV_ADD(E, EV_NUM(E, 1, 1), EV_MUL(E, a0, a0))));
        asinh_point(E);
        rule_keep_inverse(E, EV_COEF(E, X, 0));
        return;
    }
    hl_ev inv = EV_KEPT(E, KEEP_INV);
    hl_ev aa = rule_conv(E, A, A, 0, k, k, &has);
    hl_ev xx = rule_conv(E, X, X, 1, k - 1, k, &has);
    EV_STORE(E, X, k, EV_MUL(E, EV_MUL(E, rule_minus(E, aa, xx, has), inv), EV_NUM(E, 1, 2)));
    hl_ev kak = EV_MUL(E, EV_NUM(E, k, 1), EV_COEF(E, A, k));
    hl_ev s = rule_kconv(E, X, D, k, &has);
    EV_STORE(E, D, k, EV_MUL(E, EV_MUL(E, rule_minus(E, kak, s, has), inv), EV_NUM(E, 1, k)));
}
const hl_rule hl_rule_asinh = {"asinh", asinh_point, asinh_taylor};
