/* The Lie series exp(D g) phi = sum_k D^k/k! g^k phi (paper §2, g_D = exp(D g)),
 * truncated after D^order, with the limits of ham.h checked order by order so
 * that a series that grows too fast stops early with a clear message. */
#include "ham/ham_impl.h"

static int check_order(int order, hl_error *err)
{
    if (order < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the order of a Lie series must be at least 0 (got %d)", order);
    if (order > HL_LIE_MAX_ORDER)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                            "order %d refused: the Lie series is limited to order %d", order,
                            HL_LIE_MAX_ORDER);
    return HL_OK;
}

int hl_lie_terms(hl_alg *terms, const hl_alg *phi, int order, hl_system *sys, hl_error *err)
{
    int st = check_order(order, err);
    if (st != HL_OK)
        return st;
    hl_alg_set(&terms[0], phi, sys->ctx);
    for (int k = 1; k <= order; k++) {
        if ((st = hl_generator_apply(&terms[k], &terms[k - 1], sys, err)) != HL_OK)
            return st;
        long len = hl_alg_length(&terms[k], sys->ctx);
        if (len > HL_LIE_MAX_TERMS)
            return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                                "the Lie series grew past the limit: g^%d phi has %ld terms "
                                "(limit %ld); stopped at order %d",
                                k, len, HL_LIE_MAX_TERMS, k);
    }
    return HL_OK;
}

int hl_lie_series(hl_alg *r, const hl_alg *phi, int order, hl_system *sys, hl_error *err)
{
    int st = check_order(order, err);
    if (st != HL_OK)
        return st;
    hl_alg_ctx *ctx = sys->ctx;
    hl_alg *t = hl_alg_vec_new(order + 1, ctx);
    st = hl_lie_terms(t, phi, order, sys, err);
    if (st == HL_OK) {
        /* Horner in D: s = t_n/n!; s = t_k/k! + D s, written with the ratios
         * 1/(k+1) so no factorial is formed: s_k = t_k + (D/(k+1)) s_{k+1}. */
        hl_alg s, Dk;
        fmpq_t c;
        hl_alg_init(&s, ctx);
        hl_alg_init(&Dk, ctx);
        fmpq_init(c);
        hl_alg_set(&s, &t[order], ctx);
        hl_alg_gen(&Dk, hl_system_var_D(sys), ctx);
        for (int k = order - 1; k >= 0; k--) {
            fmpq_set_si(c, 1, (ulong)(k + 1));
            hl_alg_mul(&s, &s, &Dk, ctx);
            hl_alg_scalar_mul_fmpq(&s, &s, c, ctx);
            hl_alg_add(&s, &s, &t[k], ctx);
        }
        hl_alg_swap(r, &s, ctx);
        hl_alg_clear(&s, ctx);
        hl_alg_clear(&Dk, ctx);
        fmpq_clear(c);
    }
    hl_alg_vec_free(t, order + 1, ctx);
    return st;
}
