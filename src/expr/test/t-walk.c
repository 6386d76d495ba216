/* Walks: symbols in order of first appearance, has_symbol, simultaneous
 * substitution, evaluation and its errors; on DAGs whose trees are
 * exponentially large, which only a memoised walk gets through. */
#include <math.h>
#include <stdlib.h>

#include "hl_test.h"
#include "sx.h"

static const hl_expr *parse(hl_pool *pool, const char *s)
{
    const hl_expr *e = NULL;
    hl_error err;
    if (hl_parse(&e, pool, s, &err) != HL_OK)
        fprintf(stderr, "parse %s: %s\n", s, err.msg);
    return e;
}

/* e_{k+1} = e_k*e_k + y: 2^k leaves in the tree, 3k nodes in the DAG */
static const hl_expr *tower(hl_pool *pool, const hl_expr *base, const hl_expr *y, int k)
{
    const hl_expr *e = base;
    for (int i = 0; i < k; i++)
        e = hl_add(pool, hl_mul(pool, e, e), y);
    return e;
}

static void check_symbols(hl_pool *pool)
{
    const char *names[8];
    const hl_expr *e = parse(pool, "b*sin(a + b) + c^a - pi + b");
    int n = hl_expr_symbols(e, names, 8);
    CHECK(n == 3);
    CHECK_STR(names[0], "b");
    CHECK_STR(names[1], "a");
    CHECK_STR(names[2], "c");
    CHECK(hl_expr_symbols(e, names, 1) == 3 && strcmp(names[0], "b") == 0);
    CHECK(hl_expr_symbols(e, NULL, 0) == 3);
    CHECK(hl_expr_symbols(parse(pool, "2*pi"), names, 8) == 0);
    CHECK(hl_expr_has_symbol(e, "c"));
    CHECK(!hl_expr_has_symbol(e, "pi"));
    CHECK(!hl_expr_has_symbol(e, "d"));
    const hl_expr *t = tower(pool, hl_sym(pool, "x"), hl_sym(pool, "y"), 200);
    CHECK(hl_expr_symbols(t, names, 8) == 2 && !strcmp(names[0], "x") && !strcmp(names[1], "y"));
    CHECK(!hl_expr_has_symbol(t, "z") && hl_expr_has_symbol(t, "y"));
}

static void check_subst(hl_pool *pool)
{
    const char *names[] = {"x", "y"};
    const hl_expr *vals[] = {parse(pool, "y"), parse(pool, "x + 1")};
    /* simultaneous: x -> y and y -> x + 1, not y -> x + 1 -> ... */
    CHECK(hl_expr_subst(pool, parse(pool, "x*y - sin(x)"), 2, names, vals) ==
          parse(pool, "y*(x + 1) - sin(y)"));
    /* untouched expressions come back as the same pointer */
    const hl_expr *e = parse(pool, "a + b^2");
    CHECK(hl_expr_subst(pool, e, 2, names, vals) == e);
    CHECK(hl_expr_subst(pool, e, 0, NULL, NULL) == e);
    /* the 2^300-leaf tower in x becomes the tower in z */
    const hl_expr *z[] = {hl_sym(pool, "z")};
    const hl_expr *t = tower(pool, hl_sym(pool, "x"), hl_sym(pool, "y"), 300);
    CHECK(hl_expr_subst(pool, t, 1, names, z) ==
          tower(pool, hl_sym(pool, "z"), hl_sym(pool, "y"), 300));
}

static void check_eval(hl_pool *pool)
{
    const char *names[] = {"x", "y"};
    double v[] = {0.5, -2}, r;
    hl_error err;
    CHECK(hl_expr_eval_d(&r, parse(pool, "x^2 + 3*y - 1/4"), 2, names, v, &err) == HL_OK);
    CHECK(r == 0.25 - 6 - 0.25);
    CHECK(hl_expr_eval_d(&r, parse(pool, "sin(pi/6)"), 0, NULL, NULL, &err) == HL_OK);
    CHECK(fabs(r - 0.5) < 1e-15);
    CHECK(hl_expr_eval_d(&r, parse(pool, "2/3"), 0, NULL, NULL, NULL) == HL_OK);
    CHECK(r == 2.0 / 3.0);
    CHECK(hl_expr_eval_d(&r, parse(pool, "x*z"), 2, names, v, &err) == HL_EINVAL);
    CHECK_STR(err.msg, "symbol 'z' has no value");
    CHECK(hl_expr_eval_d(&r, parse(pool, "x*z"), 2, names, v, NULL) == HL_EINVAL);
    CHECK(hl_expr_eval_d(&r, parse(pool, "1/(x - x)"), 2, names, v, &err) == HL_OK && isinf(r));
    CHECK(hl_expr_eval_d(&r, parse(pool, "log(y)"), 2, names, v, &err) == HL_OK && isnan(r));
    const struct { const char *s; double want; } fns[] = {
        {"exp(1)", exp(1)}, {"log(2)", log(2)}, {"sqrt(2)", sqrt(2)}, {"tan(1)", tan(1)},
        {"cos(1)", cos(1)}, {"atan(1)", atan(1)}, {"asin(1/2)", asin(0.5)},
        {"acos(1/2)", acos(0.5)}, {"sinh(1)", sinh(1)}, {"cosh(1)", cosh(1)},
        {"tanh(1)", tanh(1)}, {"-2^2", -4}, {"2^-2", 0.25}, {"(-8)^(1/3)", NAN},
    };
    for (size_t i = 0; i < sizeof fns / sizeof *fns; i++) {
        CHECK(hl_expr_eval_d(&r, parse(pool, fns[i].s), 0, NULL, NULL, NULL) == HL_OK);
        CHECK_MSG(r == fns[i].want || (isnan(r) && isnan(fns[i].want)), "%s = %.17g", fns[i].s, r);
    }
    /* the tower at x = 0.5, y = -0.5 has a fixed point -> iterate by hand */
    const hl_expr *t = tower(pool, hl_sym(pool, "x"), hl_sym(pool, "y"), 400);
    double w[] = {0.5, -0.5}, want = 0.5;
    for (int i = 0; i < 400; i++)
        want = want * want - 0.5;
    CHECK(hl_expr_eval_d(&r, t, 2, names, w, &err) == HL_OK && r == want);
}

/* A decimal literal evaluates to the double nearest to it, as strtod reads
 * it: rounding once, not dividing two rounded integers. */
static void check_literals_round_once(hl_pool *pool)
{
    static const char *const lits[] = {"1.3", "0.1", "0.7", "2.675", "1e-7", "123456.789",
                                       "0.3333333333333333333", "1.7320508075688772"};
    hl_error err;
    for (size_t i = 0; i < sizeof lits / sizeof *lits; i++) {
        const hl_expr *e = NULL;
        double r = 0;
        CHECK(hl_parse(&e, pool, lits[i], &err) == HL_OK);
        CHECK(hl_expr_eval_d(&r, e, 0, NULL, NULL, &err) == HL_OK);
        CHECK_MSG(r == strtod(lits[i], NULL), "%s evaluates to %.17g", lits[i], r);
    }
}

int main(void)
{
    hl_pool *pool = hl_pool_new();
    check_symbols(pool);
    check_subst(pool);
    check_eval(pool);
    check_literals_round_once(pool);
    hl_pool_free(pool);
    return HL_TEST_END();
}
