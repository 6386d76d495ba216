/* Modified Hamiltonians of the pendulum H = p^2/2 + U(q), U = -cos q (so
 * U' = sin q, U'' = cos q): the Hamiltonians of sin/cos error fields, found
 * by antiderivatives (classify.c, alg's hl_alg_antiderivative), against
 * Hairer-Lubich-Wanner ch. IX — the formulas derived by BCH in t-modified.c:
 *   velocity Verlet (kdk): H_3 = p^2 U''/12 - U'^2/24
 *   position Verlet (dkd): H_3 = -p^2 U''/24 + U'^2/12
 *   symplectic Euler (VI.3.1, our "a"): H_2 = -H_p H_q/2,
 *     H_3 = (H_pp H_q^2 + H_qq H_p^2 + 4 H_pq H_p H_q)/12
 *   implicit midpoint: H_3 = -H''(f, f)/24, f = (H_p, -H_q)
 * each up to a constant (H~ = H + D H_2 + D^2 H_3 + ...).  And the h found
 * must satisfy J grad h = f_j exactly (the classifier checks; so does this
 * test, independently). */
#include <math.h>
#include <stdlib.h>

#include "analysis_test.h"
#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"

#define NM 3

static void check_h(hl_system *sys, const char *scheme, int j, const char *want)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_series Z[2];
    hl_alg *mf = hl_alg_vec_new((NM + 1) * 2, ctx), w, d;
    hl_alg_init(&w, ctx);
    hl_alg_init(&d, ctx);
    for (int i = 0; i < 2; i++)
        hl_series_init(&Z[i], 0, ctx);
    hl_scheme *s = NULL;
    hl_errfield F = {0};
    hl_error err;
    int st = hl_scheme_new(&s, scheme, 0, sys, &err);
    if (st == HL_OK)
        st = hl_scheme_expand(Z, s, NM + 1, &err);
    if (st == HL_OK)
        st = hl_modified_field(mf, Z, sys, NM, &err);
    if (st == HL_OK)
        st = hl_errfield_classify(&F, mf + 2 * j, sys, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", scheme, err.msg);
    if (st == HL_OK) {
        CHECK_MSG(F.hamiltonian && F.have_h, "%s: f_%d has no h", scheme, j);
        if (F.have_h && hl_system_read(&w, sys, want, &err) == HL_OK) {
            hl_alg_sub(&w, &F.h, &w, ctx);
            CHECK_MSG(!hl_alg_depends_on(&w, 0, ctx) && !hl_alg_depends_on(&w, 1, ctx),
                      "%s: H_%d is not %s + const", scheme, j, want);
            /* J grad h = f_j: dh/dp = f(q), -dh/dq = f(p) */
            CHECK(hl_alg_diff(&d, &F.h, 1, ctx, &err) == HL_OK &&
                  hl_alg_equal(&d, &mf[2 * j], ctx));
            CHECK(hl_alg_diff(&d, &F.h, 0, ctx, &err) == HL_OK);
            hl_alg_neg(&d, &d, ctx);
            CHECK(hl_alg_equal(&d, &mf[2 * j + 1], ctx));
        }
    }
    hl_errfield_clear(&F, sys);
    hl_scheme_free(s);
    for (int i = 0; i < 2; i++)
        hl_series_clear(&Z[i], ctx);
    hl_alg_vec_free(mf, (NM + 1) * 2, ctx);
    hl_alg_clear(&w, ctx);
    hl_alg_clear(&d, ctx);
}

/* The expected Verlet formulas checked a second way, free of the library:
 * step the pendulum in doubles and watch H + h^2 H_3 along 20000 steps; the
 * right H_3 is conserved to O(h^4), the other one only to O(h^2). */
static double drift(int kdk, double h, double a, double b) /* H_3 = a U'' p^2 + b U'^2 */
{
    double q = 1.0, p = 0.5, lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < 20000; i++) {
        double H = p * p / 2 - cos(q) + h * h * (a * cos(q) * p * p + b * sin(q) * sin(q));
        lo = H < lo ? H : lo;
        hi = H > hi ? H : hi;
        if (kdk) {
            p -= h / 2 * sin(q);
            q += h * p;
            p -= h / 2 * sin(q);
        } else {
            q += h / 2 * p;
            p -= h * sin(q);
            q += h / 2 * p;
        }
    }
    return hi - lo;
}

static void check_verlet_by_simulation(void)
{
    double h = 0.05;
    CHECK(drift(1, h, 1.0 / 12, -1.0 / 24) < 1e-6 && drift(1, h, -1.0 / 24, 1.0 / 12) > 1e-4);
    CHECK(drift(0, h, -1.0 / 24, 1.0 / 12) < 1e-6 && drift(0, h, 1.0 / 12, -1.0 / 24) > 1e-4);
}

int main(void)
{
    check_verlet_by_simulation();
    hl_system *sys = make_system("p^2/2 - cos(q)"); /* q: var 0, p: var 1 */
    check_h(sys, "stormer-verlet-kdk", 3, "p^2*cos(q)/12 - sin(q)^2/24");
    check_h(sys, "stormer-verlet-dkd", 3, "-p^2*cos(q)/24 + sin(q)^2/12");
    check_h(sys, "symplectic-euler-a", 2, "-p*sin(q)/2");
    check_h(sys, "symplectic-euler-a", 3, "(sin(q)^2 + cos(q)*p^2)/12");
    check_h(sys, "implicit-midpoint", 3, "-(cos(q)*p^2 + sin(q)^2)/24");
    hl_system_free(sys);
    return HL_TEST_END();
}
