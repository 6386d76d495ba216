/* The numeric reading against the symbolic one: one step of every catalog
 * scheme at D = 0.01 equals its series expansion (8 coefficients, so the
 * truncation is ~1e-16) evaluated at the point with Arb and summed, to
 * 1e-12 — on the pendulum and on Henon-Heiles.  Then Newton's failure: a
 * scheme without a real solution reports the step and the time and leaves
 * the state untouched; and a few steps of a user scheme. */
#include <math.h>

#include "sch.h"

#define NC 8

static double series_sum(const hl_series *a, const double *pt, double D, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int nb = hl_alg_ctx_nbase(ctx), N = hl_system_ndof(sys);
    arb_ptr v = _arb_vec_init(nb);
    for (int j = 0; j < 2 * N; j++)
        arb_set_d(v + j, pt[j]);
    arb_set_d(v + hl_system_var_D(sys), D);
    arb_t c;
    arb_init(c);
    double sum = 0, Dk = 1;
    hl_error err;
    for (int k = 0; k < a->n; k++, Dk *= D) {
        if (hl_alg_eval_arb(c, &a->c[k], v, 128, ctx, &err) != HL_OK) {
            sum = NAN;
            break;
        }
        sum += arf_get_d(arb_midref(c), ARF_RND_NEAR) * Dk;
    }
    arb_clear(c);
    _arb_vec_clear(v, nb);
    return sum;
}

static void compare(hl_system *sys, const char *name, const double *pt, double D)
{
    int N = hl_system_ndof(sys);
    hl_scheme *s;
    hl_error err;
    if (hl_scheme_new(&s, name, 0, sys, &err) != HL_OK) {
        CHECK_MSG(0, "%s: %s", name, err.msg);
        return;
    }
    hl_series *Z = expand(s, NC);
    hl_scheme_stepper *st = NULL;
    int rc = hl_scheme_stepper_new(&st, s, &err);
    CHECK_MSG(rc == HL_OK, "%s: %s", name, err.msg);
    double z[8];
    memcpy(z, pt, (size_t)(2 * N) * sizeof *z);
    if (rc == HL_OK) {
        rc = hl_scheme_step(st, z, D, 0.0, &err);
        CHECK_MSG(rc == HL_OK, "%s: step: %s", name, err.msg);
    }
    double worst = 0;
    for (int a = 0; Z && rc == HL_OK && a < 2 * N; a++)
        worst = fmax(worst, fabs(z[a] - series_sum(&Z[a], pt, D, sys)));
    printf("%-20s %s: |step - series| = %.2e, Newton iterations %d\n", name,
           hl_system_coord(sys, 0)[0] == 'q' ? "pendulum" : N == 1 ? "oscillator" : "henon-heiles", worst, st ? hl_scheme_stepper_iterations(st) : -1);
    CHECK_MSG(Z && worst <= 1e-12, "%s: step and series differ by %g", name, worst);
    if (Z)
        free_series(Z, 2 * N, hl_system_ctx(sys));
    hl_scheme_stepper_free(st);
    hl_scheme_free(s);
}

int main(void)
{
    hl_system *pend = make_system("p^2/2 - cos(q)");
    hl_system *hh = make_system("(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3");
    const double pp[] = {0.7, 0.3}, ph[] = {0.1, 0.2, 0.3, -0.1};
    for (int i = 0; i < hl_scheme_catalog_count(); i++) {
        const hl_scheme_info *info = hl_scheme_catalog(i);
        if (info->flags & (HL_SCHEME_OSCILLATOR | HL_SCHEME_QUADRATIC))
            continue;
        const char *name = info->order == HL_SCHEME_ORDER_N ? "lie4" : info->name;
        compare(pend, name, pp, 0.01);
        compare(hh, name, ph, 0.01);
    }
    /* the oscillator-only ones on the oscillator */
    hl_system *osc = make_system("(p^2 + x^2)/2");
    compare(osc, "exact-rotation", pp, 0.01);
    compare(osc, "paper-dg", pp, 0.01);
    compare(osc, "exact", pp, 0.01); /* quadratic H only */

    /* no real solution: P = p + D*P^2 with 4 D p > 1 */
    {
        hl_scheme *s;
        hl_scheme_stepper *st;
        hl_error err;
        CHECK(hl_scheme_from_equations(&s, "X = x + D*p; P = p + D*P^2", osc, &err) == HL_OK);
        CHECK(hl_scheme_stepper_new(&st, s, &err) == HL_OK);
        double z[2] = {0.5, 1.0};
        int rc = hl_scheme_step(st, z, 10.0, 3.25, &err);
        CHECK_MSG(rc == HL_ENOCONV || rc == HL_EDOM, "rc %d", rc);
        CHECK_MSG(strstr(err.msg, "step 1 (t = 3.25") != NULL, "message: %s", err.msg);
        CHECK(z[0] == 0.5 && z[1] == 1.0);
        printf("no solution: %s\n", err.msg);
        /* a small step has a solution: P = (1 - sqrt(1 - 4 D p))/(2 D) */
        rc = hl_scheme_step(st, z, 0.1, 3.25, &err);
        CHECK(rc == HL_OK);
        CHECK_MSG(fabs(z[1] - (1 - sqrt(1 - 0.4)) / 0.2) < 1e-14, "P = %.17g", z[1]);
        CHECK(fabs(z[0] - 0.6) < 1e-15);
        hl_scheme_stepper_free(st);
        hl_scheme_free(s);
    }
    /* the paper's discrete gradient in its own form, (P^2-p^2)/(2(P-p)): at
     * the equilibrium P = p, and near it, the step is the closed form
     * (4x + 4Dp - D^2 x)/(4 + D^2) (the 0/0 is removed exactly) */
    {
        hl_scheme *s;
        hl_scheme_stepper *st;
        hl_error err;
        CHECK(hl_scheme_from_equations(&s, "(X-x)/D = (P^2-p^2)/(2*(P-p)); "
                                           "(P-p)/D = -(X^2-x^2)/(2*(X-x))",
                                       osc, &err) == HL_OK);
        CHECK(hl_scheme_stepper_new(&st, s, &err) == HL_OK);
        double z[2] = {0, 0}, D = 0.1;
        CHECK_MSG(hl_scheme_step(st, z, D, 0, &err) == HL_OK, "%s", err.msg);
        CHECK(z[0] == 0 && z[1] == 0);
        double x = 1e-9, p = 0.5;
        z[0] = x, z[1] = p;
        CHECK_MSG(hl_scheme_step(st, z, D, 0, &err) == HL_OK, "%s", err.msg);
        CHECK(fabs(z[0] - (4 * x + 4 * D * p - D * D * x) / (4 + D * D)) < 1e-15);
        CHECK(fabs(z[1] - (4 * p - 4 * D * x - D * D * p) / (4 + D * D)) < 1e-15);
        hl_scheme_stepper_free(st);
        hl_scheme_free(s);
    }
    /* long runs on Henon-Heiles: the energy-preserving schemes keep H to
     * rounding (Newton converges every step), the others do not (a drift
     * or oscillation far above rounding) */
    {
        const char *names[] = {"avf", "gonzalez", "itoh-abe", "implicit-midpoint", "rk4"};
        const int keeps[] = {1, 1, 1, 0, 0};
        const char *vars[] = {"x", "y", "px", "py"};
        for (int i = 0; i < 5; i++) {
            hl_scheme *s;
            hl_scheme_stepper *st;
            hl_error err;
            CHECK(hl_scheme_new(&s, names[i], 0, hh, &err) == HL_OK);
            CHECK(hl_scheme_stepper_new(&st, s, &err) == HL_OK);
            double z[4] = {0.1, 0.2, 0.3, -0.1}, h0, h, worst = 0;
            hl_expr_eval_d(&h0, hl_system_H_expr(hh), 4, vars, z, &err);
            int k = 0, rc = HL_OK;
            for (; k < 2000 && rc == HL_OK; k++) {
                rc = hl_scheme_step(st, z, 0.1, k * 0.1, &err);
                hl_expr_eval_d(&h, hl_system_H_expr(hh), 4, vars, z, &err);
                worst = fmax(worst, fabs(h - h0));
            }
            printf("%-20s 2000 steps of 0.1: max |H - H0| = %.2e\n", names[i], worst);
            CHECK_MSG(rc == HL_OK, "%s: %s", names[i], err.msg);
            CHECK_MSG(keeps[i] ? worst < 1e-13 : worst > 1e-9, "%s: |H - H0| = %g", names[i],
                      worst);
            hl_scheme_stepper_free(st);
            hl_scheme_free(s);
        }
    }
    /* the exact rotation for 628 steps of 0.01: back near the start, to
     * the accuracy of cos/sin in double (independent of any scheme code) */
    {
        hl_scheme *s;
        hl_scheme_stepper *st;
        hl_error err;
        CHECK(hl_scheme_new(&s, "exact-rotation", 0, osc, &err) == HL_OK);
        CHECK(hl_scheme_stepper_new(&st, s, &err) == HL_OK);
        double z[2] = {1.0, 0.0};
        for (int k = 0; k < 628; k++)
            hl_scheme_step(st, z, 0.01, k * 0.01, &err);
        CHECK_MSG(fabs(z[0] - cos(6.28)) < 1e-12 && fabs(z[1] + sin(6.28)) < 1e-12, "%g %g",
                  z[0], z[1]);
        hl_scheme_stepper_free(st);
        hl_scheme_free(s);
    }
    hl_system_free(osc);
    hl_system_free(pend);
    hl_system_free(hh);
    return HL_TEST_END();
}
