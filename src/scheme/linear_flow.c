/* The exact flow of a Hamiltonian whose field is affine, z' = A z + g (H a
 * polynomial of degree <= 2 in the phase variables; coefficients may be
 * parameters), in closed form, for pairs (q_j, p_j) that H does not couple
 * (a coupled H goes to linear_modes.c: normal modes).
 *
 * In one pair, A = [[a, b], [c, -a]] with a = H_qp, b = H_pp, c = -H_qq has
 * trace 0, so A^2 = -w2 I with w2 = H_qq H_pp - H_qp^2, and
 *   exp(D A) = C I + S A,      int_0^D exp(s A) ds = S I + K A,
 *   C = cos(w D),  S = sin(w D)/w,  K = (1 - cos(w D))/w^2     (w = sqrt(w2)),
 * which are even in w, hence functions of w2 for either sign of it: for a
 * rational w2 < 0 they are written with cosh and sinh, for w2 = 0 they are
 * 1, D, D^2/2; a symbolic w2 keeps the trigonometric form.  The flow is
 *   z(D) = (C I + S A) z + (S I + K A) g.
 * (K' = S, S' = C and C' = -w2 S: z' = A z + g holds for every D.) */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/scheme.h"
#include "scheme/scheme_impl.h"

/* a as text that reads back (expr.h's printer of alg.h's form). */
static char *text_of(const hl_alg *a, hl_system *sys)
{
    return hl_expr_print(hl_alg_to_expr(a, hl_system_ctx(sys), hl_system_pool(sys)),
                         HL_STYLE_TEXT);
}

/* The Hessian of H (2N x 2N) and its gradient at z = 0; HL_EINVAL when a
 * second derivative still depends on a phase variable. */
static int hessian(hl_alg *hess, hl_alg *g0, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys), st = HL_OK;
    hl_alg *grad = hl_alg_vec_new(M, ctx), *zero = hl_alg_vec_new(M, ctx);
    int *vars = malloc((size_t)M * sizeof *vars);
    for (int i = 0; i < M; i++)
        vars[i] = i; /* the phase variables are base symbols 0 .. 2N-1 */
    for (int i = 0; i < M && st == HL_OK; i++)
        st = hl_alg_diff(&grad[i], hl_system_H(sys), i, ctx, err);
    for (int i = 0; i < M && st == HL_OK; i++)
        for (int k = 0; k < M && st == HL_OK; k++) {
            hl_alg *h = &hess[i * M + k];
            if ((st = hl_alg_diff(h, &grad[i], k, ctx, err)) != HL_OK)
                break;
            for (int v = 0; v < M; v++)
                if (hl_alg_depends_on(h, v, ctx)) {
                    st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                      "H is not quadratic in the phase variables: its second "
                                      "derivatives depend on %s",
                                      hl_alg_ctx_name(ctx, v));
                    break;
                }
        }
    for (int i = 0; i < M && st == HL_OK; i++)
        st = hl_alg_subst(&g0[i], &grad[i], M, vars, zero, ctx, err);
    free(vars);
    hl_alg_vec_free(grad, M, ctx);
    hl_alg_vec_free(zero, M, ctx);
    return st;
}

/* C, S, K of the header as functions of w2 and D. */
static int trig_parts(hl_alg *C, hl_alg *S, hl_alg *K, const hl_alg *w2, hl_system *sys,
                      hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    fmpq_t c;
    fmpq_init(c);
    int rational = hl_alg_is_fmpq(w2, c, ctx), sign = rational ? fmpq_sgn(c) : 1;
    hl_alg W;
    hl_alg_init(&W, ctx);
    if (sign < 0)
        hl_alg_neg(&W, w2, ctx);
    else
        hl_alg_set(&W, w2, ctx);
    char *w = text_of(&W, sys);
    hl_buf b[3];
    for (int i = 0; i < 3; i++)
        hl_buf_init(&b[i]);
    const char *D = hl_system_step(sys);
    if (sign == 0) {
        hl_buf_puts(&b[0], "1");
        hl_buf_puts(&b[1], D);
        hl_buf_printf(&b[2], "%s^2/2", D);
    } else {
        const char *cf = sign > 0 ? "cos" : "cosh", *sf = sign > 0 ? "sin" : "sinh";
        hl_buf_printf(&b[0], "%s(sqrt(%s)*%s)", cf, w, D);
        hl_buf_printf(&b[1], "%s(sqrt(%s)*%s)/sqrt(%s)", sf, w, D, w);
        if (sign > 0)
            hl_buf_printf(&b[2], "(1 - cos(sqrt(%s)*%s))/(%s)", w, D, w);
        else
            hl_buf_printf(&b[2], "(cosh(sqrt(%s)*%s) - 1)/(%s)", w, D, w);
    }
    hl_alg *out[3] = {C, S, K};
    int st = HL_OK;
    for (int i = 0; i < 3 && st == HL_OK; i++)
        st = hl_system_read(out[i], sys, b[i].s, err);
    for (int i = 0; i < 3; i++)
        hl_buf_clear(&b[i]);
    free(w);
    hl_alg_clear(&W, ctx);
    fmpq_clear(c);
    return st;
}

/* r = x*u + y*v + z*w (any of the pairs may be skipped with NULL). */
static void lincomb(hl_alg *r, const hl_alg *x, const hl_alg *u, const hl_alg *y,
                    const hl_alg *v, hl_alg_ctx *ctx)
{
    hl_alg t;
    hl_alg_init(&t, ctx);
    hl_alg_mul(r, x, u, ctx);
    if (y != NULL) {
        hl_alg_mul(&t, y, v, ctx);
        hl_alg_add(r, r, &t, ctx);
    }
    hl_alg_clear(&t, ctx);
}

/* The images of pair j: Q = C q + S (a q + b p + g1) + K (a g1 + b g2),
 * P = C p + S (c q - a p + g2) + K (c g1 - a g2). */
static int pair_images(hl_alg *Q, hl_alg *P, int j, const hl_alg *hess, const hl_alg *g0,
                       hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N, iq = j, ip = N + j;
    hl_alg *v = hl_alg_vec_new(12, ctx);
    hl_alg *a = &v[0], *b = &v[1], *c = &v[2], *g1 = &v[3], *g2 = &v[4], *w2 = &v[5];
    hl_alg *C = &v[6], *S = &v[7], *K = &v[8], *q = &v[9], *p = &v[10], *t = &v[11];
    hl_alg_set(a, &hess[iq * M + ip], ctx);
    hl_alg_set(b, &hess[ip * M + ip], ctx);
    hl_alg_neg(c, &hess[iq * M + iq], ctx);
    hl_alg_set(g1, &g0[ip], ctx);
    hl_alg_neg(g2, &g0[iq], ctx);
    lincomb(w2, &hess[iq * M + iq], &hess[ip * M + ip], NULL, NULL, ctx);
    hl_alg_mul(t, a, a, ctx);
    hl_alg_sub(w2, w2, t, ctx);
    int st = trig_parts(C, S, K, w2, sys, err);
    if (st == HL_OK) {
        hl_alg_gen(q, iq, ctx);
        hl_alg_gen(p, ip, ctx);
        /* Q */
        lincomb(t, a, q, b, p, ctx);
        hl_alg_add(t, t, g1, ctx);
        lincomb(Q, C, q, S, t, ctx);
        lincomb(t, a, g1, b, g2, ctx);
        hl_alg_mul(t, K, t, ctx);
        hl_alg_add(Q, Q, t, ctx);
        /* P */
        lincomb(t, c, q, a, p, ctx);
        hl_alg_mul(w2, a, p, ctx); /* w2 is free now: c q - a p = t - 2 a p */
        hl_alg_sub(t, t, w2, ctx);
        hl_alg_sub(t, t, w2, ctx);
        hl_alg_add(t, t, g2, ctx);
        lincomb(P, C, p, S, t, ctx);
        lincomb(t, c, g1, a, g2, ctx);
        hl_alg_mul(w2, a, g2, ctx);
        hl_alg_sub(t, t, w2, ctx);
        hl_alg_sub(t, t, w2, ctx);
        hl_alg_mul(t, K, t, ctx);
        hl_alg_add(P, P, t, ctx);
    }
    hl_alg_vec_free(v, 12, ctx);
    return st;
}

/* Does H couple pair j with another pair? */
static int coupled(int *other, const hl_alg *hess, int j, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N;
    for (int k = 0; k < N; k++) {
        if (k == j)
            continue;
        int a[2] = {j, N + j}, b[2] = {k, N + k};
        for (int x = 0; x < 2; x++)
            for (int y = 0; y < 2; y++)
                if (!hl_alg_is_zero(&hess[a[x] * M + b[y]], ctx)) {
                    *other = k;
                    return 1;
                }
    }
    return 0;
}

hl_status hl_scheme_linear_flow(hl_alg *images, hl_system *sys, hl_error *err)
{
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the exact flow needs a Hamiltonian");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N;
    hl_alg *hess = hl_alg_vec_new(M * M, ctx), *g0 = hl_alg_vec_new(M, ctx);
    int st = hessian(hess, g0, sys, err), other = -1, any = 0;
    for (int j = 0; j < N && st == HL_OK && !any; j++)
        any = coupled(&other, hess, j, sys);
    if (any) /* normal modes (linear_modes.c) */
        st = scheme_linear_modes(images, hess, g0, sys, err);
    for (int j = 0; j < N && st == HL_OK && !any; j++)
        st = pair_images(&images[j], &images[N + j], j, hess, g0, sys, err);
    hl_alg_vec_free(hess, M * M, ctx);
    hl_alg_vec_free(g0, M, ctx);
    return st;
}

hl_status hl_scheme_linear_modes(char **text, hl_system *sys, hl_error *err)
{
    *text = NULL;
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the normal modes need a Hamiltonian");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N;
    hl_alg *hess = hl_alg_vec_new(M * M, ctx), *g0 = hl_alg_vec_new(M, ctx);
    int st = hessian(hess, g0, sys, err), other = -1, any = 0;
    for (int j = 0; j < N && st == HL_OK && !any; j++)
        any = coupled(&other, hess, j, sys);
    if (st == HL_OK && !any)
        st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "H does not couple its pairs");
    if (st == HL_OK)
        st = scheme_linear_modes_text(text, hess, g0, sys, err);
    hl_alg_vec_free(hess, M * M, ctx);
    hl_alg_vec_free(g0, M, ctx);
    return st;
}

int hl_scheme_linear_flow_applies(hl_system *sys)
{
    if (!hl_system_has_H(sys))
        return 0;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys);
    hl_alg *img = hl_alg_vec_new(M, ctx);
    hl_error err;
    int st = hl_scheme_linear_flow(img, sys, &err);
    hl_alg_vec_free(img, M, ctx);
    return st == HL_OK;
}

hl_status hl_scheme_linear_flow_map(char **map, hl_system *sys, hl_error *err)
{
    *map = NULL;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N;
    hl_alg *img = hl_alg_vec_new(M, ctx);
    int st = hl_scheme_linear_flow(img, sys, err);
    if (st == HL_OK) {
        hl_buf b;
        hl_buf_init(&b);
        for (int i = 0; i < M; i++) {
            char *s = text_of(&img[i], sys);
            hl_buf_printf(&b, "%s%s' = %s", i ? "; " : "",
                          i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N), s);
            free(s);
        }
        *map = hl_buf_take(&b);
    }
    hl_alg_vec_free(img, M, ctx);
    return st;
}
