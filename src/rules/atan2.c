/* atan2(a, b) (a = y, b = x, libm's order), with X = a^2 + b^2.  From
 * x d' = b a' - a b':
 *   x[k] = (a*a)[k] + (b*b)[k],
 *   d[k] = (sum_{j=1..k} j a[j] b[k-j] - sum_{j=1..k} j b[j] a[k-j]
 *           - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]). */
#include "rules/rules_impl.h"

static void atan2_point(hl_em *E)
{
    EV_STORE(E, D, 0, EV_CALL2(E, HL_PFN_ATAN2, EV_COEF(E, A, 0), EV_COEF(E, B, 0)));
}

static void atan2_taylor(hl_em *E, int k)
{
    int has;
    hl_ev aa = rule_conv(E, A, A, 0, k, k, &has);
    EV_STORE(E, X, k, EV_ADD(E, aa, rule_conv(E, B, B, 0, k, k, &has)));
    if (k == 0) {
        atan2_point(E);
        rule_keep_inverse(E, EV_COEF(E, X, 0));
        return;
    }
    hl_ev ab = rule_dconv(E, A, B, k, &has);
    hl_ev v = EV_SUB(E, ab, rule_dconv(E, B, A, k, &has));
    hl_ev s = rule_kconv(E, X, D, k, &has);
    v = rule_minus(E, v, s, has);
    EV_STORE(E, D, k, EV_MUL(E, EV_MUL(E, v, EV_KEPT(E, KEEP_INV)), EV_NUM(E, 1, k)));
}
const hl_rule hl_rule_atan2 = {"atan2", atan2_point, atan2_taylor};
