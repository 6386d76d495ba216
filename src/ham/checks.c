/* §2 checks: integrals of motion ({I,H} = 0), involution, functional
 * independence (rank of the Jacobian), canonical maps ({Q_i,P_j} = delta_ij,
 * {Q_i,Q_j} = {P_i,P_j} = 0). */
#include "ham/ham_impl.h"

hl_status hl_check_integral(int *yes, hl_alg *br, const hl_alg *I, hl_system *sys, hl_error *err)
{
    hl_alg b;
    hl_alg_init(&b, sys->ctx);
    int st = hl_generator_apply(&b, I, sys, err); /* {I, H} */
    if (st == HL_OK) {
        *yes = hl_alg_is_zero(&b, sys->ctx);
        if (br != NULL)
            hl_alg_swap(br, &b, sys->ctx);
    }
    hl_alg_clear(&b, sys->ctx);
    return st;
}

hl_status hl_check_involution(int *all_zero, hl_alg *br, const hl_alg *f, int n, hl_system *sys,
                              hl_error *err)
{
    int st = HL_OK;
    *all_zero = 1;
    for (int i = 0; i < n; i++)
        hl_alg_zero(&br[i * n + i], sys->ctx);
    for (int i = 0; i < n && st == HL_OK; i++)
        for (int j = i + 1; j < n && st == HL_OK; j++) {
            st = hl_bracket(&br[i * n + j], &f[i], &f[j], sys, err);
            if (st != HL_OK)
                break;
            hl_alg_neg(&br[j * n + i], &br[i * n + j], sys->ctx);
            if (!hl_alg_is_zero(&br[i * n + j], sys->ctx))
                *all_zero = 0;
        }
    return st;
}

/* Rank by Bareiss' fraction-free elimination: after step k every entry of
 * the remaining block is a (k+1)-minor, and dividing by the previous pivot
 * is exact.  Over rational functions every division is exact anyway; the
 * point is that the entries stay minors instead of growing products. */
static int rank_bareiss(int *rank, hl_alg *m, int rows, int cols, hl_alg_ctx *ctx,
                        hl_error *err)
{
    hl_alg prev, t, u;
    int r = 0, st = HL_OK;
    hl_alg_init(&prev, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&u, ctx);
    hl_alg_one(&prev, ctx);
    for (int c = 0; c < cols && r < rows && st == HL_OK; c++) {
        int piv = -1;
        for (int i = r; i < rows && piv < 0; i++)
            if (!hl_alg_is_zero(&m[i * cols + c], ctx))
                piv = i;
        if (piv < 0)
            continue;
        if (piv != r)
            for (int j = 0; j < cols; j++)
                hl_alg_swap(&m[piv * cols + j], &m[r * cols + j], ctx);
        for (int i = r + 1; i < rows && st == HL_OK; i++) {
            for (int j = c + 1; j < cols && st == HL_OK; j++) {
                hl_alg_mul(&t, &m[r * cols + c], &m[i * cols + j], ctx);
                hl_alg_mul(&u, &m[i * cols + c], &m[r * cols + j], ctx);
                hl_alg_sub(&t, &t, &u, ctx);
                st = hl_alg_div(&m[i * cols + j], &t, &prev, ctx, err);
            }
            hl_alg_zero(&m[i * cols + c], ctx);
        }
        hl_alg_set(&prev, &m[r * cols + c], ctx);
        r++;
    }
    *rank = r;
    hl_alg_clear(&prev, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&u, ctx);
    return st;
}

hl_status hl_jacobian_rank(int *rank, const hl_alg *f, int n, hl_system *sys, hl_error *err)
{
    int cols = 2 * sys->n, st = HL_OK;
    *rank = 0;
    if (n == 0)
        return HL_OK;
    hl_alg *m = hl_alg_vec_new(n * cols, sys->ctx);
    for (int i = 0; i < n && st == HL_OK; i++)
        for (int v = 0; v < cols && st == HL_OK; v++)
            st = hl_alg_diff(&m[i * cols + v], &f[i], v, sys->ctx, err);
    if (st == HL_OK)
        st = rank_bareiss(rank, m, n, cols, sys->ctx, err);
    hl_alg_vec_free(m, n * cols, sys->ctx);
    return st;
}

/* Entry (a, b) of J = [[0, I], [-I, 0]]. */
static long J_entry(int a, int b, int N)
{
    if (a < N && b == a + N)
        return 1;
    if (a >= N && b == a - N)
        return -1;
    return 0;
}

hl_status hl_check_canonical(int *canonical, hl_alg *br, const hl_alg *images, hl_system *sys,
                             hl_error *err)
{
    int N = sys->n, N2 = 2 * N, st = HL_OK;
    hl_alg d;
    hl_alg_init(&d, sys->ctx);
    *canonical = 1;
    for (int a = 0; a < N2; a++)
        hl_alg_zero(&br[a * N2 + a], sys->ctx);
    for (int a = 0; a < N2 && st == HL_OK; a++)
        for (int b = a + 1; b < N2 && st == HL_OK; b++) {
            st = hl_bracket(&br[a * N2 + b], &images[a], &images[b], sys, err);
            if (st != HL_OK)
                break;
            hl_alg_neg(&br[b * N2 + a], &br[a * N2 + b], sys->ctx);
            hl_alg_set_si(&d, J_entry(a, b, N), sys->ctx);
            hl_alg_sub(&d, &br[a * N2 + b], &d, sys->ctx);
            if (!hl_alg_is_zero(&d, sys->ctx))
                *canonical = 0;
        }
    hl_alg_clear(&d, sys->ctx);
    return st;
}
