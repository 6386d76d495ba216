/* The Lie series exp(D g) phi = sum_k D^k/k! g^k phi (paper §2, g_D = exp(D g)),
 * truncated after D^order, with the limits of ham.h checked order by order so
 * that a series that grows too fast stops early with a clear message. */
#include <math.h>

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

/* Sizes grow like a power of the order (polynomially, as the degree of the
 * terms grows linearly), so extrapolate len_n = len_k (n/k)^a with a from the
 * last two orders, and the total to order n as len_n * n / (a + 1). */
static double projected_total(long len_prev, long len_k, int k, int n)
{
    double a = log((double)len_k / (double)len_prev) / log((double)k / (k - 1));
    if (!(a > 0))
        a = 0;
    return (double)len_k * pow((double)n / k, a) * n / (a + 1);
}

/* The largest order whose projected total still fits the budget. */
static int largest_order_that_fits(long len_prev, long len_k, int k)
{
    int n = k;
    while (n < HL_LIE_MAX_ORDER && projected_total(len_prev, len_k, k, n + 1) <= HL_LIE_MAX_TERMS)
        n++;
    return n;
}

static int refuse_growth(int order, int k, long total, long len_prev, long len_k, hl_error *err)
{
    if (total > HL_LIE_MAX_TERMS)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                            "order %d refused: stopped at order %d, where the terms so far hold "
                            "%ld polynomial terms, past the limit of %ld",
                            order, k, total, HL_LIE_MAX_TERMS);
    return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                        "order %d refused: g^%d phi already has %ld terms, and extrapolating "
                        "their growth the series would pass the limit of %ld terms; the "
                        "largest order that fits is about %d",
                        order, k, len_k, HL_LIE_MAX_TERMS,
                        largest_order_that_fits(len_prev, len_k, k));
}

hl_status hl_lie_terms(hl_alg *terms, const hl_alg *phi, int order, hl_system *sys, hl_error *err)
{
    return hl_lie_terms_watched(terms, phi, order, sys, NULL, NULL, err);
}

hl_status hl_lie_terms_watched(hl_alg *terms, const hl_alg *phi, int order, hl_system *sys,
                               hl_progress_fn progress, void *arg, hl_error *err)
{
    int st = check_order(order, err);
    if (st != HL_OK)
        return st;
    hl_alg_set(&terms[0], phi, sys->ctx);
    long total = hl_alg_length(&terms[0], sys->ctx), len_prev = total;
    for (int k = 1; k <= order; k++) {
        if ((st = hl_generator_apply(&terms[k], &terms[k - 1], sys, err)) != HL_OK)
            return st;
        long len = hl_alg_length(&terms[k], sys->ctx);
        total += len;
        if (total > HL_LIE_MAX_TERMS ||
            (k >= 6 && projected_total(len_prev, len, k, order) > 2.0 * HL_LIE_MAX_TERMS))
            return refuse_growth(order, k, total, len_prev, len, err);
        len_prev = len;
        if (progress != NULL && progress(k, order, arg) != 0)
            return hl_error_set(err, HL_ESTOP, NULL, -1, 0, "stopped at order %d of %d", k,
                                order);
    }
    return HL_OK;
}

hl_status hl_lie_series(hl_alg *r, const hl_alg *phi, int order, hl_system *sys, hl_error *err)
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
