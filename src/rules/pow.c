/* a^c, c a real constant (in B).  From a d' = c a' d:
 *   d[k] = sum_{m=1..k} ((c+1) m - k) a[m] d[k-m] / (k a[0]).
 * The term m = k, the only one that reads a coefficient k (a[k]), is
 * c a[k] d[0] / a[0]: taken apart with d[0]/a[0] kept, as in div.c.  The
 * recurrence is shared with a^(3/2) (pow3h.c), whose exponent is known
 * when the rule runs. */
#include "rules/rules_impl.h"

static void powk_point(hl_em *E)
{
    EV_STORE(E, D, 0, EV_CALL2(E, HL_PFN_POW, EV_COEF(E, A, 0), EV_COEF(E, B, 0)));
}

static void keep_pow(hl_em *E, hl_ev c)
{
    hl_ev inv = rule_keep_inverse(E, EV_COEF(E, A, 0));
    hl_ev cd0 = EV_MUL(E, c, EV_COEF(E, D, 0));
    EV_KEEP(E, KEEP_RATIO, EV_MUL(E, cd0, inv));
}

void rule_pow_step(hl_em *E, int k, hl_ev c1)
{
    int has;
    hl_ev s = rule_wconv(E, A, D, 1, k - 1, k, c1, EV_NUM(E, -k, 1), &has);
    hl_ev fresh = EV_MUL(E, EV_COEF(E, A, k), EV_KEPT(E, KEEP_RATIO));
    if (!has) {
        EV_STORE(E, D, k, fresh);
        return;
    }
    hl_ev known = EV_MUL(E, EV_MUL(E, s, EV_KEPT(E, KEEP_INV)), EV_NUM(E, 1, k));
    EV_STORE(E, D, k, EV_ADD(E, known, fresh));
}

static void powk_taylor(hl_em *E, int k)
{
    if (k == 0) {
        powk_point(E);
        keep_pow(E, EV_COEF(E, B, 0));
        return;
    }
    rule_pow_step(E, k, EV_ADD(E, EV_COEF(E, B, 0), EV_NUM(E, 1, 1)));
}
const hl_rule hl_rule_powk = {"powk", powk_point, powk_taylor};
