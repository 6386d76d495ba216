/* atan2(y, x) in the exact algebra and the series layer (the numeric back
 * ends: src/tape/test/t-atan2.c):
 *   exact values where x is a number: atan2(3, -4) = pi - atan(3/4),
 *     atan2(-3, -4) = atan(3/4) - pi, atan2(0, -2) = pi, atan2(+-3, 0) =
 *     +-pi/2, atan2(y, 2) = atan(y/2); atan2(0, 0) refused (HL_EDOM);
 *   odd in y: atan2(-y, x) = -atan2(y, x), one atom; sin, cos and tan of
 *     atan2(y, x) are y/r, x/r, y/x (r = sqrt(x^2 + y^2));
 *   the derivative rule against the closed forms x/(x^2+y^2), -y/(x^2+y^2),
 *     also through a composite argument;
 *   substitution remakes the atom from both arguments (y -> 0, x -> -2: pi);
 *   Arb evaluation in every quadrant against mpmath (30 digits);
 *   the printed form parses back to the same element;
 *   series: atan2(y + a D, x + b D) against the line's closed form
 *     c1 = (x a - y b)/r^2, c2 = -(x a - y b)(x b + y a)/r^4, and against
 *     the derivatives of atan2 (c_k = d^k/dy^k atan2 / k! for a = 1, b = 0);
 *     atan2(sin(x + D), cos(x + D)) = atan2(sin x, cos x) + D exactly. */
#include <string.h>

#include "sr.h"

#define N 7

static void same(const char *a, const char *b)
{
    hl_alg x, y;
    hl_alg_init(&x, ctx);
    hl_alg_init(&y, ctx);
    rd(&x, a);
    rd(&y, b);
    CHECK_MSG(hl_alg_equal(&x, &y, ctx), "%s != %s", a, b);
    hl_alg_clear(&x, ctx);
    hl_alg_clear(&y, ctx);
}

static void exact_values(void)
{
    same("atan2(3, -4)", "pi - atan(3/4)");
    same("atan2(-3, -4)", "atan(3/4) - pi");
    same("atan2(3, 4)", "atan(3/4)");
    same("atan2(0, -2)", "pi");
    same("atan2(0, 5)", "0");
    same("atan2(3, 0)", "pi/2");
    same("atan2(-3, 0)", "-pi/2");
    same("atan2(y, 2)", "atan(y/2)");
    same("atan2(-y, x)", "-atan2(y, x)");
    same("atan2(x - y, -x)", "-atan2(y - x, -x)");
    /* sin, cos, tan of the angle: the point's coordinates over its radius,
     * in the canonical form (no numeric zero test) */
    hl_alg_ctx_reset_numeric_used(ctx);
    same("sin(atan2(y, x))", "y/sqrt(x^2 + y^2)");
    same("cos(atan2(y, x))", "x/sqrt(x^2 + y^2)");
    same("sin(atan2(-y, x))", "-y/sqrt(x^2 + y^2)");
    same("cos(-atan2(y, x))", "x/sqrt(x^2 + y^2)");
    same("tan(atan2(y, x - 1))", "y/(x - 1)");
    CHECK_MSG(!hl_alg_ctx_numeric_used(ctx), "sin(atan2(y, x)) needed the numeric test");
    const hl_expr *e;
    hl_alg r;
    hl_error err;
    hl_alg_init(&r, ctx);
    CHECK(hl_parse(&e, pool, "atan2(0, 0)", &err) == HL_OK);
    CHECK(hl_alg_from_expr(&r, e, ctx, &err) == HL_EDOM && strstr(err.msg, "atan2(0, 0)"));
    hl_alg_clear(&r, ctx);
}

static void derivatives(void)
{
    hl_alg a, d, want;
    hl_error err;
    hl_alg_init(&a, ctx);
    hl_alg_init(&d, ctx);
    hl_alg_init(&want, ctx);
    int iy = hl_alg_ctx_index(ctx, "y"), ix = hl_alg_ctx_index(ctx, "x");
    rd(&a, "atan2(y, x)");
    CHECK(hl_alg_diff(&d, &a, iy, ctx, &err) == HL_OK);
    rd(&want, "x/(x^2 + y^2)");
    CHECK(hl_alg_equal(&d, &want, ctx));
    CHECK(hl_alg_diff(&d, &a, ix, ctx, &err) == HL_OK);
    rd(&want, "-y/(x^2 + y^2)");
    CHECK(hl_alg_equal(&d, &want, ctx));
    rd(&a, "atan2(sin(x), 1 + x^2)");
    CHECK(hl_alg_diff(&d, &a, ix, ctx, &err) == HL_OK);
    rd(&want, "((1 + x^2)*cos(x) - 2*x*sin(x))/((1 + x^2)^2 + sin(x)^2)");
    CHECK(hl_alg_equal(&d, &want, ctx));
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&want, ctx);
}

static void substitution_and_eval(void)
{
    hl_alg a, r, v[2];
    hl_error err;
    hl_alg_init(&a, ctx), hl_alg_init(&r, ctx), hl_alg_init(&v[0], ctx), hl_alg_init(&v[1], ctx);
    int vars[2] = {hl_alg_ctx_index(ctx, "y"), hl_alg_ctx_index(ctx, "x")};
    rd(&a, "atan2(y, x) + x");
    rd(&v[0], "0");
    rd(&v[1], "-2");
    CHECK(hl_alg_subst(&r, &a, 2, vars, v, ctx, &err) == HL_OK);
    rd(&v[0], "pi - 2");
    CHECK(hl_alg_equal(&r, &v[0], ctx));
    /* Arb in each quadrant: mpmath.atan2(y, x) + x */
    static const struct {
        double y, x;
        const char *mp;
    } q[] = {{0.5, 0.75, "1.338002603547567551245611"},
             {0.5, -0.75, "1.803590050042225687217032"},
             {-0.5, -0.75, "-3.303590050042225687217032"},
             {-0.5, 0.75, "0.1619973964524324487543889"}};
    int nb = hl_alg_ctx_nbase(ctx);
    arb_ptr vals = _arb_vec_init(nb);
    arb_t out, want;
    arb_init(out), arb_init(want);
    for (int i = 0; i < 4; i++) {
        arb_set_d(vals + vars[0], q[i].y);
        arb_set_d(vals + vars[1], q[i].x);
        CHECK(hl_alg_eval_arb(out, &a, vals, 128, ctx, &err) == HL_OK);
        char s[64];
        snprintf(s, sizeof s, "[%s +/- 1e-24]", q[i].mp);
        arb_set_str(want, s, 128);
        CHECK_MSG(arb_overlaps(out, want), "quadrant %d", i);
    }
    arb_clear(out), arb_clear(want);
    _arb_vec_clear(vals, nb);
    /* printed, parsed back */
    char *s = hl_expr_print(hl_alg_to_expr(&a, ctx, pool), HL_STYLE_TEXT);
    CHECK_MSG(strstr(s, "atan2(y, x)") != NULL, "%s", s);
    same(s, "atan2(y, x) + x");
    free(s);
    hl_alg_clear(&a, ctx), hl_alg_clear(&r, ctx), hl_alg_clear(&v[0], ctx), hl_alg_clear(&v[1], ctx);
}

static void series_of(hl_series *out, const char *src)
{
    const hl_expr *e;
    hl_error err;
    CHECK(hl_parse(&e, pool, src, &err) == HL_OK);
    const char *names[] = {"y", "x", "a", "b", "D"};
    hl_series in[5];
    for (int i = 0; i < 5; i++) {
        hl_series_init(&in[i], 0, ctx);
        if (i < 4)
            rds(&in[i], N, names[i], NULL);
        else
            rds(&in[i], N, "0", "1", NULL);
    }
    CHECK_MSG(hl_series_eval_expr(out, e, 5, names, in, N, ctx, &err) == HL_OK, "%s: %s", src,
              err.msg);
    for (int i = 0; i < 5; i++)
        hl_series_clear(&in[i], ctx);
}

static void series(void)
{
    hl_series s, want;
    hl_series_init(&s, 0, ctx);
    hl_series_init(&want, 0, ctx);
    /* a line through (x, y) with velocity (b, a) */
    series_of(&s, "atan2(y + a*D, x + b*D)");
    hl_alg c;
    hl_alg_init(&c, ctx);
    rd(&c, "atan2(y, x)");
    CHECK(hl_alg_equal(&s.c[0], &c, ctx));
    rd(&c, "(x*a - y*b)/(x^2 + y^2)");
    CHECK(hl_alg_equal(&s.c[1], &c, ctx));
    rd(&c, "-(x*a - y*b)*(x*b + y*a)/(x^2 + y^2)^2");
    CHECK(hl_alg_equal(&s.c[2], &c, ctx));
    /* against the derivative rule: c_k = d^k/dy^k atan2(y, x) / k! */
    series_of(&s, "atan2(y + D, x)");
    hl_series_zero(&want, N, ctx);
    hl_error err;
    rd(&want.c[0], "atan2(y, x)");
    for (int k = 1; k < N; k++) {
        CHECK(hl_alg_diff(&want.c[k], &want.c[k - 1], hl_alg_ctx_index(ctx, "y"), ctx, &err) ==
              HL_OK);
        fmpq_t f; /* running: c_k = (c_{k-1})' / k = f^(k) / k! */
        fmpq_init(f);
        fmpq_set_si(f, 1, (ulong)k);
        hl_alg_scalar_mul_fmpq(&want.c[k], &want.c[k], f, ctx);
        fmpq_clear(f);
    }
    CHECK_SERIES(&s, &want, N);
    /* the circle: the angle advances by D exactly */
    series_of(&s, "atan2(sin(x + D), cos(x + D))");
    rds(&want, N, "atan2(sin(x), cos(x))", "1", NULL);
    CHECK_SERIES(&s, &want, N);
    hl_alg_clear(&c, ctx);
    hl_series_clear(&s, ctx);
    hl_series_clear(&want, ctx);
}

int main(void)
{
    const char *names[] = {"y", "x", "a", "b", "D"};
    setup(5, names);
    exact_values();
    derivatives();
    substitution_and_eval();
    series();
    teardown();
    flint_cleanup();
    return HL_TEST_END();
}
