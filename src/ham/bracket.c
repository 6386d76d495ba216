/* §2 of the paper: the Poisson bracket (eq. PB) and the evolution generator
 * g = sum_j dH/dp_j d/dq_j - dH/dq_j d/dp_j, with g o phi = {phi, H}. */
#include "ham/ham_impl.h"

static int need_H(const hl_system *sys, hl_error *err)
{
    if (!sys->has_H)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "this needs a Hamiltonian, and none was given (give it with -H)");
    return HL_OK;
}

/* {a,b} = sum_j da/dq_j db/dp_j - db/dq_j da/dp_j */
hl_status hl_bracket(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = sys->ctx;
    hl_alg s, da, db, t;
    int st = HL_OK;
    hl_alg_init(&s, ctx);
    hl_alg_init(&da, ctx);
    hl_alg_init(&db, ctx);
    hl_alg_init(&t, ctx);
    for (int j = 0; j < sys->n && st == HL_OK; j++) {
        int q = hl_system_var_q(sys, j), p = hl_system_var_p(sys, j);
        if ((st = hl_alg_diff(&da, a, q, ctx, err)) != HL_OK ||
            (st = hl_alg_diff(&db, b, p, ctx, err)) != HL_OK)
            break;
        hl_alg_mul(&t, &da, &db, ctx);
        hl_alg_add(&s, &s, &t, ctx);
        if ((st = hl_alg_diff(&da, a, p, ctx, err)) != HL_OK ||
            (st = hl_alg_diff(&db, b, q, ctx, err)) != HL_OK)
            break;
        hl_alg_mul(&t, &da, &db, ctx);
        hl_alg_sub(&s, &s, &t, ctx);
    }
    if (st == HL_OK)
        hl_alg_swap(r, &s, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&da, ctx);
    hl_alg_clear(&db, ctx);
    hl_alg_clear(&t, ctx);
    return st;
}

int ham_field(hl_system *sys, hl_error *err)
{
    int st;
    if (sys->have_field)
        return HL_OK;
    if ((st = need_H(sys, err)) != HL_OK)
        return st;
    hl_alg *xi = hl_alg_vec_new(sys->n, sys->ctx), *eta = hl_alg_vec_new(sys->n, sys->ctx);
    st = HL_OK;
    for (int j = 0; j < sys->n && st == HL_OK; j++) {
        st = hl_alg_diff(&xi[j], &sys->H, hl_system_var_p(sys, j), sys->ctx, err);
        if (st == HL_OK)
            st = hl_alg_diff(&eta[j], &sys->H, hl_system_var_q(sys, j), sys->ctx, err);
        if (st == HL_OK)
            hl_alg_neg(&eta[j], &eta[j], sys->ctx);
    }
    if (st != HL_OK) {
        hl_alg_vec_free(xi, sys->n, sys->ctx);
        hl_alg_vec_free(eta, sys->n, sys->ctx);
        return st;
    }
    sys->xi = xi;
    sys->eta = eta;
    sys->have_field = 1;
    return HL_OK;
}

hl_status hl_generator(hl_alg *xi, hl_alg *eta, hl_system *sys, hl_error *err)
{
    int st = ham_field(sys, err);
    if (st != HL_OK)
        return st;
    for (int j = 0; j < sys->n; j++) {
        hl_alg_set(&xi[j], &sys->xi[j], sys->ctx);
        hl_alg_set(&eta[j], &sys->eta[j], sys->ctx);
    }
    return HL_OK;
}

/* g o phi = sum_j xi_j dphi/dq_j + eta_j dphi/dp_j, the same as {phi, H}
 * but with the derivatives of H taken once per system. */
hl_status hl_generator_apply(hl_alg *r, const hl_alg *phi, hl_system *sys, hl_error *err)
{
    int st = ham_field(sys, err);
    if (st != HL_OK)
        return st;
    hl_alg_ctx *ctx = sys->ctx;
    hl_alg s, d;
    hl_alg_init(&s, ctx);
    hl_alg_init(&d, ctx);
    for (int j = 0; j < sys->n && st == HL_OK; j++) {
        if ((st = hl_alg_diff(&d, phi, hl_system_var_q(sys, j), ctx, err)) != HL_OK)
            break;
        hl_alg_mul(&d, &d, &sys->xi[j], ctx);
        hl_alg_add(&s, &s, &d, ctx);
        if ((st = hl_alg_diff(&d, phi, hl_system_var_p(sys, j), ctx, err)) != HL_OK)
            break;
        hl_alg_mul(&d, &d, &sys->eta[j], ctx);
        hl_alg_add(&s, &s, &d, ctx);
    }
    if (st == HL_OK)
        hl_alg_swap(r, &s, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&d, ctx);
    return st;
}
