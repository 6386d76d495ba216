/* Pendulum H = p^2/2 - cos q: the Lie series of q and p to order 6.
 *
 * Hand derivation, with g = p d/dq - sin q d/dp (so g q = p, g p = -sin q,
 * g sin q = p cos q, g cos q = -p sin q):
 *   g q   = p
 *   g^2 q = -sin q
 *   g^3 q = -p cos q
 *   g^4 q = -(g p) cos q - p g(cos q) = sin q cos q + p^2 sin q
 *   g^5 q = p (cos^2 q - sin^2 q) + 2 p (-sin q) sin q + p^3 cos q
 *         = p cos^2 q - 3 p sin^2 q + p^3 cos q
 *   g^6 q = g(p cos^2 q) + g(-3 p sin^2 q) + g(p^3 cos q)
 *         = (-sin q cos^2 q - 2 p^2 sin q cos q) + (3 sin^3 q - 6 p^2 sin q cos q)
 *           + (-3 p^2 sin q cos q - p^4 sin q)
 *         = -sin q cos^2 q + 3 sin^3 q - 11 p^2 sin q cos q - p^4 sin q
 *   g^7 q = (-p cos^3 q + 2 p sin^2 q cos q) + 9 p sin^2 q cos q
 *           + (22 p sin^2 q cos q - 11 p^3 cos^2 q + 11 p^3 sin^2 q)
 *           + (4 p^3 sin^2 q - p^5 cos q)
 *         = -p cos^3 q + 33 p sin^2 q cos q - 11 p^3 cos^2 q + 15 p^3 sin^2 q - p^5 cos q
 * and g^k p = g^{k+1} q.  The expected values are written below in this
 * form (with sin^2 q, not reduced), so the comparison also exercises the
 * relation sin^2 + cos^2 = 1.
 *
 * Second way: the order-6 series evaluated at D = h must match the exact flow
 * (RK4 with 20000 steps, error ~1e-17) to O(h^7): the error at h = 0.1 is
 * below 1e-8, and halving h divides it by about 2^7 = 128. */
#include <math.h>

#include "ham_test.h"

static const char *gq[8] = {
    "q",
    "p",
    "-sin(q)",
    "-p*cos(q)",
    "sin(q)*cos(q) + p^2*sin(q)",
    "p*cos(q)^2 - 3*p*sin(q)^2 + p^3*cos(q)",
    "-sin(q)*cos(q)^2 + 3*sin(q)^3 - 11*p^2*sin(q)*cos(q) - p^4*sin(q)",
    "-p*cos(q)^3 + 33*p*sin(q)^2*cos(q) - 11*p^3*cos(q)^2 + 15*p^3*sin(q)^2 - p^5*cos(q)",
};

static void rk4(double *q, double *p, double t, int n)
{
    double h = t / n;
    for (int i = 0; i < n; i++) {
        double q0 = *q, p0 = *p;
        double k1q = p0, k1p = -sin(q0);
        double k2q = p0 + h / 2 * k1p, k2p = -sin(q0 + h / 2 * k1q);
        double k3q = p0 + h / 2 * k2p, k3p = -sin(q0 + h / 2 * k2q);
        double k4q = p0 + h * k3p, k4p = -sin(q0 + h * k3q);
        *q = q0 + h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
        *p = p0 + h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
    }
}

static double eval(const hl_alg *a, hl_system *sys, double q, double p, double D)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    arb_ptr v = _arb_vec_init(3);
    arb_t r;
    arb_init(r);
    arb_set_d(v + hl_system_var_q(sys, 0), q);
    arb_set_d(v + hl_system_var_p(sys, 0), p);
    arb_set_d(v + hl_system_var_D(sys), D);
    double out = NAN;
    if (hl_alg_eval_arb(r, a, v, 128, ctx, NULL) == HL_OK)
        out = arf_get_d(arb_midref(r), ARF_RND_NEAR);
    arb_clear(r);
    _arb_vec_clear(v, 3);
    return out;
}

int main(void)
{
    hl_system *sys = sys_new("p^2/2 - cos(q)", NULL);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    CHECK(hl_system_ndof(sys) == 1 && hl_system_nparams(sys) == 0);
    hl_alg *t = hl_alg_vec_new(8, ctx), phi, sq, sp;
    hl_alg_init(&phi, ctx), hl_alg_init(&sq, ctx), hl_alg_init(&sp, ctx);

    rd(&phi, sys, "q");
    CHECK(hl_lie_terms(t, &phi, 7, sys, NULL) == HL_OK);
    for (int k = 0; k <= 7; k++)
        CHECK_MSG(eq_formula(&t[k], sys, gq[k]), "g^%d q", k);
    hl_alg_vec_free(t, 8, ctx);
    t = hl_alg_vec_new(7, ctx);
    rd(&phi, sys, "p");
    CHECK(hl_lie_terms(t, &phi, 6, sys, NULL) == HL_OK);
    for (int k = 0; k <= 6; k++)
        CHECK_MSG(eq_formula(&t[k], sys, gq[k + 1]), "g^%d p", k);
    hl_alg_vec_free(t, 7, ctx);

    /* the series in closed form: sum D^k/k! g^k q */
    char want[2048];
    snprintf(want, sizeof want,
             "%s + D*(%s) + D^2/2*(%s) + D^3/6*(%s) + D^4/24*(%s) + D^5/120*(%s) + D^6/720*(%s)",
             gq[0], gq[1], gq[2], gq[3], gq[4], gq[5], gq[6]);
    rd(&phi, sys, "q");
    CHECK(hl_lie_series(&sq, &phi, 6, sys, NULL) == HL_OK);
    CHECK(eq_formula(&sq, sys, want));
    rd(&phi, sys, "p");
    CHECK(hl_lie_series(&sp, &phi, 6, sys, NULL) == HL_OK);

    /* second way: against the numerically integrated exact flow */
    const double q0 = 0.7, p0 = -0.4;
    double err[2];
    for (int i = 0; i < 2; i++) {
        double h = i == 0 ? 0.1 : 0.05, q = q0, p = p0;
        rk4(&q, &p, h, 20000);
        double eq = fabs(eval(&sq, sys, q0, p0, h) - q), ep = fabs(eval(&sp, sys, q0, p0, h) - p);
        err[i] = eq > ep ? eq : ep;
    }
    printf("series vs RK4 flow: error %.3g at h = 0.1, %.3g at h = 0.05\n", err[0], err[1]);
    CHECK_MSG(err[0] < 1e-8, "error at h = 0.1: %g", err[0]);
    CHECK_MSG(err[0] / err[1] > 64 && err[0] / err[1] < 256,
              "error ratio %g, want about 128 (order 7)", err[0] / err[1]);

    hl_alg_clear(&phi, ctx), hl_alg_clear(&sq, ctx), hl_alg_clear(&sp, ctx);
    hl_system_free(sys);
    return HL_TEST_END();
}
