/* The Taylor recurrences of every function against the exact Taylor
 * coefficients f^(k)(u)/k! obtained by repeated hl_alg_diff:
 *   - on the series u + D directly;
 *   - on w = u + D + x D^2 - p D^3 through the composition
 *     f(w) = sum_k f^(k)(u)/k! (w - u)^k computed with products only;
 * and the same through hl_series_eval_expr on written expressions (powers with
 * rational and symbolic exponents, shared subterms, unknown symbols). */
#include "sr.h"

#define N 8

static const hl_fun funs[] = {HL_SIN,  HL_COS,  HL_TAN,  HL_EXP,  HL_LOG,  HL_SQRT,
                              HL_ATAN, HL_ASIN, HL_ACOS, HL_SINH, HL_COSH, HL_TANH};

/* t[k] = f^(k)(u)/k! for k < N, u = base symbol 0 */
static int taylor_coeffs(hl_series *t, hl_fun f)
{
    hl_alg u;
    hl_error err;
    hl_alg_init(&u, ctx);
    hl_alg_gen(&u, 0, ctx);
    hl_series_zero(t, N, ctx);
    int st = hl_alg_apply(&t->c[0], f, &u, ctx, &err);
    for (int k = 1; st == HL_OK && k < N; k++) {
        st = hl_alg_diff(&t->c[k], &t->c[k - 1], 0, ctx, &err);
        fmpq_t c;
        fmpq_init(c);
        fmpq_set_si(c, 1, (unsigned long)k);
        hl_alg_scalar_mul_fmpq(&t->c[k], &t->c[k], c, ctx);
        fmpq_clear(c);
    }
    if (st != HL_OK)
        fprintf(stderr, "%s: %s\n", hl_fun_name(f), err.msg);
    hl_alg_clear(&u, ctx);
    return st;
}

static void one_fun(hl_fun f)
{
    hl_series t, a, r, w, d, dk, sum, term;
    hl_error err;
    hl_series_init(&t, 0, ctx);
    hl_series_init(&a, 0, ctx);
    hl_series_init(&r, 0, ctx);
    hl_series_init(&w, 0, ctx);
    hl_series_init(&d, 0, ctx);
    hl_series_init(&dk, 0, ctx);
    hl_series_init(&sum, 0, ctx);
    hl_series_init(&term, 0, ctx);
    CHECK_MSG(taylor_coeffs(&t, f) == HL_OK, "%s", hl_fun_name(f));

    rds(&a, N, "u", "1", NULL);
    int st = hl_series_apply(&r, f, &a, ctx, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", hl_fun_name(f), st ? err.msg : "");
    CHECK_MSG(r.n == N, "%s", hl_fun_name(f));
    CHECK_SERIES(&r, &t, N);

    /* composite argument */
    rds(&w, N, "u", "1", "x", "-p", NULL);
    rds(&d, N, "0", "1", "x", "-p", NULL);
    rds(&dk, N, "1", NULL);
    hl_series_zero(&sum, N, ctx);
    for (int k = 0; k < N; k++) {
        hl_series_scalar_mul(&term, &dk, &t.c[k], ctx);
        hl_series_add(&sum, &sum, &term, ctx);
        hl_series_mul(&dk, &dk, &d, ctx);
    }
    st = hl_series_apply(&r, f, &w, ctx, &err);
    CHECK_MSG(st == HL_OK, "%s composite", hl_fun_name(f));
    CHECK_SERIES(&r, &sum, N);

    hl_series_clear(&t, ctx);
    hl_series_clear(&a, ctx);
    hl_series_clear(&r, ctx);
    hl_series_clear(&w, ctx);
    hl_series_clear(&d, ctx);
    hl_series_clear(&dk, ctx);
    hl_series_clear(&sum, ctx);
    hl_series_clear(&term, ctx);
}

/* rational powers: u^(1/3), u^(-3/2), u^7, u^(-2) on u + D against
 * binomial(e, k) u^(e-k) */
static void powers(void)
{
    const long num[] = {1, -3, 7, -2, 5};
    const unsigned long den[] = {3, 2, 1, 1, 2};
    hl_series a, r;
    hl_error err;
    hl_series_init(&a, 0, ctx);
    hl_series_init(&r, 0, ctx);
    rds(&a, N, "u", "1", NULL);
    for (int i = 0; i < 5; i++) {
        fmpq_t e, b, t;
        fmpq_init(e);
        fmpq_init(b);
        fmpq_init(t);
        fmpq_set_si(e, num[i], den[i]);
        int st = hl_series_pow_fmpq(&r, &a, e, ctx, &err);
        CHECK_MSG(st == HL_OK, "%ld/%lu", num[i], den[i]);
        fmpq_one(b); /* binomial(e, k) */
        for (int k = 0; st == HL_OK && k < N; k++) {
            hl_alg want, base;
            hl_alg_init(&want, ctx);
            hl_alg_init(&base, ctx);
            rd(&base, "u");
            fmpq_sub_si(t, e, k); /* u^(e - k) */
            CHECK(hl_alg_pow_fmpq(&want, &base, t, ctx, &err) == HL_OK);
            hl_alg_scalar_mul_fmpq(&want, &want, b, ctx);
            CHECK_MSG(hl_alg_equal(&r.c[k], &want, ctx), "u^(%ld/%lu) at D^%d", num[i], den[i], k);
            fmpq_mul(b, b, t); /* binomial(e, k+1) = binomial(e, k) (e - k)/(k + 1) */
            fmpq_set_si(t, 1, (ulong)(k + 1));
            fmpq_mul(b, b, t);
            hl_alg_clear(&want, ctx);
            hl_alg_clear(&base, ctx);
        }
        fmpq_clear(e);
        fmpq_clear(b);
        fmpq_clear(t);
    }
    /* a non-integer power of a series vanishing at 0 */
    rds(&a, N, "0", "1", NULL);
    fmpq_t h;
    fmpq_init(h);
    fmpq_set_si(h, 1, 2);
    CHECK(hl_series_pow_fmpq(&r, &a, h, ctx, &err) == HL_EDOM);
    fmpq_clear(h);
    hl_series_clear(&a, ctx);
    hl_series_clear(&r, ctx);
}

/* Taylor mode on written expressions against the exact expansion of the
 * same expression read as an element with D a base symbol and expanded by
 * hl_series_from_alg where that is rational, or by hand. */
static void expressions(void)
{
    const char *names[] = {"u", "x", "p", "D"};
    hl_series vals[4], r, s;
    hl_alg a;
    hl_error err;
    for (int i = 0; i < 4; i++) {
        hl_series_init(&vals[i], 0, ctx);
        hl_alg_init(&a, ctx);
        hl_alg_gen(&a, i, ctx);
        if (i == 3)
            rds(&vals[i], N, "0", "1", NULL);
        else
            hl_series_set_alg(&vals[i], &a, N, ctx);
        hl_alg_clear(&a, ctx);
    }
    hl_series_init(&r, 0, ctx);
    hl_series_init(&s, 0, ctx);
    hl_alg_init(&a, ctx);

    /* a rational expression with shared subterms */
    const char *src = "(x + D*p)^3/(1 - u*D)^2 - (x + D*p)*(1 + D^2)/(x + p*D^3)";
    const hl_expr *e;
    CHECK(hl_parse(&e, pool, src, &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_OK);
    rd(&a, src);
    CHECK(hl_series_from_alg(&s, &a, 3, N, ctx, &err) == HL_OK);
    CHECK_SERIES(&r, &s, N);

    /* exp(D)^x = exp(x D): coefficients x^k/k! (symbolic exponent path) */
    CHECK(hl_parse(&e, pool, "exp(D)^x", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_OK);
    CHECK_COEF(&r, 0, "1");
    CHECK_COEF(&r, 3, "x^3/6");
    CHECK_COEF(&r, 5, "x^5/120");

    /* sqrt(1 + D)^2 = 1 + D and (u + D)^(1/2) * (u + D)^(-1/2) = 1 */
    CHECK(hl_parse(&e, pool, "sqrt(1 + D)^2 + (u + D)^(1/2) * (u + D)^(-1/2)", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_OK);
    CHECK_COEF(&r, 0, "2");
    CHECK_COEF(&r, 1, "1");
    for (int k = 2; k < N; k++)
        CHECK_COEF(&r, k, "0");

    /* pi and atan: tan(atan(D) + pi) = D */
    CHECK(hl_parse(&e, pool, "tan(atan(D) + pi)", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_OK);
    CHECK_SERIES(&r, &vals[3], N);

    /* constant subterms are folded exactly: sin(pi/6) = 1/2, sqrt(8)/sqrt(2) = 2 */
    CHECK(hl_parse(&e, pool, "sin(pi/6)*x + sqrt(8)/sqrt(2)*D", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_OK);
    CHECK_COEF(&r, 0, "x/2");
    CHECK_COEF(&r, 1, "2");
    /* integer powers need no constant term: (D + x D^2)^3 */
    CHECK(hl_parse(&e, pool, "(D + x*D^2)^3", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_OK);
    const char *cube[] = {"0", "0", "0", "1", "3*x", "3*x^2", "x^3", "0"};
    for (int k = 0; k < N; k++)
        CHECK_COEF(&r, k, cube[k]);
    CHECK(hl_parse(&e, pool, "(D + x*D^2)^(-1)", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_EDOM);
    /* an irrational constant exponent: (u + D)^pi = u^pi (1 + pi D/u + ...) */
    CHECK(hl_parse(&e, pool, "(u + D)^pi", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, 3, ctx, &err) == HL_OK);
    {
        hl_alg w, b;
        hl_alg_init(&w, ctx);
        hl_alg_init(&b, ctx);
        rd(&b, "pi");
        rd(&a, "u");
        CHECK(hl_alg_pow(&w, &a, &b, ctx, &err) == HL_OK);
        CHECK(hl_alg_equal(&r.c[0], &w, ctx));
        hl_alg_mul(&w, &w, &b, ctx);
        CHECK(hl_alg_div(&w, &w, &a, ctx, &err) == HL_OK);
        CHECK(hl_alg_equal(&r.c[1], &w, ctx));
        hl_alg_clear(&w, ctx);
        hl_alg_clear(&b, ctx);
    }
    /* a long left-leaning sum (5000 deep) does not recurse */
    {
        const hl_expr *sum = hl_sym(pool, "D");
        for (int i = 1; i < 5000; i++)
            sum = hl_add(pool, sum, hl_mul(pool, hl_num_si(pool, i % 3), hl_sym(pool, "D")));
        CHECK(hl_series_eval_expr(&r, sum, 4, names, vals, 3, ctx, &err) == HL_OK);
        CHECK_COEF(&r, 1, "5000"); /* 1 + sum_{i<5000} (i mod 3) = 1 + 1666*3 + 1 */
        CHECK_COEF(&r, 2, "0");
    }

    /* a symbol with no value is named */
    CHECK(hl_parse(&e, pool, "x + sin(zz)", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "'zz'") != NULL);
    /* a value with too few coefficients */
    CHECK(hl_parse(&e, pool, "x", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N + 1, ctx, &err) == HL_EINVAL);
    /* division by D */
    CHECK(hl_parse(&e, pool, "(x + D)/D", &err) == HL_OK);
    CHECK(hl_series_eval_expr(&r, e, 4, names, vals, N, ctx, &err) == HL_EDOM);

    for (int i = 0; i < 4; i++)
        hl_series_clear(&vals[i], ctx);
    hl_series_clear(&r, ctx);
    hl_series_clear(&s, ctx);
    hl_alg_clear(&a, ctx);
}

int main(void)
{
    const char *names[] = {"u", "x", "p", "D"};
    setup(4, names);
    for (size_t i = 0; i < sizeof funs / sizeof funs[0]; i++)
        one_fun(funs[i]);
    powers();
    expressions();
    teardown();
    flint_cleanup();
    return HL_TEST_END();
}
