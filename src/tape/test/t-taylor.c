/* Taylor mode of every op against exact rational series from FLINT's
 * fmpq_poly series functions (an independent implementation).  The input is
 * the series u(t) = t + t^2/2 - t^3/3 rather than t itself, so that every
 * recurrence sees an operand with several nonzero coefficients.  Arb Taylor
 * mode at 200 bits must contain the exact coefficient; double must agree to
 * a few ulps of the coefficient's scale. */
#include <math.h>
#include <stdlib.h>

#include <flint/fmpq_poly.h>
#include <arb_poly.h>
#include "hl_test.h"
#include "hamlie/tape.h"

#define N 14 /* coefficients 0..N-1 */

static hl_pool *P;
static fmpq_poly_t u, one_u; /* u and 1 + u */
static const char *const tname[] = {"t"};

static void check(const char *label, const hl_expr *e, const fmpq_poly_t want)
{
    hl_tape *t = NULL;
    hl_error err;
    int st = hl_tape_new(&t, &e, 1, tname, 1, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", label, err.msg);
    if (st != HL_OK)
        return;
    double in[N] = {0}, out[N];
    arb_ptr ain = _arb_vec_init(N), aout = _arb_vec_init(N);
    fmpq_t c;
    fmpq_init(c);
    for (int k = 0; k < N; k++) {
        fmpq_poly_get_coeff_fmpq(c, u, k);
        in[k] = fmpq_get_d(c);
        arb_set_fmpq(ain + k, c, 200);
    }
    hl_tape_taylor_d(out, in, N - 1, t);
    hl_tape_taylor_arb(aout, ain, N - 1, 200, t);
    int bad = 0;
    for (int k = 0; k < N; k++) {
        fmpq_poly_get_coeff_fmpq(c, want, k);
        double w = fmpq_get_d(c);
        if (!(fabs(out[k] - w) <= 1e-13 * fabs(w) + 1e-15) || !arb_contains_fmpq(aout + k, c)
            || mag_cmp_2exp_si(arb_radref(aout + k), -150) > 0) {
            if (bad++ == 0) {
                char *s = arb_get_str(aout + k, 20, 0);
                fprintf(stderr, "%s: coefficient %d: double %.17g arb %s want %.17g\n", label, k,
                        out[k], s, w);
                flint_free(s);
            }
        }
    }
    CHECK_MSG(bad == 0, "%s: %d coefficients wrong", label, bad);
    fmpq_clear(c);
    _arb_vec_clear(ain, N);
    _arb_vec_clear(aout, N);
    hl_tape_free(t);
}

/* The same against an Arb series (for constants like pi): the tape's Arb
 * coefficients must overlap the expected balls. */
static void check_arb(const char *label, const hl_expr *e, const arb_poly_t want)
{
    hl_tape *t = NULL;
    hl_error err;
    int st = hl_tape_new(&t, &e, 1, tname, 1, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", label, err.msg);
    if (st != HL_OK)
        return;
    double in[N] = {0}, out[N];
    arb_ptr ain = _arb_vec_init(N), aout = _arb_vec_init(N);
    fmpq_t c;
    fmpq_init(c);
    for (int k = 0; k < N; k++) {
        fmpq_poly_get_coeff_fmpq(c, u, k);
        in[k] = fmpq_get_d(c);
        arb_set_fmpq(ain + k, c, 200);
    }
    hl_tape_taylor_d(out, in, N - 1, t);
    hl_tape_taylor_arb(aout, ain, N - 1, 200, t);
    arb_t w;
    arb_init(w);
    int bad = 0;
    for (int k = 0; k < N; k++) {
        arb_poly_get_coeff_arb(w, want, k);
        double wd = arf_get_d(arb_midref(w), ARF_RND_NEAR);
        if (!(fabs(out[k] - wd) <= 1e-13 * fabs(wd) + 1e-15) || !arb_overlaps(aout + k, w)
            || mag_cmp_2exp_si(arb_radref(aout + k), -150) > 0)
            bad++;
    }
    CHECK_MSG(bad == 0, "%s: %d coefficients wrong", label, bad);
    arb_clear(w);
    fmpq_clear(c);
    _arb_vec_clear(ain, N);
    _arb_vec_clear(aout, N);
    hl_tape_free(t);
}

/* (1+u)^(p/q) = exp((p/q) log(1+u)) computed exactly */
static void rational_power(fmpq_poly_t r, long p, long q)
{
    fmpq_t a;
    fmpq_init(a);
    fmpq_set_si(a, p, (ulong)q);
    fmpq_poly_log_series(r, one_u, N);
    fmpq_poly_scalar_mul_fmpq(r, r, a);
    fmpq_poly_exp_series(r, r, N);
    fmpq_clear(a);
}

int main(void)
{
    P = hl_pool_new();
    fmpq_poly_init(u);
    fmpq_poly_init(one_u);
    fmpq_poly_set_coeff_si(u, 1, 1);
    fmpq_t c;
    fmpq_init(c);
    fmpq_set_si(c, 1, 2);
    fmpq_poly_set_coeff_fmpq(u, 2, c);
    fmpq_set_si(c, -1, 3);
    fmpq_poly_set_coeff_fmpq(u, 3, c);
    fmpq_poly_add_si(one_u, u, 1);

    const hl_expr *t = hl_sym(P, "t"), *one = hl_num_si(P, 1), *two = hl_num_si(P, 2);
    const hl_expr *opt = hl_add(P, one, t);
    fmpq_poly_t w, v;
    fmpq_poly_init(w);
    fmpq_poly_init(v);

    fmpq_poly_exp_series(w, u, N);
    check("exp", hl_call(P, HL_EXP, t), w);
    fmpq_poly_log_series(w, one_u, N);
    check("log(1+t)", hl_call(P, HL_LOG, opt), w);
    fmpq_poly_sin_series(w, u, N);
    check("sin", hl_call(P, HL_SIN, t), w);
    fmpq_poly_cos_series(w, u, N);
    check("cos", hl_call(P, HL_COS, t), w);
    fmpq_poly_tan_series(w, u, N);
    check("tan", hl_call(P, HL_TAN, t), w);
    fmpq_poly_atan_series(w, u, N);
    check("atan", hl_call(P, HL_ATAN, t), w);
    fmpq_poly_asin_series(w, u, N);
    check("asin", hl_call(P, HL_ASIN, t), w);
    /* acos(u) = pi/2 - asin(u): compare acos(t) + asin(t) - pi/2 with 0 */
    fmpq_poly_zero(w);
    check("acos", hl_sub(P, hl_add(P, hl_call(P, HL_ACOS, t), hl_call(P, HL_ASIN, t)),
                         hl_div(P, hl_pi(P), two)), w);
    fmpq_poly_sinh_series(w, u, N);
    check("sinh", hl_call(P, HL_SINH, t), w);
    fmpq_poly_cosh_series(w, u, N);
    check("cosh", hl_call(P, HL_COSH, t), w);
    fmpq_poly_tanh_series(w, u, N);
    check("tanh", hl_call(P, HL_TANH, t), w);
    fmpq_poly_sqrt_series(w, one_u, N);
    check("sqrt(1+t)", hl_call(P, HL_SQRT, opt), w);
    check("(1+t)^(1/2)", hl_pow(P, opt, hl_num_frac(P, 1, 2)), w);
    fmpq_poly_inv_series(w, one_u, N);
    check("1/(1+t)", hl_div(P, one, opt), w);
    check("(1+t)^-1", hl_pow(P, opt, hl_num_si(P, -1)), w);
    rational_power(w, 1, 3);
    check("(1+t)^(1/3)", hl_pow(P, opt, hl_num_frac(P, 1, 3)), w);
    rational_power(w, -3, 2);
    check("(1+t)^(-3/2)", hl_pow(P, opt, hl_num_frac(P, -3, 2)), w);
    rational_power(w, 5, 1);
    check("(1+t)^5", hl_pow(P, opt, hl_num_si(P, 5)), w);
    rational_power(w, -3, 1);
    check("(1+t)^-3", hl_pow(P, opt, hl_num_si(P, -3)), w);
    /* a^[0] = 0: t^2, t^3 (lowered to SQR / MUL, no division by a^[0]) */
    fmpq_poly_mullow(w, u, u, N);
    check("t^2", hl_pow(P, t, two), w);
    fmpq_poly_mullow(w, w, u, N);
    check("t^3", hl_pow(P, t, hl_num_si(P, 3)), w);
    /* DIV of two series: (1+2t)/(1+t) */
    fmpq_poly_scalar_mul_si(v, u, 2);
    fmpq_poly_add_si(v, v, 1);
    fmpq_poly_div_series(w, v, one_u, N);
    check("(1+2t)/(1+t)", hl_div(P, hl_add(P, one, hl_mul(P, two, t)), opt), w);
    /* MUL of two series: exp(t) sin(t) */
    fmpq_poly_exp_series(v, u, N);
    fmpq_poly_sin_series(w, u, N);
    fmpq_poly_mullow(w, w, v, N);
    check("exp(t)*sin(t)", hl_mul(P, hl_call(P, HL_EXP, t), hl_call(P, HL_SIN, t)), w);
    /* the K ops: (3 - t) * (t - 2) / 4 - 5 / (1 + t) */
    {
        fmpq_poly_t a, b;
        fmpq_poly_init(a);
        fmpq_poly_init(b);
        fmpq_poly_neg(a, u);
        fmpq_poly_add_si(a, a, 3);
        fmpq_poly_sub_si(b, u, 2);
        fmpq_poly_mullow(a, a, b, N);
        fmpq_set_si(c, 1, 4);
        fmpq_poly_scalar_mul_fmpq(a, a, c);
        fmpq_poly_inv_series(b, one_u, N);
        fmpq_poly_scalar_mul_si(b, b, 5);
        fmpq_poly_sub(w, a, b);
        const hl_expr *e = hl_sub(P, hl_div(P, hl_mul(P, hl_sub(P, hl_num_si(P, 3), t),
                                                      hl_sub(P, t, two)), hl_num_si(P, 4)),
                                  hl_div(P, hl_num_si(P, 5), opt));
        check("K ops", e, w);
        fmpq_poly_clear(a);
        fmpq_poly_clear(b);
    }
    /* non-constant exponent: (1+t)^(1+t) = exp((1+t) log(1+t)) */
    fmpq_poly_log_series(v, one_u, N);
    fmpq_poly_mullow(v, v, one_u, N);
    fmpq_poly_exp_series(w, v, N);
    check("(1+t)^(1+t)", hl_pow(P, opt, opt), w);
    /* negation and a sum of shared subexpressions: -(sin t) + sin(t)*cos(t) */
    fmpq_poly_sin_series(v, u, N);
    fmpq_poly_cos_series(w, u, N);
    fmpq_poly_mullow(w, w, v, N);
    fmpq_poly_sub(w, w, v);
    check("-sin+sin*cos", hl_add(P, hl_neg(P, hl_call(P, HL_SIN, t)),
                                 hl_mul(P, hl_call(P, HL_SIN, t), hl_call(P, HL_COS, t))), w);

    /* the K ops with an irrational constant (rationals fold into scales):
     * (pi - t)(t - pi)/pi - pi/(1+t) + pi t (t + pi) */
    {
        const slong prec = 300;
        const hl_expr *pi = hl_pi(P);
        const hl_expr *e = hl_add(P, hl_sub(P, hl_div(P, hl_mul(P, hl_sub(P, pi, t), hl_sub(P, t, pi)), pi),
                                             hl_div(P, pi, opt)),
                                  hl_mul(P, hl_mul(P, pi, t), hl_add(P, t, pi)));
        arb_poly_t U, A, B, D;
        arb_t api;
        arb_poly_init(U);
        arb_poly_init(A);
        arb_poly_init(B);
        arb_poly_init(D);
        arb_init(api);
        arb_const_pi(api, prec);
        arb_poly_set_fmpq_poly(U, u, prec);
        arb_poly_neg(A, U);
        arb_poly_set_coeff_arb(B, 0, api);
        arb_poly_add(A, A, B, prec);               /* pi - u */
        arb_poly_sub(B, U, B, prec);               /* u - pi */
        arb_poly_mullow(A, A, B, N, prec);
        arb_poly_scalar_div(A, A, api, prec);      /* (pi-u)(u-pi)/pi */
        arb_poly_add_si(D, U, 1, prec);
        arb_poly_inv_series(D, D, N, prec);
        arb_poly_scalar_mul(D, D, api, prec);      /* pi/(1+u) */
        arb_poly_sub(A, A, D, prec);
        arb_poly_zero(B);
        arb_poly_set_coeff_arb(B, 0, api);
        arb_poly_add(B, U, B, prec);               /* u + pi */
        arb_poly_mullow(B, B, U, N, prec);
        arb_poly_scalar_mul(B, B, api, prec);      /* pi u (u + pi) */
        arb_poly_add(A, A, B, prec);
        check_arb("K ops with pi", e, A);
        arb_poly_clear(U);
        arb_poly_clear(A);
        arb_poly_clear(B);
        arb_poly_clear(D);
        arb_clear(api);
    }

    fmpq_clear(c);
    fmpq_poly_clear(w);
    fmpq_poly_clear(v);
    fmpq_poly_clear(u);
    fmpq_poly_clear(one_u);
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
