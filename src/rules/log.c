/* log(a).  From a d' = a': d[k] = (k a[k] - sum_{j=1..k-1} (k-j) a[j] d[k-j]) / (k a[0]),
 * 1/a[0] kept from k = 0. */
#include "rules/rules_impl.h"

static void log_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_LOG, EV_COEF(E, A, 0))); }

static void log_taylor(hl_em *E, int k)
{
    if (k == 0) {
        log_point(E);
        rule_keep_inverse(E, EV_COEF(E, A, 0));
        return;
    }
    int has;
    hl_ev s = rule_kconv(E, A, D, k, &has);
    hl_ev v = rule_minus(E, EV_MUL(E, EV_NUM(E, k, 1), EV_COEF(E, A, k)), s, has);
    EV_STORE(E, D, k, EV_MUL(E, EV_MUL(E, v, EV_KEPT(E, KEEP_INV)), EV_NUM(E, 1, k)));
}
const hl_rule hl_rule_log = {"log", log_point, log_taylor};
