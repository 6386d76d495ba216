/* Substitution: eval(subst(f, x -> g)) at P = eval(f) at (g(P), ...), and
 * composition of maps: substituting twice = substituting the composed map. */
#include <math.h>
#include <stdlib.h>

#include "hamlie/alg.h"
#include "hl_test.h"
#include "alg_test.h"

#define PREC 256



static int close_to(const arb_t a, const arb_t b)
{
    arb_t d;
    arb_init(d);
    arb_sub(d, a, b, PREC);
    double x = fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR));
    double m = fabs(arf_get_d(arb_midref(a), ARF_RND_NEAR));
    arb_clear(d);
    return x <= 1e-60 * (1 + m);
}

int main(void)
{
    const char *names[] = {"x", "y", "q", "p"};
    pool = hl_pool_new();
    ctx = hl_alg_ctx_new(4, names, 64);
    const char *fs[] = {"x^2*y - p/(q + 1)", "sqrt(x^2 + y^2) + p^2/2", "sin(q)*p - cos(q)^2",
                        "exp(x*y)/(1 + x^2)", "log(x + 2)*sqrt(1 + sqrt(y))", "x^(1/3) + atan(q*p)",
                        "1/sqrt(x^2+y^2) - q"};
    /* the map: x -> x + q*y, y -> y/(1 + p^2), q -> q + p/3 (p unchanged) */
    const char *map[] = {"x + q*y", "y/(1 + p^2)", "q + p/3"};
    int vars[] = {0, 1, 2};
    hl_alg *img = hl_alg_vec_new(3, ctx), *img2 = hl_alg_vec_new(3, ctx);
    for (int i = 0; i < 3; i++)
        rd(&img[i], map[i]);
    hl_alg f, g, h, k;
    hl_alg_init(&f, ctx);
    hl_alg_init(&g, ctx);
    hl_alg_init(&h, ctx);
    hl_alg_init(&k, ctx);
    arb_ptr P = _arb_vec_init(4), Q = _arb_vec_init(4);
    arb_t a, b;
    arb_init(a);
    arb_init(b);
    hl_error err;
    for (size_t i = 0; i < sizeof fs / sizeof fs[0]; i++) {
        rd(&f, fs[i]);
        int st = hl_alg_subst(&g, &f, 3, vars, img, ctx, &err);
        CHECK_MSG(st == HL_OK && hl_alg_is_canonical(&g, ctx), "subst %s", fs[i]);
        for (int pt = 0; pt < 3; pt++) {
            for (int v = 0; v < 4; v++)
                arb_set_d(P + v, 0.15 + 0.1 * v + 0.13 * pt);
            for (int v = 0; v < 3; v++)
                CHECK(hl_alg_eval_arb(Q + v, &img[v], P, PREC, ctx, NULL) == HL_OK);
            arb_set(Q + 3, P + 3);
            CHECK(hl_alg_eval_arb(a, &g, P, PREC, ctx, NULL) == HL_OK);
            CHECK(hl_alg_eval_arb(b, &f, Q, PREC, ctx, NULL) == HL_OK);
            CHECK_MSG(close_to(a, b), "subst then eval, %s, point %d", fs[i], pt);
        }
        /* composition: f(M(M(.))) two ways */
        for (int v = 0; v < 3; v++)
            CHECK(hl_alg_subst(&img2[v], &img[v], 3, vars, img, ctx, NULL) == HL_OK);
        CHECK(hl_alg_subst(&h, &g, 3, vars, img, ctx, NULL) == HL_OK);
        CHECK(hl_alg_subst(&k, &f, 3, vars, img2, ctx, NULL) == HL_OK);
        CHECK_MSG(hl_alg_equal(&h, &k, ctx), "composition, %s", fs[i]);
        /* identity map and a polynomial map (FLINT composition path) */
        hl_alg *id = hl_alg_vec_new(3, ctx);
        for (int v = 0; v < 3; v++)
            hl_alg_gen(&id[v], v, ctx);
        CHECK(hl_alg_subst(&h, &f, 3, vars, id, ctx, NULL) == HL_OK);
        CHECK(fmpz_mpoly_equal(h.num, f.num, hl_alg_ctx_mpoly(ctx))
              && fmpz_mpoly_equal(h.den, f.den, hl_alg_ctx_mpoly(ctx)));
        hl_alg_vec_free(id, 3, ctx);
    }
    /* substitution hitting a zero denominator is a status */
    rd(&f, "1/(x - y)");
    hl_alg_gen(&g, 1, ctx);
    CHECK(hl_alg_subst(&h, &f, 1, vars, &g, ctx, &err) == HL_EDOM);
    /* sin(q) with q -> -q is -sin(q); sqrt(x^2+y^2) with x -> 0, y -> 3 is 3 */
    rd(&f, "sin(q)");
    rd(&g, "-q");
    CHECK(hl_alg_subst(&h, &f, 1, vars + 2, &g, ctx, NULL) == HL_OK);
    rd(&k, "-sin(q)");
    CHECK(fmpz_mpoly_equal(h.num, k.num, hl_alg_ctx_mpoly(ctx)));
    rd(&f, "sqrt(x^2+y^2)");
    hl_alg_set_si(&img2[0], 0, ctx);
    hl_alg_set_si(&img2[1], 3, ctx);
    CHECK(hl_alg_subst(&h, &f, 2, vars, img2, ctx, NULL) == HL_OK);
    fmpq_t c;
    fmpq_init(c);
    CHECK(hl_alg_is_fmpq(&h, c, ctx) && fmpz_equal_si(fmpq_numref(c), 3)
          && fmpz_is_one(fmpq_denref(c)));
    fmpq_clear(c);

    arb_clear(a);
    arb_clear(b);
    _arb_vec_clear(P, 4);
    _arb_vec_clear(Q, 4);
    hl_alg_clear(&f, ctx);
    hl_alg_clear(&g, ctx);
    hl_alg_clear(&h, ctx);
    hl_alg_clear(&k, ctx);
    hl_alg_vec_free(img, 3, ctx);
    hl_alg_vec_free(img2, 3, ctx);
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
    return HL_TEST_END();
}
