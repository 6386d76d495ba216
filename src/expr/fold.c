/* Smart constructors: the light simplification that generated expressions
 * need (derivatives, Taylor coefficients), so that tapes built from them
 * stay small.  They fold 0 and 1 operands, double negation and rational
 * constants (NUM op NUM, 2*(3*x) -> 6*x), so d/dx x^3*y is 3*x^2*y and not
 * 3*x^2*1*y + x^3*0.  No other algebra: that is the alg layer's job. */
#include "expr/fold.h"

int hl_fold_is_num(const hl_expr *e, long v)
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

const hl_expr *hl_fold_neg(hl_pool *pool, const hl_expr *a)
{
    if (a->kind == HL_NUM)
        return num_op(pool, HL_NEG, a, NULL);
    if (a->kind == HL_NEG)
        return a->a;
    return hl_neg(pool, a);
}

const hl_expr *hl_fold_add(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (hl_fold_is_num(a, 0))
        return b;
    if (hl_fold_is_num(b, 0))
        return a;
    if (a->kind == HL_NUM && b->kind == HL_NUM)
        return num_op(pool, HL_ADD, a, b);
    if (b->kind == HL_NEG) /* a + -b -> a - b */
        return hl_sub(pool, a, b->a);
    return hl_add(pool, a, b);
}

const hl_expr *hl_fold_sub(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (hl_fold_is_num(b, 0))
        return a;
    if (hl_fold_is_num(a, 0))
        return hl_fold_neg(pool, b);
    if (a == b)
        return hl_num_si(pool, 0);
    if (a->kind == HL_NUM && b->kind == HL_NUM)
        return num_op(pool, HL_SUB, a, b);
    if (b->kind == HL_NEG)
        return hl_add(pool, a, b->a);
    return hl_sub(pool, a, b);
}

/* Strips a run of NEG nodes, flipping *neg once for each: a product of
 * -(-(...x)) folds with x, whatever the length of the run. */
static const hl_expr *strip_negs(const hl_expr *e, int *neg)
{
    for (; e->kind == HL_NEG; e = e->a)
        *neg = !*neg;
    return e;
}

static const hl_expr *signed_result(hl_pool *pool, int neg, const hl_expr *e)
{
    return neg ? hl_fold_neg(pool, e) : e;
}

static const hl_expr *fold_mul_unsigned(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (hl_fold_is_num(a, 0) || hl_fold_is_num(b, 0))
        return hl_num_si(pool, 0);
    if (hl_fold_is_num(a, 1))
        return b;
    if (hl_fold_is_num(b, 1))
        return a;
    if (hl_fold_is_num(a, -1))
        return hl_fold_neg(pool, b);
    if (hl_fold_is_num(b, -1))
        return hl_fold_neg(pool, a);
    if (a->kind == HL_NUM && b->kind == HL_NUM)
        return num_op(pool, HL_MUL, a, b);
    if (b->kind == HL_NUM) { /* constant first: x*3 -> 3*x */
        const hl_expr *t = a;
        a = b;
        b = t;
    }
    if (a->kind == HL_NUM && b->kind == HL_MUL && b->a->kind == HL_NUM) /* 2*(3*x) */
        return hl_fold_mul(pool, num_op(pool, HL_MUL, a, b->a), b->b);
    return hl_mul(pool, a, b);
}

const hl_expr *hl_fold_mul(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    int neg = 0;
    a = strip_negs(a, &neg);
    b = strip_negs(b, &neg);
    return signed_result(pool, neg, fold_mul_unsigned(pool, a, b));
}

static const hl_expr *fold_div_unsigned(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (hl_fold_is_num(b, 1))
        return a;
    if (hl_fold_is_num(a, 0) && !hl_fold_is_num(b, 0))
        return a;
    if (a->kind == HL_NUM && b->kind == HL_NUM && !hl_fold_is_num(b, 0))
        return num_op(pool, HL_DIV, a, b);
    if (b->kind == HL_NUM && !hl_fold_is_num(b, 0)) /* (2*p)/2 -> p */
        return hl_fold_mul(pool, num_op(pool, HL_DIV, hl_num_si(pool, 1), b), a);
    return hl_div(pool, a, b);
}

const hl_expr *hl_fold_div(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    int neg = 0;
    a = strip_negs(a, &neg); /* the sign of a numerator comes out: -(a/b) */
    return signed_result(pool, neg, fold_div_unsigned(pool, a, b));
}

const hl_expr *hl_fold_pow(hl_pool *pool, const hl_expr *a, const hl_expr *b)
{
    if (hl_fold_is_num(b, 0))
        return hl_num_si(pool, 1);
    if (hl_fold_is_num(b, 1))
        return a;
    return hl_pow(pool, a, b);
}
