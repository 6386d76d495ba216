/* The exact scheme read as a series (hl_exact_flow_series) against the Lie
 * series of the flow (Taylor mode of the vector field), and its numeric
 * error analysis (hl_numerr_from_series):
 *   pendulum from q0 = 1.3 at the turning point and at points mid-orbit
 *     (after steps of 0.7, 2.1, 3.3: between the table's samples),
 *     Morse V = (1 - exp(-q))^2, quartic V = q^4/4, and a coupled quadratic
 *     H (the matrix kind): psi_0(z) = z to 4e-16, coefficients equal to
 *     1e-12 relative for k <= 30, no v_k above round-off up to order 30;
 *   a wrong scheme is seen: the series of the flow of 1.001 H (time running
 *     0.1% fast) analysed against H has its leading error at k = 2; a
 *     separatrix point: an error. */
#include <math.h>
#include <stdlib.h>

#include "hl_test.h"
#include "hamlie/exact.h"
#include "hamlie/numerr.h"
#include "hamlie/tape.h"

#define ORDER 30

static hl_system *sys_new(const char *H)
{
    hl_system *s = NULL;
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL};
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

/* The scheme's series at z equals the flow's, and the analysis finds no
 * error up to ORDER. */
static void check_point(const char *H, hl_system *s, hl_exact_flow *f, const double *z)
{
    int m = 2 * hl_system_ndof(s);
    double psi[(ORDER + 1) * 4], lie[(ORDER + 1) * 4];
    hl_error err;
    int st = hl_exact_flow_series(psi, z, ORDER, f, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, err.msg);
    if (st != HL_OK)
        return;
    lie_series(lie, s, z, ORDER);
    for (int i = 0; i < m; i++) /* the table's point for z's time is z */
        CHECK_MSG(fabs(psi[i] - z[i]) <= 4e-16 * fmax(1, fabs(z[i])), "%s: psi_0 - z = %.3g", H,
                  psi[i] - z[i]);
    double worst = 0;
    for (int k = 0; k <= ORDER; k++) {
        double scale = 1e-300;
        for (int i = 0; i < m; i++)
            scale = fmax(scale, fabs(lie[k * m + i]));
        for (int i = 0; i < m; i++)
            worst = fmax(worst, fabs(psi[k * m + i] - lie[k * m + i]) / scale);
    }
    CHECK_MSG(worst < 1e-12, "%s at (%g, %g): worst relative difference %.3g", H, z[0], z[1],
              worst);
    hl_numerr nr;
    st = hl_numerr_from_series(&nr, s, z, psi, ORDER, &err);
    CHECK_MSG(st == HL_OK && nr.leading == 0 && nr.order == ORDER && isnan(nr.K[0]),
              "%s: leading %d", H, nr.leading);
    hl_numerr_clear(&nr);
    printf("%-40s at (%.4f, %.4f): coefficients to D^%d within %.2g\n", H, z[0], z[1], ORDER,
           worst);
}

/* The points come from one exact flow and the series from another, so
 * that each series locates its point on the table afresh (a flow remembers
 * the time of the point it last returned). */
static void test_one_dof(const char *H, double q0, double p0)
{
    hl_system *s = sys_new(H);
    hl_exact_flow *f = NULL, *g = NULL;
    hl_error err;
    CHECK(hl_exact_flow_new(&f, s, &err) == HL_OK && hl_exact_flow_new(&g, s, &err) == HL_OK);
    double z[2] = {q0, p0};
    check_point(H, s, g, z);
    static const double steps[] = {0.7, 2.1, 3.3};
    for (int i = 0; i < 3; i++) {
        CHECK(hl_exact_flow_step(z, steps[i], f, &err) == HL_OK);
        check_point(H, s, g, z);
    }
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
    check_point(H, s, f, z);
    hl_exact_flow_free(f);
    hl_system_free(s);
}

/* A scheme that is not the flow of H: the flow of 1.001 H. */
static void test_wrong(void)
{
    hl_system *s = sys_new("p^2/2 - cos(q)"), *s2 = sys_new("1.001*(p^2/2 - cos(q))");
    hl_exact_flow *f = NULL;
    hl_error err;
    CHECK(hl_exact_flow_new(&f, s2, &err) == HL_OK);
    double z[2] = {1.0, 0.4}, psi[(ORDER + 1) * 2];
    CHECK(hl_exact_flow_series(psi, z, ORDER, f, &err) == HL_OK);
    hl_numerr nr;
    CHECK(hl_numerr_from_series(&nr, s, z, psi, ORDER, &err) == HL_OK);
    CHECK_MSG(nr.leading == 2 && nr.order == 1, "leading %d", nr.leading);
    hl_numerr_clear(&nr);
    /* a separatrix */
    hl_exact_flow_free(f);
    CHECK(hl_exact_flow_new(&f, s, &err) == HL_OK);
    double sep[2] = {0, 2};
    CHECK(hl_exact_flow_series(psi, sep, 4, f, &err) != HL_OK);
    printf("separatrix: %s\n", err.msg);
    hl_exact_flow_free(f);
    hl_system_free(s);
    hl_system_free(s2);
}

int main(void)
{
    test_one_dof("p^2/2 - cos(q)", 1.3, 0);
    test_one_dof("p^2/2 + (1 - exp(-q))^2", 0.5, 0.3);
    test_one_dof("p^2/2 + q^4/4", 0.2, 0.9);
    test_linear();
    test_wrong();
    return HL_TEST_END();
}
