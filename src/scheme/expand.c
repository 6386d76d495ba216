/* The symbolic reading: a scheme expanded in D to O(D^n). */
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq_mat.h>

#include "base/buf.h"
#include "scheme/scheme_impl.h"

/* Weights of the interpolatory rule on the nodes i/(k-1), i < k (k >= 2):
 * sum_i w_i s_i^e = 1/(e+1) for e < k, so the rule is exact for degree k-1. */
static void newton_cotes(fmpq *w, int k)
{
    fmpq_mat_t A, X, B;
    fmpq_mat_init(A, k, k);
    fmpq_mat_init(X, k, 1);
    fmpq_mat_init(B, k, 1);
    fmpq_t s;
    fmpq_init(s);
    for (int e = 0; e < k; e++) {
        fmpq_set_si(fmpq_mat_entry(B, e, 0), 1, (ulong)(e + 1));
        for (int i = 0; i < k; i++) {
            fmpq_set_si(s, i, (ulong)(k - 1));
            fmpz_pow_ui(fmpq_numref(fmpq_mat_entry(A, e, i)), fmpq_numref(s), (ulong)e);
            fmpz_pow_ui(fmpq_denref(fmpq_mat_entry(A, e, i)), fmpq_denref(s), (ulong)e);
            fmpq_canonicalise(fmpq_mat_entry(A, e, i));
        }
    }
    fmpq_mat_solve_fraction_free(X, A, B); /* a Vandermonde matrix: invertible */
    for (int i = 0; i < k; i++)
        fmpq_set(&w[i], fmpq_mat_entry(X, i, 0));
    fmpq_clear(s);
    fmpq_mat_clear(A);
    fmpq_mat_clear(X);
    fmpq_mat_clear(B);
}

/* The integrals' symbols replaced by the rule with k nodes. */
static void quadrature(const hl_expr **lhs, const hl_expr **rhs, const hl_scheme *s, int k,
                       hl_pool *pool)
{
    for (int i = 0; i < s->m; i++)
        lhs[i] = s->lhs[i], rhs[i] = s->rhs[i];
    if (s->nint == 0)
        return;
    fmpq *w = _fmpq_vec_init(k);
    newton_cotes(w, k);
    const hl_expr **val = hl_xmalloc((size_t)s->nint * sizeof *val);
    const char *sv = HL_SCHEME_S;
    for (int t = 0; t < s->nint; t++) {
        const hl_expr *sum = NULL;
        for (int i = 0; i < k; i++) {
            if (fmpq_is_zero(&w[i]))
                continue;
            const hl_expr *node = hl_num_frac(pool, i, (ulong)(k - 1));
            const hl_expr *f = hl_expr_subst(pool, s->int_body[t], 1, &sv, &node);
            f = hl_mul(pool, hl_num_fmpq(pool, &w[i]), f);
            sum = sum ? hl_add(pool, sum, f) : f;
        }
        val[t] = sum;
    }
    for (int i = 0; i < s->m; i++) {
        lhs[i] = hl_expr_subst(pool, lhs[i], s->nint, (const char *const *)s->int_name, val);
        rhs[i] = hl_expr_subst(pool, rhs[i], s->nint, (const char *const *)s->int_name, val);
    }
    free(val);
    _fmpq_vec_clear(w, k);
}

/* Every equation explicit: evaluate the right sides in order. */
static int evaluate(hl_series *U, const hl_scheme *s, const hl_expr *const *rhs, int n,
                    hl_alg_ctx *ctx, hl_error *err)
{
    int nb = hl_alg_ctx_nbase(ctx), var_D = hl_system_var_D(s->sys), st = HL_OK;
    const char **names = hl_xmalloc((size_t)(nb + s->m) * sizeof *names);
    hl_series *vals = hl_xmalloc((size_t)(nb + s->m) * sizeof *vals);
    hl_alg g;
    hl_alg_init(&g, ctx);
    for (int i = 0; i < nb; i++) {
        names[i] = hl_alg_ctx_name(ctx, i);
        hl_series_init(&vals[i], n, ctx);
        if (i == var_D) {
            if (n > 1)
                hl_alg_one(&vals[i].c[1], ctx);
        } else {
            hl_alg_gen(&g, i, ctx);
            hl_series_set_alg(&vals[i], &g, n, ctx);
        }
    }
    for (int u = 0; u < s->m; u++) {
        names[nb + u] = s->unknown[u];
        hl_series_init(&vals[nb + u], n, ctx);
    }
    for (int i = 0; i < s->m && st == HL_OK; i++) {
        int u = s->defines[i];
        st = hl_series_eval_expr(&vals[nb + u], rhs[i], nb + s->m, names, vals, n, ctx, err);
        if (st != HL_OK)
            hl_error_prefix(err, "in equation %d (for '%s')", i + 1, s->display[u]);
    }
    for (int u = 0; u < s->m; u++) {
        if (st == HL_OK)
            hl_series_set(&U[u], &vals[nb + u], ctx);
        hl_series_clear(&vals[nb + u], ctx);
    }
    for (int i = 0; i < nb; i++)
        hl_series_clear(&vals[i], ctx);
    hl_alg_clear(&g, ctx);
    free(names);
    free(vals);
    return st;
}

/* The solver's messages name the unknowns: give it the display names when
 * they are distinct and clash with nothing. */
static int display_names_usable(const hl_scheme *s, hl_alg_ctx *ctx)
{
    for (int u = 0; u < s->m; u++) {
        if (hl_alg_ctx_index(ctx, s->display[u]) >= 0 || strcmp(s->display[u], hl_system_step(s->sys)) == 0)
            return 0;
        for (int v = 0; v < u; v++)
            if (strcmp(s->display[u], s->display[v]) == 0)
                return 0;
    }
    return 1;
}

static int solve(hl_series *U, const hl_scheme *s, const hl_expr **lhs, const hl_expr **rhs,
                 int n, hl_alg_ctx *ctx, hl_pool *pool, hl_error *err)
{
    int m = s->m, st = HL_OK;
    const char *const *unk = (const char *const *)s->unknown;
    if (display_names_usable(s, ctx)) {
        const hl_expr **ds = hl_xmalloc((size_t)m * sizeof *ds);
        for (int u = 0; u < m; u++)
            ds[u] = hl_sym(pool, s->display[u]);
        for (int i = 0; i < m; i++) {
            lhs[i] = hl_expr_subst(pool, lhs[i], m, unk, ds);
            rhs[i] = hl_expr_subst(pool, rhs[i], m, unk, ds);
        }
        free(ds);
        unk = (const char *const *)s->display;
    }
    hl_eqn *eqs = hl_xmalloc((size_t)m * sizeof *eqs);
    hl_alg *z0 = hl_alg_vec_new(m, ctx);
    for (int i = 0; i < m; i++) {
        eqs[i].lhs = lhs[i];
        eqs[i].rhs = rhs[i];
        eqs[i].pos = -1;
    }
    for (int u = 0; u < m && st == HL_OK; u++) {
        st = hl_alg_from_expr(&z0[u], s->z0[u], ctx, err);
        if (st != HL_OK)
            hl_error_prefix(err, "the value of '%s' at D = 0", s->display[u]);
    }
    if (st == HL_OK)
        st = hl_series_solve(U, m, eqs, unk, z0, hl_system_step(s->sys), n, ctx, err);
    hl_alg_vec_free(z0, m, ctx);
    free(eqs);
    return st;
}

/* D^0: the identity; D^1: the generator (when there is an H). */
static int check_start(const hl_series *Z, const hl_scheme *s, int n, hl_alg_ctx *ctx,
                       hl_error *err)
{
    int N = s->N, st = HL_OK;
    hl_alg g;
    hl_alg_init(&g, ctx);
    hl_alg *xi = hl_alg_vec_new(N, ctx), *eta = hl_alg_vec_new(N, ctx);
    int have_g = n >= 2 && hl_system_has_H(s->sys) &&
                 hl_generator(xi, eta, s->sys, NULL) == HL_OK;
    for (int a = 0; a < 2 * N && st == HL_OK; a++) {
        int j = a % N;
        int var = a < N ? hl_system_var_q(s->sys, j) : hl_system_var_p(s->sys, j);
        const char *who = s->display[a < N ? s->iQ[j] : s->iP[j]];
        hl_alg_gen(&g, var, ctx);
        if (n >= 1 && !hl_alg_equal(&Z[a].c[0], &g, ctx)) {
            char *got = hl_expr_print(hl_alg_to_expr(&Z[a].c[0], ctx, hl_system_pool(s->sys)),
                                      HL_STYLE_TEXT);
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                              "the scheme is not the identity at D = 0: %s = %s there, not %s",
                              who, got, hl_alg_ctx_name(ctx, var));
            free(got);
        } else if (have_g && !hl_alg_equal(&Z[a].c[1], a < N ? &xi[j] : &eta[j], ctx)) {
            hl_pool *pool = hl_system_pool(s->sys);
            char *got = hl_expr_print(hl_alg_to_expr(&Z[a].c[1], ctx, pool), HL_STYLE_TEXT);
            char *want = hl_expr_print(hl_alg_to_expr(a < N ? &xi[j] : &eta[j], ctx, pool),
                                       HL_STYLE_TEXT);
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                              "the scheme is not consistent with H: the D^1 coefficient of %s "
                              "is %s, the generator gives %s%s",
                              who, got, a < N ? "dH/dp = " : "-dH/dq = ", want);
            free(got);
            free(want);
        }
    }
    hl_alg_vec_free(xi, N, ctx);
    hl_alg_vec_free(eta, N, ctx);
    hl_alg_clear(&g, ctx);
    return st;
}

hl_status hl_scheme_expand(hl_series *Z, const hl_scheme *s, int n, hl_error *err)
{
    if (n < 1 || n > HL_SERIES_MAX_N)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "series length %d outside 1..%d", n,
                            HL_SERIES_MAX_N);
    hl_alg_ctx *ctx = hl_system_ctx(s->sys);
    hl_pool *pool = hl_system_pool(s->sys);
    int m = s->m, N = s->N;
    const hl_expr **lhs = hl_xmalloc((size_t)m * sizeof *lhs);
    const hl_expr **rhs = hl_xmalloc((size_t)m * sizeof *rhs);
    quadrature(lhs, rhs, s, n + 1 > 2 ? n + 1 : 2, pool);
    hl_series *U = hl_xmalloc((size_t)m * sizeof *U);
    for (int u = 0; u < m; u++)
        hl_series_init(&U[u], n, ctx);
    int st = s->all_explicit ? evaluate(U, s, rhs, n, ctx, err)
                             : solve(U, s, lhs, rhs, n, ctx, pool, err);
    if (st == HL_OK) {
        for (int j = 0; j < N; j++) {
            hl_series_set(&Z[j], &U[s->iQ[j]], ctx);
            hl_series_set(&Z[N + j], &U[s->iP[j]], ctx);
        }
        st = check_start(Z, s, n, ctx, err);
    }
    for (int u = 0; u < m; u++)
        hl_series_clear(&U[u], ctx);
    free(U);
    free(lhs);
    free(rhs);
    return st;
}
