/* The exact flow of a quadratic H (any number of degrees of freedom): the
 * vector field is affine, z' = A z + b, so the step is the matrix
 * exponential of the augmented matrix [[A, b], [0, 0]] times (z, 1), and
 * its series in D the powers of that matrix.  The exponential is taken in
 * Arb so that it is right to the last bit of the double it is stored in. */
#include <string.h>

#include <arb_mat.h>

#include "base/buf.h"
#include "exact/exact_impl.h"

/* Is H quadratic (degree <= 2 in q,p, constant coefficients)?  Fills the
 * augmented matrix when it is. */
int hl_exact_linear_matrix_(double *Aaug, int *yes, hl_system *sys, hl_error *err)
{
    int N = hl_system_ndof(sys), n = 2 * N, m = n + 1, st = HL_OK;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    const hl_alg *H = hl_system_H(sys);
    hl_alg *g = hl_alg_vec_new(n, ctx), d2, zero;
    hl_alg *zeros = hl_alg_vec_new(n, ctx);
    int *vars = hl_xmalloc(sizeof(int) * n);
    fmpq_t c;
    fmpq_init(c);
    hl_alg_init(&d2, ctx);
    hl_alg_init(&zero, ctx);
    *yes = 1;
    memset(Aaug, 0, sizeof(double) * m * m);
    for (int a = 0; a < n; a++)
        vars[a] = a < N ? hl_system_var_q(sys, a) : hl_system_var_p(sys, a - N);
    for (int a = 0; a < n && st == HL_OK && *yes; a++) {
        st = hl_alg_diff(&g[a], H, vars[a], ctx, err);
        /* row of A: (J grad H)_i = dH/dp_i (i < N), -dH/dq_i */
        int row = a < N ? a + N : a - N;
        double sgn = a < N ? -1.0 : 1.0;
        for (int b = 0; b < n && st == HL_OK && *yes; b++) {
            st = hl_alg_diff(&d2, &g[a], vars[b], ctx, err);
            if (st == HL_OK && !hl_alg_is_fmpq(&d2, c, ctx))
                *yes = 0;
            else if (st == HL_OK)
                Aaug[row * m + b] = sgn * fmpq_get_d(c);
        }
        if (st == HL_OK && *yes) {
            st = hl_alg_subst(&d2, &g[a], n, vars, zeros, ctx, err);
            if (st == HL_OK && !hl_alg_is_fmpq(&d2, c, ctx))
                *yes = 0;
            else if (st == HL_OK)
                Aaug[row * m + n] = sgn * fmpq_get_d(c);
        }
    }
    fmpq_clear(c);
    hl_alg_clear(&d2, ctx);
    hl_alg_clear(&zero, ctx);
    hl_alg_vec_free(g, n, ctx);
    hl_alg_vec_free(zeros, n, ctx);
    free(vars);
    return st;
}

static void linear_exp(hl_exact_flow *f, double dt)
{
    int m = 2 * f->N + 1;
    slong prec = 128;
    arb_mat_t A, E;
    arb_t h;
    arb_init(h);
    arb_set_d(h, dt);
    arb_mat_init(A, m, m);
    arb_mat_init(E, m, m);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++) {
            arb_set_d(arb_mat_entry(A, i, j), f->Aaug[i * m + j]);
            arb_mul(arb_mat_entry(A, i, j), arb_mat_entry(A, i, j), h, prec);
        }
    arb_mat_exp(E, A, prec);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            f->E[i * m + j] = arf_get_d(arb_midref(arb_mat_entry(E, i, j)), ARF_RND_NEAR);
    arb_mat_clear(A);
    arb_mat_clear(E);
    arb_clear(h);
    f->Edt = dt;
    f->have_E = 1;
}

int hl_exact_linear_step_(double *z, double dt, hl_exact_flow *f)
{
    int n = 2 * f->N, m = n + 1;
    if (!f->have_E || f->Edt != dt)
        linear_exp(f, dt);
    double *w = hl_xmalloc(sizeof(double) * n);
    for (int i = 0; i < n; i++) {
        double s = f->E[i * m + n];
        for (int j = 0; j < n; j++)
            s += f->E[i * m + j] * z[j];
        w[i] = s;
    }
    memcpy(z, w, sizeof(double) * n);
    free(w);
    return HL_OK;
}

/* (A^k (z, 1))/k! with the augmented matrix: the series of exp(D A). */
void hl_exact_linear_series_(double *coef, const double *z, int n, const hl_exact_flow *f)
{
    int m2 = 2 * f->N, m = m2 + 1;
    double *x = hl_xmalloc(sizeof(double) * m), *y = hl_xmalloc(sizeof(double) * m);
    memcpy(x, z, sizeof(double) * m2);
    x[m2] = 1;
    memcpy(coef, z, sizeof(double) * m2);
    for (int k = 1; k <= n; k++) {
        for (int i = 0; i < m; i++) {
            double t = 0;
            for (int j = 0; j < m; j++)
                t += f->Aaug[i * m + j] * x[j];
            y[i] = t / k;
        }
        memcpy(x, y, sizeof(double) * m);
        memcpy(coef + (size_t)k * m2, x, sizeof(double) * m2);
    }
    free(x), free(y);
}
