/* The numeric rules for the integrals int(s, f) of a scheme (scheme.h):
 * Gauss-Legendre, and the Taylor series of f at s = 1/2 with the check
 * that tells, at run time, whether its truncation is below rounding. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/memo.h"
#include "hamlie/expr.h"
#include "scheme/scheme_impl.h"

/* x exactly, as a rational (a double is a dyadic rational). */
static const hl_expr *num_d(hl_pool *pool, double x)
{
    int e;
    double f = frexp(x, &e);
    fmpq_t r;
    fmpq_init(r);
    fmpz_set_d(fmpq_numref(r), ldexp(f, 53));
    e -= 53;
    if (e >= 0)
        fmpz_mul_2exp(fmpq_numref(r), fmpq_numref(r), (ulong)e);
    else
        fmpz_mul_2exp(fmpq_denref(r), fmpq_denref(r), (ulong)(-e));
    fmpq_canonicalise(r);
    const hl_expr *v = hl_num_fmpq(pool, r);
    fmpq_clear(r);
    return v;
}

/* Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n, the usual
 * recurrence). */
static void gauss_legendre(double *s, double *w, int n)
{
    for (int i = 0; i < (n + 1) / 2; i++) {
        double x = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1, p1 = p2;
            }
            double pn = n == 1 ? x : p1, pm = n == 1 ? 1 : p0;
            dp = n * (x * pn - pm) / (x * x - 1);
            double dx = pn / dp;
            x -= dx;
            if (fabs(dx) < 1e-17)
                break;
        }
        s[i] = (1 - x) / 2;
        s[n - 1 - i] = (1 + x) / 2;
        w[i] = w[n - 1 - i] = 1 / ((1 - x * x) * dp * dp);
    }
}

/* int_0^1 f(s) ds by Gauss-Legendre with n nodes. */
static const hl_expr *gauss_rule(const hl_expr *f, int n, hl_pool *pool)
{
    double sn[HL_SCHEME_GAUSS_NODES], wn[HL_SCHEME_GAUSS_NODES];
    gauss_legendre(sn, wn, n);
    const char *sv = HL_SCHEME_S;
    const hl_expr *sum = NULL;
    for (int i = 0; i < n; i++) {
        const hl_expr *node = num_d(pool, sn[i]);
        const hl_expr *t = hl_mul(pool, num_d(pool, wn[i]), hl_expr_subst(pool, f, 1, &sv, &node));
        sum = sum ? hl_add(pool, sum, t) : t;
    }
    return sum;
}

/* int_0^1 f(s) ds from f's Taylor series at s = 1/2 to degree K:
 * sum over even k of c_k / (2^k (k + 1)); the odd terms integrate to 0, so
 * an even K is exact for polynomials of degree K + 1. */
static const hl_expr *midpoint_taylor_rule(const hl_expr *f, int K, hl_pool *pool)
{
    const hl_expr **c = hl_xmalloc((size_t)(K + 1) * sizeof *c);
    hl_expr_taylor(c, pool, f, HL_SCHEME_S, hl_num_frac(pool, 1, 2), K);
    int n = 0;
    for (int k = 0; k <= K; k += 2)
        if (!(c[k]->kind == HL_NUM && fmpq_is_zero(c[k]->num)))
            c[n++] = hl_mul(pool, hl_num_frac(pool, 1, (1UL << k) * (unsigned long)(k + 1)), c[k]);
    /* summed pairwise: the terms are independent, and a tree of sums waits
     * for log2 n additions where a chain waits for n */
    while (n > 1) {
        int m = 0;
        for (int i = 0; i + 1 < n; i += 2)
            c[m++] = hl_add(pool, c[i], c[i + 1]);
        if (n % 2)
            c[m++] = c[n - 1];
        n = m;
    }
    const hl_expr *sum = n ? c[0] : hl_num_si(pool, 0);
    free(c);
    return sum;
}


/* ---- where the Taylor rule is exact to rounding -------------------------
 * The walk below accepts f when it is built from polynomial operations in
 * s and from sin, cos, exp, sinh, cosh of arguments linear in s, a s + b
 * (anything else in s: a quotient, a root, a non-integer power, another
 * function, is refused and the Gauss rule taken).  Such an f is entire;
 * with d the degree of its polynomial part and A the sum of the |a|, its
 * Taylor coefficients at s = 1/2 are bounded by |f| A^(k-d)/(k-d)! and the
 * rule's truncation after degree K, relative to f's size, by about
 * (A/2)^e / e!, e = K + 1 - d.  That is below DBL_EPSILON where A <= R =
 * 2 (e! eps)^(1/e) (K = 14, d = 0: R = 1.16, the pendulum's AVF at
 * |Q - q| <= 1.16); the stepper checks sum a^2 <= R^2 / n (n functions,
 * A^2 <= n sum a^2) after each step and otherwise takes the step again
 * with the Gauss rule. */

typedef struct entire_walk {
    hl_pool *pool;
    hl_memo seen;
    const hl_expr *slopes; /* sum of a^2 */
    int nfun;
} entire_walk;

enum { FREE = -2, REFUSED = -1 }; /* else the degree in s; + 1000 with a function */

#define WITH_FUN 1000

static int free_of_s(int r) { return r == FREE; }
static int degree(int r) { return r == FREE ? 0 : r % WITH_FUN; }
static int has_fun(int r) { return r >= WITH_FUN; }
static int with(int deg, int fun) { return deg > 500 ? REFUSED : deg + (fun ? WITH_FUN : 0); }

static int walk(entire_walk *w, const hl_expr *e);

static int walk_fun(entire_walk *w, const hl_expr *e)
{
    int r = walk(w, e->a);
    if (e->b != NULL) /* atan2: not entire; fine where s is in neither argument */
        return free_of_s(r) && free_of_s(walk(w, e->b)) ? FREE : REFUSED;
    if (free_of_s(r))
        return FREE;
    int entire = e->fun == HL_SIN || e->fun == HL_COS || e->fun == HL_EXP || e->fun == HL_SINH ||
                 e->fun == HL_COSH;
    if (r == REFUSED || !entire || has_fun(r) || degree(r) != 1)
        return REFUSED;
    const hl_expr *a = hl_expr_diff(w->pool, e->a, HL_SCHEME_S); /* free of s */
    const hl_expr *a2 = hl_mul(w->pool, a, a);
    w->slopes = w->slopes ? hl_add(w->pool, w->slopes, a2) : a2;
    w->nfun++;
    return with(0, 1);
}

static int walk_pow(entire_walk *w, const hl_expr *e)
{
    int ra = walk(w, e->a), rb = walk(w, e->b);
    if (ra == REFUSED || rb == REFUSED || !free_of_s(rb))
        return REFUSED;
    if (free_of_s(ra))
        return FREE;
    const hl_expr *n = e->b;
    if (n->kind != HL_NUM || !fmpz_is_one(fmpq_denref(n->num)) ||
        fmpz_sgn(fmpq_numref(n->num)) < 0 || fmpz_cmp_si(fmpq_numref(n->num), 64) > 0)
        return REFUSED;
    return with(degree(ra) * (int)fmpz_get_si(fmpq_numref(n->num)), has_fun(ra));
}

static int walk_node(entire_walk *w, const hl_expr *e)
{
    int ra, rb;
    switch (e->kind) {
    case HL_SYM: return strcmp(e->name, HL_SCHEME_S) == 0 ? 1 : FREE;
    case HL_NUM:
    case HL_PI: return FREE;
    case HL_NEG: return walk(w, e->a);
    case HL_FUN: return walk_fun(w, e);
    case HL_POW: return walk_pow(w, e);
    default: break;
    }
    ra = walk(w, e->a), rb = walk(w, e->b);
    if (ra == REFUSED || rb == REFUSED)
        return REFUSED;
    if (free_of_s(ra) && free_of_s(rb))
        return FREE;
    int fun = has_fun(ra) || has_fun(rb);
    switch (e->kind) {
    case HL_ADD:
    case HL_SUB: return with(degree(ra) > degree(rb) ? degree(ra) : degree(rb), fun);
    case HL_MUL: return with(degree(ra) + degree(rb), fun);
    default: return free_of_s(rb) ? ra : REFUSED; /* DIV: by a constant only */
    }
}

static int walk(entire_walk *w, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&w->seen, e);
    if (v)
        return v->i;
    int r = walk_node(w, e);
    hl_memo_put(&w->seen, e)->i = r;
    return r;
}

/* The Taylor rule's degree: 14, the exactness of the 8-node Gauss rule. */
#define TAYLOR_K (2 * HL_SCHEME_GAUSS_NODES - 2)

const hl_expr *scheme_integral(const hl_expr *f, int taylor_ok, hl_pool *pool,
                               const hl_expr **check, double *bound)
{
    *check = NULL, *bound = INFINITY;
    const hl_expr *gl = gauss_rule(f, HL_SCHEME_GAUSS_NODES, pool);
    if (!taylor_ok)
        return gl;
    entire_walk w = {.pool = pool};
    hl_memo_init(&w.seen);
    int r = walk(&w, f);
    hl_memo_clear(&w.seen);
    int d = degree(r), e = TAYLOR_K + 1 - d;
    if (r == REFUSED || (w.nfun > 0 && e < 8) || (w.nfun == 0 && d > TAYLOR_K + 1))
        return gl;
    const hl_expr *ty = midpoint_taylor_rule(f, TAYLOR_K, pool);
    if (2 * hl_expr_cost(&ty, 1) > hl_expr_cost(&gl, 1))
        return gl;
    if (w.nfun > 0) { /* else a polynomial of degree <= K + 1: exact */
        double lf = lgamma(e + 1.0), R = 2 * exp((lf + log(DBL_EPSILON)) / e);
        *check = w.slopes;
        *bound = R * R / w.nfun;
    }
    return ty;
}
