/* tan and tanh, with X = d^2.  From d' = a' (1 +- d^2):
 *   d[k] = a[k] +- (1/k) sum_{j=1..k} j a[j] x[k-j],   x[k] = (d*d)[k]. */
#include "rules/rules_impl.h"

static void tan_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_TAN, EV_COEF(E, A, 0))); }
static void tanh_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_TANH, EV_COEF(E, A, 0))); }

static void tan_common(hl_em *E, int k, int circular)
{
    int has;
    if (k == 0) {
        if (circular)
            tan_point(E);
        else
            tanh_point(E);
    } else {
        hl_ev s = EV_MUL(E, rule_dconv(E, A, X, k, &has), EV_NUM(E, 1, k));
        hl_ev ak = EV_COEF(E, A, k);
        EV_STORE(E, D, k, circular ? EV_ADD(E, ak, s) : EV_SUB(E, ak, s));
    }
    EV_STORE(E, X, k, rule_sqr(E, D, 0, k, &has));
}

static void tan_taylor(hl_em *E, int k) { tan_common(E, k, 1); }
static void tanh_taylor(hl_em *E, int k) { tan_common(E, k, 0); }
const hl_rule hl_rule_tan = {"tan", tan_point, tan_taylor};
const hl_rule hl_rule_tanh = {"tanh", tanh_point, tanh_taylor};
