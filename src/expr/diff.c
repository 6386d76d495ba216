/* Differentiation, through the folding constructors of fold.h, so d/dx
 * x^3*y is 3*x^2*y and not 3*x^2*1*y + x^3*0.  Node by node in post-order
 * (hl_expr_postorder): each rule reads its operands' derivatives from the
 * memo, so no chain is too deep. */
#include <string.h>

#include "expr/fold.h"
#include "base/memo.h"
#include "expr/prec.h"

typedef struct diff_walk {
    hl_pool *pool;
    const char *var;
    hl_memo done;
} diff_walk;

/* f'(u) for each function */
static const hl_expr *fun_deriv(hl_pool *pool, hl_fun f, const hl_expr *e, const hl_expr *u)
{
    const hl_expr *one = hl_num_si(pool, 1), *two = hl_num_si(pool, 2);
    switch (f) {
    case HL_SIN: return hl_call(pool, HL_COS, u);
    case HL_COS: return hl_fold_neg(pool, hl_call(pool, HL_SIN, u));
    case HL_TAN: return hl_add(pool, one, hl_pow(pool, e, two)); /* 1 + tan(u)^2 */
    case HL_EXP: return e;
    case HL_LOG: return hl_fold_div(pool, one, u);
    case HL_SQRT: return hl_fold_div(pool, one, hl_mul(pool, two, e));
    case HL_ATAN: return hl_fold_div(pool, one, hl_add(pool, one, hl_pow(pool, u, two)));
    case HL_ASIN:
        return hl_fold_div(pool, one,
                           hl_call(pool, HL_SQRT, hl_sub(pool, one, hl_pow(pool, u, two))));
    case HL_ACOS:
        return hl_fold_neg(pool, hl_fold_div(pool, one,
                                             hl_call(pool, HL_SQRT,
                                                     hl_sub(pool, one, hl_pow(pool, u, two)))));
    case HL_SINH: return hl_call(pool, HL_COSH, u);
    case HL_COSH: return hl_call(pool, HL_SINH, u);
    case HL_TANH: return hl_sub(pool, one, hl_pow(pool, e, two)); /* 1 - tanh(u)^2 */
    case HL_ASINH:
        return hl_fold_div(pool, one,
                           hl_call(pool, HL_SQRT, hl_add(pool, one, hl_pow(pool, u, two))));
    default: return hl_num_si(pool, 0); /* unreachable: every hl_fun is listed */
    }
}

/* The derivative of an operand, done before the node (post-order). */
static const hl_expr *d(diff_walk *w, const hl_expr *e)
{
    return hl_memo_get(&w->done, e)->e;
}

static const hl_expr *d_pow(diff_walk *w, const hl_expr *e)
{
    hl_pool *pool = w->pool;
    const hl_expr *a = e->a, *b = e->b, *da = d(w, a), *db = d(w, b);
    if (hl_fold_is_num(a, 0)) /* 0^b is 0 wherever it is defined */
        return a;
    if (hl_fold_is_num(db, 0)) { /* b constant: b*a^(b-1)*a' */
        const hl_expr *bm1 = b->kind == HL_NUM ? hl_fold_sub(pool, b, hl_num_si(pool, 1))
                                               : hl_sub(pool, b, hl_num_si(pool, 1));
        return hl_fold_mul(pool, hl_fold_mul(pool, b, hl_fold_pow(pool, a, bm1)), da);
    }
    /* a^b*(b'*log(a) + b*a'/a) */
    const hl_expr *t = hl_fold_add(pool, hl_fold_mul(pool, db, hl_call(pool, HL_LOG, a)),
                                   hl_fold_div(pool, hl_fold_mul(pool, b, da), a));
    return hl_fold_mul(pool, e, t);
}

/* atan2(y, x)' = (x y' - y x')/(x^2 + y^2) */
static const hl_expr *d_atan2(diff_walk *w, const hl_expr *e)
{
    hl_pool *pool = w->pool;
    const hl_expr *y = e->a, *x = e->b, *dy = d(w, y), *dx = d(w, x), *two = hl_num_si(pool, 2);
    const hl_expr *num = hl_fold_sub(pool, hl_fold_mul(pool, x, dy), hl_fold_mul(pool, y, dx));
    if (hl_fold_is_num(num, 0))
        return num;
    return hl_fold_div(pool, num, hl_add(pool, hl_pow(pool, x, two), hl_pow(pool, y, two)));
}

static int d_node(void *arg, const hl_expr *e)
{
    diff_walk *w = arg;
    hl_pool *pool = w->pool;
    const hl_expr *r, *da, *db;
    switch (e->kind) {
    case HL_SYM:
        r = hl_num_si(pool, strcmp(e->name, w->var) == 0);
        break;
    case HL_NEG:
        r = hl_fold_neg(pool, d(w, e->a));
        break;
    case HL_ADD:
        r = hl_fold_add(pool, d(w, e->a), d(w, e->b));
        break;
    case HL_SUB:
        r = hl_fold_sub(pool, d(w, e->a), d(w, e->b));
        break;
    case HL_MUL:
        da = d(w, e->a);
        db = d(w, e->b);
        r = hl_fold_add(pool, hl_fold_mul(pool, da, e->b), hl_fold_mul(pool, e->a, db));
        break;
    case HL_DIV:
        da = d(w, e->a);
        db = d(w, e->b);
        if (hl_fold_is_num(db, 0))
            r = hl_fold_div(pool, da, e->b);
        else
            r = hl_fold_div(pool,
                            hl_fold_sub(pool, hl_fold_mul(pool, da, e->b),
                                        hl_fold_mul(pool, e->a, db)),
                            hl_pow(pool, e->b, hl_num_si(pool, 2)));
        break;
    case HL_POW:
        r = d_pow(w, e);
        break;
    case HL_FUN:
        if (e->b != NULL) {
            r = d_atan2(w, e);
            break;
        }
        da = d(w, e->a);
        r = hl_fold_is_num(da, 0) ? da : hl_fold_mul(pool, fun_deriv(pool, e->fun, e, e->a), da);
        break;
    default: /* NUM, PI */
        r = hl_num_si(pool, 0);
    }
    hl_memo_put(&w->done, e)->e = r;
    return 0;
}

const hl_expr *hl_expr_diff(hl_pool *pool, const hl_expr *e, const char *var)
{
    diff_walk w = {.pool = pool, .var = var};
    hl_memo_init(&w.done);
    hl_expr_postorder(&e, 1, d_node, &w);
    const hl_expr *r = d(&w, e);
    hl_memo_clear(&w.done);
    return r;
}
