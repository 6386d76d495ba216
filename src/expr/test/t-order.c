/* hl_expr_ordered: writings of one formula that differ only in the order of
 * terms and factors become one DAG; the value is unchanged (against the
 * formula as typed, at random points); long flat sums and exponentially
 * large DAGs go through without deep recursion. */
#include <math.h>
#include <stdlib.h>

#include "hamlie/expr.h"
#include "hl_test.h"

static const hl_expr *parse(hl_pool *pool, const char *s)
{
    const hl_expr *e = NULL;
    hl_error err;
    if (hl_parse(&e, pool, s, &err) != HL_OK)
        fprintf(stderr, "parse %s: %s\n", s, err.msg);
    return e;
}

static void check_same(hl_pool *pool, const char *a, const char *b)
{
    const hl_expr *x = hl_expr_ordered(pool, parse(pool, a));
    const hl_expr *y = hl_expr_ordered(pool, parse(pool, b));
    char *sx = hl_expr_print(x, HL_STYLE_TEXT), *sy = hl_expr_print(y, HL_STYLE_TEXT);
    CHECK_MSG(x == y, "%s -> %s but %s -> %s", a, sx, b, sy);
    free(sx), free(sy);
}

static void check_value_kept(hl_pool *pool, const char *s)
{
    static const char *const names[] = {"x", "y", "px", "py"};
    const hl_expr *e = parse(pool, s), *o = hl_expr_ordered(pool, e);
    hl_error err;
    srand(13);
    for (int k = 0; k < 20; k++) {
        double v[4], a = 0, b = 0;
        for (int i = 0; i < 4; i++)
            v[i] = 2.0 * rand() / RAND_MAX - 1;
        CHECK(hl_expr_eval_d(&a, e, 4, names, v, &err) == HL_OK);
        CHECK(hl_expr_eval_d(&b, o, 4, names, v, &err) == HL_OK);
        CHECK_MSG(fabs(a - b) <= 1e-14 * (1 + fabs(a)), "%s: %.17g vs %.17g", s, a, b);
    }
}

/* 1*x^0 + 2*x^1 + ... + n*x^(n-1), a left chain n deep, and its reverse
 * with the factors swapped. */
static void check_long_sum(hl_pool *pool, int n)
{
    const hl_expr *up = NULL, *down = NULL, *x = hl_sym(pool, "x");
    for (int i = 0; i < n; i++) {
        const hl_expr *t =
            hl_mul(pool, hl_num_si(pool, i + 1), hl_pow(pool, x, hl_num_si(pool, i)));
        up = up ? hl_add(pool, up, t) : t;
        int j = n - 1 - i;
        t = hl_mul(pool, hl_pow(pool, x, hl_num_si(pool, j)), hl_num_si(pool, j + 1));
        down = down ? hl_add(pool, down, t) : t;
    }
    CHECK(hl_expr_ordered(pool, up) == hl_expr_ordered(pool, down));
}

int main(void)
{
    hl_pool *pool = hl_pool_new();
    check_same(pool, "(px^2+py^2)/2 + x^2*y - y^3/3", "-y^3/3 + (py^2 + px^2)/2 + y*x^2");
    check_same(pool, "-3*x + 2", "2 - 3*x");
    check_same(pool, "a*b/c - d + e", "e - d + b*a/c");
    check_same(pool, "-(a - b)*c", "c*(-(-b + a))");
    check_same(pool, "sin(x + y)*exp(-x) - 2", "-2 + exp(-x)*sin(y + x)");
    check_same(pool, "x - -y", "y + x");
    const hl_expr *xy = hl_expr_ordered(pool, parse(pool, "x - y"));
    const hl_expr *yx = hl_expr_ordered(pool, parse(pool, "y - x"));
    CHECK(xy != yx); /* signs are kept with their terms */
    check_value_kept(pool, "(px^2+py^2)/2 + x^2*y - y^3/3");
    check_value_kept(pool, "-(x - y/px)*(py - 3)/(x^2 + 1) - sin(-x*y)/(2 - cos(py))");
    check_value_kept(pool, "x/y/px*py - -x");
    check_long_sum(pool, 200000);
    /* e_{k+1} = e_k*e_k + y: a tree of 2^60 leaves, a DAG of 180 nodes */
    const hl_expr *e = hl_sym(pool, "x");
    for (int i = 0; i < 60; i++)
        e = hl_add(pool, hl_mul(pool, e, e), hl_sym(pool, "y"));
    CHECK(hl_expr_ordered(pool, e) != NULL);
    hl_pool_free(pool);
    return HL_TEST_END();
}
