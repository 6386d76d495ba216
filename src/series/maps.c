/* Series maps: the Lie series exp(D g) phi, composition of maps, and the
 * paper's K(D) = psi_{-D} o d/dD psi_D (§4, eq. Err).
 *
 * The Lie series is computed here from H directly (hl_alg_diff) rather than
 * through ham.h, so that series sits below ham in the layer order. */
#include <stdlib.h>

#include "base/buf.h"
#include "series/series_impl.h"

/* r = g f = sum_j df/dq_j dH/dp_j - df/dp_j dH/dq_j with Hq, Hp precomputed. */
static int generator(hl_alg *r, const hl_alg *f, int ndof, const int *qv, const int *pv,
                     const hl_alg *Hq, const hl_alg *Hp, hl_alg_ctx *ctx, hl_error *err)
{
    hl_alg acc, d;
    hl_alg_init(&acc, ctx);
    hl_alg_init(&d, ctx);
    int status = HL_OK;
    for (int j = 0; status == HL_OK && j < ndof; j++) {
        status = hl_alg_diff(&d, f, qv[j], ctx, err);
        if (status != HL_OK)
            break;
        hl_alg_mul(&d, &d, &Hp[j], ctx);
        hl_alg_add(&acc, &acc, &d, ctx);
        status = hl_alg_diff(&d, f, pv[j], ctx, err);
        if (status != HL_OK)
            break;
        hl_alg_mul(&d, &d, &Hq[j], ctx);
        hl_alg_sub(&acc, &acc, &d, ctx);
    }
    if (status == HL_OK)
        hl_alg_swap(r, &acc, ctx);
    hl_alg_clear(&acc, ctx);
    hl_alg_clear(&d, ctx);
    return status;
}

hl_status hl_series_lie(hl_series *r, const hl_alg *phi, const hl_alg *H, int ndof,
                        const int *qvars, const int *pvars, int n, hl_alg_ctx *ctx, hl_error *err)
{
    if (n < 0 || n > HL_SERIES_MAX_N)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "series length %d outside 0..%d", n,
                            HL_SERIES_MAX_N);
    hl_alg *Hq = hl_alg_vec_new(ndof, ctx), *Hp = hl_alg_vec_new(ndof, ctx);
    hl_series s;
    hl_series_init(&s, n, ctx);
    int status = HL_OK;
    for (int j = 0; status == HL_OK && j < ndof; j++) {
        status = hl_alg_diff(&Hq[j], H, qvars[j], ctx, err);
        if (status == HL_OK)
            status = hl_alg_diff(&Hp[j], H, pvars[j], ctx, err);
    }
    if (n > 0)
        hl_alg_set(&s.c[0], phi, ctx);
    /* c_k = g c_{k-1} / k = g^k phi / k!, g being linear */
    for (int k = 1; status == HL_OK && k < n; k++) {
        status = generator(&s.c[k], &s.c[k - 1], ndof, qvars, pvars, Hq, Hp, ctx, err);
        if (status == HL_OK) {
            fmpq_t c;
            fmpq_init(c);
            fmpq_set_si(c, 1, (unsigned long)k);
            hl_alg_scalar_mul_fmpq(&s.c[k], &s.c[k], c, ctx);
            fmpq_clear(c);
        }
    }
    if (status == HL_OK)
        hl_series_swap(r, &s);
    hl_series_clear(&s, ctx);
    hl_alg_vec_free(Hq, ndof, ctx);
    hl_alg_vec_free(Hp, ndof, ctx);
    return status;
}

static int compose(hl_series *r, int m, const hl_series *A, int nvars, const int *vars,
                   const hl_series *B, int var_D, long max_terms, hl_alg_ctx *ctx,
                   hl_error *err);

hl_status hl_series_compose(hl_series *r, int m, const hl_series *A, int nvars, const int *vars,
                            const hl_series *B, int var_D, hl_alg_ctx *ctx, hl_error *err)
{
    return compose(r, m, A, nvars, vars, B, var_D, 0, ctx, err);
}

static int compose(hl_series *r, int m, const hl_series *A, int nvars, const int *vars,
                   const hl_series *B, int var_D, long max_terms, hl_alg_ctx *ctx,
                   hl_error *err)
{
    int nb = hl_alg_ctx_nbase(ctx);
    if (var_D < 0 || var_D >= nb)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no base symbol number %d", var_D);
    int n = HL_SERIES_MAX_N;
    for (int i = 0; i < m; i++)
        n = A[i].n < n ? A[i].n : n;
    for (int j = 0; j < nvars; j++) {
        if (vars[j] < 0 || vars[j] >= nb || vars[j] == var_D)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "cannot substitute for base symbol number %d", vars[j]);
        n = B[j].n < n ? B[j].n : n;
    }
    /* Every coefficient a_ik(z) of every A_i is one root of a single Taylor
     * program (their common subterms shared), run with z -> B: this Taylor-
     * expands them around B's constant term, whatever it is.  Then
     * r_i = sum_k D^k a_ik(B).  Keeping the coefficients apart avoids one
     * fraction over a common denominator for all the powers of D. */
    series_table t;
    series_table_init(&t, var_D, n, ctx);
    for (int j = 0; j < nvars; j++)
        series_table_bind(&t, hl_alg_ctx_name(ctx, vars[j]), &B[j], ctx);
    hl_pool *pool = hl_pool_new();
    const hl_expr **roots = hl_xmalloc((size_t)(m * n > 0 ? m * n : 1) * sizeof *roots);
    for (int i = 0; i < m; i++)
        for (int k = 0; k < n; k++)
            roots[i * n + k] = hl_alg_to_expr(&A[i].c[k], ctx, pool);
    series_prog *prog = NULL;
    int status =
        series_prog_compile(&prog, m * n, roots, t.nsym, (const char *const *)t.names, n, ctx, err);
    if (status == HL_OK) {
        series_prog_set_budget(prog, max_terms);
        status = series_prog_run(prog, n, t.vals, ctx, err);
    }
    for (int i = 0; status == HL_OK && i < m; i++) {
        hl_series_zero(&r[i], n, ctx);
        for (int k = 0; k < n; k++) {
            const hl_series *v = series_prog_root(prog, i * n + k);
            for (int j = 0; j + k < n; j++)
                hl_alg_add(&r[i].c[j + k], &r[i].c[j + k], &v->c[j], ctx);
        }
    }
    series_prog_free(prog, ctx);
    free(roots);
    hl_pool_free(pool);
    series_table_clear(&t, ctx);
    return status;
}

hl_status hl_series_scheme_K(hl_series *K, int m, const hl_series *psi, const int *vars, int var_D,
                             hl_alg_ctx *ctx, hl_error *err)
{
    return hl_series_scheme_K_bounded(K, m, psi, vars, var_D, 0, ctx, err);
}

hl_status hl_series_scheme_K_bounded(hl_series *K, int m, const hl_series *psi, const int *vars,
                                     int var_D, long max_terms, hl_alg_ctx *ctx, hl_error *err)
{
    hl_series *dpsi = hl_xmalloc((size_t)(m > 0 ? m : 1) * sizeof *dpsi);
    hl_series *back = hl_xmalloc((size_t)(m > 0 ? m : 1) * sizeof *back);
    for (int i = 0; i < m; i++) {
        hl_series_init(&dpsi[i], 0, ctx);
        hl_series_init(&back[i], 0, ctx);
        hl_series_derivative(&dpsi[i], &psi[i], ctx);
        hl_series_reflect(&back[i], &psi[i], ctx);
    }
    int status = compose(K, m, dpsi, m, vars, back, var_D, max_terms, ctx, err);
    for (int i = 0; i < m; i++) {
        hl_series_clear(&dpsi[i], ctx);
        hl_series_clear(&back[i], ctx);
    }
    free(dpsi);
    free(back);
    return status;
}
