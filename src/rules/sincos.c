/* sin and cos of one argument together (D = sin a, X = cos a), and sinh and
 * cosh.  From d' = a' x, x' = -+ a' d:
 *   d[k] = (1/k) sum_{j=1..k} j a[j] x[k-j],   x[k] = -+(1/k) sum_{j=1..k} j a[j] d[k-j]. */
#include "rules/rules_impl.h"

static void pair_point(hl_em *E, hl_pfn f, hl_pfn g)
{
    hl_ev a0 = EV_COEF(E, A, 0);
    EV_STORE(E, D, 0, EV_CALL(E, f, a0));
    EV_STORE(E, X, 0, EV_CALL(E, g, a0));
}

static void pair_taylor(hl_em *E, int k, int circular)
{
    int has;
    hl_ev rk = EV_NUM(E, 1, k);
    EV_STORE(E, D, k, EV_MUL(E, rule_dconv(E, A, X, k, &has), rk));
    hl_ev c = rule_dconv(E, A, D, k, &has);
    EV_STORE(E, X, k, EV_MUL(E, circular ? EV_NEG(E, c) : c, rk));
}

static void sincos_point(hl_em *E) { pair_point(E, HL_PFN_SIN, HL_PFN_COS); }
static void sincos_taylor(hl_em *E, int k)
{
    if (k == 0)
        sincos_point(E);
    else
        pair_taylor(E, k, 1);
}
const hl_rule hl_rule_sincos = {"sincos", sincos_point, sincos_taylor};

static void sinhcosh_point(hl_em *E) { pair_point(E, HL_PFN_SINH, HL_PFN_COSH); }
static void sinhcosh_taylor(hl_em *E, int k)
{
    if (k == 0)
        sinhcosh_point(E);
    else
        pair_taylor(E, k, 0);
}
const hl_rule hl_rule_sinhcosh = {"sinhcosh", sinhcosh_point, sinhcosh_taylor};
