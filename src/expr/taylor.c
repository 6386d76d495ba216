/* Taylor coefficients of an expression in one symbol, as expressions.
 *
 * Each node gets its K + 1 coefficients from its operands' by the rule of
 * its operation (rules/rule.h), run with an emitter whose values are
 * expressions built by the folding constructors (fold.h), so a coefficient
 * that vanishes is the number 0 and costs nothing further.  A node whose
 * operands' series are constant keeps its own expression.
 *
 * One shortcut, an optimisation only: a function of an argument linear in
 * the symbol (sin(q + s h), exp(q + s h)) takes its closed-form
 * coefficients, +-f^(k) h^k/k!, with the powers built in a tree, so the
 * compiled code waits on about log2 k products rather than on the
 * recurrence's chain of k. */
#include <stdlib.h>
#include <string.h>

#include "expr/fold.h"
#include "base/memo.h"
#include "base/buf.h"
#include "rules/rule.h"

typedef struct taylor_walk {
    hl_em em; /* the rules' emitter (first: the rules pass &em) */
    hl_pool *pool;
    const char *var;
    const hl_expr *at, *zero;
    int K;
    hl_memo done; /* node -> index in series[] */
    const hl_expr ***series;
    int count, cap;
    /* the rule being run: its series, B's coefficient 0 for a^c, what it keeps */
    const hl_expr **slot[HL_SLOT_COUNT];
    const hl_expr *exponent;
    const hl_expr *keep[2];
    const hl_expr **aux; /* X when the caller does not want it */
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

/* ---- the emitter: values are expressions ---------------------------------------- */

static taylor_walk *walk_of(hl_em *em)
{
    return (taylor_walk *)em;
}

static hl_ev ev_of(const hl_expr *e)
{
    hl_ev v;
    v.p = (void *)e;
    return v;
}

static const hl_expr *ex(hl_ev v)
{
    return v.p;
}

static hl_ev em_num(hl_em *em, long p, long q)
{
    return ev_of(num(walk_of(em), p, (unsigned long)q));
}

static hl_ev em_coef(hl_em *em, hl_slot s, int j)
{
    taylor_walk *w = walk_of(em);
    if (s == HL_SLOT_B && w->exponent) /* a^c: c is B's coefficient 0 */
        return ev_of(j == 0 ? w->exponent : w->zero);
    return ev_of(w->slot[s][j]);
}

static void em_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    walk_of(em)->slot[s][j] = ex(v);
}

static hl_ev em_add(hl_em *em, hl_ev a, hl_ev b)
{
    return ev_of(hl_fold_add(walk_of(em)->pool, ex(a), ex(b)));
}

static hl_ev em_sub(hl_em *em, hl_ev a, hl_ev b)
{
    return ev_of(hl_fold_sub(walk_of(em)->pool, ex(a), ex(b)));
}

static hl_ev em_mul(hl_em *em, hl_ev a, hl_ev b)
{
    return ev_of(hl_fold_mul(walk_of(em)->pool, ex(a), ex(b)));
}

static hl_ev em_neg(hl_em *em, hl_ev a)
{
    return ev_of(hl_fold_neg(walk_of(em)->pool, ex(a)));
}

static hl_ev em_div(hl_em *em, hl_ev a, hl_ev b)
{
    return ev_of(hl_fold_div(walk_of(em)->pool, ex(a), ex(b)));
}

static hl_ev em_fma(hl_em *em, hl_ev a, hl_ev b, hl_ev c)
{
    return em_add(em, em_mul(em, a, b), c);
}

/* a^c at order 0 in the node's own form, so that it is the node of the
 * same power written elsewhere (Gonzalez's remainder cancels its term of
 * order 0 exactly) */
static hl_ev em_call(hl_em *em, hl_pfn f, hl_ev a, hl_ev b)
{
    hl_pool *pool = walk_of(em)->pool;
    if (f == HL_PFN_POW)
        return ev_of(hl_fold_pow(pool, ex(a), ex(b)));
    if (f == HL_PFN_ATAN2)
        return ev_of(hl_call2(pool, HL_ATAN2, ex(a), ex(b)));
    return ev_of(hl_call(pool, hl_pfn_fun(f), ex(a)));
}

/* term j of a convolution (rules/rule.h: where the weight goes) */
static const hl_expr *conv_term(taylor_walk *w, const hl_conv *c, int j)
{
    hl_pool *pool = w->pool;
    const hl_expr *x = w->slot[c->x][j], *y = w->slot[c->y][c->k - j], *wt = NULL;
    if (c->weighted)
        wt = hl_fold_add(pool, hl_fold_mul(pool, ex(c->wa), hl_num_si(pool, j)), ex(c->wb));
    else if (c->sym && 2 * j < c->k)
        wt = hl_num_si(pool, 2);
    if (wt == NULL)
        return hl_fold_mul(pool, x, y);
    if (j == c->k && j > 0) /* a fresh x[k]: (w y[0]) x[k] */
        return hl_fold_mul(pool, hl_fold_mul(pool, wt, y), x);
    return hl_fold_mul(pool, hl_fold_mul(pool, wt, x), y);
}

/* The sum in hl_conv_plan's order, so that the expression adds as the
 * double back ends do. */
static hl_ev em_conv(hl_em *em, const hl_conv *c, int *has)
{
    taylor_walk *w = walk_of(em);
    int n = c->hi - c->lo + 1 > 0 ? c->hi - c->lo + 1 : 0;
    int *idx = hl_xmalloc((size_t)(n + 1) * 2 * sizeof *idx), *lane = idx + n + 1, nk, fresh[2], nf;
    hl_conv_plan(c, idx, lane, &nk, fresh, &nf);
    const hl_expr *l[4] = {NULL, NULL, NULL, NULL}, *s = NULL;
    for (int i = 0; i < nk; i++) {
        const hl_expr *t = conv_term(w, c, idx[i]);
        l[lane[i]] = l[lane[i]] ? hl_fold_add(w->pool, l[lane[i]], t) : t;
    }
    for (int h = 0; h < 2; h++) { /* (l0 + l1) + (l2 + l3), empty lanes left out */
        const hl_expr *p = l[2 * h] && l[2 * h + 1] ? hl_fold_add(w->pool, l[2 * h], l[2 * h + 1])
                           : l[2 * h]               ? l[2 * h]
                                                    : l[2 * h + 1];
        if (p)
            s = s ? hl_fold_add(w->pool, s, p) : p;
    }
    for (int i = 0; i < nf; i++) {
        const hl_expr *t = conv_term(w, c, fresh[i]);
        s = s ? hl_fold_add(w->pool, s, t) : t;
    }
    free(idx);
    *has = s != NULL;
    return ev_of(s ? s : w->zero);
}

static void em_keep(hl_em *em, int slot, hl_ev v)
{
    walk_of(em)->keep[slot] = ex(v);
}

static hl_ev em_kept(hl_em *em, int slot)
{
    return ev_of(walk_of(em)->keep[slot]);
}

static const hl_em_ops expr_em_ops = {em_num, em_coef, em_store, em_add,  em_sub,  em_mul, em_neg,
                                      em_div, em_fma,  em_call,  em_conv, em_keep, em_kept};

/* d (and x, the rule's second series, when wanted) = op(a, b), orders 0..K */
static void run_rule(taylor_walk *w, hl_op op, const hl_expr **d, const hl_expr **x,
                     const hl_expr *const *a, const hl_expr *const *b)
{
    w->slot[HL_SLOT_D] = d;
    w->slot[HL_SLOT_X] = x ? x : w->aux;
    w->slot[HL_SLOT_A] = (const hl_expr **)a;
    w->slot[HL_SLOT_B] = (const hl_expr **)b;
    const hl_rule *rule = hl_rule_of(op);
    for (int k = 0; k <= w->K; k++)
        rule->taylor(&w->em, k);
    w->exponent = NULL;
}

/* ---- the nodes ---------------------------------------------------------------- */

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
            run_rule(w, HL_OP_MUL, tmp, NULL, r, base);
            memcpy(r, tmp, (size_t)(K + 1) * sizeof *r);
        }
        if (n > 1) {
            run_rule(w, HL_OP_SQR, tmp, NULL, base, NULL);
            memcpy(base, tmp, (size_t)(K + 1) * sizeof *base);
        }
    }
    free(base), free(tmp);
}

/* r = a^c, c free of the variable: an integer |c| <= 64 by binary powering
 * (then 1/a^|c| by the division rule), else by the rule of a^c. */
static void pow_series(taylor_walk *w, const hl_expr **r, const hl_expr *const *a, const hl_expr *c)
{
    hl_pool *pool = w->pool;
    int K = w->K;
    if (c->kind == HL_NUM && fmpz_is_one(fmpq_denref(c->num)) &&
        fmpz_fits_si(fmpq_numref(c->num)) && labs(fmpz_get_si(fmpq_numref(c->num))) <= 64) {
        long n = fmpz_get_si(fmpq_numref(c->num));
        int_pow_series(w, r, a, labs(n));
        if (n < 0) {
            const hl_expr **pos = hl_xmalloc((size_t)(K + 1) * 2 * sizeof *pos),
                          **one = pos + K + 1;
            memcpy(pos, r, (size_t)(K + 1) * sizeof *r);
            for (int k = 0; k <= K; k++)
                one[k] = k == 0 ? hl_num_si(pool, 1) : w->zero;
            run_rule(w, HL_OP_DIV, r, NULL, one, pos);
            free(pos);
        }
        r[0] = hl_fold_pow(pool, a[0], c); /* the node's own form, as em_call */
        return;
    }
    w->exponent = c;
    run_rule(w, HL_OP_POWK, r, NULL, a, NULL);
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
    if (!is_linear(w, a)) {
        run_rule(w, HL_OP_EXP, r, NULL, a, NULL);
        return;
    }
    r[0] = hl_call(w->pool, HL_EXP, a[0]);
    const hl_expr **pw = hl_xmalloc((size_t)(w->K + 1) * sizeof *pw);
    scaled_powers(w, pw, a[1]);
    for (int k = 1; k <= w->K; k++)
        r[k] = hl_fold_mul(w->pool, r[0], pw[k]);
    free(pw);
}

/* s = sin a, c = cos a, or sinh, cosh */
static void sincos_series(taylor_walk *w, const hl_expr **s, const hl_expr **c,
                          const hl_expr *const *a, int hyperbolic)
{
    hl_pool *pool = w->pool;
    if (!is_linear(w, a)) {
        run_rule(w, hyperbolic ? HL_OP_SINHCOSH : HL_OP_SINCOS, s, c, a, NULL);
        return;
    }
    s[0] = hl_call(pool, hyperbolic ? HL_SINH : HL_SIN, a[0]);
    c[0] = hl_call(pool, hyperbolic ? HL_COSH : HL_COS, a[0]);
    /* s[k] = sin^(k)(a0) a1^k/k!: sin, cos, -sin, -cos, ...; c[k] likewise
     * from cos; no signs for sinh, cosh */
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
}

static const hl_expr *const *series_of(taylor_walk *w, const hl_expr *e);


static void fun_series(taylor_walk *w, const hl_expr **r, const hl_expr *e, const hl_expr *const *a,
                       const hl_expr *const *b)
{
    hl_pool *pool = w->pool;
    if (e->fun == HL_SIN || e->fun == HL_COS || e->fun == HL_SINH || e->fun == HL_COSH) {
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
    } else if (e->fun == HL_EXP) {
        exp_series(w, r, a);
    } else {
        run_rule(w, hl_fun_op(e->fun, NULL), r, NULL, a, b);
    }
}

static void node_series(taylor_walk *w, const hl_expr **r, const hl_expr *e)
{
    const hl_expr *const *a = e->a ? series_of(w, e->a) : NULL;
    const hl_expr *const *b = e->b ? series_of(w, e->b) : NULL;
    int K = w->K;
    switch (e->kind) {
    case HL_NEG:
        run_rule(w, HL_OP_NEG, r, NULL, a, NULL);
        return;
    case HL_ADD:
        run_rule(w, HL_OP_ADD, r, NULL, a, b);
        return;
    case HL_SUB:
        run_rule(w, HL_OP_SUB, r, NULL, a, b);
        return;
    case HL_MUL:
        run_rule(w, HL_OP_MUL, r, NULL, a, b);
        return;
    case HL_DIV:
        run_rule(w, HL_OP_DIV, r, NULL, a, b);
        return;
    case HL_POW:
        if (is_constant(w, b)) {
            pow_series(w, r, a, b[0]);
        } else { /* a^b = exp(b log a) */
            const hl_expr **l = hl_xmalloc((size_t)(K + 1) * 2 * sizeof *l), **bl = l + K + 1;
            run_rule(w, HL_OP_LOG, l, NULL, a, NULL);
            run_rule(w, HL_OP_MUL, bl, NULL, b, l);
            exp_series(w, r, bl);
            free(l);
        }
        return;
    default: /* HL_FUN */
        fun_series(w, r, e, a, b);
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
    taylor_walk w = {.em = {&expr_em_ops},
                     .pool = pool,
                     .var = var,
                     .at = at,
                     .zero = hl_num_si(pool, 0),
                     .K = K};
    w.aux = hl_xmalloc((size_t)(K + 1) * sizeof *w.aux);
    hl_memo_init(&w.done);
    hl_expr_postorder(&e, 1, series_node, &w);
    const hl_expr *const *c = series_of(&w, e);
    memcpy(out, c, (size_t)(K + 1) * sizeof *out);
    for (int i = 0; i < w.count; i++)
        free(w.series[i]);
    free(w.series);
    free(w.aux);
    hl_memo_clear(&w.done);
}
