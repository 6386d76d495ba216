/* A user's action-angle map, verified:
 *   the oscillator's map (theta = atan2(x, p), I = (x^2+p^2)/2, x = sqrt(2I)
 *     sin theta, p = sqrt(2I) cos theta, nu = 1) passes, and its scheme
 *     equals x cos D + p sin D, p cos D - x sin D at points in all four
 *     quadrants and on the axes (evaluated, against the rotation by hand);
 *   the paper's angle atan(x/p), an inverse for p > 0 only, is rejected;
 *   the oscillator with frequency 2 (H = (p^2 + 4x^2)/2) with its map;
 *   wrong maps rejected with the failing condition named: I scaled
 *     ({theta, I} = 1), I not an integral, a wrong nu, a wrong inverse;
 *   malformed input (missing item, unknown item). */
#include <math.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/exact.h"

static hl_system *sys_new(const char *H)
{
    hl_system *s = NULL;
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    int st = hl_system_new(&s, &spec, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, err.msg);
    return s;
}

static void verify(const char *H, const char *map, const char *want_fail)
{
    hl_system *s = sys_new(H);
    hl_exact_aa aa;
    hl_error err;
    int st = hl_exact_aa_read(&aa, s, map, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    int ok = -1;
    char why[256];
    if (st == HL_OK)
        CHECK_MSG(hl_exact_aa_verify(&ok, why, sizeof why, &aa, s, &err) == HL_OK, "%s",
                  err.msg);
    if (want_fail == NULL)
        CHECK_MSG(ok == 1, "%s: %s", map, why);
    else
        CHECK_MSG(ok == 0 && strstr(why, want_fail) != NULL, "%s: got '%s'", map, why);
    hl_system_free(s);
}

static void test_scheme(void)
{
    hl_system *s = sys_new("(p^2+x^2)/2");
    hl_alg_ctx *ctx = hl_system_ctx(s);
    hl_exact_aa aa;
    hl_error err;
    CHECK(hl_exact_aa_read(&aa, s,
                           "theta = atan2(x, p); I = (x^2+p^2)/2; x = sqrt(2*I)*sin(theta); "
                           "p = sqrt(2*I)*cos(theta); nu = 1",
                           &err) == HL_OK);
    hl_alg *im = hl_alg_vec_new(2, ctx);
    CHECK_MSG(hl_exact_aa_scheme(im, &aa, s, &err) == HL_OK, "%s", err.msg);
    static const double pts[][3] = {{0.3, 0.8, 0.5},   {-1.2, 0.4, 2.0}, {0.7, 2.0, -3.1},
                                    {-0.6, -0.9, 1.3}, {0.5, -0.3, -0.7}, {-0.8, 0, 0.9},
                                    {0.8, 0, -2.2},    {0, -0.7, 2.5},   {0, 0.4, 0.3}};
    for (int i = 0; i < (int)(sizeof pts / sizeof *pts); i++) {
        double x = pts[i][0], p = pts[i][1], D = pts[i][2];
        arb_ptr v = _arb_vec_init(hl_alg_ctx_nbase(ctx));
        arb_set_d(v + hl_system_var_q(s, 0), x);
        arb_set_d(v + hl_system_var_p(s, 0), p);
        arb_set_d(v + hl_system_var_D(s), D);
        arb_t r;
        arb_init(r);
        CHECK(hl_alg_eval_arb(r, &im[0], v, 128, ctx, &err) == HL_OK);
        double X = arf_get_d(arb_midref(r), ARF_RND_NEAR);
        CHECK(hl_alg_eval_arb(r, &im[1], v, 128, ctx, &err) == HL_OK);
        double P = arf_get_d(arb_midref(r), ARF_RND_NEAR);
        CHECK_MSG(fabs(X - (x * cos(D) + p * sin(D))) < 1e-14, "X %g", X);
        CHECK_MSG(fabs(P - (p * cos(D) - x * sin(D))) < 1e-14, "P %g", P);
        arb_clear(r);
        _arb_vec_clear(v, hl_alg_ctx_nbase(ctx));
    }
    hl_alg_vec_free(im, 2, ctx);
    hl_system_free(s);
}

int main(void)
{
    const char *osc = "(p^2+x^2)/2";
    verify(osc,
           "theta = atan2(x, p); I = (x^2+p^2)/2; x = sqrt(2*I)*sin(theta); "
           "p = sqrt(2*I)*cos(theta); nu = 1",
           NULL);
    /* the paper's angle: right for p > 0, x sign(p) for p < 0 */
    verify(osc,
           "theta = atan(x/p); I = (x^2+p^2)/2; x = sqrt(2*I)*sin(theta); "
           "p = sqrt(2*I)*cos(theta); nu = 1",
           "the inverse fails");
    verify("(p^2+4*x^2)/2",
           "theta = atan2(2*x, p); I = (p^2+4*x^2)/4; x = sqrt(I)*sin(theta); "
           "p = 2*sqrt(I)*cos(theta); nu = 2",
           NULL);
    verify(osc,
           "theta = atan(x/p); I = x^2+p^2; x = sqrt(I)*sin(theta); "
           "p = sqrt(I)*cos(theta); nu = 1",
           "{theta, I} = 1");
    verify(osc,
           "theta = x; I = p; x = theta; p = I; nu = 1", "{I, H} = 0");
    verify(osc,
           "theta = atan(x/p); I = (x^2+p^2)/2; x = sqrt(2*I)*sin(theta); "
           "p = sqrt(2*I)*cos(theta); nu = 2",
           "{theta, H} = nu(I)");
    verify(osc,
           "theta = atan(x/p); I = (x^2+p^2)/2; x = sqrt(2*I)*cos(theta); "
           "p = sqrt(2*I)*sin(theta); nu = 1",
           "the inverse");
    /* malformed */
    hl_system *s = sys_new(osc);
    hl_exact_aa aa;
    hl_error err;
    CHECK(hl_exact_aa_read(&aa, s, "theta = x; I = p", &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "lacks") != NULL);
    CHECK(hl_exact_aa_read(&aa, s, "theta = x; J = p", &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "unknown item 'J'") != NULL);
    hl_system_free(s);
    test_scheme();
    flint_cleanup();
    return HL_TEST_END();
}
