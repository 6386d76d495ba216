/* The linear operations: -a, a + b, a - b, and those with a constant k
 * (a + k, a - k, k - a, a k, a / k).  Coefficient k is the same operation
 * on the operands' coefficients k, except that a constant only has a
 * coefficient 0. */
#include "rules/rules_impl.h"

#define A0 EV_COEF(E, A, 0)
#define B0 EV_COEF(E, B, 0)

static void neg_taylor(hl_em *E, int k) { EV_STORE(E, D, k, EV_NEG(E, EV_COEF(E, A, k))); }
static void neg_point(hl_em *E) { neg_taylor(E, 0); }
const hl_rule hl_rule_neg = {"neg", neg_point, neg_taylor};

static void add_taylor(hl_em *E, int k)
{
    EV_STORE(E, D, k, EV_ADD(E, EV_COEF(E, A, k), EV_COEF(E, B, k)));
}
static void add_point(hl_em *E) { add_taylor(E, 0); }
const hl_rule hl_rule_add = {"add", add_point, add_taylor};

static void sub_taylor(hl_em *E, int k)
{
    EV_STORE(E, D, k, EV_SUB(E, EV_COEF(E, A, k), EV_COEF(E, B, k)));
}
static void sub_point(hl_em *E) { sub_taylor(E, 0); }
const hl_rule hl_rule_sub = {"sub", sub_point, sub_taylor};

static void addk_point(hl_em *E) { EV_STORE(E, D, 0, EV_ADD(E, A0, B0)); }
static void addk_taylor(hl_em *E, int k)
{
    if (k == 0)
        addk_point(E);
    else
        EV_STORE(E, D, k, EV_COEF(E, A, k));
}
const hl_rule hl_rule_addk = {"addk", addk_point, addk_taylor};

static void subk_point(hl_em *E) { EV_STORE(E, D, 0, EV_SUB(E, A0, B0)); }
static void subk_taylor(hl_em *E, int k)
{
    if (k == 0)
        subk_point(E);
    else
        EV_STORE(E, D, k, EV_COEF(E, A, k));
}
const hl_rule hl_rule_subk = {"subk", subk_point, subk_taylor};

static void ksub_point(hl_em *E) { EV_STORE(E, D, 0, EV_SUB(E, B0, A0)); }
static void ksub_taylor(hl_em *E, int k)
{
    if (k == 0)
        ksub_point(E);
    else
        EV_STORE(E, D, k, EV_NEG(E, EV_COEF(E, A, k)));
}
const hl_rule hl_rule_ksub = {"ksub", ksub_point, ksub_taylor};

static void mulk_taylor(hl_em *E, int k) { EV_STORE(E, D, k, EV_MUL(E, EV_COEF(E, A, k), B0)); }
static void mulk_point(hl_em *E) { mulk_taylor(E, 0); }
const hl_rule hl_rule_mulk = {"mulk", mulk_point, mulk_taylor};

static void divk_taylor(hl_em *E, int k) { EV_STORE(E, D, k, EV_DIV(E, EV_COEF(E, A, k), B0)); }
static void divk_point(hl_em *E) { divk_taylor(E, 0); }
const hl_rule hl_rule_divk = {"divk", divk_point, divk_taylor};
