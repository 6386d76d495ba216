/* exp(a).  From d' = a' d: d[k] = (1/k) sum_{j=1..k} j a[j] d[k-j]. */
#include "rules/rules_impl.h"

static void exp_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_EXP, EV_COEF(E, A, 0))); }

static void exp_taylor(hl_em *E, int k)
{
    if (k == 0) {
        exp_point(E);
        return;
    }
    int has;
    EV_STORE(E, D, k, EV_MUL(E, rule_dconv(E, A, D, k, &has), EV_NUM(E, 1, k)));
}
const hl_rule hl_rule_exp = {"exp", exp_point, exp_taylor};
