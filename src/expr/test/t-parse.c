/* Parser: precedence and folding against DAGs built by constructors (sx.h),
 * bad inputs against their status, position and message, lists, depth. */
#include <stdio.h>
#include <string.h>

#include "hl_test.h"
#include "sx.h"

static const struct {
    const char *src, *want;
} good[] = {
    {"x", "x"},
    {"pi", "pi"},
    {"-x^2", "(neg (pow x 2))"},
    {"a^b^c", "(pow a (pow b c))"},
    {"a**b**c", "(pow a (pow b c))"},
    {"2^-1/2", "(div (pow 2 -1) 2)"},
    {"x^-2", "(pow x -2)"},
    {"x^-y^2", "(pow x (neg (pow y 2)))"},
    {"a-b-c", "(sub (sub a b) c)"},
    {"a/b/c", "(div (div a b) c)"},
    {"a-b+c", "(add (sub a b) c)"},
    {"a-(b-c)", "(sub a (sub b c))"},
    {"a*b/c*d", "(mul (div (mul a b) c) d)"},
    {"2/3*x", "(mul 2/3 x)"},
    {"x/2/3", "(div (div x 2) 3)"},
    {"2/3/5", "2/15"},
    {"(2)/3", "(div 2 3)"},
    {"2/(3)", "(div 2 3)"},
    {"-2/3", "-2/3"},
    {"2/-3", "-2/3"},
    {"-(2/3)", "(neg 2/3)"},
    {"-(3)", "(neg 3)"},
    {"--3", "(neg -3)"},
    {"-+3", "-3"},
    {"+x", "x"},
    {"-3*x", "(mul -3 x)"},
    {"-x*y", "(mul (neg x) y)"},
    {"-2^2", "(neg (pow 2 2))"},
    {"(-2)^2", "(pow -2 2)"},
    {"0.25", "1/4"},
    {"0.1", "1/10"},
    {"1e-3", "1/1000"},
    {"2.5e-3", "1/400"},
    {"1E4", "10000"},
    {"1e+2", "100"},
    {"007", "7"},
    {"0.000", "0"},
    {"123456789012345678901234567890", "123456789012345678901234567890"},
    {"sin(x)^2", "(pow (sin x) 2)"},
    {"sqrt(x^2 + y^2)", "(sqrt (add (pow x 2) (pow y 2)))"},
    {"atan(asin(acos(sinh(cosh(tanh(tan(exp(log(x)))))))))",
     "(atan (asin (acos (sinh (cosh (tanh (tan (exp (log x)))))))))"},
    {"2*pi*r", "(mul (mul 2 pi) r)"},
    {"  q_1 +\tp2\n", "(add q_1 p2)"},
    {"(px^2+py^2)/2 - 1/sqrt(x^2+y^2)",
     "(sub (div (add (pow px 2) (pow py 2)) 2) (div 1 (sqrt (add (pow x 2) (pow y 2)))))"},
    {"x*-y", "(mul x (neg y))"},
    {"1/2*x", "(mul 1/2 x)"},
    {"2^3", "(pow 2 3)"},
    {"e", "e"},
    {"2 * e", "(mul 2 e)"},
    {"1e-10000", NULL}, /* checked below: 10^-10000 */
};

static const struct {
    const char *src;
    hl_status status;
    int pos;
    const char *msg; /* exact message */
} bad[] = {
    {"x +", HL_EPARSE, 3, "expected an expression after '+'"},
    {"(x", HL_EPARSE, 2, "expected ')' to close '(' opened at column 1"},
    {"a*(b+(c)", HL_EPARSE, 8, "expected ')' to close '(' opened at column 3"},
    {"x)", HL_EPARSE, 1, "unmatched ')'"},
    {"2x", HL_EPARSE, 1, "expected an operator between '2' and 'x'"},
    {"x y", HL_EPARSE, 2, "expected an operator between 'x' and 'y'"},
    {"(a)(b)", HL_EPARSE, 3, "expected an operator between ')' and '('"},
    {"(2 x)", HL_EPARSE, 3, "expected an operator between '2' and 'x'"},
    {"foo(x)", HL_EPARSE, 0, "unknown function 'foo'"},
    {"sin x", HL_EPARSE, 4, "expected '(' after 'sin'"},
    {"sin", HL_EPARSE, 3, "expected '(' after 'sin'"},
    {"1/0", HL_EDOM, 2, "division by zero"},
    {"x + 1/0.00", HL_EDOM, 6, "division by zero"},
    {"1/-0", HL_EDOM, 2, "division by zero"},
    {"x # y", HL_EPARSE, 2, "unexpected character '#'"},
    {"", HL_EPARSE, 0, "empty formula"},
    {"   ", HL_EPARSE, 0, "empty formula"},
    {"x^", HL_EPARSE, 2, "expected an expression after '^'"},
    {"x^*2", HL_EPARSE, 2, "expected an expression after '^'"},
    {"-", HL_EPARSE, 1, "expected an expression after '-'"},
    {"()", HL_EPARSE, 1, "expected an expression after '('"},
    {")", HL_EPARSE, 0, "expected an expression, found ')'"},
    {"1e99999", HL_ELIMIT, 1, "exponent too large (the limit is 1e10000)"},
    {"1e-10001", HL_ELIMIT, 1, "exponent too large (the limit is 1e10000)"},
    {"2.", HL_EPARSE, 2, "expected a digit after '.'"},
    {".5", HL_EPARSE, 0, "unexpected character '.' (a number starts with a digit: 0.5)"},
    {"x = 1", HL_EPARSE, 2, "unexpected '=': an expression is expected here, not an equation"},
    {"x; y", HL_EPARSE, 1, "unexpected ';': a single expression is expected here"},
    {"x\xc3\xa9", HL_EPARSE, 1, "unexpected byte 0xc3"},
    {"_x", HL_EPARSE, 0, "unexpected character '_'"},
    {"pi(x)", HL_EPARSE, 0, "unknown function 'pi'"},
    {"2e", HL_EPARSE, 1, "expected an operator between '2' and 'e'"},
};

static void check_good(void)
{
    for (size_t i = 0; i < sizeof good / sizeof *good; i++) {
        hl_pool *pool = hl_pool_new();
        hl_error err;
        const hl_expr *e = NULL;
        int st = hl_parse(&e, pool, good[i].src, &err);
        CHECK_MSG(st == HL_OK, "\"%s\": %s", good[i].src, err.msg);
        if (st == HL_OK && good[i].want) {
            const hl_expr *want = sx(pool, good[i].want);
            char *got = hl_expr_print(e, HL_STYLE_TEXT);
            CHECK_MSG(e == want, "\"%s\" parsed as \"%s\", want %s", good[i].src, got,
                      good[i].want);
            free(got);
        }
        hl_pool_free(pool);
    }
    /* 1e-10000 is exactly 1/10^10000 */
    hl_pool *pool = hl_pool_new();
    const hl_expr *e;
    CHECK(hl_parse(&e, pool, "1e-10000", NULL) == HL_OK);
    fmpz_t t;
    fmpz_init_set_ui(t, 10);
    fmpz_pow_ui(t, t, 10000);
    CHECK(e->kind == HL_NUM && fmpz_is_one(fmpq_numref(e->num)) &&
          fmpz_equal(fmpq_denref(e->num), t));
    fmpz_clear(t);
    hl_pool_free(pool);
}

static void check_bad(void)
{
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        hl_pool *pool = hl_pool_new();
        hl_error err;
        const hl_expr *e = (const hl_expr *)&err;
        hl_status st = hl_parse(&e, pool, bad[i].src, &err);
        CHECK_MSG(st == bad[i].status && err.status == st, "\"%s\": status %d, want %d (%s)",
                  bad[i].src, (int)st, (int)bad[i].status, err.msg);
        CHECK_MSG(err.pos == bad[i].pos, "\"%s\": pos %d, want %d (%s)", bad[i].src, err.pos,
                  bad[i].pos, err.msg);
        CHECK_STR(err.msg, bad[i].msg);
        CHECK(err.src == bad[i].src);
        CHECK(e == NULL);
        CHECK(hl_parse(&e, pool, bad[i].src, NULL) == bad[i].status); /* err may be NULL */
        hl_pool_free(pool);
    }
}

/* 200 nested parentheses are fine, 201 are refused at the 201st '(';
 * deep unary and power chains likewise, and never crash. */
static void check_depth(void)
{
    char buf[4096];
    hl_pool *pool = hl_pool_new();
    hl_error err;
    const hl_expr *e;
    for (int n = 199; n <= 202; n++) {
        int k = 0;
        for (int i = 0; i < n; i++)
            buf[k++] = '(';
        buf[k++] = 'x';
        for (int i = 0; i < n; i++)
            buf[k++] = ')';
        buf[k] = '\0';
        int st = hl_parse(&e, pool, buf, &err);
        if (n <= HL_PARSE_MAX_DEPTH) {
            CHECK_MSG(st == HL_OK && e == hl_sym(pool, "x"), "%d parentheses: %s", n, err.msg);
        } else {
            CHECK_MSG(st == HL_ELIMIT, "%d parentheses", n);
            CHECK(err.pos == HL_PARSE_MAX_DEPTH);
            CHECK_STR(err.msg, "formula nested too deeply (limit 200) at position 201");
        }
    }
    /* sin(sin(...)) */
    strcpy(buf, "");
    for (int i = 0; i < 201; i++)
        strcat(buf, "sin(");
    CHECK(hl_parse(&e, pool, buf, &err) == HL_ELIMIT && err.pos == 4 * 200 + 3);
    /* x^x^...^x: 200 exponents fine, 201 refused */
    for (int n = 200; n <= 201; n++) {
        int k = 0;
        for (int i = 0; i < n; i++)
            buf[k++] = 'x', buf[k++] = '^';
        buf[k++] = 'x';
        buf[k] = '\0';
        CHECK(hl_parse(&e, pool, buf, &err) == (n <= 200 ? HL_OK : HL_ELIMIT));
    }
    /* x^-x^-...: a unary after '^' costs a level, as does the "(" that the
     * printer writes instead: 100 of them is 200 levels */
    for (int n = 100; n <= 101; n++) {
        int k = 0;
        for (int i = 0; i < n; i++)
            buf[k++] = 'x', buf[k++] = '^', buf[k++] = '-';
        buf[k++] = 'x';
        buf[k] = '\0';
        int st = hl_parse(&e, pool, buf, &err);
        CHECK(st == (n <= 100 ? HL_OK : HL_ELIMIT));
        if (st == HL_OK) {
            char *s = hl_expr_print(e, HL_STYLE_TEXT);
            const hl_expr *e2;
            CHECK_MSG(hl_parse(&e2, pool, s, &err) == HL_OK && e2 == e, "%s", err.msg);
            CHECK(strncmp(s, "x^(-x^(-x", 9) == 0);
            free(s);
        }
    }
    /* 3000 unary minus signs are one level; 3000 terms are no level */
    memset(buf, '-', 3000);
    strcpy(buf + 3000, "x");
    CHECK(hl_parse(&e, pool, buf, &err) == HL_OK);
    for (int i = 0; i < 1500; i++)
        buf[2 * i] = 'x', buf[2 * i + 1] = '+';
    strcpy(buf + 3000, "x");
    CHECK(hl_parse(&e, pool, buf, &err) == HL_OK && e->kind == HL_ADD);
    hl_pool_free(pool);
}

static void check_list(void)
{
    hl_pool *pool = hl_pool_new();
    hl_eqn items[4];
    hl_error err;
    int n = -1;

    CHECK(hl_parse_list(items, 4, &n, pool, "X = x + D*p; P = p - D*x", &err) == HL_OK);
    CHECK(n == 2);
    CHECK(items[0].lhs == sx(pool, "X") && items[0].rhs == sx(pool, "(add x (mul D p))"));
    CHECK(items[1].lhs == sx(pool, "P") && items[1].rhs == sx(pool, "(sub p (mul D x))"));
    CHECK(items[0].pos == 0 && items[1].pos == 13);

    CHECK(hl_parse_list(items, 4, &n, pool, "x^2; y = 1;", &err) == HL_OK && n == 2);
    CHECK(items[0].lhs == sx(pool, "(pow x 2)") && items[0].rhs == NULL);
    CHECK(items[1].pos == 5 && items[1].rhs == sx(pool, "1"));

    CHECK(hl_parse_list(items, 4, &n, pool, "", &err) == HL_OK && n == 0);
    CHECK(hl_parse_list(items, 4, &n, pool, " ; ", &err) == HL_EPARSE && err.pos == 1);
    CHECK(hl_parse_list(items, 0, &n, pool, "", &err) == HL_OK && n == 0);

    CHECK(hl_parse_list(items, 4, &n, pool, "a = b = c", &err) == HL_EPARSE);
    CHECK(err.pos == 6 && n == 0);
    CHECK_STR(err.msg, "only one '=' is allowed in an item");
    CHECK(hl_parse_list(items, 2, &n, pool, "a; b; c", &err) == HL_ELIMIT && err.pos == 6);
    CHECK_STR(err.msg, "more than 2 items");
    CHECK(hl_parse_list(items, 4, &n, pool, "a;; b", &err) == HL_EPARSE && err.pos == 2);
    CHECK_STR(err.msg, "expected an expression after ';'");
    CHECK(hl_parse_list(items, 4, &n, pool, "= b", &err) == HL_EPARSE && err.pos == 0);
    CHECK(hl_parse_list(items, 4, &n, pool, "a = ", &err) == HL_EPARSE && err.pos == 4);
    CHECK(hl_parse_list(items, 4, &n, pool, "a = b c", &err) == HL_EPARSE && err.pos == 6);
    CHECK(hl_parse_list(items, 4, &n, pool, "a = (b", &err) == HL_EPARSE && err.pos == 6);
    CHECK(hl_parse_list(items, 4, &n, pool, "a = b)", &err) == HL_EPARSE && err.pos == 5);
    hl_pool_free(pool);
}

static void check_symbol_pos(void)
{
    CHECK(hl_symbol_pos("x + y*z", "y") == 4);
    CHECK(hl_symbol_pos("xy + y", "y") == 5);
    CHECK(hl_symbol_pos("1e5 + e", "e") == 6); /* the e of 1e5 is not a symbol */
    CHECK(hl_symbol_pos("sin(q1) + q", "q") == 10);
    CHECK(hl_symbol_pos("a # b", "b") == 4);   /* a bad character does not stop it */
    CHECK(hl_symbol_pos("a + b", "c") == -1);
    CHECK(hl_symbol_pos("", "c") == -1);
}

int main(void)
{
    check_good();
    check_bad();
    check_depth();
    check_list();
    check_symbol_pos();
    return HL_TEST_END();
}
