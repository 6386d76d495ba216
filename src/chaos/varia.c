/* The variational equations and MEGNO's integrals as one ODE (the layout
 * is in chaos_impl.h), differentiated symbolically from H and compiled to
 * a tape for the Taylor integrator. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "chaos/chaos_impl.h"

/* Names of the extra inputs.  A ':' cannot appear in a name the parser
 * reads, so these never collide with the user's symbols. */
static char *delta_name(const char *var)
{
    size_t len = strlen(var) + 8;
    char *s = hl_xmalloc(len);
    snprintf(s, len, "delta:%s", var);
    return s;
}

static const char *const extra_names[4] = {"chaos:k", "chaos:c", "chaos:a", "chaos:b"};

/* v_i = sum_j (d f_i / d z_j) delta_j: the variational right-hand side. */
static const hl_expr *variational(hl_pool *pool, const hl_expr *fi, int n, const char *const *names)
{
    const hl_expr *v = hl_num_si(pool, 0);
    for (int j = 0; j < n; j++) {
        const hl_expr *d = hl_expr_diff(pool, fi, names[j]);
        if (d->kind == HL_NUM && fmpq_is_zero(d->num))
            continue; /* most of a sparse Jacobian: keep the tape small */
        v = hl_add(pool, v, hl_mul(pool, d, hl_sym(pool, names[n + j])));
    }
    return v;
}

/* r = delta . v / delta . delta */
static const hl_expr *growth_rate(hl_pool *pool, const hl_expr *const *v, int n,
                                  const char *const *names)
{
    const hl_expr *num = hl_num_si(pool, 0), *den = hl_num_si(pool, 0);
    for (int i = 0; i < n; i++) {
        const hl_expr *d = hl_sym(pool, names[n + i]);
        num = hl_add(pool, num, hl_mul(pool, d, v[i]));
        den = hl_add(pool, den, hl_mul(pool, d, d));
    }
    return hl_div(pool, num, den);
}

/* An unset parameter would reach the tape as an unknown symbol; say what
 * it is instead. */
static hl_status check_params(hl_system *sys, hl_error *err)
{
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "chaos indicators need a Hamiltonian (-H)");
    if (hl_system_nparams(sys) > 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "parameter '%s' needs a value (--param %s=...)",
                            hl_system_param(sys, 0), hl_system_param(sys, 0));
    return HL_OK;
}

hl_status chaos_tape(hl_tape **out, hl_system *sys, int with_b, hl_error *err)
{
    *out = NULL;
    hl_status st = check_params(sys, err);
    if (st != HL_OK)
        return st;
    hl_pool *pool = hl_system_pool(sys);
    const hl_expr *H = hl_system_H_expr(sys);
    int N = hl_system_ndof(sys), n = 2 * N, dim = with_b ? CHAOS_DIM(n) : CHAOS_DIM_NO_B(n);
    const char **names = hl_xmalloc((size_t)CHAOS_DIM(n) * sizeof *names);
    const hl_expr **f = hl_xmalloc((size_t)CHAOS_DIM(n) * sizeof *f);
    for (int j = 0; j < N; j++) {
        names[j] = hl_system_coord(sys, j);
        names[N + j] = hl_system_momentum(sys, j);
    }
    for (int i = 0; i < n; i++)
        names[n + i] = delta_name(names[i]);
    for (int i = 0; i < 4; i++)
        names[2 * n + i] = extra_names[i];
    for (int j = 0; j < N; j++) {
        f[j] = hl_expr_diff(pool, H, names[N + j]);
        f[N + j] = hl_neg(pool, hl_expr_diff(pool, H, names[j]));
    }
    for (int i = 0; i < n; i++)
        f[n + i] = variational(pool, f[i], n, names);
    const hl_expr *k = hl_sym(pool, extra_names[0]), *c = hl_sym(pool, extra_names[1]);
    const hl_expr *a = hl_sym(pool, extra_names[2]);
    f[CHAOS_K(n)] = hl_num_si(pool, 0);
    f[CHAOS_C(n)] = k;
    f[CHAOS_A(n)] = hl_mul(pool, hl_mul(pool, c, growth_rate(pool, f + n, n, names)), k);
    f[CHAOS_B(n)] = hl_div(pool, hl_mul(pool, hl_mul(pool, hl_num_si(pool, 2), a), k), c);
    st = hl_tape_new(out, f, dim, names, dim, err);
    for (int i = 0; i < n; i++)
        free((char *)names[n + i]);
    free(names);
    free(f);
    return st;
}
