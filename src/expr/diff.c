/* Differentiation with light simplification.
 *
 * The smart constructors below fold what differentiation keeps producing:
 * 0 and 1 operands, double negation, and rational constants (NUM op NUM,
 * 2*(3*x) -> 6*x), so d/dx x^3*y is 3*x^2*y and not 3*x^2*1*y + x^3*0.  No
 * other algebra: that is the alg layer's job. */
#include <string.h>

#include "expr/memo.h"
#include "expr/prec.h"

typedef struct diff_walk {
    hl_pool *pool;
    const char *var;
    hl_memo done;
} diff_walk;

static int is_num(const hl_expr *e, long v)
{
    return e->kind == HL_NUM && fmpz_is_one(fmpq_denref(e->num)) &&
           fmpz_cmp_si(fmpq_numref(e->num), v) == 0;
}

/* gcc 12 misreads FLINT's inline fmpq_div in -O2 builds (a false
 * -Wstringop-overread, as in lex.c). */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overread"
static const hl_expr *num_op(hl_pool *pool, hl_expr_kind k, const hl_expr *a,
                             const hl_expr *b)
{
    fmpq_t r;
    fmpq_init(r);
    switch (k) {
    case HL_ADD: fmpq_add(r, a->num, b->num); break;
    case HL_SUB: fmpq_sub(r, a->num, b->num); break;
    case HL_MUL: fmpq_mul(r, a->num, b->num); break;
    case HL_DIV: fmpq_div(r, a->num, b->num); break; /* b != 0: checked by callers */
    default: fmpq_neg(r, a->num); break;
    }
    const hl_expr *e = hl_num_fmpq(pool, r);
    fmpq_clear(r);
    return e;
}
#pragma GCC diagnostic pop

static const hl_expr *s_neg(hl_pool *pool, const hl_expr *a)
{
    if (a->kind == HL_NUM)
        return num_op(pool, HL_NEG, a, NULL);
    if (a->kind == HL_NEG)
        return a->a;
    return hl_neg(pool, a);
}

static const hl_expr *s_add(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (is_num(a, 0))
        return b;
    if (is_num(b, 0))
        return a;
    if (a->kind == HL_NUM && b->kind == HL_NUM)
        return num_op(pool, HL_ADD, a, b);
    if (b->kind == HL_NEG) /* a + -b -> a - b */
        return hl_sub(pool, a, b->a);
    return hl_add(pool, a, b);
}

static const hl_expr *s_sub(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (is_num(b, 0))
        return a;
    if (is_num(a, 0))
        return s_neg(pool, b);
    if (a == b)
        return hl_num_si(pool, 0);
    if (a->kind == HL_NUM && b->kind == HL_NUM)
        return num_op(pool, HL_SUB, a, b);
    if (b->kind == HL_NEG)
        return hl_add(pool, a, b->a);
    return hl_sub(pool, a, b);
}

static const hl_expr *s_mul(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (is_num(a, 0) || is_num(b, 0))
        return hl_num_si(pool, 0);
    if (is_num(a, 1))
        return b;
    if (is_num(b, 1))
        return a;
    if (is_num(a, -1))
        return s_neg(pool, b);
    if (is_num(b, -1))
        return s_neg(pool, a);
    if (a->kind == HL_NUM && b->kind == HL_NUM)
        return num_op(pool, HL_MUL, a, b);
    if (b->kind == HL_NUM) /* constant first: x*3 -> 3*x */
        return s_mul(pool, b, a);
    if (a->kind == HL_NEG)
        return s_neg(pool, s_mul(pool, a->a, b));
    if (b->kind == HL_NEG)
        return s_neg(pool, s_mul(pool, a, b->a));
    if (a->kind == HL_NUM && b->kind == HL_MUL && b->a->kind == HL_NUM) /* 2*(3*x) */
        return s_mul(pool, num_op(pool, HL_MUL, a, b->a), b->b);
    return hl_mul(pool, a, b);
}

static const hl_expr *s_div(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (is_num(b, 1))
        return a;
    if (is_num(a, 0) && !is_num(b, 0))
        return a;
    if (a->kind == HL_NUM && b->kind == HL_NUM && !is_num(b, 0))
        return num_op(pool, HL_DIV, a, b);
    if (b->kind == HL_NUM && !is_num(b, 0)) /* (2*p)/2 -> p */
        return s_mul(pool, num_op(pool, HL_DIV, hl_num_si(pool, 1), b), a);
    if (a->kind == HL_NEG)
        return s_neg(pool, s_div(pool, a->a, b));
    return hl_div(pool, a, b);
}

static const hl_expr *s_pow(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (is_num(b, 0))
        return hl_num_si(pool, 1);
    if (is_num(b, 1))
        return a;
    return hl_pow(pool, a, b);
}

/* f'(u) for each function */
static const hl_expr *fun_deriv(hl_pool *pool, hl_fun f, const hl_expr *e, const hl_expr *u)
{
    const hl_expr *one = hl_num_si(pool, 1), *two = hl_num_si(pool, 2);
    switch (f) {
    case HL_SIN: return hl_call(pool, HL_COS, u);
    case HL_COS: return s_neg(pool, hl_call(pool, HL_SIN, u));
    case HL_TAN: return hl_add(pool, one, hl_pow(pool, e, two)); /* 1 + tan(u)^2 */
    case HL_EXP: return e;
    case HL_LOG: return s_div(pool, one, u);
    case HL_SQRT: return s_div(pool, one, hl_mul(pool, two, e));
    case HL_ATAN: return s_div(pool, one, hl_add(pool, one, hl_pow(pool, u, two)));
    case HL_ASIN:
        return s_div(pool, one, hl_call(pool, HL_SQRT, hl_sub(pool, one, hl_pow(pool, u, two))));
    case HL_ACOS:
        return s_neg(pool, s_div(pool, one,
                                 hl_call(pool, HL_SQRT, hl_sub(pool, one, hl_pow(pool, u, two)))));
    case HL_SINH: return hl_call(pool, HL_COSH, u);
    case HL_COSH: return hl_call(pool, HL_SINH, u);
    case HL_TANH: return hl_sub(pool, one, hl_pow(pool, e, two)); /* 1 - tanh(u)^2 */
    default: return hl_num_si(pool, 0); /* unreachable: every hl_fun is listed */
    }
}

static const hl_expr *d(diff_walk *w, const hl_expr *e);

static const hl_expr *d_pow(diff_walk *w, const hl_expr *e)
{
    hl_pool *pool = w->pool;
    const hl_expr *a = e->a, *b = e->b, *da = d(w, a), *db = d(w, b);
    if (is_num(a, 0)) /* 0^b is 0 wherever it is defined */
        return a;
    if (is_num(db, 0)) { /* b constant: b*a^(b-1)*a' */
        const hl_expr *bm1 = b->kind == HL_NUM ? num_op(pool, HL_SUB, b, hl_num_si(pool, 1))
                                               : hl_sub(pool, b, hl_num_si(pool, 1));
        return s_mul(pool, s_mul(pool, b, s_pow(pool, a, bm1)), da);
    }
    /* a^b*(b'*log(a) + b*a'/a) */
    const hl_expr *t = s_add(pool, s_mul(pool, db, hl_call(pool, HL_LOG, a)),
                             s_div(pool, s_mul(pool, b, da), a));
    return s_mul(pool, e, t);
}

static const hl_expr *d(diff_walk *w, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&w->done, e);
    if (v)
        return v->e;
    hl_pool *pool = w->pool;
    const hl_expr *r, *da, *db;
    switch (e->kind) {
    case HL_SYM:
        r = hl_num_si(pool, strcmp(e->name, w->var) == 0);
        break;
    case HL_NEG:
        r = s_neg(pool, d(w, e->a));
        break;
    case HL_ADD:
        r = s_add(pool, d(w, e->a), d(w, e->b));
        break;
    case HL_SUB:
        r = s_sub(pool, d(w, e->a), d(w, e->b));
        break;
    case HL_MUL:
        da = d(w, e->a);
        db = d(w, e->b);
        r = s_add(pool, s_mul(pool, da, e->b), s_mul(pool, e->a, db));
        break;
    case HL_DIV:
        da = d(w, e->a);
        db = d(w, e->b);
        if (is_num(db, 0))
            r = s_div(pool, da, e->b);
        else
            r = s_div(pool, s_sub(pool, s_mul(pool, da, e->b), s_mul(pool, e->a, db)),
                      hl_pow(pool, e->b, hl_num_si(pool, 2)));
        break;
    case HL_POW:
        r = d_pow(w, e);
        break;
    case HL_FUN:
        da = d(w, e->a);
        r = is_num(da, 0) ? da : s_mul(pool, fun_deriv(pool, e->fun, e, e->a), da);
        break;
    default: /* NUM, PI */
        r = hl_num_si(pool, 0);
    }
    hl_memo_put(&w->done, e)->e = r;
    return r;
}

const hl_expr *hl_expr_diff(hl_pool *pool, const hl_expr *e, const char *var)
{
    diff_walk w = {.pool = pool, .var = var};
    hl_memo_init(&w.done);
    const hl_expr *r = d(&w, e);
    hl_memo_clear(&w.done);
    return r;
}
