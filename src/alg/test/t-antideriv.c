/* hl_alg_antiderivative: a table of integrands with antiderivatives known in
 * closed form (tables of integrals; the reduction formula for cos^n); the
 * result must differ from the known one by a constant (its derivative in x
 * is zero and it does not involve x), and — what the function checks
 * itself — differentiate back to the integrand.  Integrands outside its
 * reach (exp(x), sin(2x), rational in x, a denominator with cos x) must
 * come back "not found", not wrong. */
#include <string.h>

#include "alg_test.h"
#include "hl_test.h"

enum { X = 0, Y = 1 };

static void known(const char *f, const char *F)
{
    hl_alg a, r, want;
    hl_alg_init(&a, ctx);
    hl_alg_init(&r, ctx);
    hl_alg_init(&want, ctx);
    hl_error err;
    int found = 0;
    if (rd(&a, f) == HL_OK && rd(&want, F) == HL_OK) {
        int st = hl_alg_antiderivative(&r, &found, &a, X, ctx, &err);
        CHECK_MSG(st == HL_OK && found, "int %s dx: not found", f);
        if (found) {
            hl_alg_sub(&r, &r, &want, ctx);
            CHECK_MSG(!hl_alg_depends_on(&r, X, ctx), "int %s dx is not %s + const", f, F);
        }
    } else
        CHECK_MSG(0, "cannot read %s or %s", f, F);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&r, ctx);
    hl_alg_clear(&want, ctx);
}

static void not_found(const char *f)
{
    hl_alg a, r;
    hl_alg_init(&a, ctx);
    hl_alg_init(&r, ctx);
    hl_error err;
    int found = 1;
    CHECK(rd(&a, f) == HL_OK);
    int st = hl_alg_antiderivative(&r, &found, &a, X, ctx, &err);
    CHECK_MSG(st == HL_OK && !found, "int %s dx: status %d, found %d", f, st, found);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&r, ctx);
}

int main(void)
{
    const char *names[] = {"x", "y"};
    pool = hl_pool_new();
    ctx = hl_alg_ctx_new(2, names, 32);
    known("x^3", "x^4/4");
    known("y*x", "y*x^2/2");
    known("sin(x)", "-cos(x)");
    known("cos(x)", "sin(x)");
    known("sin(x)^2", "x/2 - sin(x)*cos(x)/2");
    known("cos(x)^2", "x/2 + sin(x)*cos(x)/2");
    known("sin(x)*cos(x)^3", "-cos(x)^4/4");
    known("cos(x)^3", "sin(x) - sin(x)^3/3");
    known("cos(x)^4", "3*x/8 + 3*sin(x)*cos(x)/8 + sin(x)*cos(x)^3/4");
    known("sin(x)^5", "-cos(x) + 2*cos(x)^3/3 - cos(x)^5/5");
    known("cos(x)^6", "5*x/16 + 5*sin(x)*cos(x)/16 + 5*sin(x)*cos(x)^3/24 + sin(x)*cos(x)^5/6");
    known("x*sin(x)", "sin(x) - x*cos(x)");
    known("x^2*cos(x)", "x^2*sin(x) + 2*x*cos(x) - 2*sin(x)");
    known("x*cos(x)^2", "x^2/4 + x*sin(x)*cos(x)/2 + cos(x)^2/4");
    known("(y^2*sin(x)*cos(x) + x)/(1 + y^2)", "(-y^2*cos(x)^2/2 + x^2/2)/(1 + y^2)");
    known("sin(y)*cos(x)", "sin(y)*sin(x)"); /* sin(y) is free of x */
    not_found("exp(x)");
    not_found("sin(2*x)");
    not_found("1/(1 + x^2)");
    not_found("sin(x)/cos(x)");
    not_found("sqrt(x)");
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
    return HL_TEST_END();
}
