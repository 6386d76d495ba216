/* The numeric exact flow against closed forms and the Taylor integrator:
 *   oscillator, anisotropic 2-dof oscillator, hyperbolic and uniform-field H
 *     (matrix exponential) against cos/sin, cosh/sinh, polynomials;
 *   pendulum q0 = 1.3 (acceptance): 2000 steps of 0.5 against hl_flow at
 *     1e-15 at t = 1000 (1e-13), energy error at round-off every step;
 *     period against 4 K(sin^2(q0/2)) (Arb's complete elliptic integral);
 *   Morse V = (1 - exp(-q))^2: period 2 pi / sqrt(2 (1 - E)), and t = 100;
 *   quartic V = q^4/4: period 4 sqrt(2) K(1/2) / (sqrt(2) A) closed form;
 *   failures: pendulum rotation and separatrix refused, z unchanged. */
#include <math.h>
#include <stdlib.h>

#include <acb_elliptic.h>

#include "hl_test.h"
#include "hamlie/exact.h"
#include "hamlie/flow.h"
#include "hamlie/tape.h"

static hl_system *sys_new(const char *H)
{
    hl_system *s = NULL;
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    int st = hl_system_new(&s, &spec, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, err.msg);
    return s;
}

static hl_exact_flow *flow_new(hl_system *s)
{
    hl_exact_flow *f = NULL;
    hl_error err;
    int st = hl_exact_flow_new(&f, s, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    return f;
}

static void test_linear(void)
{
    hl_error err;
    /* oscillator: rotation by angle t */
    hl_system *s = sys_new("(p^2+x^2)/2");
    hl_exact_flow *f = flow_new(s);
    CHECK(hl_exact_flow_is_linear(f));
    double z[2] = {0.3, -0.7};
    for (int n = 1; n <= 100; n++) {
        CHECK(hl_exact_flow_step(z, 0.37, f, &err) == HL_OK);
    }
    double t = 37;
    CHECK_MSG(fabs(z[0] - (0.3 * cos(t) - 0.7 * sin(t))) < 1e-13, "%g", z[0]);
    CHECK_MSG(fabs(z[1] - (-0.7 * cos(t) - 0.3 * sin(t))) < 1e-13, "%g", z[1]);
    hl_exact_flow_free(f);
    hl_system_free(s);

    /* anisotropic: x rotates at 1, y at 2 */
    s = sys_new("(px^2+py^2)/2+(x^2+4*y^2)/2");
    f = flow_new(s);
    double w[4] = {1, 0.5, 0, 0}; /* x, y, px, py */
    CHECK(hl_exact_flow_step(w, 1.9, f, &err) == HL_OK);
    CHECK(fabs(w[0] - cos(1.9)) < 1e-15 && fabs(w[2] + sin(1.9)) < 1e-15);
    CHECK(fabs(w[1] - 0.5 * cos(3.8)) < 1e-15 && fabs(w[3] + sin(3.8)) < 1e-15);
    hl_exact_flow_free(f);
    hl_system_free(s);

    /* hyperbolic: x'' = x */
    s = sys_new("(p^2-x^2)/2");
    f = flow_new(s);
    double h[2] = {0.2, 0.1};
    CHECK(hl_exact_flow_step(h, 3.0, f, &err) == HL_OK);
    CHECK_MSG(fabs(h[0] - (0.2 * cosh(3.0) + 0.1 * sinh(3.0))) < 1e-14, "%.17g", h[0]);
    CHECK(fabs(h[1] - (0.1 * cosh(3.0) + 0.2 * sinh(3.0))) < 1e-14);
    hl_exact_flow_free(f);
    hl_system_free(s);

    /* uniform field: x = x0 + p0 t - g t^2/2 (affine) */
    s = sys_new("p^2/2 + 3*x");
    f = flow_new(s);
    double u[2] = {1, 2};
    CHECK(hl_exact_flow_step(u, 1.5, f, &err) == HL_OK);
    CHECK(fabs(u[0] - (1 + 2 * 1.5 - 1.5 * 1.5 * 1.5)) < 1e-14);
    CHECK(fabs(u[1] - (2 - 3 * 1.5)) < 1e-14);
    hl_exact_flow_free(f);
    hl_system_free(s);
}

static double K(double m)
{
    acb_t r, a;
    acb_init(r);
    acb_init(a);
    acb_set_d(a, m);
    acb_elliptic_k(r, a, 128);
    double v = arf_get_d(arb_midref(acb_realref(r)), ARF_RND_NEAR);
    acb_clear(r);
    acb_clear(a);
    return v;
}

/* digits 0: the double Taylor integrator at 1e-15; else the Arb one */
static void reference(double *z, const char *H, double t1, double digits)
{
    hl_system *s = sys_new(H);
    hl_tape *tape = NULL;
    hl_error err;
    const char *q = hl_system_coord(s, 0), *p = hl_system_momentum(s, 0);
    CHECK(hl_tape_hamiltonian(&tape, hl_system_pool(s), hl_system_H_expr(s), 1, &q, &p, 0, NULL,
                              NULL, &err) == HL_OK);
    if (digits == 0) {
        hl_flow *fl = NULL;
        CHECK(hl_flow_new(&fl, tape, 1e-15, 1e-15, &err) == HL_OK);
        double t = 0;
        CHECK(hl_flow_evolve(fl, &t, t1, z, &err) == HL_OK);
        hl_flow_free(fl);
    } else {
        hl_flow_arb *fa = NULL;
        CHECK(hl_flow_arb_new(&fa, tape, digits, &err) == HL_OK);
        arb_t t, tf;
        arb_ptr w = _arb_vec_init(2);
        arb_init(t);
        arb_init(tf);
        arb_set_d(tf, t1);
        arb_set_d(w, z[0]);
        arb_set_d(w + 1, z[1]);
        CHECK(hl_flow_arb_evolve(fa, t, tf, w, &err) == HL_OK);
        z[0] = arf_get_d(arb_midref(w), ARF_RND_NEAR);
        z[1] = arf_get_d(arb_midref(w + 1), ARF_RND_NEAR);
        _arb_vec_clear(w, 2);
        arb_clear(t);
        arb_clear(tf);
        hl_flow_arb_free(fa);
    }
    hl_tape_free(tape);
    hl_system_free(s);
}

static void test_pendulum(void)
{
    hl_error err;
    const char *H = "p^2/2 - cos(q)";
    hl_system *s = sys_new(H);
    hl_exact_flow *f = flow_new(s);
    CHECK(!hl_exact_flow_is_linear(f));
    double z[2] = {1.3, 0}, E0 = -cos(1.3), maxdE = 0, T;
    CHECK(hl_exact_flow_period(&T, z, f, &err) == HL_OK);
    double Tref = 4 * K(sin(0.65) * sin(0.65));
    CHECK_MSG(fabs(T - Tref) < 1e-14 * Tref, "T %.17g vs %.17g", T, Tref);
    for (int n = 0; n < 2000; n++) {
        int st = hl_exact_flow_step(z, 0.5, f, &err);
        if (st != HL_OK) {
            CHECK_MSG(0, "%s", err.msg);
            break;
        }
        maxdE = fmax(maxdE, fabs(z[1] * z[1] / 2 - cos(z[0]) - E0));
    }
    double r[2] = {1.3, 0};
    reference(r, H, 1000, 0);
    double ra[2] = {1.3, 0};
    reference(ra, H, 1000, 24);
    printf("Lie double vs Arb 24 digits at t=1000: %.3g\n", fmax(fabs(r[0] - ra[0]), fabs(r[1] - ra[1])));
    double d = fmax(fabs(z[0] - r[0]), fabs(z[1] - r[1]));
    printf("pendulum t=1000: |exact - lie| = %.3g, max |dE| = %.3g, T = %.17g\n", d, maxdE, T);
    /* The double Lie-series reference is itself 3.5e-13 off the Arb one at
     * t = 1000 (printed above), so against it only 1e-12 can be asked. */
    CHECK_MSG(d < 1e-12, "%.3g", d);
    CHECK_MSG(maxdE < 1e-15, "%.3g", maxdE);
    /* one big step = many small ones */
    double a[2] = {1.3, 0};
    CHECK(hl_exact_flow_step(a, 1000, f, &err) == HL_OK);
    CHECK_MSG(fabs(a[0] - ra[0]) < 1e-14 && fabs(a[1] - ra[1]) < 1e-14, "%.3g %.3g",
              a[0] - ra[0], a[1] - ra[1]);
    double d2 = fmax(fabs(z[0] - ra[0]), fabs(z[1] - ra[1]));
    printf("pendulum 2000 steps vs Arb: %.3g\n", d2);
    CHECK_MSG(d2 < 1e-13, "%.3g", d2);
    /* backwards */
    CHECK(hl_exact_flow_step(a, -1000, f, &err) == HL_OK);
    CHECK_MSG(fabs(a[0] - 1.3) < 1e-14 && fabs(a[1]) < 1e-14, "%.3g %.3g", a[0] - 1.3, a[1]);

    /* the search path: two flows alternate, so that neither is given its own
     * last output and each step finds the time on the orbit by Newton */
    hl_exact_flow *g = flow_new(s);
    double b[2] = {1.3, 0};
    for (int n = 0; n < 2000; n++)
        CHECK(hl_exact_flow_step(b, 0.5, n % 2 ? f : g, &err) == HL_OK);
    double d3 = fmax(fabs(b[0] - ra[0]), fabs(b[1] - ra[1]));
    printf("pendulum 2000 steps, time searched each step, vs Arb: %.3g\n", d3);
    CHECK_MSG(d3 < 1e-13, "%.3g", d3);
    hl_exact_flow_free(g);

    /* rotation and separatrix refused, z unchanged */
    double rot[2] = {0, 2.5};
    CHECK(hl_exact_flow_step(rot, 0.5, f, &err) != HL_OK);
    CHECK(rot[0] == 0 && rot[1] == 2.5);
    printf("rotation: %s\n", err.msg);
    double sep[2] = {0, 2};
    CHECK(hl_exact_flow_step(sep, 0.5, f, &err) != HL_OK);
    CHECK(sep[0] == 0 && sep[1] == 2);
    printf("separatrix: %s\n", err.msg);
    hl_exact_flow_free(f);
    hl_system_free(s);
}

static void test_morse_quartic(void)
{
    hl_error err;
    const char *H = "p^2/2 + (1-exp(-q))^2";
    hl_system *s = sys_new(H);
    hl_exact_flow *f = flow_new(s);
    double z[2] = {0.4, 0.3}, T;
    double E = 0.045 + (1 - exp(-0.4)) * (1 - exp(-0.4));
    CHECK(hl_exact_flow_period(&T, z, f, &err) == HL_OK);
    double Tref = 2 * M_PI / sqrt(2 * (1 - E));
    CHECK_MSG(fabs(T - Tref) < 1e-13 * Tref, "Morse T %.17g vs %.17g", T, Tref);
    for (int n = 0; n < 200; n++)
        CHECK(hl_exact_flow_step(z, 0.5, f, &err) == HL_OK);
    double r[2] = {0.4, 0.3};
    reference(r, H, 100, 24);
    CHECK_MSG(fabs(z[0] - r[0]) < 1e-13 && fabs(z[1] - r[1]) < 1e-13, "Morse %.3g %.3g",
              z[0] - r[0], z[1] - r[1]);
    /* escape: E above the dissociation energy 1 */
    double esc[2] = {0, 1.5};
    CHECK(hl_exact_flow_step(esc, 0.5, f, &err) != HL_OK);
    printf("Morse escape: %s\n", err.msg);
    hl_exact_flow_free(f);
    hl_system_free(s);

    H = "p^2/2 + q^4/4";
    s = sys_new(H);
    f = flow_new(s);
    double w[2] = {1.5, 0};
    CHECK(hl_exact_flow_period(&T, w, f, &err) == HL_OK);
    Tref = 4 * sqrt(2.0) * (K(0.5) / sqrt(2.0)) / 1.5; /* int_0^1 du/sqrt(1-u^4) = K(1/2)/sqrt 2 */
    CHECK_MSG(fabs(T - Tref) < 1e-13 * Tref, "quartic T %.17g vs %.17g", T, Tref);
    for (int n = 0; n < 200; n++)
        CHECK(hl_exact_flow_step(w, 0.5, f, &err) == HL_OK);
    double r2[2] = {1.5, 0};
    reference(r2, H, 100, 24);
    CHECK_MSG(fabs(w[0] - r2[0]) < 1e-13 && fabs(w[1] - r2[1]) < 1e-13, "quartic %.3g %.3g",
              w[0] - r2[0], w[1] - r2[1]);
    hl_exact_flow_free(f);
    hl_system_free(s);
}

int main(void)
{
    test_linear();
    test_pendulum();
    test_morse_quartic();
    flint_cleanup();
    return HL_TEST_END();
}
