/* parse(print(e, TEXT)) == e, the same pointer, for random DAGs of every
 * kind, for hand-picked ones the parser would never produce, and for what
 * the parser produces from printed text (print is a fixed point). */
#include <stdlib.h>

#include "gen.h"
#include "hl_test.h"
#include "sx.h"

static int roundtrip(hl_pool *pool, const hl_expr *e)
{
    char *s = hl_expr_print(e, HL_STYLE_TEXT);
    const hl_expr *back = NULL;
    hl_error err;
    int st = hl_parse(&back, pool, s, &err);
    int ok = st == HL_OK && back == e;
    if (!ok) {
        char *b = back ? hl_expr_print(back, HL_STYLE_TEXT) : NULL;
        fprintf(stderr, "round trip failed: \"%s\" -> %s%s (%s)\n", s, back ? "" : "error ",
                b ? b : "", err.msg);
        free(b);
    }
    free(s);
    return ok;
}

static const char *const special[] = {
    "(mul -3 x)", "(pow 2/3 x)", "(neg -2)", "(neg 2)", "(neg 2/3)", "(neg -2/3)",
    "(div 2 3)", "(div -2 3)", "(div 2/3 5)", "(div 2 -3)", "(div -2/3 -5/7)",
    "(mul x -3)", "(add x -3)", "(sub x -3)", "(sub x -2/3)", "(pow x -1/2)",
    "(pow -2 2)", "(pow -1/2 -1/2)", "(neg (neg x))", "(neg (neg (neg 3)))",
    "(mul x (neg y))", "(neg (mul x y))", "(mul (neg x) y)", "(pow (neg x) 2)",
    "(neg (pow x 2))", "(pow x (pow y z))", "(pow (pow x y) z)", "(sub a (sub b c))",
    "(div a (mul b c))", "(div a (div b c))", "(mul a (div b c))", "(add a (add b c))",
    "(pow (add x 1) 2)", "(mul 2/3 5)", "(div (div 1 2) 3)", "(div 0 0)", "(div 1 0)",
    "(mul (mul -2/3 x) y)", "(add (mul -2/3 x) (mul -5 y))", "(neg (add x y))",
    "(neg (sin x))", "(sin (neg x))", "(pow (sin x) -2)", "(neg (div 1 2))",
    "(sub (neg x) (neg y))", "(pow e (neg (pow x 2)))", "(div x (neg 3))",
    "(mul (neg 3) x)", "(neg (mul -3 x))", "(neg (pow -3 x))", "(pow (neg 3) x)",
};

int main(void)
{
    hl_pool *pool = hl_pool_new();
    gen g = {.s = 12345};
    int failures = 0;

    for (size_t i = 0; i < sizeof special / sizeof *special; i++)
        CHECK_MSG(roundtrip(pool, sx(pool, special[i])), "%s", special[i]);

    /* random DAGs: a few thousand, depths 1..7 */
    for (int i = 0; i < 4000; i++) {
        if (i % 500 == 0) { /* a fresh pool now and then, so ids start small too */
            hl_pool_free(pool);
            pool = hl_pool_new();
            g.nmade = 0;
        }
        const hl_expr *e = gen_expr(&g, pool, 1 + i % 7);
        if (!roundtrip(pool, e) && ++failures > 10)
            break;
    }
    CHECK_MSG(failures == 0, "%d random DAGs did not round trip", failures);

    /* printing what the parser returns is a fixed point of print . parse */
    const char *texts[] = {"x + D*p", "-x^2", "x^(-1/2)", "(x + 1)^2", "a - (b - c)",
                           "a/(b*c)", "-3*x", "2/3*x", "(-2/3)^x", "x*(-y)", "--x",
                           "-(3)", "2/(3)", "sin(x)^2 + cos(x)^2", "-2/3/(5)"};
    for (size_t i = 0; i < sizeof texts / sizeof *texts; i++) {
        const hl_expr *e;
        CHECK(hl_parse(&e, pool, texts[i], NULL) == HL_OK);
        char *s = hl_expr_print(e, HL_STYLE_TEXT);
        CHECK_STR(s, texts[i]);
        free(s);
    }
    hl_pool_free(pool);
    return HL_TEST_END();
}
