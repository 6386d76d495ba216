/* asin(a) and acos(a), with X = sqrt(1 - a^2).  From x d' = +-a':
 *   x[k] = (-(a*a)[k] - sum_{j=1..k-1} x[j] x[k-j]) / (2 x[0])   (the sqrt rule on 1 - a^2),
 *   d[k] = (+-k a[k] - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]). */
#include "rules/rules_impl.h"

static void asin_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_ASIN, EV_COEF(E, A, 0))); }
static void acos_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_ACOS, EV_COEF(E, A, 0))); }

void rule_root_inverse(hl_em *E, int k, void (*point)(hl_em *), int a2_sign, int sign)
{
    int has;
    if (k == 0) {
        hl_ev a0 = EV_COEF(E, A, 0), one = EV_NUM(E, 1, 1);
        hl_ev a0a0 = EV_MUL(E, a0, a0);
        hl_ev w0 = a2_sign > 0 ? EV_ADD(E, one, a0a0) : EV_SUB(E, one, a0a0);
        EV_STORE(E, X, 0, EV_CALL(E, HL_PFN_SQRT, w0));
        point(E);
        rule_keep_inverse(E, EV_COEF(E, X, 0));
        return;
    }
    hl_ev inv = EV_KEPT(E, KEEP_INV);
    hl_ev aa = rule_conv(E, A, A, 0, k, k, &has);
    hl_ev xx = rule_conv(E, X, X, 1, k - 1, k, &has);
    hl_ev xk = rule_minus(E, a2_sign > 0 ? aa : EV_NEG(E, aa), xx, has);
    EV_STORE(E, X, k, EV_MUL(E, EV_MUL(E, xk, inv), EV_NUM(E, 1, 2)));
    hl_ev kak = EV_MUL(E, EV_NUM(E, sign > 0 ? k : -k, 1), EV_COEF(E, A, k));
    hl_ev s = rule_kconv(E, X, D, k, &has);
    EV_STORE(E, D, k, EV_MUL(E, EV_MUL(E, rule_minus(E, kak, s, has), inv), EV_NUM(E, 1, k)));
}

static void asin_taylor(hl_em *E, int k) { rule_root_inverse(E, k, asin_point, -1, 1); }
static void acos_taylor(hl_em *E, int k) { rule_root_inverse(E, k, acos_point, -1, -1); }
const hl_rule hl_rule_asin = {"asin", asin_point, asin_taylor};
const hl_rule hl_rule_acos = {"acos", acos_point, acos_taylor};
