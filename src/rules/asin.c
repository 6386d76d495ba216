/* asin(a) and acos(a), with X = sqrt(1 - a^2).  From x d' = +-a':
 *   x[k] = (-(a*a)[k] - sum_{j=1..k-1} x[j] x[k-j]) / (2 x[0])   (the sqrt rule on 1 - a^2),
 *   d[k] = (+-k a[k] - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]). */
#include "rules/rules_impl.h"

static void asin_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_ASIN, EV_COEF(E, A, 0))); }
static void acos_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_ACOS, EV_COEF(E, A, 0))); }

static void arc_taylor(hl_em *E, int k, int sine)
{
    int has;
    if (k == 0) {
        hl_ev a0 = EV_COEF(E, A, 0);
        EV_STORE(E, X, 0, EV_CALL(E, HL_PFN_SQRT, EV_SUB(E, EV_NUM(E, 1, 1), EV_MUL(E, a0, a0))));
        if (sine)
            asin_point(E);
        else
            acos_point(E);
        rule_keep_inverse(E, EV_COEF(E, X, 0));
        return;
    }
    hl_ev inv = EV_KEPT(E, KEEP_INV);
    hl_ev aa = rule_conv(E, A, A, 0, k, k, &has);
    hl_ev xx = rule_conv(E, X, X, 1, k - 1, k, &has);
    hl_ev xk = rule_minus(E, EV_NEG(E, aa), xx, has);
    EV_STORE(E, X, k, EV_MUL(E, EV_MUL(E, xk, inv), EV_NUM(E, 1, 2)));
    hl_ev kak = EV_MUL(E, EV_NUM(E, sine ? k : -k, 1), EV_COEF(E, A, k));
    hl_ev s = rule_kconv(E, X, D, k, &has);
    EV_STORE(E, D, k, EV_MUL(E, EV_MUL(E, rule_minus(E, kak, s, has), inv), EV_NUM(E, 1, k)));
}

static void asin_taylor(hl_em *E, int k) { arc_taylor(E, k, 1); }
static void acos_taylor(hl_em *E, int k) { arc_taylor(E, k, 0); }
const hl_rule hl_rule_asin = {"asin", asin_point, asin_taylor};
const hl_rule hl_rule_acos = {"acos", acos_point, acos_taylor};
