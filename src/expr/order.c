/* The terms of every sum and the factors of every product of an expression
 * put in a fixed order, so that two writings of one formula that differ only
 * in that order become the same DAG — and evaluate to the same bits.  The
 * order compares structure and names, never pool ids or pointers, which
 * depend on the order the formula was typed in. */
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>

#include "base/buf.h"
#include "base/memo.h"
#include "hamlie/expr.h"

/* A total order on expressions by their structure. */
static int cmp_expr(const hl_expr *x, const hl_expr *y)
{
    while (x != y) {
        if (x->kind != y->kind)
            return (int)x->kind - (int)y->kind;
        switch (x->kind) {
        case HL_NUM:
            return fmpq_cmp(x->num, y->num);
        case HL_SYM:
            return strcmp(x->name, y->name);
        case HL_PI:
            return 0;
        case HL_FUN:
            if (x->fun != y->fun)
                return (int)x->fun - (int)y->fun;
            if (x->b) { /* a function of two arguments: its second one first */
                int c = cmp_expr(x->b, y->b);
                if (c != 0)
                    return c;
            }
            break;
        case HL_NEG:
            break;
        default: {
            /* The right operand first: the left one is the long chain of
             * a sum or product, walked by the loop, not by recursion. */
            int c = cmp_expr(x->b, y->b);
            if (c != 0)
                return c;
            break;
        }
        }
        x = x->a, y = y->a;
    }
    return 0;
}

/* One operand of a flattened sum (sign -1 subtracts it) or product
 * (sign -1 divides by it). */
typedef struct operand {
    const hl_expr *e;
    int sign;
} operand;

static int cmp_operand(const void *a, const void *b)
{
    const operand *x = a, *y = b;
    int c = cmp_expr(x->e, y->e);
    return c != 0 ? c : y->sign - x->sign;
}

typedef struct order_walk {
    hl_pool *pool;
    hl_memo done;
    operand *ops; /* a stack shared by the nested flattenings */
    int n, cap;
} order_walk;

static const hl_expr *order(order_walk *w, const hl_expr *e);

static void push(order_walk *w, const hl_expr *e, int sign)
{
    if (w->n == w->cap) {
        w->cap = w->cap ? 2 * w->cap : 32;
        w->ops = hl_xrealloc(w->ops, (size_t)w->cap * sizeof *w->ops);
    }
    w->ops[w->n++] = (operand){e, sign};
}

static const hl_expr *negated(hl_pool *pool, const hl_expr *num)
{
    fmpq_t v;
    fmpq_init(v);
    fmpq_neg(v, num->num);
    const hl_expr *r = hl_num_fmpq(pool, v);
    fmpq_clear(v);
    return r;
}

/* A minus sign in front of e: a negative literal if e is a number. */
static const hl_expr *minus(hl_pool *pool, const hl_expr *e)
{
    return e->kind == HL_NUM ? negated(pool, e) : hl_neg(pool, e);
}

/* Is e a node of a sum (products: of a product) that flattening walks
 * through? */
static int joins(const hl_expr *e, int sum)
{
    return sum ? e->kind == HL_ADD || e->kind == HL_SUB : e->kind == HL_MUL || e->kind == HL_DIV;
}

/* Flatten the sum (or product) at e into w->ops[base..]: each operand in its
 * own order, a minus sign taken out of it into *neg (products) or into its
 * sign (sums).  Iterative: a sum of 10^5 terms is a chain that deep. */
static void flatten(order_walk *w, const hl_expr *e, int sum, int base, int *neg)
{
    push(w, e, 1);
    for (int i = base; i < w->n;) {
        const hl_expr *t = w->ops[i].e;
        int sign = w->ops[i].sign;
        if (joins(t, sum)) {
            int second = (t->kind == HL_SUB || t->kind == HL_DIV) ? -sign : sign;
            w->ops[i].e = t->a;
            push(w, t->b, second);
            continue;
        }
        if (t->kind == HL_NEG) {
            w->ops[i].e = t->a;
            if (sum)
                w->ops[i].sign = -sign;
            else
                *neg = !*neg;
            continue;
        }
        const hl_expr *o = order(w, t);
        if (o->kind == HL_NEG || (o->kind == HL_NUM && fmpq_sgn(o->num) < 0)) {
            /* the operand's own sign, out: -2 and -(2) are one term */
            o = o->kind == HL_NEG ? o->a : negated(w->pool, o);
            if (sum)
                sign = -sign;
            else
                *neg = !*neg;
        }
        w->ops[i] = (operand){o, sign};
        i++;
    }
    qsort(w->ops + base, (size_t)(w->n - base), sizeof *w->ops, cmp_operand);
}

static const hl_expr *rebuild_sum(order_walk *w, int base)
{
    const operand *t = w->ops + base;
    const hl_expr *r = t[0].sign > 0 ? t[0].e : minus(w->pool, t[0].e);
    for (int i = 1; i < w->n - base; i++)
        r = t[i].sign > 0 ? hl_add(w->pool, r, t[i].e) : hl_sub(w->pool, r, t[i].e);
    return r;
}

/* Numerator factors (sorted first by cmp_operand) times each other, then
 * divided by each denominator factor in turn. */
static const hl_expr *rebuild_product(order_walk *w, int base, int neg)
{
    const hl_expr *r = NULL;
    for (int i = base; i < w->n; i++)
        if (w->ops[i].sign > 0)
            r = r ? hl_mul(w->pool, r, w->ops[i].e) : w->ops[i].e;
    if (r == NULL)
        r = hl_num_si(w->pool, 1);
    for (int i = base; i < w->n; i++)
        if (w->ops[i].sign < 0)
            r = hl_div(w->pool, r, w->ops[i].e);
    return neg ? minus(w->pool, r) : r;
}

static const hl_expr *order_node(order_walk *w, const hl_expr *e)
{
    int base = w->n, neg = 0;
    const hl_expr *r;
    switch (e->kind) {
    case HL_NUM:
    case HL_SYM:
    case HL_PI:
        return e;
    case HL_FUN:
        if (e->b)
            return hl_call2(w->pool, e->fun, order(w, e->a), order(w, e->b));
        return hl_call(w->pool, e->fun, order(w, e->a));
    case HL_POW:
        return hl_pow(w->pool, order(w, e->a), order(w, e->b));
    case HL_MUL:
    case HL_DIV:
        flatten(w, e, 0, base, &neg);
        r = rebuild_product(w, base, neg);
        break;
    default: /* a sum, or a minus sign in front of anything */
        flatten(w, e, 1, base, &neg);
        r = rebuild_sum(w, base);
    }
    w->n = base;
    return r;
}

static const hl_expr *order(order_walk *w, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&w->done, e);
    if (v != NULL)
        return v->e;
    const hl_expr *r = order_node(w, e);
    hl_memo_put(&w->done, e)->e = r;
    return r;
}

const hl_expr *hl_expr_ordered(hl_pool *pool, const hl_expr *e)
{
    order_walk w = {.pool = pool};
    hl_memo_init(&w.done);
    const hl_expr *r = order(&w, e);
    hl_memo_clear(&w.done);
    free(w.ops);
    return r;
}
