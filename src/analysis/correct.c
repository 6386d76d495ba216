/* Closed forms of explicit schemes, K(D) in closed form, corrected schemes
 * (analysis.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/memo.h"
#include "hamlie/expr.h"
#include "hamlie/analysis.h"
#include "hamlie/scheme.h"

/* How deep functions (sin, sqrt, a non-integer power, ...) nest: per node,
 * from its operands' depths (post-order, so no chain is too deep). */
static int nesting_node(void *seen, const hl_expr *e)
{
    int a = e->a ? hl_memo_get(seen, e->a)->i : 0, b = e->b ? hl_memo_get(seen, e->b)->i : 0;
    int d = a > b ? a : b;
    if (e->kind == HL_FUN ||
        (e->kind == HL_POW && (e->b->kind != HL_NUM || !fmpz_is_one(fmpq_denref(e->b->num)))))
        d++;
    hl_memo_put(seen, e)->i = d;
    return 0;
}

/* binomial(n + k - 1, k): the monomials of degree k in n symbols, a bound
 * on the terms of the k-th power of n terms */
static double multisets(double n, long k)
{
    double c = 1;
    for (long i = 1; i <= k && c < HUGE_VAL; i++)
        c = c * (n + (double)i - 1) / (double)i;
    return c;
}

/* The walk of terms_node: bounds per node, and the largest. */
typedef struct terms_walk {
    hl_memo bound;
    double most;
} terms_walk;

/* A bound on the terms of a node expanded, from its operands' bounds: a sum
 * adds them, a product or quotient multiplies them, an integer power k
 * takes the monomials of degree k; a function or another power is one
 * atom, 1 (its argument is bounded at its own node).  A symbol counts 1
 * unless its bound is set before the walk (an earlier stage, by its
 * terms). */
static int terms_node(void *arg, const hl_expr *e)
{
    terms_walk *w = arg;
    const hl_memo *m = &w->bound;
    double a = e->a ? hl_memo_get(m, e->a)->d : 1, b = e->b ? hl_memo_get(m, e->b)->d : 1;
    double t = 1;
    if (e->kind == HL_SYM) {
        const hl_memo_val *v = hl_memo_get(m, e);
        t = v ? v->d : 1;
    } else if (e->kind == HL_NEG)
        t = a;
    else if (e->kind == HL_ADD || e->kind == HL_SUB)
        t = a + b;
    else if (e->kind == HL_MUL || e->kind == HL_DIV)
        t = a * b;
    else if (e->kind == HL_POW && e->b->kind == HL_NUM &&
             fmpz_is_one(fmpq_denref(e->b->num)) && fmpz_bits(fmpq_numref(e->b->num)) <= 20) {
        long k = labs(fmpz_get_si(fmpq_numref(e->b->num)));
        double pw = pow(a, (double)k), ms = multisets(a, k);
        t = pw < ms ? pw : ms;
    }
    hl_memo_put(&w->bound, e)->d = t;
    w->most = t > w->most ? t : w->most;
    return 0;
}

/* The largest bound on the terms of a node of equation i's right side
 * (terms_node), the unknowns given before it counted by their terms len[u] */
static double stage_bound(int i, const long *len, const hl_scheme *s)
{
    hl_pool *pool = hl_system_pool(s->sys);
    terms_walk w = {.most = 0};
    hl_memo_init(&w.bound);
    for (int u = 0; u < s->m; u++)
        if (len[u] > 0)
            hl_memo_put(&w.bound, hl_sym(pool, s->unknown[u]))->d = (double)len[u];
    hl_expr_postorder(&s->rhs[i], 1, terms_node, &w);
    hl_memo_clear(&w.bound);
    return w.most;
}

/* Each unknown's value expanded, in the order the equations give them, as
 * long as the bound on its terms (stage_bound, from the earlier stages'
 * terms) is within HL_ERRORS_MAP_MAX_STAGE_BOUND: the stages of a
 * composition feed powers of one another, and the images' degree
 * multiplies at each (yoshida4 on p^2/2 + q^6/6: 5^6 in q, no answer in
 * minutes).  HL_ELIMIT at the first stage past it, before it is paid. */
static int stages_within(const hl_expr **val_of, const hl_scheme *s, hl_alg_ctx *ctx,
                         hl_error *err)
{
    hl_alg a;
    hl_alg_init(&a, ctx);
    long *len = hl_xcalloc((size_t)s->m, sizeof *len);
    int st = HL_OK;
    for (int i = 0; i < s->m && st == HL_OK; i++) {
        double bound = stage_bound(i, len, s);
        if (bound > HL_ERRORS_MAP_MAX_STAGE_BOUND) {
            st = hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                              "the map's stage %d may have %.3g terms (more than %g)", i + 1,
                              bound, HL_ERRORS_MAP_MAX_STAGE_BOUND);
            break;
        }
        st = hl_alg_from_expr(&a, val_of[s->defines[i]], ctx, err);
        if (st == HL_OK)
            len[s->defines[i]] = hl_alg_length(&a, ctx);
    }
    hl_alg_clear(&a, ctx);
    free(len);
    return st;
}

hl_status hl_errors_scheme_map(hl_alg *images, const hl_scheme *s, hl_error *err)
{
    if (!s->all_explicit || s->nint > 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "scheme '%s' is implicit: no closed-form map", s->name);
    hl_pool *pool = hl_system_pool(s->sys);
    hl_alg_ctx *ctx = hl_system_ctx(s->sys);
    int m = s->m, nk = 0, st = HL_OK;
    const char **names = hl_xmalloc((size_t)m * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)m * sizeof *vals);
    const hl_expr **val_of = hl_xcalloc((size_t)m, sizeof *val_of);
    /* Each equation's right side with the unknowns defined before it
     * substituted: the DAG shares them, the algebra layer expands once. */
    for (int i = 0; i < m; i++) {
        int u = s->defines[i];
        const hl_expr *e = hl_expr_subst(pool, s->rhs[i], nk, names, vals);
        val_of[u] = e;
        names[nk] = s->unknown[u];
        vals[nk++] = e;
    }
    hl_memo seen;
    hl_memo_init(&seen);
    int depth = 0;
    for (int j = 0; j < 2 * s->N; j++) {
        const hl_expr *img = val_of[j < s->N ? s->iQ[j] : s->iP[j - s->N]];
        hl_expr_postorder(&img, 1, nesting_node, &seen);
        int d = hl_memo_get(&seen, img)->i;
        depth = d > depth ? d : depth;
    }
    hl_memo_clear(&seen);
    if (depth > HL_ERRORS_MAP_MAX_NESTING)
        st = hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                          "functions nest %d deep in the map (more than %d)", depth,
                          HL_ERRORS_MAP_MAX_NESTING);
    if (st == HL_OK)
        st = stages_within(val_of, s, ctx, err);
    for (int j = 0; j < 2 * s->N && st == HL_OK; j++) {
        int u = j < s->N ? s->iQ[j] : s->iP[j - s->N];
        st = hl_alg_from_expr(&images[j], val_of[u], ctx, err);
    }
    free(names);
    free(vals);
    free(val_of);
    return st;
}

hl_status hl_errors_K_closed(hl_alg *K, const hl_alg *images, hl_system *sys, hl_error *err)
{
    long reached;
    return hl_errors_K_closed_bounded(K, &reached, images, 0, sys, err);
}

hl_status hl_errors_K_closed_bounded(hl_alg *K, long *reached, const hl_alg *images, long max_terms,
                                     hl_system *sys, hl_error *err)
{
    *reached = 0;
    long most = 0;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int m = 2 * hl_system_ndof(sys), vD = hl_system_var_D(sys), st = HL_OK;
    int *vars = hl_xmalloc((size_t)m * sizeof *vars);
    hl_alg *back = hl_alg_vec_new(m, ctx), mD, d;
    hl_alg_init(&mD, ctx);
    hl_alg_init(&d, ctx);
    hl_alg_gen(&mD, vD, ctx);
    hl_alg_neg(&mD, &mD, ctx);
    for (int i = 0; i < m && st == HL_OK; i++) {
        vars[i] = i; /* q_1..q_N, p_1..p_N are base symbols 0..2N-1 (ham.h) */
        st = hl_alg_subst_bounded(&back[i], reached, &images[i], 1, &vD, &mD, max_terms, ctx,
                                  err);
        most = *reached > most ? *reached : most;
    }
    for (int i = 0; i < m && st == HL_OK; i++) {
        st = hl_alg_diff(&d, &images[i], vD, ctx, err);
        if (st == HL_OK)
            st = hl_alg_subst_bounded(&K[i], reached, &d, m, vars, back, max_terms, ctx, err);
        most = *reached > most ? *reached : most;
    }
    *reached = most;
    hl_alg_clear(&mD, ctx);
    hl_alg_clear(&d, ctx);
    hl_alg_vec_free(back, m, ctx);
    free(vars);
    return st;
}

void hl_errors_correct_series(hl_series *out, const hl_series *psi, const hl_vfields *e, int m,
                              hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * e->N;
    hl_alg d;
    fmpq_t f;
    hl_alg_init(&d, ctx);
    fmpq_init(f);
    for (int i = 0; i < M; i++) {
        hl_series_set(&out[i], &psi[i], ctx);
        for (int k = 2; k <= m && k < out[i].n; k++) {
            fmpq_one(f);
            fmpz_fac_ui(fmpq_denref(f), (ulong)k);
            hl_alg_scalar_mul_fmpq(&d, &hl_vfields_v(e, k)[i], f, ctx);
            hl_alg_sub(&out[i].c[k], &out[i].c[k], &d, ctx);
        }
    }
    hl_alg_clear(&d, ctx);
    fmpq_clear(f);
}

void hl_errors_correct_map(hl_alg *images, const hl_vfields *e, int m, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * e->N;
    hl_alg d, Dk;
    fmpq_t f;
    hl_alg_init(&d, ctx);
    hl_alg_init(&Dk, ctx);
    fmpq_init(f);
    for (int k = 2; k <= m; k++) {
        hl_error err;
        hl_alg_gen(&Dk, hl_system_var_D(sys), ctx);
        hl_alg_pow_si(&Dk, &Dk, k, ctx, &err); /* cannot fail: k > 0 */
        fmpq_one(f);
        fmpz_fac_ui(fmpq_denref(f), (ulong)k);
        hl_alg_scalar_mul_fmpq(&Dk, &Dk, f, ctx);
        for (int i = 0; i < M; i++) {
            hl_alg_mul(&d, &Dk, &hl_vfields_v(e, k)[i], ctx);
            hl_alg_sub(&images[i], &images[i], &d, ctx);
        }
    }
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&Dk, ctx);
    fmpq_clear(f);
}
