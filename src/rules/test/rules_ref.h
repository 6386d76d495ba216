/* The reference back end of the rules: an eager double emitter written
 * straight from rule.h's contract, one IEEE operation per emitter call and
 * a convolution summed in hl_conv_plan's order.  Tests run a rule over
 * series held in arrays (ref_taylor, ref_point) and compare other back ends
 * with it bit for bit (t-backends.c) or check identities with it
 * (t-rules.c).  Written without looking at the interpreters on purpose, so
 * that it checks them rather than copies them. */
#ifndef HAMLIE_RULES_TEST_REF_H
#define HAMLIE_RULES_TEST_REF_H

#include <math.h>
#include <stdlib.h>

#include "rules/rule.h"

typedef struct ref_em {
    hl_em em;
    double *s[HL_SLOT_COUNT]; /* D, A, B, X: coefficient arrays */
    double keep[2];
} ref_em;

static hl_ev ref_v(double d)
{
    hl_ev v;
    v.d = d;
    return v;
}

static ref_em *ref_of(hl_em *e)
{
    return (ref_em *)e;
}

static hl_ev ref_num(hl_em *e, long p, long q)
{
    (void)e;
    return ref_v((double)p / (double)q);
}
static hl_ev ref_coef(hl_em *e, hl_slot s, int j)
{
    return ref_v(ref_of(e)->s[s][j]);
}
static void ref_store(hl_em *e, hl_slot s, int j, hl_ev v)
{
    ref_of(e)->s[s][j] = v.d;
}
static hl_ev ref_add(hl_em *e, hl_ev a, hl_ev b)
{
    (void)e;
    return ref_v(a.d + b.d);
}
static hl_ev ref_sub(hl_em *e, hl_ev a, hl_ev b)
{
    (void)e;
    return ref_v(a.d - b.d);
}
static hl_ev ref_mul(hl_em *e, hl_ev a, hl_ev b)
{
    (void)e;
    return ref_v(a.d * b.d);
}
static hl_ev ref_div(hl_em *e, hl_ev a, hl_ev b)
{
    (void)e;
    return ref_v(a.d / b.d);
}
static hl_ev ref_neg(hl_em *e, hl_ev a)
{
    (void)e;
    return ref_v(-a.d);
}
static hl_ev ref_fma(hl_em *e, hl_ev a, hl_ev b, hl_ev c)
{
    (void)e;
    return ref_v(fma(a.d, b.d, c.d));
}

static double ref_libm(hl_pfn f, double x, double y)
{
    switch (f) {
    case HL_PFN_SIN:
        return sin(x);
    case HL_PFN_COS:
        return cos(x);
    case HL_PFN_TAN:
        return tan(x);
    case HL_PFN_SINH:
        return sinh(x);
    case HL_PFN_COSH:
        return cosh(x);
    case HL_PFN_TANH:
        return tanh(x);
    case HL_PFN_EXP:
        return exp(x);
    case HL_PFN_LOG:
        return log(x);
    case HL_PFN_SQRT:
        return sqrt(x);
    case HL_PFN_ATAN:
        return atan(x);
    case HL_PFN_ASIN:
        return asin(x);
    case HL_PFN_ACOS:
        return acos(x);
    case HL_PFN_ASINH:
        return asinh(x);
    case HL_PFN_ATAN2:
        return atan2(x, y);
    case HL_PFN_POW:
        return pow(x, y);
    default:
        abort();
    }
}

static hl_ev ref_call(hl_em *e, hl_pfn f, hl_ev a, hl_ev b)
{
    (void)e;
    return ref_v(ref_libm(f, a.d, b.d));
}

/* One term of a convolution, as rule.h writes it. */
static double ref_term(const hl_conv *c, const double *x, const double *y, int j)
{
    int k = c->k;
    int pair = c->sym && 2 * j < k;
    double w = c->weighted ? c->wa.d * j + c->wb.d : 2.0;
    if (j == k && k > 0) /* a fresh x[k] term */
        return c->weighted ? (w * y[0]) * x[k] : x[k] * y[0];
    return c->weighted || pair ? (w * x[j]) * y[k - j] : x[j] * y[k - j];
}

/* s += t, where "has" says whether s holds anything yet */
static void ref_acc(double *s, int *has, double t)
{
    *s = *has ? *s + t : t;
    *has = 1;
}

static hl_ev ref_conv(hl_em *e, const hl_conv *c, int *has)
{
    int n = c->hi - c->lo + 1, nk, nf, fresh[2];
    int *idx = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    int *lane = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    hl_conv_plan(c, idx, lane, &nk, fresh, &nf);
    const double *x = ref_of(e)->s[c->x], *y = ref_of(e)->s[c->y];
    double l[4] = {0, 0, 0, 0};
    int used[4] = {0, 0, 0, 0};
    for (int i = 0; i < nk; i++)
        ref_acc(&l[lane[i]], &used[lane[i]], ref_term(c, x, y, idx[i]));
    double p01 = 0, p23 = 0, s = 0;
    int h01 = 0, h23 = 0;
    for (int i = 0; i < 2; i++) {
        if (used[i])
            ref_acc(&p01, &h01, l[i]);
        if (used[2 + i])
            ref_acc(&p23, &h23, l[2 + i]);
    }
    *has = 0;
    if (h01)
        ref_acc(&s, has, p01);
    if (h23)
        ref_acc(&s, has, p23);
    for (int i = 0; i < nf; i++)
        ref_acc(&s, has, ref_term(c, x, y, fresh[i]));
    free(idx);
    free(lane);
    return ref_v(s);
}

static void ref_keep(hl_em *e, int slot, hl_ev v)
{
    ref_of(e)->keep[slot] = v.d;
}
static hl_ev ref_kept(hl_em *e, int slot)
{
    return ref_v(ref_of(e)->keep[slot]);
}

static const hl_em_ops ref_ops = {ref_num,  ref_coef, ref_store, ref_add, ref_sub,
                                  ref_mul,  ref_neg,  ref_div,   ref_fma, ref_call,
                                  ref_conv, ref_keep, ref_kept};

/* Coefficients 0..order of d = op(a, b) (x: the auxiliary series; b: for a
 * K op, the constant in b[0]; unused arrays may be NULL). */
static inline void ref_taylor(hl_op op, double *d, double *x, const double *a, const double *b,
                              int order)
{
    ref_em g = {{&ref_ops}, {d, (double *)a, (double *)b, x}, {0, 0}};
    const hl_rule *r = hl_rule_of(op);
    for (int k = 0; k <= order; k++)
        r->taylor(&g.em, k);
}

/* d[0] (and x[0]) = op(a[0], b[0]) by the point rule */
static inline void ref_point(hl_op op, double *d, double *x, const double *a, const double *b)
{
    ref_em g = {{&ref_ops}, {d, (double *)a, (double *)b, x}, {0, 0}};
    hl_rule_of(op)->point(&g.em);
}

#endif /* HAMLIE_RULES_TEST_REF_H */
