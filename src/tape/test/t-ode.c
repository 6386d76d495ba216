/* Taylor coefficients of ODE solutions (hl_tape_taylor_ode_*):
 *   oscillator q' = p, p' = -q: closed form q cos t + p sin t;
 *   pendulum q' = p, p' = -sin q: hand-derived Lie-series coefficients up to
 *     t^5, and the whole series summed at t = 0.2 against a fine RK4 run;
 *   Kepler: double against Arb at 256 bits, first coefficients by hand, and
 *     energy conservation of the summed series. */
#include <math.h>
#include <stdlib.h>

#include "hl_test.h"
#include "hamlie/tape.h"

static hl_pool *P;

static hl_tape *tape(const hl_expr *const *f, const char *const *names, int n)
{
    hl_tape *t = NULL;
    hl_error err;
    int st = hl_tape_new(&t, f, n, names, n, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    return t;
}

static double horner(const double *c, int K, double t)
{
    double s = c[K];
    for (int k = K - 1; k >= 0; k--)
        s = s * t + c[k];
    return s;
}

static void test_oscillator(void)
{
    const char *names[] = {"q", "p"};
    const hl_expr *q = hl_sym(P, "q"), *p = hl_sym(P, "p");
    const hl_expr *f[] = {p, hl_neg(P, q)};
    hl_tape *t = tape(f, names, 2);
    enum { K = 30, S = K + 1 };
    double z[2 * S] = {0};
    z[0] = 0.3;
    z[S] = -0.8;
    hl_error err;
    CHECK(hl_tape_taylor_ode_d(z, K, t, &err) == HL_OK);
    arb_ptr za = _arb_vec_init(2 * S);
    arb_set_si(za, 3);
    arb_div_si(za, za, 10, 300);
    arb_set_si(za + S, -8);
    arb_div_si(za + S, za + S, 10, 300);
    CHECK(hl_tape_taylor_ode_arb(za, K, 300, t, &err) == HL_OK);
    double fact = 1;
    int bad = 0;
    for (int k = 0; k <= K; k++) {
        if (k > 0)
            fact *= k;
        double sg = (k / 2) % 2 ? -1 : 1;
        /* q = x cos t + p sin t, p = p cos t - x sin t */
        double wq = (k % 2 == 0 ? 0.3 : -0.8) * sg / fact;
        double wp = (k % 2 == 0 ? -0.8 : -0.3) * sg / fact;
        if (fabs(z[k] - wq) > 1e-15 * fabs(wq) || fabs(z[S + k] - wp) > 1e-15 * fabs(wp))
            bad++;
        double aq = arf_get_d(arb_midref(za + k), ARF_RND_NEAR);
        double ap = arf_get_d(arb_midref(za + S + k), ARF_RND_NEAR);
        if (fabs(aq - wq) > 1e-15 * fabs(wq) || fabs(ap - wp) > 1e-15 * fabs(wp))
            bad++;
    }
    CHECK_MSG(bad == 0, "oscillator: %d coefficients wrong", bad);
    /* a non-square tape is refused */
    hl_tape *t1 = NULL;
    CHECK(hl_tape_new(&t1, f, 1, names, 2, &err) == HL_OK);
    CHECK(t1 && hl_tape_taylor_ode_d(z, K, t1, &err) == HL_EINVAL);
    hl_tape_free(t1);
    _arb_vec_clear(za, 2 * S);
    hl_tape_free(t);
}

static void rk4_pendulum(double *q, double *p, double T, int n)
{
    double h = T / n;
    for (int i = 0; i < n; i++) {
        double q1 = *q, p1 = *p;
        double kq1 = p1, kp1 = -sin(q1);
        double kq2 = p1 + h / 2 * kp1, kp2 = -sin(q1 + h / 2 * kq1);
        double kq3 = p1 + h / 2 * kp2, kp3 = -sin(q1 + h / 2 * kq2);
        double kq4 = p1 + h * kp3, kp4 = -sin(q1 + h * kq3);
        *q = q1 + h / 6 * (kq1 + 2 * kq2 + 2 * kq3 + kq4);
        *p = p1 + h / 6 * (kp1 + 2 * kp2 + 2 * kp3 + kp4);
    }
}

static void test_pendulum(void)
{
    const char *names[] = {"q", "p"};
    const hl_expr *q = hl_sym(P, "q"), *p = hl_sym(P, "p");
    const hl_expr *f[] = {p, hl_neg(P, hl_call(P, HL_SIN, q))};
    hl_tape *t = tape(f, names, 2);
    enum { K = 30, S = K + 1 };
    const double q0 = 1.3, p0 = 0.4;
    double z[2 * S] = {0};
    z[0] = q0;
    z[S] = p0;
    hl_error err;
    CHECK(hl_tape_taylor_ode_d(z, K, t, &err) == HL_OK);
    /* by hand: q'' = -sin q, q''' = -p cos q, q'''' = sin q cos q + p^2 sin q,
     * q^(5) = p cos^2 q - 3 p sin^2 q + p^3 cos q; q^[k] = q^(k)/k!; p^[k] = (k+1) q^[k+1] */
    double s = sin(q0), c = cos(q0);
    double want[6] = {q0, p0, -s / 2, -p0 * c / 6, (s * c + p0 * p0 * s) / 24,
                      (p0 * c * c - 3 * p0 * s * s + p0 * p0 * p0 * c) / 120};
    for (int k = 0; k < 6; k++)
        CHECK_MSG(fabs(z[k] - want[k]) < 1e-15, "pendulum q^[%d] = %.17g, want %.17g", k, z[k], want[k]);
    for (int k = 0; k < 5; k++)
        CHECK_MSG(fabs(z[S + k] - (k + 1) * want[k + 1]) < 1e-15, "pendulum p^[%d]", k);
    /* the whole series against RK4 with 4000 steps to t = 0.2 (error ~1e-17) */
    double qr = q0, pr = p0;
    rk4_pendulum(&qr, &pr, 0.2, 4000);
    CHECK_MSG(fabs(horner(z, K, 0.2) - qr) < 1e-13, "q(0.2): series %.17g rk4 %.17g",
              horner(z, K, 0.2), qr);
    CHECK(fabs(horner(z + S, K, 0.2) - pr) < 1e-13);
    /* Arb at 200 bits agrees */
    arb_ptr za = _arb_vec_init(2 * S);
    arb_set_d(za, q0);
    arb_set_d(za + S, p0);
    CHECK(hl_tape_taylor_ode_arb(za, K, 200, t, &err) == HL_OK);
    int bad = 0;
    for (int k = 0; k < 2 * S; k++)
        if (fabs(arf_get_d(arb_midref(za + k), ARF_RND_NEAR) - z[k]) > 1e-15 * (fabs(z[k]) + 1e-3)
            || mag_cmp_2exp_si(arb_radref(za + k), -150) > 0)
            bad++;
    CHECK_MSG(bad == 0, "pendulum: %d arb coefficients disagree", bad);
    _arb_vec_clear(za, 2 * S);
    hl_tape_free(t);
}

static void test_kepler(void)
{
    const char *names[] = {"x", "y", "px", "py"};
    const hl_expr *x = hl_sym(P, "x"), *y = hl_sym(P, "y");
    const hl_expr *r2 = hl_add(P, hl_pow(P, x, hl_num_si(P, 2)), hl_pow(P, y, hl_num_si(P, 2)));
    const hl_expr *r3i = hl_pow(P, r2, hl_num_frac(P, -3, 2));
    const hl_expr *f[] = {hl_sym(P, "px"), hl_sym(P, "py"), hl_neg(P, hl_mul(P, x, r3i)),
                          hl_neg(P, hl_mul(P, y, r3i))};
    hl_tape *t = tape(f, names, 4);
    enum { K = 25, S = K + 1 };
    double z[4 * S] = {0};
    z[0] = 0.5;
    z[3 * S] = sqrt(3);
    hl_error err;
    CHECK(hl_tape_taylor_ode_d(z, K, t, &err) == HL_OK);
    /* by hand: px^[1] = -x/r^3 = -4, x^[2] = -2, y^[1] = sqrt 3, py^[1] = 0 */
    CHECK(fabs(z[2 * S + 1] + 4) < 1e-15 && fabs(z[2] + 2) < 1e-15);
    CHECK(fabs(z[S + 1] - sqrt(3)) < 1e-15 && z[3 * S + 1] == 0);
    arb_ptr za = _arb_vec_init(4 * S);
    arb_set_d(za, 0.5);
    arb_set_d(za + 3 * S, sqrt(3)); /* the same double start */
    CHECK(hl_tape_taylor_ode_arb(za, K, 256, t, &err) == HL_OK);
    int bad = 0;
    for (int k = 0; k <= K; k++) {
        double scale = 0;
        for (int i = 0; i < 4; i++)
            scale = fmax(scale, fabs(z[i * S + k]));
        for (int i = 0; i < 4; i++) {
            double a = arf_get_d(arb_midref(za + i * S + k), ARF_RND_NEAR);
            if (fabs(a - z[i * S + k]) > 1e-13 * scale)
                bad++;
        }
    }
    CHECK_MSG(bad == 0, "kepler: %d coefficients differ from Arb", bad);
    /* energy of the summed series at t = 0.05 */
    double v[4];
    for (int i = 0; i < 4; i++)
        v[i] = horner(z + i * S, K, 0.05);
    double H = (v[2] * v[2] + v[3] * v[3]) / 2 - 1 / hypot(v[0], v[1]);
    CHECK_MSG(fabs(H + 0.5) < 1e-14, "kepler energy %.17g", H);
    _arb_vec_clear(za, 4 * S);
    hl_tape_free(t);
}

int main(void)
{
    P = hl_pool_new();
    test_oscillator();
    test_pendulum();
    test_kepler();
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
