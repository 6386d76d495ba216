/* Backward error analysis: the modified vector field (analysis.h, part 6). */
#include <stdlib.h>

#include "base/buf.h"
#include "hamlie/analysis.h"

/* a with the powers of D above deg dropped (a a polynomial in D). */
static int truncate_D(hl_alg *a, int vD, long deg, hl_alg_ctx *ctx, hl_error *err)
{
    long d = hl_alg_degree(a, vD, ctx);
    if (d <= deg)
        return HL_OK;
    hl_alg r, c, Dk;
    hl_alg_init(&r, ctx);
    hl_alg_init(&c, ctx);
    hl_alg_init(&Dk, ctx);
    hl_alg_one(&Dk, ctx);
    int st = HL_OK;
    for (long k = 0; k <= deg && st == HL_OK; k++) {
        if ((st = hl_alg_coeff(&c, a, vD, k, ctx, err)) != HL_OK)
            break;
        hl_alg_mul(&c, &c, &Dk, ctx);
        hl_alg_add(&r, &r, &c, ctx);
        hl_alg_gen(&c, vD, ctx);
        hl_alg_mul(&Dk, &Dk, &c, ctx);
    }
    if (st == HL_OK)
        hl_alg_swap(a, &r, ctx);
    hl_alg_clear(&r, ctx);
    hl_alg_clear(&c, ctx);
    hl_alg_clear(&Dk, ctx);
    return st;
}

/* out_i = [D^J] exp(D F) z_i with F_i = sum_{j=1}^{J-1} D^(j-1) f_j. */
static int exp_coeff(hl_alg *out, const hl_alg *F, int m, int J, int vD, hl_alg_ctx *ctx,
                     hl_error *err)
{
    hl_alg *L = hl_alg_vec_new(m, ctx), t, d, c;
    hl_alg_init(&t, ctx);
    hl_alg_init(&d, ctx);
    hl_alg_init(&c, ctx);
    fmpq_t f;
    fmpq_init(f);
    int st = HL_OK;
    for (int i = 0; i < m && st == HL_OK; i++) {
        hl_alg_zero(&out[i], ctx);
        hl_alg_gen(&L[i], i, ctx); /* L^0 z_i */
        for (int k = 1; k <= J && st == HL_OK; k++) {
            hl_alg_zero(&t, ctx);
            for (int l = 0; l < m && st == HL_OK; l++)
                if ((st = hl_alg_diff(&d, &L[i], l, ctx, err)) == HL_OK) {
                    hl_alg_mul(&d, &d, &F[l], ctx);
                    hl_alg_add(&t, &t, &d, ctx);
                }
            if (st == HL_OK)
                st = truncate_D(&t, vD, J - k, ctx, err);
            hl_alg_swap(&L[i], &t, ctx);
            if (st == HL_OK && (st = hl_alg_coeff(&c, &L[i], vD, J - k, ctx, err)) == HL_OK) {
                fmpq_one(f);
                fmpz_fac_ui(fmpq_denref(f), (ulong)k);
                hl_alg_scalar_mul_fmpq(&c, &c, f, ctx);
                hl_alg_add(&out[i], &out[i], &c, ctx);
            }
        }
    }
    hl_alg_vec_free(L, m, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&c, ctx);
    fmpq_clear(f);
    return st;
}

hl_status hl_modified_field(hl_alg *mf, const hl_series *psi, hl_system *sys, int n, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int m = 2 * hl_system_ndof(sys), vD = hl_system_var_D(sys), st = HL_OK;
    for (int i = 0; i < m; i++)
        if (psi[i].n < n + 1)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "the scheme's expansion is known to O(D^%d), need O(D^%d)",
                                psi[i].n, n + 1);
    hl_alg *F = hl_alg_vec_new(m, ctx), *E = hl_alg_vec_new(m, ctx), Dk, t;
    hl_alg_init(&Dk, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_one(&Dk, ctx);
    for (int J = 1; J <= n && st == HL_OK; J++) {
        /* F holds f_1 + ... + D^(J-2) f_(J-1); Dk = D^(J-1) */
        if ((st = exp_coeff(E, F, m, J, vD, ctx, err)) != HL_OK)
            break;
        for (int i = 0; i < m; i++) {
            hl_alg_sub(&mf[J * m + i], &psi[i].c[J], &E[i], ctx);
            hl_alg_mul(&t, &Dk, &mf[J * m + i], ctx);
            hl_alg_add(&F[i], &F[i], &t, ctx);
        }
        hl_alg_gen(&t, vD, ctx);
        hl_alg_mul(&Dk, &Dk, &t, ctx);
    }
    hl_alg_vec_free(F, m, ctx);
    hl_alg_vec_free(E, m, ctx);
    hl_alg_clear(&Dk, ctx);
    hl_alg_clear(&t, ctx);
    return st;
}
