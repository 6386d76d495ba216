/* The error fields v_k of a scheme, computed two ways (analysis.h). */
#include <stdlib.h>

#include "base/buf.h"
#include "hamlie/analysis.h"

static void fact(fmpq_t f, int k, int inverse)
{
    fmpq_one(f);
    fmpz_fac_ui(inverse ? fmpq_denref(f) : fmpq_numref(f), (ulong)k);
}

/* lie[i] = exp(D g) z_i to O(D^n). */
static int lie_vec(hl_series *lie, hl_system *sys, int n, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), st = HL_OK;
    int *qv = hl_xmalloc((size_t)N * sizeof *qv), *pv = hl_xmalloc((size_t)N * sizeof *pv);
    for (int j = 0; j < N; j++) {
        qv[j] = hl_system_var_q(sys, j);
        pv[j] = hl_system_var_p(sys, j);
    }
    hl_alg z;
    hl_alg_init(&z, ctx);
    for (int i = 0; i < 2 * N && st == HL_OK; i++) {
        hl_alg_gen(&z, i < N ? qv[i] : pv[i - N], ctx);
        st = hl_series_lie(&lie[i], &z, hl_system_H(sys), N, qv, pv, n, ctx, err);
    }
    hl_alg_clear(&z, ctx);
    free(qv);
    free(pv);
    return st;
}

/* v_k from K alone (see analysis.h): the partial map psi~ is rebuilt for each
 * k from the Lie series and the v_j (j < k) found so far by this route. */
static int errors_from_K(hl_vfields *e, const hl_series *psi, const hl_series *lie, hl_system *sys,
                         hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = e->N, m = 2 * N, n = e->n, st = HL_OK;
    int *vars = hl_xmalloc((size_t)m * sizeof *vars);
    for (int i = 0; i < m; i++)
        vars[i] = i < N ? hl_system_var_q(sys, i) : hl_system_var_p(sys, i - N);
    int vD = hl_system_var_D(sys);
    hl_series *K = e->K, *Kt = hl_series_vec_new(m, 0, ctx), *pt = hl_series_vec_new(m, 0, ctx);
    hl_alg d;
    fmpq_t f;
    hl_alg_init(&d, ctx);
    fmpq_init(f);
    st = hl_series_scheme_K_bounded(K, m, psi, vars, vD, e->budget, ctx, err); /* K.n >= n */
    if (st != HL_OK) {
        hl_series_vec_free(e->K, m, ctx);
        e->K = NULL;
    }
    for (int k = 2; k <= n && st == HL_OK; k++) {
        for (int i = 0; i < m; i++) {
            hl_series_set(&pt[i], &lie[i], ctx);
            hl_series_set_length(&pt[i], k + 1, ctx);
            for (int j = 2; j < k; j++) {
                fact(f, j, 1);
                hl_alg_scalar_mul_fmpq(&d, &e->vK[j * m + i], f, ctx);
                hl_alg_add(&pt[i].c[j], &pt[i].c[j], &d, ctx);
            }
        }
        st = hl_series_scheme_K_bounded(Kt, m, pt, vars, vD, e->budget, ctx, err);
        fact(f, k - 1, 0);
        for (int i = 0; i < m && st == HL_OK; i++) {
            hl_alg_sub(&d, &K[i].c[k - 1], &Kt[i].c[k - 1], ctx);
            hl_alg_scalar_mul_fmpq(&e->vK[k * m + i], &d, f, ctx);
        }
    }
    hl_alg_clear(&d, ctx);
    fmpq_clear(f);
    hl_series_vec_free(Kt, m, ctx);
    hl_series_vec_free(pt, m, ctx);
    free(vars);
    if (st == HL_ELIMIT && e->budget > 0) { /* a check left out, not a failure */
        e->over_budget = 1;
        e->checked = e->agree = 0;
        hl_error_clear(err);
        st = HL_OK;
    }
    return st;
}

static int compute(hl_vfields *e, const hl_series *psi, hl_system *sys, int n, int cross,
                   long budget, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), m = 2 * N, st = HL_OK;
    e->N = N;
    e->n = n;
    e->v = e->vK = NULL;
    e->K = NULL;
    e->budget = budget;
    e->over_budget = 0;
    e->checked = cross;
    e->agree = cross;
    e->disagree_k = 0;
    e->leading = 0;
    e->order = n;
    if (n < 2 || n > HL_SERIES_MAX_N - 2)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the order must be between 2 and %d, not %d", HL_SERIES_MAX_N - 2, n);
    e->v = hl_alg_vec_new((n + 1) * m, ctx);
    e->vK = hl_alg_vec_new((n + 1) * m, ctx);
    e->K = cross ? hl_series_vec_new(m, 0, ctx) : NULL;
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "error analysis needs a Hamiltonian");
    for (int i = 0; i < m; i++)
        if (psi[i].n < n + 1)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "the scheme's expansion is known to O(D^%d), need O(D^%d)",
                                psi[i].n, n + 1);
    hl_series *lie = hl_series_vec_new(m, 0, ctx);
    st = lie_vec(lie, sys, n + 1, err);
    hl_alg d;
    fmpq_t f;
    hl_alg_init(&d, ctx);
    fmpq_init(f);
    for (int k = 2; k <= n && st == HL_OK; k++) {
        fact(f, k, 0);
        for (int i = 0; i < m; i++) {
            hl_alg_sub(&d, &psi[i].c[k], &lie[i].c[k], ctx);
            hl_alg_scalar_mul_fmpq(&e->v[k * m + i], &d, f, ctx);
        }
    }
    if (st == HL_OK && cross)
        st = errors_from_K(e, psi, lie, sys, err);
    for (int k = 2; k <= n && st == HL_OK; k++) {
        int zero = 1;
        for (int i = 0; i < m; i++) {
            if (e->checked && e->agree && !hl_alg_equal(&e->v[k * m + i], &e->vK[k * m + i], ctx)) {
                e->agree = 0;
                e->disagree_k = k;
            }
            zero = zero && hl_alg_is_zero(&e->v[k * m + i], ctx);
        }
        if (!zero && e->leading == 0) {
            e->leading = k;
            e->order = k - 1;
        }
    }
    hl_alg_clear(&d, ctx);
    fmpq_clear(f);
    hl_series_vec_free(lie, m, ctx);
    return st;
}

hl_status hl_vfields_compute(hl_vfields *e, const hl_series *psi, hl_system *sys, int n,
                             hl_error *err)
{
    return compute(e, psi, sys, n, 1, 0, err);
}

hl_status hl_vfields_compute_bounded(hl_vfields *e, const hl_series *psi, hl_system *sys, int n,
                                     long max_terms, hl_error *err)
{
    return compute(e, psi, sys, n, 1, max_terms, err);
}

hl_status hl_vfields_compute_direct(hl_vfields *e, const hl_series *psi, hl_system *sys, int n,
                                    hl_error *err)
{
    return compute(e, psi, sys, n, 0, 0, err);
}

void hl_vfields_clear(hl_vfields *e, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg_vec_free(e->v, (e->n + 1) * 2 * e->N, ctx);
    hl_alg_vec_free(e->vK, (e->n + 1) * 2 * e->N, ctx);
    hl_series_vec_free(e->K, 2 * e->N, ctx);
    e->v = e->vK = NULL;
    e->K = NULL;
}
