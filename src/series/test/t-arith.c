/* Series arithmetic: geometric series, exp o log = id, sin^2 + cos^2 = 1,
 * division against multiplication, conversion to and from elements (hand
 * expansions of rational functions and of sin D), derivative / reflect /
 * shift, aliasing, and the domain errors. */
#include "sr.h"

#define N 12

static void geometric(void)
{
    hl_series one, a, r, s;
    hl_error err;
    hl_series_init(&one, 0, ctx);
    hl_series_init(&a, 0, ctx);
    hl_series_init(&r, 0, ctx);
    hl_series_init(&s, 0, ctx);
    rds(&one, N, "1", NULL);
    rds(&a, N, "1", "-1", NULL);
    /* 1/(1 - D) = sum D^k */
    CHECK(hl_series_div(&r, &one, &a, ctx, &err) == HL_OK);
    CHECK(r.n == N);
    for (int k = 0; k < N; k++)
        CHECK_COEF(&r, k, "1");
    /* (1 - D)^-2 = sum (k+1) D^k */
    CHECK(hl_series_pow_si(&s, &a, -2, ctx, &err) == HL_OK);
    for (int k = 0; k < N; k++) {
        char buf[16];
        snprintf(buf, sizeof buf, "%d", k + 1);
        CHECK_COEF(&s, k, buf);
    }
    /* (1 - D)^5 by the binomial theorem: 1 -5 10 -10 5 -1 0 ... */
    CHECK(hl_series_pow_si(&s, &a, 5, ctx, &err) == HL_OK);
    const char *binom[] = {"1", "-5", "10", "-10", "5", "-1", "0", "0"};
    for (int k = 0; k < 8; k++)
        CHECK_COEF(&s, k, binom[k]);
    /* the same 1/(1 - x D)^1 with a symbolic ratio: coefficients x^k */
    rds(&a, N, "1", "-x", NULL);
    CHECK(hl_series_div(&r, &one, &a, ctx, &err) == HL_OK);
    CHECK_COEF(&r, 7, "x^7");
    /* pow_si(0) = 1, pow_si(1) = a */
    CHECK(hl_series_pow_si(&s, &a, 0, ctx, &err) == HL_OK);
    CHECK_SERIES(&s, &one, N);
    CHECK(hl_series_pow_si(&s, &a, 1, ctx, &err) == HL_OK);
    CHECK_SERIES(&s, &a, N);
    hl_series_clear(&one, ctx);
    hl_series_clear(&a, ctx);
    hl_series_clear(&r, ctx);
    hl_series_clear(&s, ctx);
}

static void exp_log(void)
{
    hl_series a, l, e;
    hl_error err;
    hl_series_init(&a, 0, ctx);
    hl_series_init(&l, 0, ctx);
    hl_series_init(&e, 0, ctx);
    rds(&a, 8, "1", "u", "x", "p*u", "1/(1+x^2)", NULL);
    CHECK(hl_series_apply(&l, HL_LOG, &a, ctx, &err) == HL_OK);
    CHECK_COEF(&l, 0, "0");
    CHECK_COEF(&l, 1, "u");
    CHECK_COEF(&l, 2, "x - u^2/2"); /* log(1+t) = t - t^2/2 + ..., t = uD + xD^2 + ... */
    CHECK(hl_series_apply(&e, HL_EXP, &l, ctx, &err) == HL_OK);
    CHECK_SERIES(&e, &a, 8);
    /* log o exp = id on a series with zero constant term */
    rds(&a, 8, "0", "u", "x", "p", NULL);
    CHECK(hl_series_apply(&e, HL_EXP, &a, ctx, &err) == HL_OK);
    CHECK_COEF(&e, 2, "x + u^2/2");
    CHECK(hl_series_apply(&l, HL_LOG, &e, ctx, &err) == HL_OK);
    CHECK_SERIES(&l, &a, 8);
    hl_series_clear(&a, ctx);
    hl_series_clear(&l, ctx);
    hl_series_clear(&e, ctx);
}

static void pythagoras(void)
{
    hl_series a, s, c, one;
    hl_error err;
    hl_series_init(&a, 0, ctx);
    hl_series_init(&s, 0, ctx);
    hl_series_init(&c, 0, ctx);
    hl_series_init(&one, 0, ctx);
    rds(&a, 9, "x", "p", "u", "x*p", NULL);
    CHECK(hl_series_apply(&s, HL_SIN, &a, ctx, &err) == HL_OK);
    CHECK(hl_series_apply(&c, HL_COS, &a, ctx, &err) == HL_OK);
    CHECK_COEF(&s, 1, "p*cos(x)");
    CHECK_COEF(&c, 1, "-p*sin(x)");
    hl_series_mul(&s, &s, &s, ctx); /* aliasing */
    hl_series_mul(&c, &c, &c, ctx);
    hl_series_add(&s, &s, &c, ctx);
    rds(&one, 9, "1", NULL);
    CHECK_SERIES(&s, &one, 9);
    /* cosh^2 - sinh^2 = 1 */
    CHECK(hl_series_apply(&s, HL_SINH, &a, ctx, &err) == HL_OK);
    CHECK(hl_series_apply(&c, HL_COSH, &a, ctx, &err) == HL_OK);
    hl_series_mul(&s, &s, &s, ctx);
    hl_series_mul(&c, &c, &c, ctx);
    hl_series_sub(&c, &c, &s, ctx);
    CHECK_SERIES(&c, &one, 9);
    hl_series_clear(&a, ctx);
    hl_series_clear(&s, ctx);
    hl_series_clear(&c, ctx);
    hl_series_clear(&one, ctx);
}

static void div_mul(void)
{
    hl_series a, b, q, r;
    hl_error err;
    hl_series_init(&a, 0, ctx);
    hl_series_init(&b, 0, ctx);
    hl_series_init(&q, 0, ctx);
    hl_series_init(&r, 0, ctx);
    rds(&a, 7, "p", "x", "1", "u", "0", "x^2", NULL);
    rds(&b, 7, "x + 1", "p", "u", "0", "1/x", NULL);
    CHECK(hl_series_div(&q, &a, &b, ctx, &err) == HL_OK);
    CHECK_COEF(&q, 0, "p/(x+1)");
    CHECK_COEF(&q, 1, "x/(x+1) - p^2/(x+1)^2"); /* (a1 b0 - a0 b1)/b0^2 */
    hl_series_mul(&r, &q, &b, ctx);
    CHECK_SERIES(&r, &a, 7);
    /* mul is commutative; a/b computed in place */
    hl_series_mul(&r, &b, &q, ctx);
    CHECK_SERIES(&r, &a, 7);
    CHECK(hl_series_div(&a, &a, &b, ctx, &err) == HL_OK);
    CHECK_SERIES(&a, &q, 7);
    /* precision: the result has the smaller length */
    hl_series_set_length(&b, 4, ctx);
    hl_series_mul(&r, &q, &b, ctx);
    CHECK(r.n == 4);
    /* division by a series vanishing at D = 0 */
    rds(&b, 7, "0", "1", NULL);
    CHECK(hl_series_div(&r, &a, &b, ctx, &err) == HL_EDOM);
    CHECK(hl_series_pow_si(&r, &b, -1, ctx, &err) == HL_EDOM);
    CHECK(hl_series_apply(&r, HL_LOG, &b, ctx, &err) == HL_EDOM);
    CHECK(hl_series_apply(&r, HL_SQRT, &b, ctx, &err) == HL_EDOM);
    /* but D^3 is fine */
    CHECK(hl_series_pow_si(&r, &b, 3, ctx, &err) == HL_OK);
    CHECK_COEF(&r, 2, "0");
    CHECK_COEF(&r, 3, "1");
    CHECK_COEF(&r, 4, "0");
    hl_series_clear(&a, ctx);
    hl_series_clear(&b, ctx);
    hl_series_clear(&q, ctx);
    hl_series_clear(&r, ctx);
}

static void conversions(int var_D)
{
    hl_series s, t;
    hl_alg a, b;
    hl_error err;
    hl_series_init(&s, 0, ctx);
    hl_series_init(&t, 0, ctx);
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    /* the discrete-gradient map (4x + 4Dp - D^2 x)/(4 + D^2): by hand
     * (x + Dp - D^2 x/4)(1 - D^2/4 + D^4/16 - ...) */
    rd(&a, "(4*x + 4*D*p - D^2*x)/(4 + D^2)");
    CHECK(hl_series_from_alg(&s, &a, var_D, 8, ctx, &err) == HL_OK);
    CHECK(s.n == 8);
    const char *want[] = {"x", "p", "-x/2", "-p/4", "x/8", "p/16", "-x/32", "-p/64"};
    for (int k = 0; k < 8; k++)
        CHECK_COEF(&s, k, want[k]);
    /* a polynomial in D goes there and back */
    rd(&a, "x + D*p - D^3*u/7");
    CHECK(hl_series_from_alg(&s, &a, var_D, 6, ctx, &err) == HL_OK);
    hl_series_to_alg(&b, &s, var_D, ctx);
    CHECK(hl_alg_equal(&a, &b, ctx));
    /* truncation: only D^0, D^1 kept */
    CHECK(hl_series_from_alg(&s, &a, var_D, 2, ctx, &err) == HL_OK);
    hl_series_to_alg(&b, &s, var_D, ctx);
    rd(&a, "x + D*p");
    CHECK(hl_alg_equal(&a, &b, ctx));
    /* atoms in D: sin D = D - D^3/6 + D^5/120 */
    rd(&a, "x*sin(D) + cos(D)");
    CHECK(hl_series_from_alg(&s, &a, var_D, 7, ctx, &err) == HL_OK);
    const char *sc[] = {"1", "x", "-1/2", "-x/6", "1/24", "x/120", "-1/720"};
    for (int k = 0; k < 7; k++)
        CHECK_COEF(&s, k, sc[k]);
    /* a pole */
    rd(&a, "x/(D*(1 + D))");
    CHECK(hl_series_from_alg(&s, &a, var_D, 4, ctx, &err) == HL_EDOM);
    rd(&a, "x/sin(D)");
    CHECK(hl_series_from_alg(&s, &a, var_D, 4, ctx, &err) == HL_EDOM);
    /* removable zeros through atoms: sin(D)/D and (1 - cos D)/D^2 */
    rd(&a, "sin(D)/D + x*(1 - cos(D))/D^2");
    CHECK(hl_series_from_alg(&s, &a, var_D, 6, ctx, &err) == HL_OK);
    CHECK(s.n == 6);
    const char *sinc[] = {"1 + x/2", "0", "-1/6 - x/24", "0", "1/120 + x/720", "0"};
    for (int k = 0; k < 6; k++)
        CHECK_COEF(&s, k, sinc[k]);
    /* derivative, reflect, shift of 1 + 2D + 3D^2 + 4D^3 */
    rds(&s, 4, "1", "2", "3", "4", NULL);
    hl_series_derivative(&t, &s, ctx);
    CHECK(t.n == 3);
    CHECK_COEF(&t, 0, "2");
    CHECK_COEF(&t, 1, "6");
    CHECK_COEF(&t, 2, "12");
    hl_series_reflect(&t, &s, ctx);
    CHECK_COEF(&t, 1, "-2");
    CHECK_COEF(&t, 2, "3");
    CHECK_COEF(&t, 3, "-4");
    hl_series_shift(&t, &s, 2, ctx);
    CHECK(t.n == 6);
    CHECK_COEF(&t, 0, "0");
    CHECK_COEF(&t, 2, "1");
    CHECK_COEF(&t, 5, "4");
    CHECK(hl_series_valuation(&t, ctx) == 2);
    hl_series_clear(&s, ctx);
    hl_series_clear(&t, ctx);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
}

int main(void)
{
    const char *names[] = {"x", "p", "u", "D"};
    setup(4, names);
    geometric();
    exp_log();
    pythagoras();
    div_mul();
    conversions(3);
    teardown();
    flint_cleanup();
    return HL_TEST_END();
}
