/* Time reparametrisation psi_D = exp(tau(D) g) (analysis.h, part 4). */
#include <stdlib.h>

#include "base/buf.h"
#include "hamlie/analysis.h"

static int depends_on_phase(const hl_alg *a, hl_system *sys)
{
    for (int i = 0; i < 2 * hl_system_ndof(sys); i++)
        if (hl_alg_depends_on(a, i, hl_system_ctx(sys)))
            return 1;
    return 0;
}

/* E[i] = sum_{j<=len-1} lie[i].c[j] tau^j to O(D^len): exp(tau g) z_i. */
static void exp_tau(hl_series *E, const hl_series *lie, const hl_series *tau, int m, int len,
                    hl_alg_ctx *ctx)
{
    hl_series pw, t;
    hl_series_init(&pw, 0, ctx);
    hl_series_init(&t, 0, ctx);
    for (int i = 0; i < m; i++) {
        hl_series_zero(&E[i], len, ctx);
        hl_alg one;
        hl_alg_init(&one, ctx);
        hl_alg_one(&one, ctx);
        hl_series_set_alg(&pw, &one, len, ctx);
        hl_alg_clear(&one, ctx);
        for (int j = 0; j < len; j++) {
            hl_series_scalar_mul(&t, &pw, &lie[i].c[j], ctx);
            hl_series_add(&E[i], &E[i], &t, ctx);
            hl_series_mul(&pw, &pw, tau, ctx);
        }
    }
    hl_series_clear(&pw, ctx);
    hl_series_clear(&t, ctx);
}

hl_status hl_errors_time_series(hl_series *tau, int *ok, int *fail_k, const hl_series *psi,
                                hl_system *sys, int n, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), m = 2 * N, st = HL_OK;
    *ok = 1;
    *fail_k = 0;
    for (int i = 0; i < m; i++)
        if (psi[i].n < n + 1)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "the scheme's expansion is known to O(D^%d), need O(D^%d)",
                                psi[i].n, n + 1);
    int *qv = hl_xmalloc((size_t)N * sizeof *qv), *pv = hl_xmalloc((size_t)N * sizeof *pv);
    for (int j = 0; j < N; j++) {
        qv[j] = hl_system_var_q(sys, j);
        pv[j] = hl_system_var_p(sys, j);
    }
    hl_series *lie = hl_xmalloc((size_t)m * sizeof *lie), *E = hl_xmalloc((size_t)m * sizeof *E);
    hl_alg z, d, a, t;
    hl_alg_init(&z, ctx);
    hl_alg_init(&d, ctx);
    hl_alg_init(&a, ctx);
    hl_alg_init(&t, ctx);
    for (int i = 0; i < m; i++) {
        hl_series_init(&lie[i], 0, ctx);
        hl_series_init(&E[i], 0, ctx);
    }
    for (int i = 0; i < m && st == HL_OK; i++) {
        hl_alg_gen(&z, i < N ? qv[i] : pv[i - N], ctx);
        st = hl_series_lie(&lie[i], &z, hl_system_H(sys), N, qv, pv, n + 1, ctx, err);
    }
    hl_series_zero(tau, n + 1, ctx);
    hl_alg_one(&tau->c[1], ctx);
    int i0 = -1; /* a component where g z != 0 */
    for (int i = 0; i < m && i0 < 0; i++)
        if (!hl_alg_is_zero(&lie[i].c[1], ctx))
            i0 = i;
    if (i0 < 0 && st == HL_OK)
        st = hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the generator is zero");
    for (int k = 2; k <= n && st == HL_OK && *ok; k++) {
        exp_tau(E, lie, tau, m, k + 1, ctx);
        hl_alg_sub(&d, &psi[i0].c[k], &E[i0].c[k], ctx);
        if ((st = hl_alg_div(&a, &d, &lie[i0].c[1], ctx, err)) != HL_OK)
            break;
        int good = !depends_on_phase(&a, sys);
        for (int i = 0; i < m && good; i++) {
            hl_alg_sub(&d, &psi[i].c[k], &E[i].c[k], ctx);
            hl_alg_mul(&t, &a, &lie[i].c[1], ctx);
            good = hl_alg_equal(&d, &t, ctx);
        }
        if (good)
            hl_alg_set(&tau->c[k], &a, ctx);
        else {
            *ok = 0;
            *fail_k = k;
        }
    }
    for (int i = 0; i < m; i++) {
        hl_series_clear(&lie[i], ctx);
        hl_series_clear(&E[i], ctx);
    }
    free(lie);
    free(E);
    free(qv);
    free(pv);
    hl_alg_clear(&z, ctx);
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&t, ctx);
    return st;
}

hl_status hl_errors_time_closed(hl_alg *tau, hl_alg *r, int *ok, hl_alg *D2, int *have_D2,
                                const hl_alg *images, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int st = HL_OK, q = hl_system_var_q(sys, 0), p = hl_system_var_p(sys, 0),
        vD = hl_system_var_D(sys);
    *ok = *have_D2 = 0;
    if (hl_system_ndof(sys) != 1)
        return HL_OK;
    hl_alg M[4], H, t, u, one;
    for (int i = 0; i < 4; i++)
        hl_alg_init(&M[i], ctx);
    hl_alg_init(&H, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&u, ctx);
    hl_alg_init(&one, ctx);
    hl_alg_one(&one, ctx);
    /* H = (p^2 + q^2)/2 ? */
    hl_alg_gen(&t, q, ctx);
    hl_alg_mul(&H, &t, &t, ctx);
    hl_alg_gen(&t, p, ctx);
    hl_alg_mul(&t, &t, &t, ctx);
    hl_alg_add(&H, &H, &t, ctx);
    fmpq_t half;
    fmpq_init(half);
    fmpq_set_si(half, 1, 2);
    hl_alg_scalar_mul_fmpq(&H, &H, half, ctx);
    int good = hl_alg_equal(&H, hl_system_H(sys), ctx);
    for (int i = 0; i < 2 && good && st == HL_OK; i++) {
        if ((st = hl_alg_diff(&M[2 * i], &images[i], q, ctx, err)) != HL_OK ||
            (st = hl_alg_diff(&M[2 * i + 1], &images[i], p, ctx, err)) != HL_OK)
            break;
        good = !depends_on_phase(&M[2 * i], sys) && !depends_on_phase(&M[2 * i + 1], sys);
        hl_alg_gen(&t, q, ctx);
        hl_alg_mul(&t, &t, &M[2 * i], ctx);
        hl_alg_gen(&u, p, ctx);
        hl_alg_mul(&u, &u, &M[2 * i + 1], ctx);
        hl_alg_add(&t, &t, &u, ctx);
        good = good && hl_alg_equal(&t, &images[i], ctx);
    }
    if (good && st == HL_OK) { /* a rotation: M11 = M22, M12 = -M21, M11^2 + M12^2 = 1 */
        hl_alg_neg(&t, &M[2], ctx);
        good = hl_alg_equal(&M[0], &M[3], ctx) && hl_alg_equal(&M[1], &t, ctx);
        hl_alg_mul(&t, &M[0], &M[0], ctx);
        hl_alg_mul(&u, &M[1], &M[1], ctx);
        hl_alg_add(&t, &t, &u, ctx);
        good = good && hl_alg_equal(&t, &one, ctx);
    }
    if (good && st == HL_OK) {
        hl_alg_add(&t, &one, &M[0], ctx);
        if (hl_alg_is_zero(&t, ctx))
            good = 0;
        else if ((st = hl_alg_div(r, &M[1], &t, ctx, err)) == HL_OK &&
                 (st = hl_alg_apply(&u, HL_ATAN, r, ctx, err)) == HL_OK) {
            hl_alg_add(tau, &u, &u, ctx);
            *ok = 1;
        }
    }
    if (*ok && st == HL_OK) { /* r = c D? */
        hl_alg_gen(&t, vD, ctx);
        if ((st = hl_alg_div(&u, r, &t, ctx, err)) == HL_OK && !hl_alg_depends_on(&u, vD, ctx) &&
            !depends_on_phase(&u, sys) && !hl_alg_is_zero(&u, ctx)) {
            /* D2 = 2D/(1 - c^2 D^2) */
            hl_alg_mul(&u, &u, &u, ctx);
            hl_alg_mul(&u, &u, &t, ctx);
            hl_alg_mul(&u, &u, &t, ctx);
            hl_alg_sub(&u, &one, &u, ctx);
            hl_alg_add(&t, &t, &t, ctx);
            if (!hl_alg_is_zero(&u, ctx) && (st = hl_alg_div(D2, &t, &u, ctx, err)) == HL_OK)
                *have_D2 = 1;
        }
    }
    fmpq_clear(half);
    for (int i = 0; i < 4; i++)
        hl_alg_clear(&M[i], ctx);
    hl_alg_clear(&H, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&u, ctx);
    hl_alg_clear(&one, ctx);
    return st;
}

/* M[a*2+b] = the series d psi_a / d z_b when each coefficient is linear in
 * (q, p) with coefficients free of them; 0 otherwise. */
static int linear_series(hl_series *M, const hl_series *psi, hl_system *sys, int n,
                         hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg t, u, z;
    hl_alg_init(&t, ctx);
    hl_alg_init(&u, ctx);
    hl_alg_init(&z, ctx);
    int ok = 1;
    for (int a = 0; a < 2 && ok == 1; a++) {
        for (int b = 0; b < 2; b++)
            hl_series_zero(&M[2 * a + b], n + 1, ctx);
        for (int k = 0; k <= n && ok == 1; k++) {
            hl_alg_zero(&u, ctx);
            for (int b = 0; b < 2 && ok == 1; b++) {
                if (hl_alg_diff(&M[2 * a + b].c[k], &psi[a].c[k], b, ctx, err) != HL_OK) {
                    ok = -1;
                    break;
                }
                ok = !depends_on_phase(&M[2 * a + b].c[k], sys);
                hl_alg_gen(&z, b, ctx);
                hl_alg_mul(&t, &z, &M[2 * a + b].c[k], ctx);
                hl_alg_add(&u, &u, &t, ctx);
            }
            if (ok == 1)
                ok = hl_alg_equal(&u, &psi[a].c[k], ctx);
        }
    }
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&u, ctx);
    hl_alg_clear(&z, ctx);
    return ok;
}

hl_status hl_errors_time_closed_series(hl_alg *tau, hl_alg *r, int *ok, hl_alg *D2,
                                       const hl_series *psi, hl_system *sys, int n, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int st = HL_OK, vD = hl_system_var_D(sys);
    *ok = 0;
    if (hl_system_ndof(sys) != 1 || psi[0].n < n + 1 || psi[1].n < n + 1)
        return HL_OK;
    hl_alg H, t, one;
    hl_alg_init(&H, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&one, ctx);
    hl_alg_one(&one, ctx);
    hl_alg_gen(&t, 0, ctx);
    hl_alg_mul(&H, &t, &t, ctx);
    hl_alg_gen(&t, 1, ctx);
    hl_alg_mul(&t, &t, &t, ctx);
    hl_alg_add(&H, &H, &t, ctx);
    fmpq_t c;
    fmpq_init(c);
    fmpq_set_si(c, 1, 2);
    hl_alg_scalar_mul_fmpq(&H, &H, c, ctx);
    hl_series M[4], a, b;
    for (int i = 0; i < 4; i++)
        hl_series_init(&M[i], 0, ctx);
    hl_series_init(&a, 0, ctx);
    hl_series_init(&b, 0, ctx);
    int lin = hl_alg_equal(&H, hl_system_H(sys), ctx) ? linear_series(M, psi, sys, n, err) : 0;
    if (lin < 0)
        st = err->status;
    if (lin == 1) {
        /* a rotation to the order computed? */
        hl_series_neg(&a, &M[2], ctx);
        int good = hl_series_equal(&M[0], &M[3], ctx) && hl_series_equal(&M[1], &a, ctx);
        hl_series_mul(&a, &M[0], &M[0], ctx);
        hl_series_mul(&b, &M[1], &M[1], ctx);
        hl_series_add(&a, &a, &b, ctx);
        hl_series_set_alg(&b, &one, n + 1, ctx);
        good = good && hl_series_equal(&a, &b, ctx);
        if (good) {
            hl_series_add(&b, &b, &M[0], ctx); /* 1 + M11 */
            if ((st = hl_series_div(&a, &M[1], &b, ctx, err)) == HL_OK) {
                good = a.n >= 2;
                for (int k = 0; k < a.n && good; k++)
                    good = k == 1 ? !depends_on_phase(&a.c[1], sys) && !hl_alg_is_zero(&a.c[1], ctx)
                                  : hl_alg_is_zero(&a.c[k], ctx);
            }
        }
        if (good && st == HL_OK) {
            /* r = c D, tau = 2 atan(r), D2 = 2D/(1 - c^2 D^2) */
            hl_alg_gen(&t, vD, ctx);
            hl_alg_mul(r, &a.c[1], &t, ctx);
            if ((st = hl_alg_apply(tau, HL_ATAN, r, ctx, err)) == HL_OK) {
                hl_alg_add(tau, tau, tau, ctx);
                hl_alg_mul(&H, r, r, ctx);
                hl_alg_sub(&H, &one, &H, ctx);
                hl_alg_add(&t, &t, &t, ctx);
                if ((st = hl_alg_div(D2, &t, &H, ctx, err)) == HL_OK)
                    *ok = 1;
            }
        }
    }
    fmpq_clear(c);
    for (int i = 0; i < 4; i++)
        hl_series_clear(&M[i], ctx);
    hl_series_clear(&a, ctx);
    hl_series_clear(&b, ctx);
    hl_alg_clear(&H, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&one, ctx);
    return st;
}
