/* hl_alg_to_expr: the text a person would write (expected strings worked
 * out by hand from the rules in print.c), and the round trip
 * from_expr(to_expr(a)) == a on fixed and random elements. */
#include <stdlib.h>

#include "hamlie/alg.h"
#include "hl_test.h"

static hl_pool *pool;
static hl_alg_ctx *ctx;

static int rd(hl_alg *r, const char *s)
{
    const hl_expr *e;
    hl_error err;
    hl_error_clear(&err);
    int st = hl_parse(&e, pool, s, &err);
    if (st == HL_OK)
        st = hl_alg_from_expr(r, e, ctx, &err);
    if (st != HL_OK)
        fprintf(stderr, "cannot read '%s': %s\n", s, err.msg);
    return st;
}

/* from_expr(to_expr(a)) has the same num and den as a */
static int round_trip(const hl_alg *a)
{
    hl_alg b;
    hl_error err;
    hl_alg_init(&b, ctx);
    const hl_expr *e = hl_alg_to_expr(a, ctx, pool);
    int ok = hl_alg_from_expr(&b, e, ctx, &err) == HL_OK
             && fmpz_mpoly_equal(a->num, b.num, hl_alg_ctx_mpoly(ctx))
             && fmpz_mpoly_equal(a->den, b.den, hl_alg_ctx_mpoly(ctx));
    if (!ok) {
        char *s = hl_expr_print(e, HL_STYLE_TEXT);
        fprintf(stderr, "round trip failed for %s\n", s);
        free(s);
    }
    hl_alg_clear(&b, ctx);
    return ok;
}

static void check_print(const char *in, const char *want)
{
    hl_alg a;
    hl_alg_init(&a, ctx);
    if (rd(&a, in) != HL_OK) {
        CHECK_MSG(0, "'%s' did not read", in);
    } else {
        char *s = hl_expr_print(hl_alg_to_expr(&a, ctx, pool), HL_STYLE_TEXT);
        CHECK_MSG(strcmp(s, want) == 0, "%s: got \"%s\", want \"%s\"", in, s, want);
        free(s);
        CHECK_MSG(round_trip(&a), "%s", in);
    }
    hl_alg_clear(&a, ctx);
}

int main(void)
{
    const char *names[] = {"x", "y", "q", "p", "D"};
    pool = hl_pool_new();
    ctx = hl_alg_ctx_new(5, names, 0);

    check_print("-x*sqrt(x^2+y^2)/(x^2+y^2)^2", "-x/(x^2 + y^2)^(3/2)");
    check_print("-x/(x^2+y^2)^(3/2)", "-x/(x^2 + y^2)^(3/2)");
    check_print("x/sqrt(x^2+y^2)", "x/sqrt(x^2 + y^2)");
    check_print("1/sqrt(x^2+y^2)", "1/sqrt(x^2 + y^2)");
    check_print("sqrt(x^2+y^2)", "sqrt(x^2 + y^2)");
    check_print("(x^2+y^2)^(-5/2)*y", "y/(x^2 + y^2)^(5/2)");
    check_print("-sin(q)", "-sin(q)");
    check_print("p^2/2 - cos(q)", "p^2/2 - cos(q)");
    check_print("1 + D^2", "D^2 + 1");
    check_print("x/(1 + D^2)", "x/(D^2 + 1)");
    check_print("x/((x^2+y^2)^2*(x+1))", "x/((x + 1)*(x^2 + y^2)^2)");
    check_print("(x^2 - y^2)/(x^2 + 2*x*y + y^2)", "(x - y)/(x + y)");
    check_print("-(x+y)/(2*(x^2+y^2))", "-(x + y)/(2*(x^2 + y^2))");
    check_print("x/2 + 3*y/4 - 1", "x/2 + 3*y/4 - 1");
    check_print("-x + y", "-x + y");
    check_print("(x + y)^2", "x^2 + 2*x*y + y^2");
    check_print("sin(q)^2", "-cos(q)^2 + 1");
    check_print("tan(q)", "sin(q)/cos(q)");
    check_print("x^(2/3)", "x^(2/3)");
    check_print("2*pi", "2*pi");
    check_print("sqrt(2)*x", "x*sqrt(2)");
    check_print("exp(2*x)*sin(sqrt(x^2+y^2))", "exp(2*x)*sin(sqrt(x^2 + y^2))");
    check_print("0", "0");
    check_print("-3/4", "-3/4");

    /* round trip on random rational functions in x, y, q (atoms excluded) */
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    flint_rand_t state;
    flint_randinit(state);
    int nv = (int)mc->minfo->nvars;
    ulong *bounds = malloc((size_t)nv * sizeof *bounds);
    for (int v = 0; v < nv; v++)
        bounds[v] = v < 3 ? 4 : 1;
    hl_alg a, b;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    int bad = 0;
    for (int i = 0; i < 200; i++) {
        fmpz_mpoly_randtest_bounds(a.num, state, 6, 20, bounds, mc);
        fmpz_mpoly_randtest_bounds(b.num, state, 6, 20, bounds, mc);
        if (fmpz_mpoly_is_zero(b.num, mc))
            continue;
        hl_alg_one(&a, ctx);
        fmpz_mpoly_randtest_bounds(a.num, state, 6, 20, bounds, mc);
        hl_alg_div(&a, &a, &b, ctx, NULL);
        bad += !round_trip(&a);
    }
    CHECK_MSG(bad == 0, "%d random round trips failed", bad);
    free(bounds);
    flint_randclear(state);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
    return HL_TEST_END();
}
