/* The exact back end of the rules (rules/rule.h): values are hl_alg, so
 * the series layer computes each operation's coefficients by the same rule
 * as every other back end.
 *
 * A value is a rational number (the weights and constants the rules ask
 * for: they multiply by hl_alg_scalar_mul_fmpq, much cheaper than a
 * product of rational functions), an hl_alg of its own, or a reference to
 * a stored coefficient (no copy for reading an operand).  Temporaries live
 * in an arena that is reset when a rule returns and reused by the next, so
 * their polynomials keep their memory.
 *
 * Errors: the first one (a point function outside its domain, a divisor
 * that vanishes) is kept in the emitter; later calls return zero so the
 * rule runs to its end, and series_em_run returns it. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "series/series_impl.h"

struct series_val {
    int is_q;          /* a rational number q */
    const hl_alg *ref; /* a stored coefficient (not owned) */
    fmpq_t q;
    hl_alg a; /* the value otherwise */
};

static series_em *em_of(hl_em *em)
{
    return (series_em *)em;
}

static hl_ev as_ev(series_val *v)
{
    hl_ev r;
    r.p = v;
    return r;
}

static series_val *val_of(hl_ev v)
{
    return v.p;
}

static series_val *fresh(series_em *E)
{
    if (E->nval == E->aval) {
        E->aval = E->aval ? 2 * E->aval : 64;
        E->val = hl_xrealloc(E->val, (size_t)E->aval * sizeof *E->val);
        for (int i = E->nval; i < E->aval; i++) {
            E->val[i] = hl_xmalloc(sizeof *E->val[i]);
            fmpq_init(E->val[i]->q);
            hl_alg_init(&E->val[i]->a, E->ctx);
        }
    }
    series_val *v = E->val[E->nval++];
    v->is_q = 0;
    v->ref = NULL;
    return v;
}

static hl_ev rational(series_em *E, const fmpq_t q)
{
    series_val *v = fresh(E);
    v->is_q = 1;
    fmpq_set(v->q, q);
    return as_ev(v);
}

static hl_ev zero(series_em *E)
{
    series_val *v = fresh(E);
    v->is_q = 1;
    fmpq_zero(v->q);
    return as_ev(v);
}

/* v as an hl_alg (a rational one is converted in place) */
static const hl_alg *alg(series_em *E, series_val *v)
{
    if (v->ref)
        return v->ref;
    if (v->is_q)
        hl_alg_set_fmpq(&v->a, v->q, E->ctx);
    return &v->a;
}

static int failed(series_em *E, int status)
{
    if (E->status == HL_OK)
        E->status = status;
    return E->status != HL_OK;
}

static hl_ev em_num(hl_em *em, long p, long q)
{
    series_val *v = fresh(em_of(em));
    v->is_q = 1;
    fmpq_set_si(v->q, p, (ulong)q);
    return as_ev(v);
}

static hl_ev em_coef(hl_em *em, hl_slot s, int j)
{
    series_em *E = em_of(em);
    if (s == HL_SLOT_B && E->exponent) /* a^c: c is B's coefficient 0 */
        return j == 0 ? rational(E, E->exponent) : zero(E);
    series_val *v = fresh(E);
    v->ref = &E->slot[s]->c[j];
    return as_ev(v);
}

/* Put v into *to: a temporary of the arena by a swap, not a copy (a
 * coefficient of a rational function is large; the copy was the one cost
 * the old recurrences did not have), after which v reads *to, so a rule
 * may still use v; the arena keeps *to's old memory for the next value. */
static void put(series_em *E, hl_alg *to, hl_ev v)
{
    series_val *x = val_of(v);
    if (x->ref || x->is_q) {
        hl_alg_set(to, alg(E, x), E->ctx);
        return;
    }
    hl_alg_swap(to, &x->a, E->ctx);
    x->ref = to;
}

static void em_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    series_em *E = em_of(em);
    put(E, &E->slot[s]->c[j], v);
}

static hl_ev em_add(hl_em *em, hl_ev a, hl_ev b)
{
    series_em *E = em_of(em);
    series_val *x = val_of(a), *y = val_of(b), *r = fresh(E);
    if (x->is_q && y->is_q) {
        r->is_q = 1;
        fmpq_add(r->q, x->q, y->q);
    } else {
        hl_alg_add(&r->a, alg(E, x), alg(E, y), E->ctx);
    }
    return as_ev(r);
}

static hl_ev em_sub(hl_em *em, hl_ev a, hl_ev b)
{
    series_em *E = em_of(em);
    series_val *x = val_of(a), *y = val_of(b), *r = fresh(E);
    if (x->is_q && y->is_q) {
        r->is_q = 1;
        fmpq_sub(r->q, x->q, y->q);
    } else {
        hl_alg_sub(&r->a, alg(E, x), alg(E, y), E->ctx);
    }
    return as_ev(r);
}

static hl_ev em_neg(hl_em *em, hl_ev a)
{
    series_em *E = em_of(em);
    series_val *x = val_of(a), *r = fresh(E);
    if (x->is_q) {
        r->is_q = 1;
        fmpq_neg(r->q, x->q);
    } else {
        hl_alg_neg(&r->a, alg(E, x), E->ctx);
    }
    return as_ev(r);
}

static hl_ev em_mul(hl_em *em, hl_ev a, hl_ev b)
{
    series_em *E = em_of(em);
    series_val *x = val_of(a), *y = val_of(b), *r = fresh(E);
    if (x->is_q && y->is_q) {
        r->is_q = 1;
        fmpq_mul(r->q, x->q, y->q);
    } else if (x->is_q || y->is_q) {
        series_val *s = x->is_q ? x : y, *t = x->is_q ? y : x;
        hl_alg_scalar_mul_fmpq(&r->a, alg(E, t), s->q, E->ctx);
    } else {
        hl_alg_mul(&r->a, alg(E, x), alg(E, y), E->ctx);
    }
    return as_ev(r);
}

static int vanishes(series_em *E, series_val *d)
{
    if (d->is_q ? fmpq_is_zero(d->q) : hl_alg_is_zero(alg(E, d), E->ctx)) {
        failed(E, hl_error_set(E->err, HL_EDOM, NULL, -1, 0, "%s", E->vanishing));
        return 1;
    }
    return 0;
}

static hl_ev em_div(hl_em *em, hl_ev a, hl_ev b)
{
    series_em *E = em_of(em);
    series_val *x = val_of(a), *y = val_of(b);
    if (E->status != HL_OK || vanishes(E, y))
        return zero(E);
    series_val *r = fresh(E);
    if (x->is_q && y->is_q) {
        r->is_q = 1;
        fmpq_div(r->q, x->q, y->q);
    } else if (y->is_q) {
        fmpq_inv(r->q, y->q);
        hl_alg_scalar_mul_fmpq(&r->a, alg(E, x), r->q, E->ctx);
    } else {
        failed(E, hl_alg_div(&r->a, alg(E, x), alg(E, y), E->ctx, E->err));
    }
    return as_ev(r);
}

static hl_ev em_fma(hl_em *em, hl_ev a, hl_ev b, hl_ev c)
{
    return em_add(em, em_mul(em, a, b), c);
}

static hl_ev em_call(hl_em *em, hl_pfn f, hl_ev a, hl_ev b)
{
    series_em *E = em_of(em);
    if (E->status != HL_OK)
        return zero(E);
    series_val *x = val_of(a), *y = val_of(b), *r = fresh(E);
    int status;
    if (f == HL_PFN_POW) /* the exponent is a rational B (powk) */
        status = hl_alg_pow_fmpq(&r->a, alg(E, x), y->q, E->ctx, E->err);
    else if (f == HL_PFN_ATAN2)
        status = hl_alg_apply2(&r->a, HL_ATAN2, alg(E, x), alg(E, y), E->ctx, E->err);
    else
        status = hl_alg_apply(&r->a, hl_pfn_fun(f), alg(E, x), E->ctx, E->err);
    failed(E, status);
    return as_ev(r);
}

/* acc += w x y, skipping products that are structurally zero */
static void add_term(series_em *E, hl_alg *acc, const hl_alg *x, const hl_alg *y, const fmpq_t w,
                     hl_alg *tmp)
{
    if (fmpq_is_zero(w) || series_trivially_zero(x, E->ctx) || series_trivially_zero(y, E->ctx))
        return;
    hl_alg_mul(tmp, x, y, E->ctx);
    if (!fmpq_is_one(w))
        hl_alg_scalar_mul_fmpq(tmp, tmp, w, E->ctx);
    hl_alg_add(acc, acc, tmp, E->ctx);
}

/* The sum of a convolution's terms.  The order of hl_conv_plan only
 * matters to rounding; exact sums go by j. */
static hl_ev em_conv(hl_em *em, const hl_conv *c, int *has)
{
    series_em *E = em_of(em);
    const hl_series *x = E->slot[c->x], *y = E->slot[c->y];
    series_val *r = fresh(E), *t = fresh(E);
    hl_alg_zero(&r->a, E->ctx);
    fmpq_t w;
    fmpq_init(w);
    *has = 0;
    for (int j = c->lo; j <= c->hi && (!c->sym || 2 * j <= c->k); j++) {
        *has = 1;
        if (c->weighted) { /* w = wa j + wb */
            fmpq_mul_si(w, val_of(c->wa)->q, j);
            fmpq_add(w, w, val_of(c->wb)->q);
        } else {
            fmpq_set_si(w, c->sym && 2 * j < c->k ? 2 : 1, 1);
        }
        add_term(E, &r->a, &x->c[j], &y->c[c->k - j], w, &t->a);
    }
    fmpq_clear(w);
    return as_ev(r);
}

static void em_keep(hl_em *em, int slot, hl_ev v)
{
    series_em *E = em_of(em);
    put(E, &E->keep[slot], v);
}

static hl_ev em_kept(hl_em *em, int slot)
{
    series_em *E = em_of(em);
    series_val *v = fresh(E);
    v->ref = &E->keep[slot];
    return as_ev(v);
}

static const hl_em_ops series_em_ops = {em_num, em_coef, em_store, em_add,  em_sub,  em_mul, em_neg,
                                        em_div, em_fma,  em_call,  em_conv, em_keep, em_kept};

void series_em_init(series_em *E, hl_alg_ctx *ctx)
{
    memset(E, 0, sizeof *E);
    E->em.ops = &series_em_ops;
    E->ctx = ctx;
}

void series_em_clear(series_em *E)
{
    for (int i = 0; i < E->aval; i++) {
        fmpq_clear(E->val[i]->q);
        hl_alg_clear(&E->val[i]->a, E->ctx);
        free(E->val[i]);
    }
    free(E->val);
}

int series_em_run(series_em *E, const hl_rule *rule, int k, hl_error *err)
{
    E->err = err;
    E->status = HL_OK;
    E->nval = 0;
    rule->taylor(&E->em, k);
    return E->status;
}
