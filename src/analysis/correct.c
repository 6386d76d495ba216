/* Closed forms of explicit schemes, K(D) in closed form, corrected schemes
 * (analysis.h). */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "expr/memo.h"
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

int hl_errors_scheme_map(hl_alg *images, const hl_scheme *s, hl_error *err)
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
    for (int j = 0; j < 2 * s->N && st == HL_OK; j++) {
        int u = j < s->N ? s->iQ[j] : s->iP[j - s->N];
        st = hl_alg_from_expr(&images[j], val_of[u], ctx, err);
    }
    free(names);
    free(vals);
    free(val_of);
    return st;
}

int hl_errors_K_closed(hl_alg *K, const hl_alg *images, hl_system *sys, hl_error *err)
{
    long reached;
    return hl_errors_K_closed_bounded(K, &reached, images, 0, sys, err);
}

int hl_errors_K_closed_bounded(hl_alg *K, long *reached, const hl_alg *images, long max_terms,
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

void hl_errors_correct_series(hl_series *out, const hl_series *psi, const hl_errors *e, int m,
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
            hl_alg_scalar_mul_fmpq(&d, &hl_errors_field(e, k)[i], f, ctx);
            hl_alg_sub(&out[i].c[k], &out[i].c[k], &d, ctx);
        }
    }
    hl_alg_clear(&d, ctx);
    fmpq_clear(f);
}

void hl_errors_correct_map(hl_alg *images, const hl_errors *e, int m, hl_system *sys)
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
            hl_alg_mul(&d, &Dk, &hl_errors_field(e, k)[i], ctx);
            hl_alg_sub(&images[i], &images[i], &d, ctx);
        }
    }
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&Dk, ctx);
    fmpq_clear(f);
}
