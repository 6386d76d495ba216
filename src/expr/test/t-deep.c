/* Deep and large expressions: every walk of the layer (parse, print in each
 * style, fold, differentiation, symbols, substitution, evaluation) gets
 * through chains far deeper than the C stack allows a recursion to go, and
 * the parser's limits (nesting, size) give an error, not a crash.  Truths:
 * n copies of x sum to n*x, d/dx x^n = n x^(n-1) at x = 1 is n, the chain
 * rule d/dx sin(sin(...x)) = prod cos(s_k), and a run of 2k minuses is x. */
#include <math.h>
#include <stdlib.h>

#include "base/buf.h"
#include "hamlie/expr.h"
#include "hl_test.h"

#define SUM_TERMS 100000
#define CHAIN 10000

static const hl_expr *parse(hl_pool *pool, const char *s, hl_error *err)
{
    const hl_expr *e = NULL;
    if (hl_parse(&e, pool, s, err) != HL_OK)
        return NULL;
    return e;
}

static double eval_at(const hl_expr *e, double x)
{
    const char *names[] = {"x", "y"};
    double vals[] = {x, 2}, r = NAN;
    hl_error err;
    if (hl_expr_eval_d(&r, e, 2, names, vals, &err) != HL_OK)
        return NAN;
    return r;
}

/* "x + 2*y - x + ..." with n terms: sum of its coefficients known */
static char *long_sum(int n)
{
    hl_buf b;
    hl_buf_init(&b);
    for (int i = 0; i < n; i++)
        hl_buf_puts(&b, i == 0 ? "x" : i % 3 == 0 ? " - x" : i % 3 == 1 ? " + 2*y" : " + x");
    return hl_buf_take(&b);
}

static void check_long_sum(hl_pool *pool)
{
    char *s = long_sum(SUM_TERMS);
    hl_error err;
    const hl_expr *e = parse(pool, s, &err);
    CHECK_MSG(e != NULL, "%s", err.msg);
    if (e == NULL)
        return free(s);
    /* terms i = 1..n-1: i%3 = 0 gives -x, 1 gives 2y, 2 gives x; with the first x */
    int n0 = (SUM_TERMS - 1) / 3, n1 = (SUM_TERMS + 1) / 3, n2 = SUM_TERMS / 3;
    double want = 1 - n0 + 2.0 * n1 * 2 + n2;
    CHECK(eval_at(e, 1) == want);
    for (int st = HL_STYLE_TEXT; st <= HL_STYLE_C; st++) {
        char *p = hl_expr_print(e, (hl_style)st);
        CHECK(p != NULL && strlen(p) >= strlen(s) - 1);
        if (st == HL_STYLE_TEXT) {
            CHECK_STR(p, s); /* a flat sum prints as it was written */
            CHECK(parse(pool, p, &err) == e);
        }
        free(p);
    }
    const char *names[4];
    CHECK(hl_expr_symbols(e, names, 4) == 2);
    const hl_expr *d = hl_expr_diff(pool, e, "x");
    CHECK(eval_at(d, 0.5) == 1 - n0 + n2);
    const hl_expr *y = hl_sym(pool, "y"), *three = hl_num_si(pool, 3);
    const char *yname = "y";
    const hl_expr *sub = hl_expr_subst(pool, e, 1, &yname, &three);
    CHECK(eval_at(sub, 1) == 1 - n0 + 2.0 * n1 * 3 + n2);
    CHECK(hl_expr_has_symbol(e, "y") && !hl_expr_has_symbol(sub, "y") && y != NULL);
    free(s);
}

static void check_minus_run(hl_pool *pool)
{
    hl_buf b;
    hl_buf_init(&b);
    for (int i = 0; i < 65000; i++)
        hl_buf_putc(&b, '-');
    hl_buf_puts(&b, "x*y");
    char *s = hl_buf_take(&b);
    hl_error err;
    const hl_expr *e = parse(pool, s, &err);
    CHECK_MSG(e != NULL, "%s", err.msg);
    if (e != NULL) {
        CHECK(eval_at(e, 3) == 6);
        CHECK(eval_at(hl_expr_diff(pool, e, "x"), 3) == 2);
        for (int st = HL_STYLE_TEXT; st <= HL_STYLE_C; st++)
            free(hl_expr_print(e, (hl_style)st));
        char *p = hl_expr_print(e, HL_STYLE_TEXT);
        CHECK(parse(pool, p, &err) == e);
        free(p);
    }
    free(s);
}

/* x*x*...*x (CHAIN factors, left-nested CHAIN deep) and sin(sin(...(x))) */
static void check_chains(hl_pool *pool)
{
    const hl_expr *x = hl_sym(pool, "x"), *prod = x, *sines = x;
    for (int i = 1; i < CHAIN; i++)
        prod = hl_mul(pool, prod, x);
    for (int i = 0; i < CHAIN; i++)
        sines = hl_call(pool, HL_SIN, sines);

    CHECK(eval_at(hl_expr_diff(pool, prod, "x"), 1) == CHAIN);
    double at = 0.7, s = at, dprod = 1;
    for (int i = 0; i < CHAIN; i++) { /* chain rule, by hand */
        dprod *= cos(s);
        s = sin(s);
    }
    CHECK(eval_at(sines, at) == s);
    double got = eval_at(hl_expr_diff(pool, sines, "x"), at);
    CHECK_MSG(fabs(got - dprod) <= 1e-12 * fabs(dprod), "%.17g against %.17g", got, dprod);
    for (int st = HL_STYLE_TEXT; st <= HL_STYLE_C; st++) {
        free(hl_expr_print(prod, (hl_style)st));
        char *p = hl_expr_print(sines, (hl_style)st);
        CHECK(p != NULL && strlen(p) >= 5 * CHAIN);
        free(p);
    }
}

/* Nesting past the one limit is an error at the place it happens. */
static void check_limits(hl_pool *pool)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_puts(&b, "y + ");
    for (int i = 0; i < HL_PARSE_MAX_DEPTH + 1; i++)
        hl_buf_puts(&b, "sin(");
    hl_buf_putc(&b, 'x');
    for (int i = 0; i < HL_PARSE_MAX_DEPTH + 1; i++)
        hl_buf_putc(&b, ')');
    char *s = hl_buf_take(&b);
    hl_error err;
    CHECK(parse(pool, s, &err) == NULL && err.status == HL_ELIMIT);
    CHECK(err.pos == 4 + 4 * HL_PARSE_MAX_DEPTH + 3); /* the '(' one too deep */
    CHECK_MSG(strstr(err.msg, "formula nested too deeply") != NULL, "%s", err.msg);
    free(s);

    /* a formula past the size budget is refused before any work on it */
    s = long_sum(HL_PARSE_MAX_NODES + 1);
    CHECK(parse(pool, s, &err) == NULL && err.status == HL_ELIMIT);
    CHECK_MSG(strstr(err.msg, "formula too large") != NULL, "%s", err.msg);
    free(s);
}

/* The size of a printed form, each shared node counted every time it is
 * written: e_{k+1} = e_k*e_k + y has s_{k+1} = 2 s_k + 3, s_0 = 1, so
 * s_k = 2^(k+2) - 3 (past any budget for k = 60, with 3k + 2 nodes). */
static void check_tree_size(hl_pool *pool)
{
    const hl_expr *x = hl_sym(pool, "x"), *y = hl_sym(pool, "y"), *e = x;
    for (int k = 1; k <= 60; k++) {
        e = hl_add(pool, hl_mul(pool, e, e), y);
        if (k == 10)
            CHECK(hl_expr_tree_size(e) == 4093);
    }
    CHECK(fabs(hl_expr_tree_size(e) / (ldexp(1, 62) - 3) - 1) < 1e-15); /* rounded */
    CHECK(hl_expr_tree_size(e) > HL_PRINT_MAX_NODES);
}

int main(void)
{
    hl_pool *pool = hl_pool_new();
    check_long_sum(pool);
    check_minus_run(pool);
    check_chains(pool);
    check_limits(pool);
    check_tree_size(pool);
    hl_pool_free(pool);
    return HL_TEST_END();
}
