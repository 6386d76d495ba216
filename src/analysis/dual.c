/* The dual-number back end of the rules (rules/rule.h): a value is a dual
 * number a + b eps, the coefficients of the numeric analysis's series
 * (numeric.c).  A point function's eps part is its derivative times the
 * argument's eps part, the one thing this back end knows of a function
 * beyond libm.  Values are indices into a table of temporaries, emptied
 * after each coefficient. */
#include <math.h>
#include <stdlib.h>

#include "analysis/numeric_impl.h"
#include "base/buf.h"
#include "rules/rule.h"

typedef struct dual_em {
    hl_em em;
    dn *slot[HL_SLOT_COUNT];
    double exponent; /* B's coefficient 0 of a^c */
    dn keep[2];
    dn *val;
    int nval, aval;
} dual_em;

static dual_em *em_of(hl_em *em)
{
    return (dual_em *)em;
}

static hl_ev put(hl_em *em, dn v)
{
    dual_em *E = em_of(em);
    if (E->nval == E->aval) {
        E->aval = E->aval ? 2 * E->aval : 64;
        E->val = hl_xrealloc(E->val, (size_t)E->aval * sizeof *E->val);
    }
    E->val[E->nval] = v;
    hl_ev r;
    r.i = E->nval++;
    return r;
}

static dn get(hl_em *em, hl_ev v)
{
    return em_of(em)->val[v.i];
}

static hl_ev em_num(hl_em *em, long p, long q)
{
    return put(em, (dn){(double)p / (double)q, 0});
}

static hl_ev em_coef(hl_em *em, hl_slot s, int j)
{
    dual_em *E = em_of(em);
    if (s == HL_SLOT_B && E->slot[s] == NULL) /* a^c: c is B's coefficient 0 */
        return put(em, (dn){j == 0 ? E->exponent : 0, 0});
    return put(em, E->slot[s][j]);
}

static void em_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    em_of(em)->slot[s][j] = get(em, v);
}

static hl_ev em_add(hl_em *em, hl_ev a, hl_ev b)
{
    return put(em, dadd(get(em, a), get(em, b)));
}
static hl_ev em_sub(hl_em *em, hl_ev a, hl_ev b)
{
    return put(em, dsub(get(em, a), get(em, b)));
}
static hl_ev em_mul(hl_em *em, hl_ev a, hl_ev b)
{
    return put(em, dmul(get(em, a), get(em, b)));
}
static hl_ev em_neg(hl_em *em, hl_ev a)
{
    return put(em, dscal(get(em, a), -1));
}
static hl_ev em_div(hl_em *em, hl_ev a, hl_ev b)
{
    return put(em, ddiv(get(em, a), get(em, b)));
}

static hl_ev em_fma(hl_em *em, hl_ev a, hl_ev b, hl_ev c)
{
    return put(em, dadd(dmul(get(em, a), get(em, b)), get(em, c)));
}

/* f and its derivative at x */
static double point(hl_pfn f, double x, double *df)
{
    double v;
    switch (f) {
    case HL_PFN_SIN:
        *df = cos(x);
        return sin(x);
    case HL_PFN_COS:
        *df = -sin(x);
        return cos(x);
    case HL_PFN_TAN:
        v = tan(x);
        *df = 1 + v * v;
        return v;
    case HL_PFN_SINH:
        *df = cosh(x);
        return sinh(x);
    case HL_PFN_COSH:
        *df = sinh(x);
        return cosh(x);
    case HL_PFN_TANH:
        v = tanh(x);
        *df = 1 - v * v;
        return v;
    case HL_PFN_EXP:
        v = exp(x);
        *df = v;
        return v;
    case HL_PFN_LOG:
        *df = 1 / x;
        return log(x);
    case HL_PFN_SQRT:
        v = sqrt(x);
        *df = 0.5 / v;
        return v;
    case HL_PFN_ATAN:
        *df = 1 / (1 + x * x);
        return atan(x);
    case HL_PFN_ASIN:
        *df = 1 / sqrt(1 - x * x);
        return asin(x);
    case HL_PFN_ACOS:
        *df = -1 / sqrt(1 - x * x);
        return acos(x);
    case HL_PFN_ASINH:
        *df = 1 / sqrt(1 + x * x);
        return asinh(x);
    default:
        *df = NAN;
        return NAN; /* two arguments: em_call */
    }
}

static hl_ev em_call(hl_em *em, hl_pfn f, hl_ev a, hl_ev b)
{
    dn x = get(em, a), y = get(em, b);
    if (f == HL_PFN_POW) /* a constant exponent */
        return put(em, (dn){pow(x.r, y.r), y.r * pow(x.r, y.r - 1) * x.e});
    if (f == HL_PFN_ATAN2) { /* atan2(x, y): d = (y dx - x dy) / (x^2 + y^2) */
        double r2 = x.r * x.r + y.r * y.r;
        return put(em, (dn){atan2(x.r, y.r), (y.r * x.e - x.r * y.e) / r2});
    }
    double df, v = point(f, x.r, &df);
    return put(em, (dn){v, df * x.e});
}

/* The sum by j: the order of hl_conv_plan matters only bit for bit, and
 * this analysis compares within rounding. */
static hl_ev em_conv(hl_em *em, const hl_conv *c, int *has)
{
    dual_em *E = em_of(em);
    const dn *x = E->slot[c->x], *y = E->slot[c->y];
    double wa = c->weighted ? get(em, c->wa).r : 0, wb = c->weighted ? get(em, c->wb).r : 0;
    dn s = {0, 0};
    *has = 0;
    for (int j = c->lo; j <= c->hi && (!c->sym || 2 * j <= c->k); j++) {
        double w = c->weighted ? wa * j + wb : c->sym && 2 * j < c->k ? 2 : 1;
        s = dadd(s, dscal(dmul(x[j], y[c->k - j]), w));
        *has = 1;
    }
    return put(em, s);
}

static void em_keep(hl_em *em, int slot, hl_ev v)
{
    em_of(em)->keep[slot] = get(em, v);
}
static hl_ev em_kept(hl_em *em, int slot)
{
    return put(em, em_of(em)->keep[slot]);
}

static const hl_em_ops dual_em_ops = {em_num, em_coef, em_store, em_add,  em_sub,  em_mul, em_neg,
                                      em_div, em_fma,  em_call,  em_conv, em_keep, em_kept};

void dual_series_op(hl_op op, int L, dn *d, dn *x, const dn *a, const dn *b, double c)
{
    dn *scratch = x ? NULL : hl_xcalloc((size_t)L, sizeof *scratch);
    dual_em E = {.em = {&dual_em_ops}, .exponent = c};
    E.slot[HL_SLOT_D] = d;
    E.slot[HL_SLOT_X] = x ? x : scratch;
    E.slot[HL_SLOT_A] = (dn *)a;
    E.slot[HL_SLOT_B] = (dn *)b;
    const hl_rule *rule = hl_rule_of(op);
    for (int k = 0; k < L; k++) {
        E.nval = 0;
        rule->taylor(&E.em, k);
    }
    free(E.val);
    free(scratch);
}
