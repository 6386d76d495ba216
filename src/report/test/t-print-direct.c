/* Polynomials printed without the expression DAG (format.c, alg/print_poly.c)
 * against the DAG path (hl_format_no_direct): the same bytes for random
 * polynomials and series in text and SymPy styles, with signs, rational
 * and 30-digit coefficients, common factors pulled out or not, constants,
 * zero terms, with and without factorials.  A few cases by hand too. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/ham.h"
#include "hamlie/report.h"
#include "hl_test.h"
#include "report/format_impl.h"

static unsigned long long seed = 88172645463325252ull;

static unsigned rnd(unsigned n) /* xorshift64: the same cases on every run */
{
    seed ^= seed << 13;
    seed ^= seed >> 7;
    seed ^= seed << 17;
    return (unsigned)(seed % n);
}

static const char *const coords[] = {"x", "y", "px", "py", "D"};

/* A random polynomial as a formula: up to 9 terms, small or huge
 * coefficients, times a common factor sometimes (rule 4's cases). */
static void random_formula(hl_buf *b)
{
    static const char *const factors[] = {"", "3*", "12*", "-2*", "5/7*", "-1/6*"};
    int n = (int)rnd(10);
    hl_buf_printf(b, "%s(0", factors[rnd(6)]);
    for (int t = 0; t < n; t++) {
        unsigned kind = rnd(8);
        hl_buf_puts(b, rnd(2) ? " - " : " + ");
        if (kind == 0)
            hl_buf_puts(b, "123456789012345678901234567890");
        else
            hl_buf_printf(b, "%u", 1 + rnd(kind < 4 ? 3 : 40));
        if (rnd(3) == 0)
            hl_buf_printf(b, "/%u", 1 + rnd(12));
        for (int v = 0; v < 5; v++)
            if (rnd(3) == 0)
                hl_buf_printf(b, "*%s^%u", coords[v], 1 + rnd(3));
    }
    hl_buf_putc(b, ')');
}

static int same_both_ways(char *direct, char *dag, const char *what)
{
    int same = strcmp(direct, dag) == 0;
    CHECK_MSG(same, "%s: direct \"%s\", DAG \"%s\"", what, direct, dag);
    free(direct);
    free(dag);
    return same;
}

static void compare_random(hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    enum { ORDER = 5 };
    hl_alg t[ORDER + 1];
    for (int k = 0; k <= ORDER; k++)
        hl_alg_init(&t[k], ctx);
    hl_buf f;
    hl_buf_init(&f);
    int failures = 0;
    for (int round = 0; round < 150 && failures < 5; round++) {
        for (int k = 0; k <= ORDER; k++) {
            f.len = 0;
            if (rnd(4) == 0)
                hl_buf_puts(&f, "0");
            else
                random_formula(&f);
            CHECK(hl_system_read(&t[k], sys, f.s, NULL) == HL_OK);
        }
        hl_style st = rnd(2) ? HL_STYLE_TEXT : HL_STYLE_SYMPY;
        int order = (int)rnd(ORDER + 1), factorial = (int)rnd(2);
        for (int k = 0; k <= order; k++) {
            hl_format_no_direct = 0;
            char *direct = hl_format_alg(&t[k], ctx, pool, st);
            hl_format_no_direct = 1;
            failures += !same_both_ways(direct, hl_format_alg(&t[k], ctx, pool, st), "element");
        }
        hl_format_no_direct = 0;
        char *direct = hl_format_series(t, order, "D", factorial, ctx, pool, st);
        hl_format_no_direct = 1;
        char *dag = hl_format_series(t, order, "D", factorial, ctx, pool, st);
        failures += !same_both_ways(direct, dag, "series");
    }
    hl_format_no_direct = 0;
    hl_buf_clear(&f);
    for (int k = 0; k <= ORDER; k++)
        hl_alg_clear(&t[k], ctx);
}

/* Texts known by hand: the direct path on, its quirks kept ("-(3)*q"). */
static void by_hand(hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    static const struct {
        const char *terms[3];
        hl_style st;
        const char *want;
    } cases[] = {
        {{"-3*x", "-3*px", "9*x^2"}, HL_STYLE_TEXT, "-(3)*x - 3*D*px + 9*D^2/2*x^2"},
        {{"-3*x", "-3*px", "9*x^2"}, HL_STYLE_SYMPY, "-3*x - 3*D*px + 9*D**2/2*x**2"},
        {{"-3/2", "0", "x*y - x"}, HL_STYLE_TEXT, "-(3/2) + D^2/2*(x*y - x)"},
        {{"-3/2", "0", "0"}, HL_STYLE_SYMPY, "-(3/2)"},
        /* a common factor pulled out only when strictly shorter */
        {{"-x - y", "4*x + 4*y^2", "-6*x*y - 6*x - 6*y"},
         HL_STYLE_TEXT,
         "-x - y + D*(4*y^2 + 4*x) - 3*D^2*(x*y + x + y)"},
        {{"-x/3 - y/3", "-6*x*y - 6*x", "0"}, HL_STYLE_TEXT, "-x/3 - y/3 + D*(-6*x*y - 6*x)"},
        {{"(x + y + px)/3", "0", "0"}, HL_STYLE_TEXT, "(x + y + px)/3"},
        {{"-(x + y + px)/3", "0", "0"}, HL_STYLE_SYMPY, "-(x + y + px)/3"},
        {{"0", "0", "0"}, HL_STYLE_TEXT, "0"},
    };
    hl_alg t[3];
    for (int k = 0; k < 3; k++)
        hl_alg_init(&t[k], ctx);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        for (int k = 0; k < 3; k++)
            CHECK(hl_system_read(&t[k], sys, cases[i].terms[k], NULL) == HL_OK);
        char *s = hl_format_series(t, 2, "D", 1, ctx, pool, cases[i].st);
        CHECK_STR(s, cases[i].want);
        free(s);
    }
    for (int k = 0; k < 3; k++)
        hl_alg_clear(&t[k], ctx);
}

int main(void)
{
    hl_system_spec spec = {"(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    if (hl_system_new(&sys, &spec, NULL) != HL_OK)
        return 1;
    by_hand(sys);
    compare_random(sys);
    hl_system_free(sys);
    return HL_TEST_END();
}
