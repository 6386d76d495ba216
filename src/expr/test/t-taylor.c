/* Taylor coefficients as expressions (hl_expr_taylor): the published
 * Maclaurin series of every function at s = 0; at an interior point, the
 * coefficients against repeated hl_expr_diff (k-th derivative / k!) for the
 * formulas of t-diff; a polynomial's stop at its degree (the node 0, not a
 * small number); the chain that sin(q + s h) gives, to order 15. */
#include <math.h>
#include <stdlib.h>

#include <string.h>

#include "hamlie/expr.h"
#include "hl_test.h"

#define K 8

/* Maclaurin coefficients in s, k = 0..7 (Abramowitz-Stegun 4.1-4.6). */
static const struct {
    const char *e;
    double c[K];
} maclaurin[] = {
    {"exp(s)", {1, 1, 1. / 2, 1. / 6, 1. / 24, 1. / 120, 1. / 720, 1. / 5040}},
    {"sin(s)", {0, 1, 0, -1. / 6, 0, 1. / 120, 0, -1. / 5040}},
    {"cos(s)", {1, 0, -1. / 2, 0, 1. / 24, 0, -1. / 720, 0}},
    {"sinh(s)", {0, 1, 0, 1. / 6, 0, 1. / 120, 0, 1. / 5040}},
    {"cosh(s)", {1, 0, 1. / 2, 0, 1. / 24, 0, 1. / 720, 0}},
    {"tan(s)", {0, 1, 0, 1. / 3, 0, 2. / 15, 0, 17. / 315}},
    {"tanh(s)", {0, 1, 0, -1. / 3, 0, 2. / 15, 0, -17. / 315}},
    {"atan(s)", {0, 1, 0, -1. / 3, 0, 1. / 5, 0, -1. / 7}},
    {"asin(s)", {0, 1, 0, 1. / 6, 0, 3. / 40, 0, 5. / 112}},
    {"acos(s)", {M_PI / 2, -1, 0, -1. / 6, 0, -3. / 40, 0, -5. / 112}},
    {"log(1 + s)", {0, 1, -1. / 2, 1. / 3, -1. / 4, 1. / 5, -1. / 6, 1. / 7}},
    {"sqrt(1 + s)", {1, 1. / 2, -1. / 8, 1. / 16, -5. / 128, 7. / 256, -21. / 1024, 33. / 2048}},
    {"(1 + s)^(-1/2)",
     {1, -1. / 2, 3. / 8, -5. / 16, 35. / 128, -63. / 256, 231. / 1024, -429. / 2048}},
    {"1/(1 - s)", {1, 1, 1, 1, 1, 1, 1, 1}},
    {"(1 - s)^(-3)", {1, 3, 6, 10, 15, 21, 28, 36}},
    {"2^s",
     {1, M_LN2, M_LN2 *M_LN2 / 2, M_LN2 *M_LN2 *M_LN2 / 6, M_LN2 *M_LN2 *M_LN2 *M_LN2 / 24,
      M_LN2 *M_LN2 *M_LN2 *M_LN2 *M_LN2 / 120, M_LN2 *M_LN2 *M_LN2 *M_LN2 *M_LN2 *M_LN2 / 720,
      M_LN2 *M_LN2 *M_LN2 *M_LN2 *M_LN2 *M_LN2 *M_LN2 / 5040}},
    {"(1 + s)^s", {1, 0, 1, -1. / 2, 5. / 6, -3. / 4, 33. / 40, -5. / 6}},
};

static double eval1(const hl_expr *e, const char *var, double v)
{
    const char *names[] = {var};
    double r = NAN;
    hl_expr_eval_d(&r, e, 1, names, &v, NULL);
    return r;
}

static void check_maclaurin(void)
{
    hl_pool *pool = hl_pool_new();
    const hl_expr *zero = hl_num_si(pool, 0), *c[K];
    for (size_t i = 0; i < sizeof maclaurin / sizeof *maclaurin; i++) {
        const hl_expr *e;
        CHECK(hl_parse(&e, pool, maclaurin[i].e, NULL) == HL_OK);
        hl_expr_taylor(c, pool, e, "s", zero, K - 1);
        for (int k = 0; k < K; k++) {
            double got = eval1(c[k], "s", NAN), want = maclaurin[i].c[k];
            CHECK_MSG(fabs(got - want) <= 1e-15 * (1 + fabs(want)), "[s^%d] %s: %.17g, want %.17g",
                      k, maclaurin[i].e, got, want);
        }
    }
    hl_pool_free(pool);
}

/* Formulas of t-diff, valid for x, y in (0.1, 0.9). */
static const char *const formulas[] = {
    "x^3*y - 2*x*y^2 + 7",
    "(px^2 + py^2)/2 - 1/sqrt(x^2 + y^2)",
    "sin(x)*cos(y*x)",
    "tan(x)",
    "exp(-x^2/2)",
    "log(1 + x*y)",
    "sqrt(x + y)",
    "atan(x/y)",
    "asin(x*y)",
    "acos(x - y/2)",
    "sinh(x)",
    "cosh(2*x)",
    "tanh(x*y)",
    "x^y",
    "y^x",
    "x^x",
    "(x + 1)^(-3/2)",
    "-x^2",
    "x/(1 + x^2)",
    "1/x/y",
    "pi*x^2",
    "2^x",
    "x^-2",
    "--x*sin(x)",
    "log(x)^2",
    "exp(sin(x))^2 + x^(1/3)",
    "(x^2 - y)/(x + y)^2",
    "atan(x)^x",
    "sqrt(1 - x^2)*x",
    "cos(x)^2 + sin(x)^2",
    "(x*y - 1)^5",
    "x^-7*y",
};

/* At x = x0 + t: [t^k] = (d/dx)^k e / k! at x0, for k <= 5. */
static void check_against_diff(void)
{
    hl_pool *pool = hl_pool_new();
    const char *names[] = {"x", "y", "px", "py", "x0"};
    const double v[] = {NAN, 0.37, 0.8, -0.3, 0.61};
    const hl_expr *x0 = hl_sym(pool, "x0"), *c[6];
    for (size_t i = 0; i < sizeof formulas / sizeof *formulas; i++) {
        const hl_expr *e, *d;
        CHECK(hl_parse(&e, pool, formulas[i], NULL) == HL_OK);
        hl_expr_taylor(c, pool, e, "x", x0, 5);
        d = e;
        double fact = 1;
        for (int k = 0; k <= 5; k++) {
            if (k > 0)
                d = hl_expr_diff(pool, d, "x"), fact *= k;
            double xv[5];
            memcpy(xv, v, sizeof xv);
            xv[0] = v[4];
            double got = NAN, want = NAN;
            CHECK(hl_expr_eval_d(&got, c[k], 5, names, v, NULL) == HL_OK);
            CHECK(hl_expr_eval_d(&want, d, 5, names, xv, NULL) == HL_OK);
            want /= fact;
            CHECK_MSG(isfinite(want) && fabs(got - want) <= 1e-12 * (1 + fabs(want)),
                      "[t^%d] %s: %.17g, want %.17g", k, formulas[i], got, want);
        }
    }
    hl_pool_free(pool);
}

/* A polynomial's coefficients beyond its degree are the node 0; a node
 * free of the variable is kept as it is. */
static void check_structure(void)
{
    hl_pool *pool = hl_pool_new();
    const hl_expr *e, *c[16], *zero = hl_num_si(pool, 0), *half = hl_num_frac(pool, 1, 2);
    CHECK(hl_parse(&e, pool, "(x + s*(X - x))^3*y - 2*(x + s*(X - x))*y^2 + 7", NULL) == HL_OK);
    hl_expr_taylor(c, pool, e, "s", half, 15);
    CHECK(c[3] != zero);
    for (int k = 4; k <= 15; k++)
        CHECK_MSG(c[k] == zero, "[s^%d] of a cubic is not the node 0", k);
    CHECK(hl_parse(&e, pool, "sin(y)*exp(y)", NULL) == HL_OK);
    hl_expr_taylor(c, pool, e, "s", half, 3);
    CHECK(c[0] == e && c[1] == zero && c[3] == zero);
    hl_pool_free(pool);
}

/* sin(q + s h) at s = 1/2: [s^k] = h^k sin^(k)(m) / k!, m = q + h/2, to
 * order 15 (what the average vector field of the pendulum integrates). */
static void check_sin_chain(void)
{
    hl_pool *pool = hl_pool_new();
    const hl_expr *e, *c[16];
    CHECK(hl_parse(&e, pool, "sin(q + s*(Q - q))", NULL) == HL_OK);
    hl_expr_taylor(c, pool, e, "s", hl_num_frac(pool, 1, 2), 15);
    const char *names[] = {"q", "Q"};
    const double v[] = {1.3, 0.7};
    double h = v[1] - v[0], m = v[0] + h / 2, hk = 1;
    for (int k = 0; k <= 15; k++) {
        if (k > 0)
            hk *= h / k;
        double d = (k % 4 == 0) ? sin(m) : (k % 4 == 1) ? cos(m) : (k % 4 == 2) ? -sin(m) : -cos(m);
        double got = NAN, want = hk * d;
        CHECK(hl_expr_eval_d(&got, c[k], 2, names, v, NULL) == HL_OK);
        CHECK_MSG(fabs(got - want) <= 1e-15 * fabs(want) + 1e-300, "[s^%d]: %.17g, want %.17g", k,
                  got, want);
    }
    hl_pool_free(pool);
}

int main(void)
{
    check_maclaurin();
    check_against_diff();
    check_structure();
    check_sin_chain();
    return HL_TEST_END();
}
