/* Derivatives: every atom kind (and nested ones) against central finite
 * differences of hl_alg_eval_arb; Leibniz and quotient rules exactly. */
#include <math.h>
#include <stdlib.h>

#include "hamlie/alg.h"
#include "hl_test.h"
#include "alg_test.h"

#define PREC 256



static double eval_at(const hl_alg *a, const double *pt, int var, double h)
{
    arb_ptr v = _arb_vec_init(3);
    arb_t y;
    arb_init(y);
    for (int i = 0; i < 3; i++)
        arb_set_d(v + i, pt[i]);
    arb_set_d(y, h);
    arb_add(v + var, v + var, y, PREC);
    double r = NAN;
    if (hl_alg_eval_arb(y, a, v, PREC, ctx, NULL) == HL_OK)
        r = arf_get_d(arb_midref(y), ARF_RND_NEAR);
    arb_clear(y);
    _arb_vec_clear(v, 3);
    return r;
}

/* d f/d var at random points in (0.2, 0.6)^3 against (f(+h) - f(-h))/(2h) */
static void check_fd(const char *f)
{
    hl_alg a, d;
    hl_alg_init(&a, ctx);
    hl_alg_init(&d, ctx);
    hl_error err;
    if (rd(&a, f) != HL_OK) {
        CHECK_MSG(0, "%s", f);
        return;
    }
    for (int var = 0; var < 3; var++) {
        int st = hl_alg_diff(&d, &a, var, ctx, &err);
        CHECK_MSG(st == HL_OK && hl_alg_is_canonical(&d, ctx), "d%s/d%d", f, var);
        for (int k = 0; k < 3; k++) {
            double pt[3] = {0.2 + 0.1 * k + 0.037 * var, 0.45 - 0.07 * k, 0.3 + 0.05 * k};
            double h = ldexp(1.0, -20);
            double fd = (eval_at(&a, pt, var, h) - eval_at(&a, pt, var, -h)) / (2 * h);
            double ex = eval_at(&d, pt, var, 0);
            CHECK_MSG(fabs(fd - ex) <= 1e-8 * (1 + fabs(ex)), "d(%s)/d%s at point %d: %.15g vs %.15g",
                      f, hl_alg_ctx_name(ctx, var), k, ex, fd);
        }
    }
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&d, ctx);
}

static int same(const hl_alg *a, const hl_alg *b)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    return fmpz_mpoly_equal(a->num, b->num, mc) && fmpz_mpoly_equal(a->den, b->den, mc);
}

int main(void)
{
    const char *names[] = {"x", "y", "z"};
    pool = hl_pool_new();
    ctx = hl_alg_ctx_new(3, names, 64);

    const char *fs[] = {
        "x^3*y - z/(x + y)", "sqrt(x^2 + y^2)", "x/(x^2 + y^2)^(3/2)", "x^(1/3)*y",
        "(x*y + z)^(2/5)", "sin(x*y)", "cos(x)^2*y", "tan(x + z)", "exp(x/y)", "exp(-x*z)",
        "log(x^2 + y)", "atan(x*y)", "asin(x*z)", "acos(x*y)", "pi*x^2*y",
        "sqrt(1 + sqrt(x))", "sin(sqrt(x^2 + y^2))", "log(sin(x) + 2)", "tanh(x*y)",
        "cosh(z)*sinh(x)", "exp(sin(x)*y)", "x^y", "sqrt(x)*sqrt(y)/(1 + sqrt(x))",
        "atan(sqrt(x*y))/(z + 1)",
    };
    for (size_t i = 0; i < sizeof fs / sizeof fs[0]; i++)
        check_fd(fs[i]);

    /* Leibniz and quotient rules, exactly, on random rational functions with atoms */
    const char *gs[] = {"x^2*y + sqrt(x^2+y^2)", "(x - z)/(y^2 + 1)", "sin(x)/(1 + cos(x)*z)",
                        "exp(x*y)*z + 1", "y/sqrt(1 + sqrt(x))", "log(x + y)*x"};
    int n = (int)(sizeof gs / sizeof gs[0]);
    hl_alg a, b, s, t, u, v;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    hl_alg_init(&s, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&u, ctx);
    hl_alg_init(&v, ctx);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            rd(&a, gs[i]);
            rd(&b, gs[j]);
            for (int var = 0; var < 3; var++) {
                hl_alg_mul(&s, &a, &b, ctx);
                hl_alg_diff(&s, &s, var, ctx, NULL); /* (ab)' */
                hl_alg_diff(&u, &a, var, ctx, NULL);
                hl_alg_diff(&v, &b, var, ctx, NULL);
                hl_alg_mul(&t, &u, &b, ctx);
                hl_alg_mul(&u, &a, &v, ctx);
                hl_alg_add(&t, &t, &u, ctx); /* a'b + ab' */
                CHECK_MSG(same(&s, &t), "Leibniz %s * %s", gs[i], gs[j]);
                hl_alg_div(&s, &a, &b, ctx, NULL);
                hl_alg_diff(&s, &s, var, ctx, NULL); /* (a/b)' */
                hl_alg_diff(&u, &a, var, ctx, NULL);
                hl_alg_mul(&t, &u, &b, ctx);
                hl_alg_mul(&u, &a, &v, ctx);
                hl_alg_sub(&t, &t, &u, ctx);
                hl_alg_mul(&u, &b, &b, ctx);
                hl_alg_div(&t, &t, &u, ctx, NULL); /* (a'b - ab')/b^2 */
                CHECK_MSG(same(&s, &t), "quotient %s / %s", gs[i], gs[j]);
            }
        }
    /* cross derivatives commute */
    for (int i = 0; i < n; i++) {
        rd(&a, gs[i]);
        hl_alg_diff(&s, &a, 0, ctx, NULL);
        hl_alg_diff(&s, &s, 1, ctx, NULL);
        hl_alg_diff(&t, &a, 1, ctx, NULL);
        hl_alg_diff(&t, &t, 0, ctx, NULL);
        CHECK_MSG(same(&s, &t), "mixed partials of %s", gs[i]);
    }
    /* exact: d sqrt(x^2+y^2)/dx = x/sqrt(x^2+y^2) */
    rd(&a, "sqrt(x^2+y^2)");
    hl_alg_diff(&s, &a, 0, ctx, NULL);
    rd(&t, "x/sqrt(x^2+y^2)");
    CHECK(same(&s, &t));
    rd(&a, "asin(x)");
    hl_alg_diff(&s, &a, 0, ctx, NULL);
    rd(&t, "1/sqrt(1 - x^2)");
    CHECK(same(&s, &t));
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&u, ctx);
    hl_alg_clear(&v, ctx);
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
    return HL_TEST_END();
}
