/* atan(a), with X = 1 + a^2.  From x d' = a':
 *   x[k] = [k = 0] + (a*a)[k],   d[k] = (k a[k] - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]). */
#include "rules/rules_impl.h"

static void atan_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_ATAN, EV_COEF(E, A, 0))); }

static void atan_taylor(hl_em *E, int k)
{
    int has;
    hl_ev aa = rule_conv(E, A, A, 0, k, k, &has);
    if (k == 0) {
        EV_STORE(E, X, 0, EV_ADD(E, EV_NUM(E, 1, 1), aa));
        atan_point(E);
        rule_keep_inverse(E, EV_COEF(E, X, 0));
        return;
    }
    EV_STORE(E, X, k, aa);
    hl_ev s = rule_kconv(E, X, D, k, &has);
    hl_ev v = rule_minus(E, EV_MUL(E, EV_NUM(E, k, 1), EV_COEF(E, A, k)), s, has);
    EV_STORE(E, D, k, EV_MUL(E, EV_MUL(E, v, EV_KEPT(E, KEEP_INV)), EV_NUM(E, 1, k)));
}
const hl_rule hl_rule_atan = {"atan", atan_point, atan_taylor};
