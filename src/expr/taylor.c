/* Taylor coefficients of an expression in one symbol, as expressions.
 *
 * The recurrences are those of the tape's Taylor mode (tape.h), applied to
 * expressions instead of numbers: each node gets its K + 1 coefficients,
 * built from its operands' through the folding constructors (fold.h), so a
 * coefficient that vanishes is the number 0 and costs nothing further.  A
 * function of an argument linear in the symbol (sin(q + s h)) takes its
 * closed-form coefficients, +-f^(k) h^k/k!, with the powers built in a tree
 * so the compiled code waits on few products.  A node whose operands'
 * series are constant keeps its own expression. */
#include <stdlib.h>
#include <string.h>

#include "expr/fold.h"
#include "base/memo.h"
#include "base/buf.h"

typedef struct taylor_walk {
    hl_pool *pool;
    const char *var;
    const hl_expr *at, *zero;
    int K;
    hl_memo done; /* node -> index in series[] */
    const hl_expr ***series;
    int count, cap;
} taylor_walk;

static const hl_expr **new_series(taylor_walk *w)
{
    if (w->count == w->cap) {
        w->cap = w->cap ? 2 * w->cap : 64;
        w->series = hl_xrealloc(w->series, (size_t)w->cap * sizeof *w->series);
    }
    const hl_expr **c = hl_xmalloc((size_t)(w->K + 1) * sizeof *c);
    for (int k = 0; k <= w->K; k++)
        c[k] = w->zero;
    w->series[w->count++] = c;
    return c;
}

/* e's series is the last one made */
static void remember(taylor_walk *w, const hl_expr *e)
{
    hl_memo_put(&w->done, e)->i = w->count - 1;
}

static int is_constant(const taylor_walk *w, const hl_expr *const *c)
{
    for (int k = 1; k <= w->K; k++)
        if (!hl_fold_is_num(c[k], 0))
            return 0;
    return 1;
}

static const hl_expr *num(taylor_walk *w, long p, unsigned long q)
{
    return hl_num_frac(w->pool, p, q);
}

/* (a * b)[k] */
static const hl_expr *cauchy(taylor_walk *w, const hl_expr *const *a, const hl_expr *const *b,
                             int k)
{
    const hl_expr *s = w->zero;
    for (int j = 0; j <= k; j++)
        s = hl_fold_add(w->pool, s, hl_fold_mul(w->pool, a[j], b[k - j]));
    return s;
}

/* sum_{j=lo..hi} ((j / k) a[j]) b[k-j]: the weighted sums of exp, sin, ...
 * The weight goes on a, the operand's series, known before the recurrence
 * starts, so that each order waits on b (the recurrence's own) for one
 * product only. */
static const hl_expr *weighted(taylor_walk *w, const hl_expr *const *a, const hl_expr *const *b,
                               int k, int lo, int hi)
{
    hl_pool *pool = w->pool;
    const hl_expr *s = w->zero;
    for (int j = lo; j <= hi; j++) {
        const hl_expr *wa = hl_fold_mul(pool, num(w, j, (unsigned long)k), a[j]);
        s = hl_fold_add(pool, s, hl_fold_mul(pool, wa, b[k - j]));
    }
    return s;
}

static void mul_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a,
                       const hl_expr *const *b)
{
    for (int k = 0; k <= w->K; k++)
        r[k] = cauchy(w, a, b, k);
}

/* r = a / b: r[k] = (a[k] - sum_{j=1..k} b[j] r[k-j]) / b[0] */
static void div_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a,
                       const hl_expr *const *b)
{
    hl_pool *pool = w->pool;
    const hl_expr *inv = hl_fold_div(pool, hl_num_si(pool, 1), b[0]);
    r[0] = hl_fold_div(pool, a[0], b[0]);
    for (int k = 1; k <= w->K; k++) {
        const hl_expr *s = a[k];
        for (int j = 1; j <= k; j++)
            s = hl_fold_sub(pool, s, hl_fold_mul(pool, b[j], r[k - j]));
        r[k] = hl_fold_mul(pool, s, inv);
    }
}

/* r = a^n, n >= 0, by binary powering: exact where a[0] = 0. */
static void int_pow_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a, long n)
{
    int K = w->K;
    const hl_expr **base = hl_xmalloc((size_t)(K + 1) * sizeof *base);
    const hl_expr **tmp = hl_xmalloc((size_t)(K + 1) * sizeof *tmp);
    for (int k = 0; k <= K; k++)
        base[k] = a[k], r[k] = k == 0 ? hl_num_si(w->pool, 1) : w->zero;
    for (; n > 0; n >>= 1) {
        if (n & 1) {
            mul_series(w, tmp, r, base);
            memcpy(r, tmp, (size_t)(K + 1) * sizeof *r);
        }
        if (n > 1) {
            mul_series(w, tmp, base, base);
            memcpy(base, tmp, (size_t)(K + 1) * sizeof *base);
        }
    }
    free(base), free(tmp);
}

/* r = 1/a, by the division recurrence */
static void inverse_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a)
{
    const hl_expr **one = hl_xmalloc((size_t)(w->K + 1) * sizeof *one);
    for (int k = 0; k <= w->K; k++)
        one[k] = k == 0 ? hl_num_si(w->pool, 1) : w->zero;
    div_series(w, r, one, a);
    free(one);
}

/* r = a^c, c free of the variable: an integer |c| <= 64 by binary powering
 * (then 1/a^|c| for c < 0), else (sum_{j<k} (c(k-j) - j) a[k-j] r[j]) /
 * (k a[0]).  Order 0 is a[0]^c in the node's own form, so that it is the
 * node of the same power written elsewhere (Gonzalez's remainder cancels
 * its term of order 0 exactly). */
static void pow_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a, const hl_expr *c)
{
    hl_pool *pool = w->pool;
    int K = w->K;
    if (c->kind == HL_NUM && fmpz_is_one(fmpq_denref(c->num)) &&
        fmpz_fits_si(fmpq_numref(c->num)) && labs(fmpz_get_si(fmpq_numref(c->num))) <= 64) {
        long n = fmpz_get_si(fmpq_numref(c->num));
        int_pow_series(w, r, a, labs(n));
        if (n < 0) {
            const hl_expr **pos = hl_xmalloc((size_t)(K + 1) * sizeof *pos);
            memcpy(pos, r, (size_t)(K + 1) * sizeof *r);
            inverse_series(w, r, pos);
            free(pos);
        }
        r[0] = hl_fold_pow(pool, a[0], c);
        return;
    }
    r[0] = hl_fold_pow(pool, a[0], c);
    const hl_expr *inv = hl_fold_div(pool, hl_num_si(pool, 1), a[0]);
    for (int k = 1; k <= K; k++) {
        const hl_expr *s = w->zero;
        for (int j = 0; j < k; j++) {
            const hl_expr *f =
                hl_fold_sub(pool, hl_fold_mul(pool, c, hl_num_si(pool, k - j)), hl_num_si(pool, j));
            s = hl_fold_add(pool, s, hl_fold_mul(pool, f, hl_fold_mul(pool, a[k - j], r[j])));
        }
        r[k] = hl_fold_mul(pool, hl_fold_mul(pool, num(w, 1, (unsigned long)k), s), inv);
    }
}

/* Is the series a[0] + a[1] t (the argument of sin(q + s h))? */
static int is_linear(const taylor_walk *w, const hl_expr *const *a)
{
    for (int k = 2; k <= w->K; k++)
        if (!hl_fold_is_num(a[k], 0))
            return 0;
    return 1;
}

/* pw[k] = a1^k / k!, each from two lower ones, pw[h] pw[k-h] / binom(k, h)
 * with h = k/2, so that order k waits for about log2 k products rather
 * than k (the recurrences' chain): for f(a0 + a1 t) with f' = +-f or a
 * sin/cos pair, [t^k] is +-f^(k)(a0) pw[k]. */
static void scaled_powers(taylor_walk *w, const hl_expr **pw, const hl_expr *a1)
{
    pw[0] = hl_num_si(w->pool, 1);
    for (int k = 1; k <= w->K; k++) {
        if (k == 1) {
            pw[1] = a1;
            continue;
        }
        int h = k / 2;
        unsigned long binom = 1;
        for (int j = 1; j <= h; j++)
            binom = binom * (unsigned long)(k - h + j) / (unsigned long)j;
        pw[k] = hl_fold_mul(w->pool, num(w, 1, binom), hl_fold_mul(w->pool, pw[h], pw[k - h]));
    }
}

static void exp_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a)
{
    r[0] = hl_call(w->pool, HL_EXP, a[0]);
    if (is_linear(w, a)) {
        const hl_expr **pw = hl_xmalloc((size_t)(w->K + 1) * sizeof *pw);
        scaled_powers(w, pw, a[1]);
        for (int k = 1; k <= w->K; k++)
            r[k] = hl_fold_mul(w->pool, r[0], pw[k]);
        free(pw);
        return;
    }
    for (int k = 1; k <= w->K; k++)
        r[k] = weighted(w, a, r, k, 1, k);
}

/* r = log a: r[k] = (a[k] - sum_{j=1..k-1} (j/k) r[j] a[k-j]) / a[0] */
static void log_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a)
{
    hl_pool *pool = w->pool;
    r[0] = hl_call(pool, HL_LOG, a[0]);
    for (int k = 1; k <= w->K; k++)
        r[k] = hl_fold_div(pool, hl_fold_sub(pool, a[k], weighted(w, r, a, k, 1, k - 1)), a[0]);
}

/* r = sqrt a: r[k] = (a[k] - sum_{j=1..k-1} r[j] r[k-j]) / (2 r[0]) */
static void sqrt_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a)
{
    hl_pool *pool = w->pool;
    r[0] = hl_call(pool, HL_SQRT, a[0]);
    const hl_expr *half_inv = hl_fold_div(pool, num(w, 1, 2), r[0]);
    for (int k = 1; k <= w->K; k++) {
        const hl_expr *s = a[k];
        for (int j = 1; j < k; j++)
            s = hl_fold_sub(pool, s, hl_fold_mul(pool, r[j], r[k - j]));
        r[k] = hl_fold_mul(pool, s, half_inv);
    }
}

/* s = sin a, c = cos a (sign -1), or sinh, cosh (sign +1):
 * s[k] = sum (j/k) a[j] c[k-j], c[k] = sign sum (j/k) a[j] s[k-j] */
static void sincos_series(taylor_walk *w, const hl_expr **s, const hl_expr **c,
                          const hl_expr *const *a, int hyperbolic)
{
    hl_pool *pool = w->pool;
    s[0] = hl_call(pool, hyperbolic ? HL_SINH : HL_SIN, a[0]);
    c[0] = hl_call(pool, hyperbolic ? HL_COSH : HL_COS, a[0]);
    if (is_linear(w, a)) {
        /* s[k] = sin^(k)(a0) a1^k/k!: sin, cos, -sin, -cos, ...; c[k]
         * likewise from cos; no signs for sinh, cosh */
        const hl_expr **pw = hl_xmalloc((size_t)(w->K + 1) * sizeof *pw);
        scaled_powers(w, pw, a[1]);
        for (int k = 1; k <= w->K; k++) {
            int odd = k % 2, neg = !hyperbolic && (k % 4 == 2 || k % 4 == 3);
            const hl_expr *sk = hl_fold_mul(pool, odd ? c[0] : s[0], pw[k]);
            const hl_expr *ck = hl_fold_mul(pool, odd ? s[0] : c[0], pw[k]);
            s[k] = neg ? hl_fold_neg(pool, sk) : sk;
            /* cos^(k): cos, -sin, -cos, sin */
            c[k] = !hyperbolic && (k % 4 == 1 || k % 4 == 2) ? hl_fold_neg(pool, ck) : ck;
        }
        free(pw);
        return;
    }
    for (int k = 1; k <= w->K; k++) {
        s[k] = weighted(w, a, c, k, 1, k);
        const hl_expr *t = weighted(w, a, s, k, 1, k);
        c[k] = hyperbolic ? t : hl_fold_neg(pool, t);
    }
}

/* r = tan a (sign +1) or tanh a (sign -1) with x = 1 + sign r^2:
 * r[k] = sum (j/k) a[j] x[k-j], x[k] = sign (r*r)[k] */
static void tan_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a, int hyperbolic)
{
    hl_pool *pool = w->pool;
    const hl_expr **x = hl_xmalloc((size_t)(w->K + 1) * sizeof *x);
    r[0] = hl_call(pool, hyperbolic ? HL_TANH : HL_TAN, a[0]);
    for (int k = 0; k <= w->K; k++) {
        if (k > 0)
            r[k] = weighted(w, a, x, k, 1, k);
        const hl_expr *sq = cauchy(w, r, r, k);
        if (hyperbolic)
            sq = hl_fold_neg(pool, sq);
        x[k] = k == 0 ? hl_fold_add(pool, hl_num_si(pool, 1), sq) : sq;
    }
    free(x);
}

/* atan, asin, acos: r' = sign a' / x with x = 1 + a^2 or sqrt(1 - a^2):
 * r[k] = (sign a[k] - sum_{j=1..k-1} (j/k) r[j] x[k-j]) / x[0] */
static void arc_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a, hl_fun f)
{
    hl_pool *pool = w->pool;
    int K = w->K;
    const hl_expr **x = hl_xmalloc((size_t)(K + 1) * sizeof *x);
    const hl_expr **one_minus = hl_xmalloc((size_t)(K + 1) * sizeof *one_minus);
    for (int k = 0; k <= K; k++) {
        const hl_expr *sq = cauchy(w, a, a, k);
        if (f == HL_ATAN)
            x[k] = k == 0 ? hl_fold_add(pool, hl_num_si(pool, 1), sq) : sq;
        else
            one_minus[k] =
                k == 0 ? hl_fold_sub(pool, hl_num_si(pool, 1), sq) : hl_fold_neg(pool, sq);
    }
    if (f != HL_ATAN)
        sqrt_series(w, x, one_minus);
    r[0] = hl_call(pool, f, a[0]);
    for (int k = 1; k <= K; k++) {
        const hl_expr *ak = f == HL_ACOS ? hl_fold_neg(pool, a[k]) : a[k];
        r[k] = hl_fold_div(pool, hl_fold_sub(pool, ak, weighted(w, r, x, k, 1, k - 1)), x[0]);
    }
    free(x), free(one_minus);
}

/* r = atan2(y, x): r' = g/s with g = x y' - y x', s = x^2 + y^2, so
 * r[k] = (g/s)[k-1] / k */
static void atan2_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *y,
                         const hl_expr *const *x)
{
    hl_pool *pool = w->pool;
    int K = w->K;
    const hl_expr **g = hl_xmalloc((size_t)(K + 1) * sizeof *g);
    const hl_expr **s = hl_xmalloc((size_t)(K + 1) * sizeof *s);
    const hl_expr **h = hl_xmalloc((size_t)(K + 1) * sizeof *h);
    for (int m = 0; m <= K; m++) {
        g[m] = w->zero;
        s[m] = hl_fold_add(pool, cauchy(w, x, x, m), cauchy(w, y, y, m));
    }
    for (int m = 0; m < K; m++) /* g[m] = sum_j (j+1) (x[m-j] y[j+1] - y[m-j] x[j+1]) */
        for (int j = 0; j <= m; j++) {
            const hl_expr *c = num(w, j + 1, 1);
            const hl_expr *t = hl_fold_sub(pool, hl_fold_mul(pool, x[m - j], y[j + 1]),
                                           hl_fold_mul(pool, y[m - j], x[j + 1]));
            g[m] = hl_fold_add(pool, g[m], hl_fold_mul(pool, c, t));
        }
    div_series(w, h, g, s);
    r[0] = hl_call2(pool, HL_ATAN2, y[0], x[0]);
    for (int k = 1; k <= K; k++)
        r[k] = hl_fold_mul(pool, num(w, 1, (unsigned long)k), h[k - 1]);
    free(g), free(s), free(h);
}

static const hl_expr *const *series_of(taylor_walk *w, const hl_expr *e);

static void fun_series(taylor_walk *w, const hl_expr **r, const hl_expr *e, const hl_expr *const *a)
{
    hl_pool *pool = w->pool;
    switch (e->fun) {
    case HL_SIN:
    case HL_COS:
    case HL_SINH:
    case HL_COSH: {
        /* both of the pair, remembered under both nodes */
        int hyp = e->fun == HL_SINH || e->fun == HL_COSH;
        const hl_expr *sn = hl_call(pool, hyp ? HL_SINH : HL_SIN, e->a);
        const hl_expr *cs = hl_call(pool, hyp ? HL_COSH : HL_COS, e->a);
        const hl_expr **s = new_series(w);
        remember(w, sn);
        const hl_expr **c = new_series(w);
        remember(w, cs);
        sincos_series(w, s, c, a, hyp);
        memcpy(r, e == sn ? s : c, (size_t)(w->K + 1) * sizeof *r);
        return;
    }
    case HL_EXP:
        exp_series(w, r, a);
        return;
    case HL_LOG:
        log_series(w, r, a);
        return;
    case HL_SQRT:
        sqrt_series(w, r, a);
        return;
    case HL_TAN:
        tan_series(w, r, a, 0);
        return;
    case HL_TANH:
        tan_series(w, r, a, 1);
        return;
    default:
        arc_series(w, r, a, e->fun);
        return; /* ATAN, ASIN, ACOS */
    }
}

static void node_series(taylor_walk *w, const hl_expr **r, const hl_expr *e)
{
    hl_pool *pool = w->pool;
    const hl_expr *const *a = e->a ? series_of(w, e->a) : NULL;
    const hl_expr *const *b = e->b ? series_of(w, e->b) : NULL;
    int K = w->K;
    switch (e->kind) {
    case HL_NEG:
        for (int k = 0; k <= K; k++)
            r[k] = hl_fold_neg(pool, a[k]);
        return;
    case HL_ADD:
    case HL_SUB:
        for (int k = 0; k <= K; k++)
            r[k] =
                e->kind == HL_ADD ? hl_fold_add(pool, a[k], b[k]) : hl_fold_sub(pool, a[k], b[k]);
        return;
    case HL_MUL:
        mul_series(w, r, a, b);
        return;
    case HL_DIV:
        div_series(w, r, a, b);
        return;
    case HL_POW:
        if (is_constant(w, b)) {
            pow_series(w, r, a, b[0]);
        } else { /* a^b = exp(b log a) */
            const hl_expr **l = hl_xmalloc((size_t)(K + 1) * sizeof *l);
            const hl_expr **bl = hl_xmalloc((size_t)(K + 1) * sizeof *bl);
            log_series(w, l, a);
            mul_series(w, bl, b, l);
            exp_series(w, r, bl);
            free(l), free(bl);
        }
        return;
    default: /* HL_FUN */
        if (e->fun == HL_ATAN2)
            atan2_series(w, r, a, b);
        else
            fun_series(w, r, e, a);
        return;
    }
}

static const hl_expr *const *series_of(taylor_walk *w, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&w->done, e);
    if (v)
        return w->series[v->i];
    const hl_expr **r = new_series(w);
    int idx = w->count - 1;
    if (e->kind == HL_SYM && strcmp(e->name, w->var) == 0) {
        r[0] = w->at;
        if (w->K >= 1)
            r[1] = hl_num_si(w->pool, 1);
    } else if (e->kind == HL_NUM || e->kind == HL_SYM || e->kind == HL_PI) {
        r[0] = e;
    } else {
        /* operands first; then a node whose operands are constant keeps e */
        int ca = !e->a || is_constant(w, series_of(w, e->a));
        int cb = !e->b || is_constant(w, series_of(w, e->b));
        if (ca && cb)
            r[0] = e;
        else
            node_series(w, r, e);
    }
    hl_memo_put(&w->done, e)->i = idx;
    return r;
}

/* Called in post-order, series_of finds its operands done and recurses one
 * level: no chain is too deep for the C stack. */
static int series_node(void *w, const hl_expr *e)
{
    series_of(w, e);
    return 0;
}

void hl_expr_taylor(const hl_expr **out, hl_pool *pool, const hl_expr *e, const char *var,
                    const hl_expr *at, int K)
{
    taylor_walk w = {.pool = pool, .var = var, .at = at, .zero = hl_num_si(pool, 0), .K = K};
    hl_memo_init(&w.done);
    hl_expr_postorder(&e, 1, series_node, &w);
    const hl_expr *const *c = series_of(&w, e);
    memcpy(out, c, (size_t)(K + 1) * sizeof *out);
    for (int i = 0; i < w.count; i++)
        free(w.series[i]);
    free(w.series);
    hl_memo_clear(&w.done);
}
