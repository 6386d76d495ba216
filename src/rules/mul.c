/* a b and a^2: the Cauchy product (a*b)[k] = sum_{j=0..k} a[j] b[k-j]; the
 * square by symmetry, in about half the products. */
#include "rules/rules_impl.h"

static void mul_point(hl_em *E) { EV_STORE(E, D, 0, EV_MUL(E, EV_COEF(E, A, 0), EV_COEF(E, B, 0))); }
static void mul_taylor(hl_em *E, int k)
{
    int has;
    EV_STORE(E, D, k, rule_conv(E, A, B, 0, k, k, &has));
}
const hl_rule hl_rule_mul = {"mul", mul_point, mul_taylor};

static void sqr_point(hl_em *E)
{
    hl_ev a0 = EV_COEF(E, A, 0);
    EV_STORE(E, D, 0, EV_MUL(E, a0, a0));
}
static void sqr_taylor(hl_em *E, int k)
{
    int has;
    EV_STORE(E, D, k, rule_sqr(E, A, 0, k, &has));
}
const hl_rule hl_rule_sqr = {"sqr", sqr_point, sqr_taylor};
