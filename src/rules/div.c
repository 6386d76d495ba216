/* a / b and k / a.  From d b = a: d[k] = (a[k] - sum_{j=1..k} b[j] d[k-j]) / b[0].
 * The division by b[0] is a product by its reciprocal, kept from k = 0, and
 * the term j = k, the only one that reads a coefficient k (b[k]), is taken
 * apart as b[k] (d[0] / b[0]) so that compiled code can start the rest of
 * the sum before b[k] is known. */
#include "rules/rules_impl.h"

static void div_point(hl_em *E) { EV_STORE(E, D, 0, EV_DIV(E, EV_COEF(E, A, 0), EV_COEF(E, B, 0))); }

/* at k = 0: d[0], then 1/den[0] and d[0]/den[0] kept */
static void keep_quotient(hl_em *E, hl_slot den)
{
    hl_ev inv = rule_keep_inverse(E, EV_COEF(E, den, 0));
    EV_KEEP(E, KEEP_RATIO, EV_MUL(E, EV_COEF(E, D, 0), inv));
}

static void div_taylor(hl_em *E, int k)
{
    if (k == 0) {
        div_point(E);
        keep_quotient(E, B);
        return;
    }
    int has;
    hl_ev s = rule_conv(E, B, D, 1, k - 1, k, &has);
    hl_ev v = EV_MUL(E, rule_minus(E, EV_COEF(E, A, k), s, has), EV_KEPT(E, KEEP_INV));
    EV_STORE(E, D, k, EV_SUB(E, v, EV_MUL(E, EV_COEF(E, B, k), EV_KEPT(E, KEEP_RATIO))));
}
const hl_rule hl_rule_div = {"div", div_point, div_taylor};

/* k / a (k a constant in B): as a / b with a constant numerator */
static void kdiv_point(hl_em *E) { EV_STORE(E, D, 0, EV_DIV(E, EV_COEF(E, B, 0), EV_COEF(E, A, 0))); }
static void kdiv_taylor(hl_em *E, int k)
{
    if (k == 0) {
        kdiv_point(E);
        keep_quotient(E, A);
        return;
    }
    int has;
    hl_ev s = rule_conv(E, A, D, 1, k - 1, k, &has);
    hl_ev fresh = EV_MUL(E, EV_COEF(E, A, k), EV_KEPT(E, KEEP_RATIO));
    if (has)
        EV_STORE(E, D, k, EV_SUB(E, EV_MUL(E, EV_NEG(E, s), EV_KEPT(E, KEEP_INV)), fresh));
    else
        EV_STORE(E, D, k, EV_NEG(E, fresh));
}
const hl_rule hl_rule_kdiv = {"kdiv", kdiv_point, kdiv_taylor};
