/* Error fields v_k on the oscillator H = (p^2 + x^2)/2 to order 8, against
 * closed forms derived by hand (not from the paper's print, not from this
 * code):
 *   explicit Euler: the matrix [[1, D], [-D, 1]] = sqrt(1+D^2) R(atan D);
 *   paper-dg and implicit midpoint: the Cayley map (I - DJ/2)^-1 (I + DJ/2),
 *     a rotation by 2 atan(D/2);
 *   exact-rotation: R(D), every v_k = 0;
 *   rk4: R(D) truncated: (1 - D^2/2 + D^4/24) I + (D - D^3/6) J.
 * Expected v_k(z_i) = k! ([D^k] closed form - [D^k] (x cos D + p sin D, ...)),
 * expanded by hl_series_from_alg (Taylor mode on the formula).  Also the
 * classification of the leading fields: Euler v_2 = x d/dx + p d/dp (scaling
 * by 1: [D^2] of x + D p is 0, of the flow -x/2); midpoint v_3 = -g/2
 * (2 atan(D/2) = D - D^3/12 + ..., so psi - exp = -D^3/12 g + ..., times 3!),
 * Hamiltonian with h = -H/2; rk4 v_5 = -g (the flow's D^5 term g^5 z/120 is
 * missing). */
#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"
#include "analysis_test.h"

#define NORD 8

static int run_errors(hl_vfields *e, hl_system *sys, const char *name, int n)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_scheme *s;
    hl_error err;
    hl_series Z[2];
    hl_series_init(&Z[0], 0, ctx);
    hl_series_init(&Z[1], 0, ctx);
    int st = hl_scheme_new(&s, name, 0, sys, &err);
    if (st == HL_OK)
        st = hl_scheme_expand(Z, s, n + 1, &err);
    if (st == HL_OK)
        st = hl_vfields_compute(e, Z, sys, n, &err);
    if (st != HL_OK)
        fprintf(stderr, "%s: %s\n", name, err.msg);
    hl_scheme_free(s);
    hl_series_clear(&Z[0], ctx);
    hl_series_clear(&Z[1], ctx);
    return st;
}

/* Does v_k match k! ([D^k] closed - [D^k] flow) for k = 2..n? */
static int matches(const hl_vfields *e, hl_system *sys, const char *cx, const char *cp, int n)
{
    static const char *flow[2] = {"x*cos(D) + p*sin(D)", "p*cos(D) - x*sin(D)"};
    const char *closed[2] = {cx, cp};
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg a, d;
    hl_series sc, sf;
    hl_error err;
    fmpq_t f;
    int ok = 1;
    hl_alg_init(&a, ctx);
    hl_alg_init(&d, ctx);
    hl_series_init(&sc, 0, ctx);
    hl_series_init(&sf, 0, ctx);
    fmpq_init(f);
    for (int i = 0; i < 2 && ok; i++) {
        ok = hl_system_read(&a, sys, closed[i], &err) == HL_OK &&
             hl_series_from_alg(&sc, &a, hl_system_var_D(sys), n + 1, ctx, &err) == HL_OK &&
             hl_system_read(&a, sys, flow[i], &err) == HL_OK &&
             hl_series_from_alg(&sf, &a, hl_system_var_D(sys), n + 1, ctx, &err) == HL_OK;
        for (int k = 2; k <= n && ok; k++) {
            fmpq_one(f);
            fmpz_fac_ui(fmpq_numref(f), (ulong)k);
            hl_alg_sub(&d, &sc.c[k], &sf.c[k], ctx);
            hl_alg_scalar_mul_fmpq(&d, &d, f, ctx);
            ok = hl_alg_equal(&d, &hl_vfields_v(e, k)[i], ctx);
            if (!ok)
                fprintf(stderr, "v_%d component %d differs\n", k, i);
        }
    }
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&d, ctx);
    hl_series_clear(&sc, ctx);
    hl_series_clear(&sf, ctx);
    fmpq_clear(f);
    return ok;
}

static int is_const(const hl_alg *a, long num, long den, hl_alg_ctx *ctx)
{
    fmpq_t c, w;
    fmpq_init(c);
    fmpq_init(w);
    fmpq_set_si(w, num, (ulong)den);
    int ok = hl_alg_is_fmpq(a, c, ctx) && fmpq_equal(c, w);
    fmpq_clear(c);
    fmpq_clear(w);
    return ok;
}

int main(void)
{
    hl_system *sys = make_system("(p^2+x^2)/2");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_vfields e;
    hl_errfield F;
    hl_error err;
    const char *rot2 = "x*cos(2*atan(D/2)) + p*sin(2*atan(D/2))",
               *rot2p = "p*cos(2*atan(D/2)) - x*sin(2*atan(D/2))";

    /* explicit Euler */
    CHECK(run_errors(&e, sys, "euler", NORD) == HL_OK);
    CHECK(e.agree);
    CHECK(e.order == 1 && e.leading == 2);
    CHECK(matches(&e, sys, "sqrt(1+D^2)*(x*cos(atan(D)) + p*sin(atan(D)))",
                  "sqrt(1+D^2)*(p*cos(atan(D)) - x*sin(atan(D)))", NORD));
    CHECK(hl_errfield_classify(&F, hl_vfields_v(&e, 2), sys, &err) == HL_OK);
    CHECK(F.kind == HL_ERRFIELD_SCALING);
    CHECK(F.scale != NULL && is_const(&F.scale[0], 1, 1, ctx) && is_const(&F.scale[1], 1, 1, ctx));
    CHECK(!F.hamiltonian); /* divergence 2: not Hamiltonian */
    hl_errfield_clear(&F, sys);
    hl_vfields_clear(&e, sys);

    /* the paper's discrete gradient and implicit midpoint */
    const char *cayley[] = {"paper-dg", "implicit-midpoint"};
    for (int s = 0; s < 2; s++) {
        CHECK(run_errors(&e, sys, cayley[s], NORD) == HL_OK);
        CHECK_MSG(e.agree, "%s", cayley[s]);
        CHECK_MSG(e.order == 2, "%s order %d", cayley[s], e.order);
        CHECK_MSG(matches(&e, sys, rot2, rot2p, NORD), "%s", cayley[s]);
        CHECK(hl_errfield_classify(&F, hl_vfields_v(&e, 3), sys, &err) == HL_OK);
        CHECK(F.kind == HL_ERRFIELD_TIME_SHIFT && is_const(&F.lambda, -1, 2, ctx));
        CHECK(F.hamiltonian && F.have_h);
        hl_alg h;
        hl_alg_init(&h, ctx);
        CHECK(hl_system_read(&h, sys, "-(p^2+x^2)/4", &err) == HL_OK);
        CHECK(hl_alg_equal(&h, &F.h, ctx));
        hl_alg_clear(&h, ctx);
        hl_errfield_clear(&F, sys);
        hl_vfields_clear(&e, sys);
    }

    /* the exact rotation: no error at all */
    CHECK(run_errors(&e, sys, "exact-rotation", NORD) == HL_OK);
    CHECK(e.agree && e.leading == 0 && e.order == NORD);
    for (int k = 2; k <= NORD; k++)
        CHECK(hl_alg_is_zero(&hl_vfields_v(&e, k)[0], ctx) &&
              hl_alg_is_zero(&hl_vfields_v(&e, k)[1], ctx));
    hl_vfields_clear(&e, sys);

    /* RK4 */
    CHECK(run_errors(&e, sys, "rk4", NORD) == HL_OK);
    CHECK(e.agree && e.order == 4);
    CHECK(matches(&e, sys, "(1 - D^2/2 + D^4/24)*x + (D - D^3/6)*p",
                  "(1 - D^2/2 + D^4/24)*p - (D - D^3/6)*x", NORD));
    CHECK(hl_errfield_classify(&F, hl_vfields_v(&e, 5), sys, &err) == HL_OK);
    CHECK(F.kind == HL_ERRFIELD_TIME_SHIFT && is_const(&F.lambda, -1, 1, ctx));
    hl_errfield_clear(&F, sys);
    hl_vfields_clear(&e, sys);

    hl_system_free(sys);
    return HL_TEST_END();
}
