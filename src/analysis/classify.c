/* Classification of an error field (analysis.h): time shift, parallel to g,
 * scaling, Hamiltonian (with h by the homogeneous Euler formula), general. */
#include <stdlib.h>

#include "base/buf.h"
#include "hamlie/analysis.h"

/* Does a depend on any phase variable? */
static int depends_on_phase(const hl_alg *a, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    for (int i = 0; i < 2 * hl_system_ndof(sys); i++)
        if (hl_alg_depends_on(a, i, ctx))
            return 1;
    return 0;
}

/* d_{a}(x) + s * d_{b}(y) == 0 ? */
static int diff_cond(int *ok, const hl_alg *x, int vx, const hl_alg *y, int vy, int sign,
                     hl_alg_ctx *ctx, hl_error *err)
{
    hl_alg dx, dy;
    hl_alg_init(&dx, ctx);
    hl_alg_init(&dy, ctx);
    int st = hl_alg_diff(&dx, x, vx, ctx, err);
    if (st == HL_OK)
        st = hl_alg_diff(&dy, y, vy, ctx, err);
    if (st == HL_OK) {
        if (sign > 0)
            hl_alg_add(&dx, &dx, &dy, ctx);
        else
            hl_alg_sub(&dx, &dx, &dy, ctx);
        *ok = hl_alg_is_zero(&dx, ctx);
    }
    hl_alg_clear(&dx, ctx);
    hl_alg_clear(&dy, ctx);
    return st;
}

hl_status hl_errfield_is_hamiltonian(int *yes, const hl_alg *v, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), st = HL_OK, ok = 1;
    const hl_alg *a = v, *b = v + N;
    for (int i = 0; i < N && ok && st == HL_OK; i++)
        for (int j = 0; j < N && ok && st == HL_OK; j++) {
            int qi = hl_system_var_q(sys, i), qj = hl_system_var_q(sys, j);
            int pi = hl_system_var_p(sys, i), pj = hl_system_var_p(sys, j);
            st = diff_cond(&ok, &a[i], qj, &b[j], pi, +1, ctx, err);
            if (st == HL_OK && ok && i < j)
                st = diff_cond(&ok, &a[i], pj, &a[j], pi, -1, ctx, err);
            if (st == HL_OK && ok && i < j)
                st = diff_cond(&ok, &b[i], qj, &b[j], qi, -1, ctx, err);
        }
    *yes = ok;
    return st;
}

/* Is v = J grad h exactly: v(q_j) = dh/dp_j, v(p_j) = -dh/dq_j? */
static int is_J_grad(int *yes, const hl_alg *h, const hl_alg *v, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), st = HL_OK, ok = 1;
    hl_alg d;
    hl_alg_init(&d, ctx);
    for (int j = 0; j < N && ok && st == HL_OK; j++) {
        st = hl_alg_diff(&d, h, hl_system_var_p(sys, j), ctx, err);
        ok = st == HL_OK && hl_alg_equal(&d, &v[j], ctx);
        if (ok && (st = hl_alg_diff(&d, h, hl_system_var_q(sys, j), ctx, err)) == HL_OK) {
            hl_alg_neg(&d, &d, ctx);
            ok = hl_alg_equal(&d, &v[N + j], ctx);
        }
    }
    hl_alg_clear(&d, ctx);
    *yes = ok && st == HL_OK;
    return st;
}

/* h from the Euler formula: E = sum_j p_j a_j - q_j b_j = sum_d d h_d, for E a
 * polynomial in the phase variables (coefficients may involve parameters);
 * then h is checked against v.  *found = 0 when E is not such a polynomial
 * or the check fails. */
static int euler_h(int *found, hl_alg *h, const hl_alg *v, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    const fmpz_mpoly_ctx_struct *mctx = hl_alg_ctx_mpoly(ctx);
    int N = hl_system_ndof(sys), nb = hl_alg_ctx_nbase(ctx), st = HL_OK;
    hl_alg E, t, z, d;
    hl_alg_init(&E, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&z, ctx);
    hl_alg_init(&d, ctx);
    *found = 0;
    hl_alg_zero(h, ctx);
    for (int j = 0; j < N; j++) {
        hl_alg_gen(&z, hl_system_var_p(sys, j), ctx);
        hl_alg_mul(&t, &z, &v[j], ctx);
        hl_alg_add(&E, &E, &t, ctx);
        hl_alg_gen(&z, hl_system_var_q(sys, j), ctx);
        hl_alg_mul(&t, &z, &v[N + j], ctx);
        hl_alg_sub(&E, &E, &t, ctx);
    }
    slong nvars = fmpz_mpoly_ctx_nvars(mctx);
    ulong *exp = hl_xmalloc((size_t)nvars * sizeof *exp);
    int poly = 1;
    hl_alg den;
    hl_alg_init(&den, ctx);
    fmpz_mpoly_set(den.num, E.den, mctx);
    if (depends_on_phase(&den, sys))
        poly = 0;
    for (slong i = 0; poly && i < fmpz_mpoly_length(E.num, mctx); i++) {
        fmpz_mpoly_get_term_exp_ui(exp, E.num, i, mctx);
        ulong deg = 0;
        for (slong x = 0; x < nvars; x++) {
            if (x < 2 * N)
                deg += exp[x];
            else if (x >= nb && exp[x] != 0)
                poly = 0; /* an atom: not a polynomial */
        }
        if (!poly || deg == 0) {
            poly = deg == 0 ? 0 : poly;
            break;
        }
        hl_alg_zero(&t, ctx);
        fmpz_mpoly_get_term(t.num, E.num, i, mctx);
        fmpq_t c;
        fmpq_init(c);
        fmpz_one(fmpq_numref(c));
        fmpz_set_ui(fmpq_denref(c), deg);
        hl_alg_scalar_mul_fmpq(&t, &t, c, ctx);
        fmpq_clear(c);
        hl_alg_add(h, h, &t, ctx);
    }
    if (poly)
        st = hl_alg_div(h, h, &den, ctx, err);
    int ok = poly && st == HL_OK;
    if (ok)
        st = is_J_grad(&ok, h, v, sys, err);
    *found = ok && st == HL_OK;
    free(exp);
    hl_alg_clear(&den, ctx);
    hl_alg_clear(&E, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&z, ctx);
    hl_alg_clear(&d, ctx);
    return st;
}

/* h by antiderivatives, for fields with sin/cos of the coordinates (the
 * pendulum's): h = sum_j int (a_j - dh/dp_j) dp_j, then
 * h += sum_j int (-b_j - dh/dq_j) dq_j, each integrand's left-over checked
 * free of what is already integrated; finally J grad h = v exactly.
 * *found = 0 when an antiderivative is out of reach (alg.h). */
static int antiderivative_h(int *found, hl_alg *h, const hl_alg *v, hl_system *sys,
                            hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), st = HL_OK, ok = 1;
    hl_alg d, g, I;
    hl_alg_init(&d, ctx);
    hl_alg_init(&g, ctx);
    hl_alg_init(&I, ctx);
    hl_alg_zero(h, ctx);
    for (int k = 0; k < 2 * N && ok && st == HL_OK; k++) {
        int j = k % N, var = k < N ? hl_system_var_p(sys, j) : hl_system_var_q(sys, j);
        if ((st = hl_alg_diff(&d, h, var, ctx, err)) != HL_OK)
            break;
        if (k < N) /* dh/dp_j = a_j */
            hl_alg_sub(&g, &v[j], &d, ctx);
        else { /* dh/dq_j = -b_j */
            hl_alg_neg(&g, &v[N + j], ctx);
            hl_alg_sub(&g, &g, &d, ctx);
        }
        st = hl_alg_antiderivative(&I, &ok, &g, var, ctx, err);
        if (st == HL_OK && ok)
            hl_alg_add(h, h, &I, ctx);
    }
    if (ok && st == HL_OK)
        st = is_J_grad(&ok, h, v, sys, err);
    *found = ok && st == HL_OK;
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&g, ctx);
    hl_alg_clear(&I, ctx);
    return st;
}

/* v = lambda f for the generator's components f?  *par = 0 if not. */
static int parallel(int *par, hl_alg *lambda, const hl_alg *v, const hl_alg *f, int m,
                    hl_alg_ctx *ctx, hl_error *err)
{
    int i0 = -1, st = HL_OK;
    *par = 0;
    for (int i = 0; i < m && i0 < 0; i++)
        if (!hl_alg_is_zero(&f[i], ctx))
            i0 = i;
    if (i0 < 0)
        return HL_OK;
    if ((st = hl_alg_div(lambda, &v[i0], &f[i0], ctx, err)) != HL_OK)
        return st;
    hl_alg t;
    hl_alg_init(&t, ctx);
    int ok = 1;
    for (int i = 0; i < m && ok; i++) {
        hl_alg_mul(&t, lambda, &f[i], ctx);
        ok = hl_alg_equal(&t, &v[i], ctx);
    }
    hl_alg_clear(&t, ctx);
    *par = ok;
    return HL_OK;
}

hl_status hl_errfield_classify(hl_errfield *F, const hl_alg *v, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), m = 2 * N, st, zero = 1;
    hl_alg_init(&F->lambda, ctx);
    hl_alg_init(&F->h, ctx);
    F->scale = NULL;
    F->hamiltonian = F->have_h = 0;
    F->kind = HL_ERRFIELD_GENERAL;
    for (int i = 0; i < m; i++)
        zero = zero && hl_alg_is_zero(&v[i], ctx);
    if (zero) {
        F->kind = HL_ERRFIELD_ZERO;
        F->hamiltonian = F->have_h = 1;
        return HL_OK;
    }
    hl_alg *f = hl_alg_vec_new(m, ctx);
    st = hl_generator(f, f + N, sys, err);
    int par = 0;
    if (st == HL_OK)
        st = parallel(&par, &F->lambda, v, f, m, ctx, err);
    if (st == HL_OK && par)
        F->kind = depends_on_phase(&F->lambda, sys) ? HL_ERRFIELD_PARALLEL
                                                    : HL_ERRFIELD_TIME_SHIFT;
    if (st == HL_OK && !par) {
        hl_alg *c = hl_alg_vec_new(m, ctx), z;
        hl_alg_init(&z, ctx);
        int ok = 1;
        for (int i = 0; i < m && ok && st == HL_OK; i++) {
            hl_alg_gen(&z, i < N ? hl_system_var_q(sys, i) : hl_system_var_p(sys, i - N), ctx);
            st = hl_alg_div(&c[i], &v[i], &z, ctx, err);
            ok = st == HL_OK && !depends_on_phase(&c[i], sys);
        }
        hl_alg_clear(&z, ctx);
        if (ok && st == HL_OK) {
            F->kind = HL_ERRFIELD_SCALING;
            F->scale = c;
        } else
            hl_alg_vec_free(c, m, ctx);
    }
    if (st == HL_OK)
        st = hl_errfield_is_hamiltonian(&F->hamiltonian, v, sys, err);
    if (st == HL_OK && F->hamiltonian) {
        if (F->kind == HL_ERRFIELD_GENERAL)
            F->kind = HL_ERRFIELD_HAMILTONIAN;
        st = euler_h(&F->have_h, &F->h, v, sys, err);
        if (st == HL_OK && !F->have_h)
            st = antiderivative_h(&F->have_h, &F->h, v, sys, err);
    }
    hl_alg_vec_free(f, m, ctx);
    return st;
}

void hl_errfield_clear(hl_errfield *F, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg_clear(&F->lambda, ctx);
    hl_alg_clear(&F->h, ctx);
    hl_alg_vec_free(F->scale, 2 * hl_system_ndof(sys), ctx);
    F->scale = NULL;
}
