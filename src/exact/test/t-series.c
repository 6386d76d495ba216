/* The exact scheme read as a series (hl_exact_flow_series: the orbit
 * table's piece re-expanded at the point's time) against the Lie series of
 * the flow (Taylor mode of the vector field tape at z, computed here
 * independently), and its numeric error analysis (hl_numerr_from_series):
 *   pendulum from q0 = 1.3 at the turning point and at points mid-orbit
 *     (after steps of 0.7, 2.1, 3.3: between the table's samples), from
 *     the bottom q = 0 (p = 1.8) and on a rotation (p = 3),
 *     Morse V = (1 - exp(-q))^2, quartic V = q^4/4, and a coupled quadratic
 *     H (the matrix kind): psi_0(z) = z to 1e-14, coefficients equal to
 *     1e-12 relative for k <= 8, the analysis finds no error up to order 8;
 *   the series is the piece's, not Taylor mode at z: mid-orbit, its D^20
 *     coefficient differs from the flow's (the piece is centred at a sample
 *     and truncated at degree 20), and n = 21 is refused;
 *   at q = 0 of the quartic, where the flow's [D^2], [D^3] vanish, no
 *     spurious error (the thresholds of hl_numerr_from_series, by hand) and
 *     the flow of 1.001 H is seen at k = 4;
 *   wrong steps are seen: the series of the flow of 1.001 H (time running
 *     0.1% fast) differs from the flow's and the analysis puts its leading
 *     error at k = 2; the series of the point at a slightly different energy
 *     differs from the flow's at z; a separatrix point: an error. */
#include <math.h>
#include <stdlib.h>

#include "hl_test.h"
#include "hamlie/exact.h"
#include "hamlie/numerr.h"
#include "hamlie/tape.h"

#define ORDER 8
#define DEG HL_EXACT_SERIES_DEGREE

static hl_system *sys_new(const char *H)
{
    hl_system *s = NULL;
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    int st = hl_system_new(&s, &spec, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, err.msg);
    return s;
}

/* [D^k] of the flow at z by Taylor mode, as hl_exact_flow_series lays out. */
static void lie_series(double *lie, hl_system *s, const double *z, int n)
{
    int N = hl_system_ndof(s), m = 2 * N;
    const char *q[4], *p[4];
    for (int j = 0; j < N; j++)
        q[j] = hl_system_coord(s, j), p[j] = hl_system_momentum(s, j);
    hl_tape *vf = NULL;
    hl_error err;
    CHECK(hl_tape_hamiltonian(&vf, hl_system_pool(s), hl_system_H_expr(s), N, q, p, 0, NULL,
                              NULL, &err) == HL_OK);
    double *c = calloc((size_t)m * (n + 1), sizeof *c);
    for (int i = 0; i < m; i++)
        c[i * (n + 1)] = z[i];
    CHECK(hl_tape_taylor_ode_d(c, n, vf, &err) == HL_OK);
    for (int i = 0; i < m; i++)
        for (int k = 0; k <= n; k++)
            lie[k * m + i] = c[i * (n + 1) + k];
    free(c);
    hl_tape_free(vf);
}

/* max over k in [k0, k1] of |a_k - b_k|_inf / |b_k|_inf */
static double rel_diff(const double *a, const double *b, int m, int k0, int k1)
{
    double worst = 0;
    for (int k = k0; k <= k1; k++) {
        double scale = 1e-300;
        for (int i = 0; i < m; i++)
            scale = fmax(scale, fabs(b[k * m + i]));
        for (int i = 0; i < m; i++)
            worst = fmax(worst, fabs(a[k * m + i] - b[k * m + i]) / scale);
    }
    return worst;
}

/* The scheme's series at z equals the flow's to D^ORDER, and the analysis
 * finds no error up to ORDER.  mid: z is between the table's samples, so
 * the top coefficient of the piece must differ from the flow's. */
static void check_point(const char *H, hl_system *s, hl_exact_flow *f, const double *z, int mid)
{
    int m = 2 * hl_system_ndof(s);
    double psi[(DEG + 1) * 4], lie[(DEG + 1) * 4];
    hl_error err;
    int st = hl_exact_flow_series(psi, z, ORDER, f, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, err.msg);
    if (st != HL_OK)
        return;
    lie_series(lie, s, z, DEG);
    for (int i = 0; i < m; i++) /* the step by 0 gives z back */
        CHECK_MSG(fabs(psi[i] - z[i]) <= 1e-14 * fmax(1, fabs(z[i])), "%s: psi_0 - z = %.3g", H,
                  psi[i] - z[i]);
    double worst = rel_diff(psi, lie, m, 0, ORDER);
    CHECK_MSG(worst < 1e-12, "%s at (%g, %g): worst relative difference %.3g", H, z[0], z[1],
              worst);
    hl_numerr nr;
    st = hl_numerr_from_series(&nr, s, z, psi, ORDER, &err);
    CHECK_MSG(st == HL_OK && nr.leading == 0 && nr.order == ORDER && isnan(nr.K[0]),
              "%s: leading %d", H, nr.leading);
    double vmax = 0;
    for (int k = 2; st == HL_OK && k <= ORDER; k++)
        vmax = fmax(vmax, nr.vnorm[k] / nr.thresh[k]);
    hl_numerr_clear(&nr);
    double top = NAN;
    if (mid) {
        CHECK(hl_exact_flow_series(psi, z, DEG, f, &err) == HL_OK);
        top = rel_diff(psi, lie, m, DEG, DEG);
        CHECK_MSG(top > 1e-8, "%s at (%g, %g): D^%d coefficient equals Taylor mode's (%.3g)", H,
                  z[0], z[1], DEG, top);
    }
    printf("%-40s at (%.4f, %.4f): to D^%d within %.2g (|v_k|/threshold <= %.2g), "
           "D^%d: %.2g\n",
           H, z[0], z[1], ORDER, worst, vmax, DEG, top);
}

/* The points come from one exact flow and the series from another, so
 * that each series locates its point on the table afresh (a flow remembers
 * the time of the point it last returned).  start: (q0, p0) is where the
 * table starts (a turning point; a rotation's table starts at its first
 * point), so its series is the sample's own Taylor polynomial. */
static void test_one_dof(const char *H, double q0, double p0, int start)
{
    hl_system *s = sys_new(H);
    hl_exact_flow *f = NULL, *g = NULL;
    hl_error err;
    CHECK(hl_exact_flow_new(&f, s, &err) == HL_OK && hl_exact_flow_new(&g, s, &err) == HL_OK);
    double z[2] = {q0, p0}, psi[(DEG + 2) * 2];
    check_point(H, s, g, z, !start);
    static const double steps[] = {0.7, 2.1, 3.3};
    for (int i = 0; i < 3; i++) {
        CHECK(hl_exact_flow_step(z, steps[i], f, &err) == HL_OK);
        check_point(H, s, g, z, 1);
    }
    CHECK(hl_exact_flow_series(psi, z, DEG + 1, g, &err) == HL_EUNSUP);
    hl_exact_flow_free(f);
    hl_exact_flow_free(g);
    hl_system_free(s);
}

static void test_linear(void)
{
    const char *H = "(px^2+py^2)/2 + (x^2+4*y^2)/2 + x*y";
    hl_system *s = sys_new(H);
    hl_exact_flow *f = NULL;
    hl_error err;
    CHECK(hl_exact_flow_new(&f, s, &err) == HL_OK && hl_exact_flow_is_linear(f));
    double z[4] = {0.3, -0.2, 0.5, 0.1};
    check_point(H, s, f, z, 0);
    hl_exact_flow_free(f);
    hl_system_free(s);
}

/* Steps that are not the flow of H: the flow of 1.001 H, and the flow
 * through a point of another energy. */
static void test_wrong(void)
{
    hl_system *s = sys_new("p^2/2 - cos(q)"), *s2 = sys_new("1.001*(p^2/2 - cos(q))");
    hl_exact_flow *f = NULL;
    hl_error err;
    CHECK(hl_exact_flow_new(&f, s2, &err) == HL_OK);
    double z[2] = {1.0, 0.4}, psi[(ORDER + 1) * 2], lie[(ORDER + 1) * 2];
    lie_series(lie, s, z, ORDER);
    CHECK(hl_exact_flow_series(psi, z, ORDER, f, &err) == HL_OK);
    double d = rel_diff(psi, lie, 2, 1, ORDER);
    CHECK_MSG(d > 5e-4, "time-scaled flow: difference %.3g", d);
    hl_numerr nr;
    CHECK(hl_numerr_from_series(&nr, s, z, psi, ORDER, &err) == HL_OK);
    CHECK_MSG(nr.leading == 2 && nr.order == 1, "leading %d", nr.leading);
    hl_numerr_clear(&nr);
    hl_exact_flow_free(f);
    /* the series through a point of energy E + ~1e-7 (the step's map of the
     * wrong orbit), against the flow at z */
    CHECK(hl_exact_flow_new(&f, s, &err) == HL_OK);
    double zw[2] = {z[0], z[1] * (1 + 1e-6)};
    CHECK(hl_exact_flow_series(psi, zw, ORDER, f, &err) == HL_OK);
    d = rel_diff(psi, lie, 2, 0, ORDER);
    CHECK_MSG(d > 1e-7 && d < 1e-4, "wrong energy: difference %.3g", d);
    printf("wrong steps: time-scaled by 1.001 seen at k = 2; energy off by 1.6e-7: "
           "coefficients differ by %.2g\n",
           d);
    /* a separatrix */
    double sep[2] = {0, 2};
    CHECK(hl_exact_flow_series(psi, sep, 4, f, &err) == HL_EDOM);
    printf("separatrix: %s\n", err.msg);
    hl_exact_flow_free(f);
    hl_system_free(s);
    hl_system_free(s2);
}

/* q = 0 for V = q^4/4: the flow's [D^2] and [D^3] vanish there by symmetry
 * (q'' = -q^3, p'' = -3 q^2 p, p''' = -6 q p^2 - 3 q^2 p'), the table's are
 * round-off; the analysis still finds no error (its thresholds follow the
 * neighbouring orders), and the flow of 1.001 H, whose [D^2], [D^3] vanish
 * there too, is seen at k = 4. */
static void test_symmetric_point(void)
{
    hl_system *s = sys_new("p^2/2 + q^4/4"), *s2 = sys_new("1.001*(p^2/2 + q^4/4)");
    hl_exact_flow *f = NULL;
    hl_error err;
    double z[2] = {0, 1}, psi[(ORDER + 1) * 2], lie[(ORDER + 1) * 2];
    lie_series(lie, s, z, ORDER);
    CHECK(hl_exact_flow_new(&f, s, &err) == HL_OK);
    CHECK(hl_exact_flow_series(psi, z, ORDER, f, &err) == HL_OK);
    for (int k = 0; k <= ORDER; k++) /* [D^k] = 0 for k = 2, 3 mod 4 (parity) */
        if (k % 4 < 2)
            CHECK_MSG(rel_diff(psi, lie, 2, k, k) < 1e-12, "[D^%d]", k);
        else
            CHECK_MSG(lie[2 * k] == 0 && lie[2 * k + 1] == 0 && fabs(psi[2 * k]) < 1e-15 &&
                          fabs(psi[2 * k + 1]) < 1e-15,
                      "[D^%d] = %.3g", k, psi[2 * k + 1]);
    hl_numerr nr;
    CHECK(hl_numerr_from_series(&nr, s, z, psi, ORDER, &err) == HL_OK);
    CHECK_MSG(nr.leading == 0, "q = 0: leading %d", nr.leading);
    /* the hull puts orders 2 and 3 between order 1 (|p| + |p| = 2) and
     * order 4 (2 * 6/4! = 1/2): 2 * 4^(-1/3), 2 * 4^(-2/3), times 1e-10 k! */
    CHECK(fabs(nr.thresh[2] / (2e-10 * 2 * pow(4, -1.0 / 3)) - 1) < 1e-9);
    CHECK(fabs(nr.thresh[3] / (6e-10 * 2 * pow(4, -2.0 / 3)) - 1) < 1e-9);
    hl_numerr_clear(&nr);
    hl_exact_flow_free(f);
    CHECK(hl_exact_flow_new(&f, s2, &err) == HL_OK);
    CHECK(hl_exact_flow_series(psi, z, ORDER, f, &err) == HL_OK);
    CHECK(hl_numerr_from_series(&nr, s, z, psi, ORDER, &err) == HL_OK);
    CHECK_MSG(nr.leading == 4, "q = 0, 1.001 H: leading %d", nr.leading);
    hl_numerr_clear(&nr);
    hl_exact_flow_free(f);
    hl_system_free(s);
    hl_system_free(s2);
}

int main(void)
{
    test_one_dof("p^2/2 - cos(q)", 1.3, 0, 1);
    test_one_dof("p^2/2 - cos(q)", 0, 1.8, 0); /* a libration from the bottom */
    test_one_dof("p^2/2 - cos(q)", 0, 3, 1);   /* a rotation: q grows by 2 pi a lap */
    test_one_dof("p^2/2 + (1 - exp(-q))^2", 0.5, 0.3, 0);
    test_one_dof("p^2/2 + q^4/4", 0.2, 0.9, 0);
    test_linear();
    test_wrong();
    test_symmetric_point();
    return HL_TEST_END();
}
