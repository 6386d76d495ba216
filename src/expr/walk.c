/* Walks over an expression DAG: symbols, cost, size, substitution, double
 * evaluation.  Each visits every node once, so shared subexpressions cost
 * once however often they are referenced, and none recurses on the C
 * stack (a sum of 10^5 terms is a chain 10^5 nodes deep): hl_expr_postorder
 * hands the nodes over operands first, and each rule reads its operands'
 * results from a memo (memo.h). */
#include <math.h>
#include <string.h>

#include <flint/fmpq.h>
#include <mpfr.h>

#include "base/buf.h"
#include "base/memo.h"
#include "expr/prec.h"

/* ---- post-order, without recursion ------------------------------------------ */

typedef struct frame {
    const hl_expr *e;
    int operands_pushed;
} frame;

int hl_expr_postorder(const hl_expr *const *roots, int nroots,
                      int (*visit)(void *arg, const hl_expr *node), void *arg)
{
    hl_memo seen;
    size_t n = 0, cap = 64 + (size_t)nroots;
    frame *stack = hl_xmalloc(cap * sizeof *stack);
    int st = 0;

    hl_memo_init(&seen);
    for (int i = nroots - 1; i >= 0; i--) /* roots[0] first */
        stack[n++] = (frame){roots[i], 0};
    while (n > 0 && st == 0) {
        frame *f = &stack[n - 1];
        if (hl_memo_get(&seen, f->e)) { /* reached twice before it was done */
            n--;
            continue;
        }
        if (f->operands_pushed) {
            hl_memo_put(&seen, f->e);
            st = visit(arg, f->e);
            n--;
            continue;
        }
        f->operands_pushed = 1;
        const hl_expr *a = f->e->a, *b = f->e->b;
        if (n + 2 > cap)
            stack = hl_xrealloc(stack, (cap *= 2) * sizeof *stack);
        if (b && !hl_memo_get(&seen, b)) /* b pushed first: a is visited first */
            stack[n++] = (frame){b, 0};
        if (a && !hl_memo_get(&seen, a))
            stack[n++] = (frame){a, 0};
    }
    free(stack);
    hl_memo_clear(&seen);
    return st;
}

/* ---- symbols ------------------------------------------------------------------ */

typedef struct sym_walk {
    const char **names;
    int max, count;
} sym_walk;

static int collect(void *arg, const hl_expr *e)
{
    sym_walk *w = arg;
    if (e->kind == HL_SYM) { /* each SYM node is one distinct name (interned) */
        if (w->count < w->max)
            w->names[w->count] = e->name;
        w->count++;
    }
    return 0;
}

int hl_expr_symbols(const hl_expr *e, const char **names, int max)
{
    sym_walk w = {.names = names, .max = max, .count = 0};
    hl_expr_postorder(&e, 1, collect, &w);
    return w.count;
}

static int is_symbol(void *name, const hl_expr *e)
{
    return e->kind == HL_SYM && strcmp(e->name, name) == 0; /* 1 stops the walk */
}

int hl_expr_has_symbol(const hl_expr *e, const char *name)
{
    return hl_expr_postorder(&e, 1, is_symbol, (void *)name);
}

/* ---- divisors ----------------------------------------------------------------- */

typedef struct div_walk {
    int (*is_bad)(const hl_expr *d, void *arg);
    void *arg;
} div_walk;

static int bad_divisor(void *arg, const hl_expr *e) /* 1 stops the walk */
{
    div_walk *w = arg;
    if (e->kind == HL_DIV)
        return w->is_bad(e->b, w->arg);
    if (e->kind == HL_POW && (e->b->kind != HL_NUM || fmpq_sgn(e->b->num) < 0))
        return w->is_bad(e->a, w->arg);
    return 0;
}

int hl_expr_divides_by(const hl_expr *e, int (*is_bad)(const hl_expr *d, void *arg), void *arg)
{
    div_walk w = {.is_bad = is_bad, .arg = arg};
    return hl_expr_postorder(&e, 1, bad_divisor, &w);
}

/* ---- cost --------------------------------------------------------------------- */

static int node_cost(void *total, const hl_expr *e)
{
    double c;
    switch (e->kind) {
    case HL_FUN: c = 20; break;
    case HL_DIV: c = 4; break;
    case HL_POW: /* an integer power is a few products, any other exp(b log a) */
        c = e->b->kind == HL_NUM && fmpz_is_one(fmpq_denref(e->b->num)) ? 2 : 40;
        break;
    case HL_NEG:
    case HL_ADD:
    case HL_SUB:
    case HL_MUL: c = 1; break;
    default: c = 0; /* NUM, SYM, PI: operands */
    }
    *(double *)total += c;
    return 0;
}

double hl_expr_cost(const hl_expr *const *e, int n)
{
    double c = 0; /* one walk over all: a node shared between them counts once */
    hl_expr_postorder(e, n, node_cost, &c);
    return c;
}

/* ---- size written out ---------------------------------------------------------- */

static int tree_size_node(void *arg, const hl_expr *e)
{
    hl_memo *done = arg;
    double n = 1;
    if (e->a)
        n += hl_memo_get(done, e->a)->d;
    if (e->b)
        n += hl_memo_get(done, e->b)->d;
    hl_memo_put(done, e)->d = n;
    return 0;
}

double hl_expr_tree_size(const hl_expr *e)
{
    hl_memo done;
    hl_memo_init(&done);
    hl_expr_postorder(&e, 1, tree_size_node, &done);
    double n = hl_memo_get(&done, e)->d;
    hl_memo_clear(&done);
    return n;
}

/* ---- substitution -------------------------------------------------------------- */

typedef struct subst_walk {
    hl_pool *pool;
    hl_memo done;
    int n;
    const char *const *names;
    const hl_expr *const *vals;
} subst_walk;

static const hl_expr *rebuild(hl_pool *pool, const hl_expr *e, const hl_expr *a,
                              const hl_expr *b)
{
    if (a == e->a && b == e->b)
        return e;
    switch (e->kind) {
    case HL_NEG: return hl_neg(pool, a);
    case HL_FUN: return b != NULL ? hl_call2(pool, e->fun, a, b) : hl_call(pool, e->fun, a);
    case HL_ADD: return hl_add(pool, a, b);
    case HL_SUB: return hl_sub(pool, a, b);
    case HL_MUL: return hl_mul(pool, a, b);
    case HL_DIV: return hl_div(pool, a, b);
    case HL_POW: return hl_pow(pool, a, b);
    default: return e;
    }
}

static int subst_node(void *arg, const hl_expr *e)
{
    subst_walk *w = arg;
    const hl_expr *r = e;
    if (e->kind == HL_SYM) {
        for (int i = 0; i < w->n; i++)
            if (strcmp(e->name, w->names[i]) == 0) {
                r = w->vals[i];
                break;
            }
    } else if (e->a) {
        const hl_expr *b = e->b ? hl_memo_get(&w->done, e->b)->e : NULL;
        r = rebuild(w->pool, e, hl_memo_get(&w->done, e->a)->e, b);
    }
    hl_memo_put(&w->done, e)->e = r;
    return 0;
}

void hl_expr_subst_each(hl_pool *pool, const hl_expr **e, int ne, int n,
                        const char *const *names, const hl_expr *const *vals)
{
    subst_walk w = {.pool = pool, .n = n, .names = names, .vals = vals};
    hl_memo_init(&w.done);
    hl_expr_postorder(e, ne, subst_node, &w);
    for (int i = 0; i < ne; i++)
        e[i] = hl_memo_get(&w.done, e[i])->e;
    hl_memo_clear(&w.done);
}

const hl_expr *hl_expr_subst(hl_pool *pool, const hl_expr *e, int n,
                             const char *const *names, const hl_expr *const *vals)
{
    hl_expr_subst_each(pool, &e, 1, n, names, vals);
    return e;
}

/* ---- evaluation in double ---------------------------------------------------- */

typedef struct eval_walk {
    hl_memo done;
    int n;
    const char *const *names;
    const double *vals;
    hl_error *err;
} eval_walk;

static double apply_fun(hl_fun f, double x)
{
    switch (f) {
    case HL_SIN: return sin(x);
    case HL_COS: return cos(x);
    case HL_TAN: return tan(x);
    case HL_EXP: return exp(x);
    case HL_LOG: return log(x);
    case HL_SQRT: return sqrt(x);
    case HL_ATAN: return atan(x);
    case HL_ASIN: return asin(x);
    case HL_ACOS: return acos(x);
    case HL_ASINH: return asinh(x);
    case HL_SINH: return sinh(x);
    case HL_COSH: return cosh(x);
    case HL_TANH: return tanh(x);
    default: return NAN;
    }
}


/* The double nearest to a rational.  FLINT 2.9's fmpq_get_d divides two
 * rounded doubles (1.3 -> 1.2999999999999998); MPFR rounds once, exactly. */
static double rational_to_double(const fmpq_t x)
{
    mpfr_t m;
    mpfr_init2(m, 53);
    fmpq_get_mpfr(m, x, MPFR_RNDN);
    double d = mpfr_get_d(m, MPFR_RNDN);
    mpfr_clear(m);
    return d;
}

static int eval_node(void *arg, const hl_expr *e)
{
    eval_walk *w = arg;
    double a = e->a ? hl_memo_get(&w->done, e->a)->d : 0;
    double b = e->b ? hl_memo_get(&w->done, e->b)->d : 0, r;
    switch (e->kind) {
    case HL_NUM: r = rational_to_double(e->num); break;
    case HL_PI: r = 3.14159265358979323846; break;
    case HL_SYM:
        for (int i = 0;; i++) {
            if (i == w->n)
                return hl_error_set(w->err, HL_EINVAL, NULL, -1, 0,
                                    "symbol '%s' has no value", e->name);
            if (strcmp(e->name, w->names[i]) == 0) {
                r = w->vals[i];
                break;
            }
        }
        break;
    case HL_NEG: r = -a; break;
    case HL_ADD: r = a + b; break;
    case HL_SUB: r = a - b; break;
    case HL_MUL: r = a * b; break;
    case HL_DIV: r = a / b; break;
    case HL_POW: r = pow(a, b); break;
    case HL_FUN: r = e->fun == HL_ATAN2 ? atan2(a, b) : apply_fun(e->fun, a); break;
    default: r = NAN;
    }
    hl_memo_put(&w->done, e)->d = r;
    return HL_OK;
}

hl_status hl_expr_eval_d(double *out, const hl_expr *e, int n, const char *const *names,
                         const double *vals, hl_error *err)
{
    eval_walk w = {.n = n, .names = names, .vals = vals, .err = err};
    hl_error_clear(err);
    hl_memo_init(&w.done);
    int st = hl_expr_postorder(&e, 1, eval_node, &w);
    if (st == HL_OK)
        *out = hl_memo_get(&w.done, e)->d;
    hl_memo_clear(&w.done);
    return st;
}
