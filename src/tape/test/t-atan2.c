/* atan2(y, x) through every numeric back end, in all four quadrants and on
 * the axes, against libm (an independent implementation) and mpmath:
 *   values: hl_expr_eval_d, the tape interpreter and its libgccjit code,
 *     bitwise libm's atan2; the Arb interpreter, a ball around mpmath's
 *     30-digit value.  On the axes and the cut (y = 0, x < 0) the double
 *     back ends return what C99 Annex F says: atan2(+0, -1) = pi,
 *     atan2(-0, -1) = -pi, atan2(+-0, 0) = +-0 (no error).  Arb has no
 *     signed zero and returns pi on the whole cut, 0 at the origin;
 *   derivatives: hl_expr_diff against x/(x^2+y^2) and -y/(x^2+y^2);
 *   Taylor coefficients along the lines (y0 + t/4, x0 - t/2) through each
 *   quadrant, against mpmath.taylor (hl_expr_taylor, tape Taylor mode in
 *   double and in Arb), and along the circle (r cos(phi + t), r sin(phi + t)),
 *   where atan2 is phi + t, by the ODE recursion s' = atan2(y, x): s = phi t
 *   + t^2/2, interpreted and compiled (libgccjit and the system compiler). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"

static hl_pool *P;
static const char *const yx[] = {"y", "x"};

static const hl_expr *parse(const char *s)
{
    const hl_expr *e = NULL;
    hl_error err;
    CHECK_MSG(hl_parse(&e, P, s, &err) == HL_OK, "%s: %s", s, err.msg);
    return e;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* the quadrants: mpmath.atan2 to 25 digits */
static const struct {
    double y, x;
    const char *mp;
} quad[] = {
    {0.5, 0.75, "0.5880026035475675512456111"},
    {0.5, -0.75, "2.553590050042225687217032"},
    {-0.5, -0.75, "-2.553590050042225687217032"},
    {-0.5, 0.75, "-0.5880026035475675512456111"},
};

/* the axes, the cut and the origin: the values of C99 Annex F */
static const struct {
    double y, x, want;
} axis[] = {
    {1, 0, M_PI / 2}, {-1, 0, -M_PI / 2}, {0.0, 1, 0.0},  {-0.0, 1, -0.0},
    {0.0, -1, M_PI},  {-0.0, -1, -M_PI},  {0.0, 0.0, 0.0}, {-0.0, -0.0, -M_PI},
};

/* Arb on the axes: pi/2 sgn(y) on x = 0, 0 on y = 0, x >= 0, and pi on the
 * whole cut y = 0, x < 0 (no signed zero) */
static void arb_axis_value(arb_t r, double y, double x)
{
    arb_zero(r);
    if (y != 0 || x < 0)
        arb_const_pi(r, 128);
    if (y != 0)
        arb_mul_2exp_si(r, r, -1);
    if (y < 0)
        arb_neg(r, r);
}

static void test_values(void)
{
    const hl_expr *e = parse("atan2(y, x)");
    hl_tape *t = NULL, *tj = NULL;
    hl_error err;
    CHECK(hl_tape_new(&t, &e, 1, yx, 2, &err) == HL_OK);
    CHECK(hl_tape_new(&tj, &e, 1, yx, 2, &err) == HL_OK);
    int jit = hl_tape_jit(tj, &err) == HL_OK;
    if (!jit)
        printf("jit skipped: %s\n", err.msg);
    arb_t out, want;
    arb_init(out), arb_init(want);
    arb_ptr inv = _arb_vec_init(2);
    int n = (int)(sizeof quad / sizeof *quad) + (int)(sizeof axis / sizeof *axis);
    for (int i = 0; i < n; i++) {
        int q = i < 4;
        double v[2] = {q ? quad[i].y : axis[i - 4].y, q ? quad[i].x : axis[i - 4].x};
        double ref = atan2(v[0], v[1]), a = NAN, b = NAN, c = NAN;
        if (!q)
            CHECK_MSG(same_bits(ref, axis[i - 4].want), "libm atan2(%g, %g) = %g", v[0], v[1], ref);
        CHECK(hl_expr_eval_d(&a, e, 2, yx, v, &err) == HL_OK);
        hl_tape_eval_d(&b, v, t);
        if (jit)
            hl_tape_eval_d(&c, v, tj);
        CHECK_MSG(same_bits(a, ref) && same_bits(b, ref) && (!jit || same_bits(c, ref)),
                  "atan2(%g, %g): expr %.17g, tape %.17g, jit %.17g, libm %.17g", v[0], v[1], a,
                  b, c, ref);
        arb_set_d(inv + 0, v[0]);
        arb_set_d(inv + 1, v[1]);
        hl_tape_eval_arb(out, inv, 128, t);
        if (q) {
            char s[64];
            snprintf(s, sizeof s, "[%s +/- 1e-24]", quad[i].mp);
            arb_set_str(want, s, 128);
        } else {
            arb_axis_value(want, v[0], v[1]);
        }
        CHECK_MSG(arb_overlaps(out, want) && mag_cmp_2exp_si(arb_radref(out), -100) < 0,
                  "Arb atan2(%g, %g) = %s", v[0], v[1], arb_get_str(out, 30, 0));
    }
    _arb_vec_clear(inv, 2);
    arb_clear(out), arb_clear(want);
    hl_tape_free(t);
    hl_tape_free(tj);
}

static void test_derivatives(void)
{
    const hl_expr *e = parse("atan2(y, x)");
    const hl_expr *dy = hl_expr_diff(P, e, "y"), *dx = hl_expr_diff(P, e, "x");
    hl_error err;
    for (int i = 0; i < 4 + 2; i++) { /* the quadrants and two axis points */
        double v[2] = {i < 4 ? quad[i].y : 0, i < 4 ? quad[i].x : (i == 4 ? -2 : 3)};
        double r2 = v[0] * v[0] + v[1] * v[1], a = NAN, b = NAN;
        CHECK(hl_expr_eval_d(&a, dy, 2, yx, v, &err) == HL_OK);
        CHECK(hl_expr_eval_d(&b, dx, 2, yx, v, &err) == HL_OK);
        CHECK_MSG(fabs(a - v[1] / r2) < 1e-15 && fabs(b + v[0] / r2) < 1e-15,
                  "d atan2 at (%g, %g): %g %g", v[0], v[1], a, b);
    }
}

/* mpmath.taylor(lambda t: atan2(y0 + t/4, x0 - t/2), 0, 8) */
static const double line[4][9] = {
    {0.58800260354756755125, 0.53846153846153846154, 0.16568047337278106509,
     -0.0010620543164921863147, -0.032351808410069675432, -0.015681954682689951063,
     0.00025330744735635212967, 0.0044418420279159744923, 0.0023186916359865769969},
    {2.5535900500422256872, 0.076923076923076923077, -0.04733727810650887574,
     0.028978910635715369443, -0.01764644095094709569, 0.010687516328075132039,
     -0.0064368267593213929396, 0.0038543676999228068268, -0.0022940805731895440039},
    {-2.5535900500422256872, -0.53846153846153846154, 0.16568047337278106509,
     0.0010620543164921863147, -0.032351808410069675432, 0.015681954682689951063,
     0.00025330744735635212967, -0.0044418420279159744923, 0.0023186916359865769969},
    {-0.58800260354756755125, -0.076923076923076923077, -0.04733727810650887574,
     -0.028978910635715369443, -0.01764644095094709569, -0.010687516328075132039,
     -0.0064368267593213929396, -0.0038543676999228068268, -0.0022940805731895440039},
};

static void test_taylor_lines(void)
{
    enum { K = 8, S = K + 1 };
    const hl_expr *e = parse("atan2(y, x)");
    hl_tape *t = NULL;
    hl_error err;
    CHECK(hl_tape_new(&t, &e, 1, yx, 2, &err) == HL_OK);
    arb_ptr ain = _arb_vec_init(2 * S), aout = _arb_vec_init(S);
    for (int i = 0; i < 4; i++) {
        double in[2 * S] = {0}, out[S];
        in[0] = quad[i].y, in[1] = 0.25;
        in[S] = quad[i].x, in[S + 1] = -0.5;
        hl_tape_taylor_d(out, in, K, t);
        for (int k = 0; k < 2 * S; k++)
            arb_set_d(ain + k, in[k]);
        hl_tape_taylor_arb(aout, ain, K, 128, t);
        char src[96];
        snprintf(src, sizeof src, "atan2(%g + t/4, %g - t/2)", quad[i].y, quad[i].x);
        const hl_expr *c[S];
        hl_expr_taylor(c, P, parse(src), "t", hl_num_si(P, 0), K);
        for (int k = 0; k <= K; k++) {
            double want = line[i][k], ce = NAN, ca = arf_get_d(arb_midref(aout + k), ARF_RND_NEAR);
            CHECK(hl_expr_eval_d(&ce, c[k], 0, NULL, NULL, &err) == HL_OK);
            CHECK_MSG(fabs(out[k] - want) < 1e-15 && fabs(ce - want) < 1e-15 &&
                          fabs(ca - want) < 1e-18,
                      "quadrant %d, t^%d: tape %.17g, expr %.17g, Arb %.17g, mpmath %.17g", i, k,
                      out[k], ce, ca, want);
        }
    }
    _arb_vec_clear(ain, 2 * S);
    _arb_vec_clear(aout, S);
    hl_tape_free(t);
}

/* x' = -y, y' = x, s' = atan2(y, x) from (r cos phi, r sin phi, 0):
 * s = phi t + t^2/2 while |phi + t| < pi.  Interpreted, then compiled. */
static void test_taylor_circle(const char *backend)
{
    enum { K = 14, S = K + 1 };
    static const char *const xys[] = {"x", "y", "s"};
    const hl_expr *f[3] = {parse("-y"), parse("x"), parse("atan2(y, x)")};
    static const double phi[] = {0.7, 2.4, -2.4, -0.7};
    for (int pass = 0; pass < 2; pass++) {
        hl_tape *t = NULL;
        hl_error err;
        CHECK(hl_tape_new(&t, f, 3, xys, 3, &err) == HL_OK);
        if (pass == 1) {
            int st = hl_tape_native(t, K, &err);
            if (st == HL_EUNSUP) {
                printf("%s skipped: %s\n", backend, err.msg);
                hl_tape_free(t);
                return;
            }
            CHECK_MSG(st == HL_OK, "%s: %s", backend, err.msg);
        }
        for (int i = 0; i < 4; i++) {
            double z[3 * S] = {0};
            z[0] = 1.5 * cos(phi[i]), z[S] = 1.5 * sin(phi[i]);
            CHECK(hl_tape_taylor_ode_d(z, K, t, &err) == HL_OK);
            int bad = 0;
            for (int k = 0; k <= K; k++) {
                double want = k == 1 ? phi[i] : k == 2 ? 0.5 : 0;
                bad += !(fabs(z[2 * S + k] - want) < 4e-15);
            }
            CHECK_MSG(bad == 0, "%s%s, phi = %g: %d coefficients of s wrong (s1 %.17g, s2 %.17g, "
                      "s3 %.3g)", pass ? "compiled by " : "interpreted", pass ? backend : "",
                      phi[i], bad, z[2 * S + 1], z[2 * S + 2], z[2 * S + 3]);
        }
        hl_tape_free(t);
    }
}

int main(void)
{
    P = hl_pool_new();
    test_values();
    test_derivatives();
    test_taylor_lines();
    unsetenv("HL_CC");
    test_taylor_circle(hl_tape_jit_available() ? "libgccjit" : "cc");
    setenv("HL_CC", "cc", 1);
    test_taylor_circle("cc");
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
