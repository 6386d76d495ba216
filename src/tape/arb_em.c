/* The Arb back end of the rules: an eager emitter whose values are arbs.
 *
 * A rule's temporaries come from a small pool reused at every rule call; the
 * values a rule keeps from k = 0 (reciprocals) live in per-instruction
 * storage.  Arb does not follow the double order of additions (its balls
 * are correct in any order): a plain convolution is one arb_dot. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "rules/rule.h"
#include "tape/arb_em_impl.h"

#define POOL 48 /* temporaries of one rule call: a dozen at most today */

struct hl_arb_em {
    hl_em em;
    arb_ptr s[HL_SLOT_COUNT];
    arb_ptr keep; /* 2 per instruction */
    int nkeep, instr;
    arb_struct pool[POOL];
    int used;
    slong prec;
};

static hl_arb_em *of(hl_em *e)
{
    return (hl_arb_em *)e;
}

static hl_ev ev(arb_ptr p)
{
    hl_ev v;
    v.p = p;
    return v;
}
#define V(x) ((arb_ptr)(x).p)

static arb_ptr temp(hl_arb_em *a)
{
    if (a->used == POOL)
        abort(); /* a rule with more temporaries than any written so far */
    return &a->pool[a->used++];
}

static hl_ev a_num(hl_em *e, long p, long q)
{
    hl_arb_em *a = of(e);
    arb_ptr t = temp(a);
    arb_set_si(t, p);
    if (q != 1)
        arb_div_si(t, t, q, a->prec);
    return ev(t);
}

static hl_ev a_coef(hl_em *e, hl_slot s, int j)
{
    return ev(of(e)->s[s] + j);
}
static void a_store(hl_em *e, hl_slot s, int j, hl_ev v)
{
    arb_set(of(e)->s[s] + j, V(v));
}

static hl_ev a_add(hl_em *e, hl_ev x, hl_ev y)
{
    arb_ptr t = temp(of(e));
    arb_add(t, V(x), V(y), of(e)->prec);
    return ev(t);
}
static hl_ev a_sub(hl_em *e, hl_ev x, hl_ev y)
{
    arb_ptr t = temp(of(e));
    arb_sub(t, V(x), V(y), of(e)->prec);
    return ev(t);
}
static hl_ev a_mul(hl_em *e, hl_ev x, hl_ev y)
{
    arb_ptr t = temp(of(e));
    arb_mul(t, V(x), V(y), of(e)->prec);
    return ev(t);
}
static hl_ev a_div(hl_em *e, hl_ev x, hl_ev y)
{
    arb_ptr t = temp(of(e));
    arb_div(t, V(x), V(y), of(e)->prec);
    return ev(t);
}
static hl_ev a_neg(hl_em *e, hl_ev x)
{
    arb_ptr t = temp(of(e));
    arb_neg(t, V(x));
    return ev(t);
}
static hl_ev a_fma(hl_em *e, hl_ev x, hl_ev y, hl_ev z)
{
    arb_ptr t = temp(of(e));
    arb_set(t, V(z));
    arb_addmul(t, V(x), V(y), of(e)->prec);
    return ev(t);
}

static void apply(arb_ptr t, hl_pfn f, arb_srcptr x, arb_srcptr y, slong prec)
{
    switch (f) {
    case HL_PFN_SIN:
        arb_sin(t, x, prec);
        break;
    case HL_PFN_COS:
        arb_cos(t, x, prec);
        break;
    case HL_PFN_TAN:
        arb_tan(t, x, prec);
        break;
    case HL_PFN_SINH:
        arb_sinh(t, x, prec);
        break;
    case HL_PFN_COSH:
        arb_cosh(t, x, prec);
        break;
    case HL_PFN_TANH:
        arb_tanh(t, x, prec);
        break;
    case HL_PFN_EXP:
        arb_exp(t, x, prec);
        break;
    case HL_PFN_LOG:
        arb_log(t, x, prec);
        break;
    case HL_PFN_SQRT:
        arb_sqrt(t, x, prec);
        break;
    case HL_PFN_ATAN:
        arb_atan(t, x, prec);
        break;
    case HL_PFN_ASIN:
        arb_asin(t, x, prec);
        break;
    case HL_PFN_ACOS:
        arb_acos(t, x, prec);
        break;
    case HL_PFN_ASINH:
        arb_asinh(t, x, prec);
        break;
    case HL_PFN_ATAN2:
        arb_atan2(t, x, y, prec);
        break; /* arb_atan2(r, y, x) */
    default:
        arb_pow(t, x, y, prec);
        break;
    }
}

static hl_ev a_call(hl_em *e, hl_pfn f, hl_ev x, hl_ev y)
{
    arb_ptr t = temp(of(e));
    apply(t, f, V(x), V(y), of(e)->prec);
    return ev(t);
}

/* The sum of the terms; a square's symmetric sum is the plain one over
 * the whole range (the same value). */
static hl_ev a_conv(hl_em *e, const hl_conv *c, int *has)
{
    hl_arb_em *a = of(e);
    arb_ptr t = temp(a), x = a->s[c->x], y = a->s[c->y];
    *has = c->hi >= c->lo;
    if (!*has) {
        arb_zero(t);
        return ev(t);
    }
    if (!c->weighted) {
        arb_dot(t, NULL, 0, x + c->lo, 1, y + (c->k - c->lo), -1, c->hi - c->lo + 1, a->prec);
        return ev(t);
    }
    arb_ptr w = temp(a), p = temp(a);
    arb_zero(t);
    for (int j = c->lo; j <= c->hi; j++) {
        arb_mul_si(w, V(c->wa), j, a->prec);
        arb_add(w, w, V(c->wb), a->prec);
        arb_mul(p, x + j, y + c->k - j, a->prec);
        arb_addmul(t, w, p, a->prec);
    }
    return ev(t);
}

static void a_keep(hl_em *e, int slot, hl_ev v)
{
    hl_arb_em *a = of(e);
    arb_set(a->keep + 2 * a->instr + slot, V(v));
}
static hl_ev a_kept(hl_em *e, int slot)
{
    hl_arb_em *a = of(e);
    return ev(a->keep + 2 * a->instr + slot);
}

static const hl_em_ops arb_ops = {a_num, a_coef, a_store, a_add,  a_sub,  a_mul, a_neg,
                                  a_div, a_fma,  a_call,  a_conv, a_keep, a_kept};

hl_arb_em *hl_arb_em_new(int ninstr)
{
    hl_arb_em *a = hl_xcalloc(1, sizeof *a);
    a->em.ops = &arb_ops;
    for (int i = 0; i < POOL; i++)
        arb_init(&a->pool[i]);
    a->nkeep = 2 * ninstr + 1;
    a->keep = _arb_vec_init(a->nkeep);
    return a;
}

void hl_arb_em_free(hl_arb_em *a)
{
    if (a == NULL)
        return;
    for (int i = 0; i < POOL; i++)
        arb_clear(&a->pool[i]);
    _arb_vec_clear(a->keep, a->nkeep);
    free(a);
}

/* Point the slots at instruction i's registers of r (stride S). */
static void enter(hl_arb_em *a, const hl_instr *in, int i, arb_ptr r, int S, slong prec)
{
    a->instr = i;
    a->used = 0;
    a->prec = prec;
    a->s[HL_SLOT_D] = r + (size_t)in->d * S;
    a->s[HL_SLOT_A] = r + (size_t)in->a * S;
    a->s[HL_SLOT_B] = in->b >= 0 ? r + (size_t)in->b * S : NULL;
    a->s[HL_SLOT_X] = in->x >= 0 ? r + (size_t)in->x * S : NULL;
}

void hl_arb_em_taylor(hl_arb_em *a, const hl_instr *code, int n, arb_ptr r, int S, int k,
                      slong prec)
{
    for (int i = 0; i < n; i++) {
        enter(a, &code[i], i, r, S, prec);
        hl_rule_of((hl_op)code[i].op)->taylor(&a->em, k);
    }
}

void hl_arb_em_point(hl_arb_em *a, const hl_instr *code, int n, arb_ptr r, slong prec)
{
    for (int i = 0; i < n; i++) {
        enter(a, &code[i], i, r, 1, prec);
        hl_rule_of((hl_op)code[i].op)->point(&a->em);
    }
}
