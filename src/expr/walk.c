/* Walks over an expression DAG: symbols, substitution, double evaluation.
 * Each visits every node once (memo.h), so shared subexpressions cost once
 * however often they are referenced. */
#include <math.h>
#include <string.h>

#include <flint/fmpq.h>
#include <mpfr.h>

#include "expr/memo.h"
#include "expr/prec.h"

/* ---- symbols ------------------------------------------------------------------ */

typedef struct sym_walk {
    hl_memo seen;
    const char **names;
    int max, count;
} sym_walk;

static void collect(sym_walk *w, const hl_expr *e)
{
    if (hl_memo_get(&w->seen, e))
        return;
    hl_memo_put(&w->seen, e);
    if (e->kind == HL_SYM) { /* each SYM node is one distinct name (interned) */
        if (w->count < w->max)
            w->names[w->count] = e->name;
        w->count++;
    }
    if (e->a)
        collect(w, e->a);
    if (e->b)
        collect(w, e->b);
}

int hl_expr_symbols(const hl_expr *e, const char **names, int max)
{
    sym_walk w = {.names = names, .max = max, .count = 0};
    hl_memo_init(&w.seen);
    collect(&w, e);
    hl_memo_clear(&w.seen);
    return w.count;
}

static int has(hl_memo *seen, const hl_expr *e, const char *name)
{
    if (hl_memo_get(seen, e))
        return 0; /* already searched: not there */
    hl_memo_put(seen, e);
    if (e->kind == HL_SYM)
        return strcmp(e->name, name) == 0;
    return (e->a && has(seen, e->a, name)) || (e->b && has(seen, e->b, name));
}

int hl_expr_has_symbol(const hl_expr *e, const char *name)
{
    hl_memo seen;
    hl_memo_init(&seen);
    int r = has(&seen, e, name);
    hl_memo_clear(&seen);
    return r;
}

/* ---- divisors ----------------------------------------------------------------- */

typedef struct div_walk {
    hl_memo seen;
    int (*is_bad)(const hl_expr *d, void *arg);
    void *arg;
} div_walk;

static int divides(div_walk *w, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&w->seen, e);
    if (v)
        return v->i;
    int r = 0;
    if (e->kind == HL_DIV)
        r = w->is_bad(e->b, w->arg);
    else if (e->kind == HL_POW && (e->b->kind != HL_NUM || fmpq_sgn(e->b->num) < 0))
        r = w->is_bad(e->a, w->arg);
    r = r || (e->a && divides(w, e->a)) || (e->b && divides(w, e->b));
    hl_memo_put(&w->seen, e)->i = r;
    return r;
}

int hl_expr_divides_by(const hl_expr *e, int (*is_bad)(const hl_expr *d, void *arg), void *arg)
{
    div_walk w = {.is_bad = is_bad, .arg = arg};
    hl_memo_init(&w.seen);
    int r = divides(&w, e);
    hl_memo_clear(&w.seen);
    return r;
}

/* ---- cost --------------------------------------------------------------------- */

static double cost(hl_memo *seen, const hl_expr *e)
{
    if (hl_memo_get(seen, e))
        return 0;
    hl_memo_put(seen, e);
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
    return c + (e->a ? cost(seen, e->a) : 0) + (e->b ? cost(seen, e->b) : 0);
}

double hl_expr_cost(const hl_expr *const *e, int n)
{
    hl_memo seen;
    hl_memo_init(&seen);
    double c = 0;
    for (int i = 0; i < n; i++)
        c += cost(&seen, e[i]);
    hl_memo_clear(&seen);
    return c;
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
    case HL_FUN: return hl_call(pool, e->fun, a);
    case HL_ADD: return hl_add(pool, a, b);
    case HL_SUB: return hl_sub(pool, a, b);
    case HL_MUL: return hl_mul(pool, a, b);
    case HL_DIV: return hl_div(pool, a, b);
    case HL_POW: return hl_pow(pool, a, b);
    default: return e;
    }
}

static const hl_expr *subst(subst_walk *w, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&w->done, e);
    if (v)
        return v->e;
    const hl_expr *r = e;
    if (e->kind == HL_SYM) {
        for (int i = 0; i < w->n; i++)
            if (strcmp(e->name, w->names[i]) == 0) {
                r = w->vals[i];
                break;
            }
    } else if (e->a) {
        const hl_expr *a = subst(w, e->a);
        const hl_expr *b = e->b ? subst(w, e->b) : NULL;
        r = rebuild(w->pool, e, a, b);
    }
    hl_memo_put(&w->done, e)->e = r;
    return r;
}

const hl_expr *hl_expr_subst(hl_pool *pool, const hl_expr *e, int n,
                             const char *const *names, const hl_expr *const *vals)
{
    subst_walk w = {.pool = pool, .n = n, .names = names, .vals = vals};
    hl_memo_init(&w.done);
    const hl_expr *r = subst(&w, e);
    hl_memo_clear(&w.done);
    return r;
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

static int eval(eval_walk *w, const hl_expr *e, double *out)
{
    hl_memo_val *v = hl_memo_get(&w->done, e);
    if (v) {
        *out = v->d;
        return HL_OK;
    }
    double a = 0, b = 0, r;
    int st;
    if (e->a && (st = eval(w, e->a, &a)))
        return st;
    if (e->b && (st = eval(w, e->b, &b)))
        return st;
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
    case HL_FUN: r = apply_fun(e->fun, a); break;
    default: r = NAN;
    }
    hl_memo_put(&w->done, e)->d = r;
    *out = r;
    return HL_OK;
}

int hl_expr_eval_d(double *out, const hl_expr *e, int n, const char *const *names,
                   const double *vals, hl_error *err)
{
    eval_walk w = {.n = n, .names = names, .vals = vals, .err = err};
    hl_error_clear(err);
    hl_memo_init(&w.done);
    int st = eval(&w, e, out);
    hl_memo_clear(&w.done);
    return st;
}
