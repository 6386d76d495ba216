/* The numeric exact flow against closed forms and the Taylor integrator:
 *   oscillator, anisotropic 2-dof oscillator, hyperbolic and uniform-field H
 *     (matrix exponential) against cos/sin, cosh/sinh, polynomials;
 *   pendulum q0 = 1.3 (acceptance): 2000 steps of 0.5 against hl_flow at
 *     1e-15 at t = 1000 (1e-13), energy error at round-off every step;
 *     period against 4 K(sin^2(q0/2)) (Arb's complete elliptic integral);
 *   Morse V = (1 - exp(-q))^2: period 2 pi / sqrt(2 (1 - E)), and t = 100;
 *   quartic V = q^4/4: period 4 sqrt(2) K(1/2) / (sqrt(2) A) closed form;
 *   pendulum librations (from the bottom, near the separatrix, tiny
 *     amplitudes), rotations and the equilibrium against Jacobi's closed
 *     forms (mpmath values); quartic, Morse and a double well from the
 *     bottom, turning points, p < 0, inside one well and above the barrier,
 *     against the Arb integrator;
 *   failures: the pendulum's separatrix and a Morse escape refused, z
 *     unchanged. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

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


/* The pendulum p^2/2 - cos q against its Jacobi elliptic closed forms
 * (issue 13, defect 2).  Libration of energy E, k^2 = (1 + E)/2:
 * sin(q/2) = k sn(t + t0 | k^2), p = 2 k cn(t + t0 | k^2), T = 4 K(k^2);
 * rotation (E > 1) from q = 0, k0 = p0/2: q = 2 am(k0 t | 1/k0^2),
 * p = 2 k0 dn(k0 t | 1/k0^2), T = 2 K(1/k0^2)/k0, and q grows by 2 pi a
 * period.  Reference values from python3 + mpmath at 40 digits (the initial
 * values are the doubles, mpf(3.14) etc.):
 *   t0 = ellipf(asin(sin(q0/2)/k), k^2), or 2K - that when p0 < 0;
 *   q = 2*asin(k*ellipfun('sn', t + t0, k^2)), p = 2*k*ellipfun('cn', ...);
 *   rotation: u = k0 t, n = floor(u/2K), r = u - 2 n K,
 *   q = 2 (n pi + atan2(sn(r), cn(r))), p = 2 k0 ellipfun('dn', u, 1/k0^2);
 *   with the sign of p0 on both for p0 < 0.
 * The state after t/dt steps of dt, and the period, each within tol
 * (absolute; for the tiny amplitudes tol is relative to the amplitude). */
struct closed_case {
    double q0, p0, t, dt, q, p, T, tol;
    const char *what;
};

static const struct closed_case pendulum_cases[] = {
    /* librations that start at the bottom of the well */
    {0, 1.8, 4, 0.5, 0.96024797467077008154, -1.5448733473536317719, 9.122196553691081202,
     1e-13, "libration from the bottom"},
    {0, -1.8, 4, 0.5, -0.96024797467077008154, 1.5448733473536317719, 9.122196553691081202,
     1e-13, "libration from the bottom, p < 0"},
    {0, 1.8, 4, 4, 0.96024797467077008154, -1.5448733473536317719, 9.122196553691081202,
     1e-13, "libration from the bottom, one step"},
    /* near the separatrix: long periods */
    {0, 1.99, 4, 0.5, 2.9323094298043855628, -0.061154189248036036636, 14.787500329574816745,
     1e-12, "libration near the separatrix, from the bottom"},
    {0, 1.99, 30, 0.5, 0.82137234293311765971, 1.8227820398325132196, 14.787500329574816745,
     1e-11, "libration near the separatrix, t = 30"},
    {3.14, 0, 4, 0.5, 3.0981018376428383977, -0.043458214566915281301, 34.087186277155886909,
     1e-11, "libration near the separatrix, from the turning point 3.14"},
    {3.14, 0, 30, 0.5, 3.0941427313064833678, 0.047418732328223017769, 34.087186277155886909,
     1e-10, "libration near the separatrix, from 3.14, t = 30"},
    /* rotations */
    {0, 2.5, 4, 0.5, 8.1248114944345763644, 1.9274173704147389419, 3.1924844442635670203,
     1e-13, "rotation"},
    {0, -2.5, 4, 0.5, -8.1248114944345763644, -1.9274173704147389419, 3.1924844442635670203,
     1e-13, "rotation, p < 0"},
    {0, 2.5, 100, 0.5, 197.0317563811194165, 1.7288642419686790437, 3.1924844442635670203,
     1e-12, "rotation, t = 100"},
    {0, 2.01, 4, 0.5, 3.2065756885930578401, 0.21052626688302054096, 7.3618610553122156245,
     1e-12, "rotation near the separatrix"},
};

/* tiny amplitudes: tol relative to the amplitude a */
static const struct closed_case tiny_cases[] = {
    {1e-8, 0, 4, 0.5, -6.5364362086361194802e-9, 7.5680249530792824569e-9,
     6.2831853071795865162, 1e-13, "q0 = 1e-8"},
    {1e-6, 0, 4, 0.5, -6.5364362086380888515e-7, 7.5680249530771306379e-7, 6.283185307179979176,
     1e-13, "q0 = 1e-6"},
    {0, 1e-8, 4, 0.5, -7.5680249530792825469e-9, -6.536436208636119449e-9,
     6.2831853071795865162, 1e-13, "p0 = 1e-8"},
    /* the linearised flow is the limit: q0 cos t, -q0 sin t (mpmath) */
    {1e-300, 0, 4, 0.5, -6.536436208636119310188837058173778e-301,
     7.568024953079282703374223255483496e-301, 6.283185307179586476925286766559006, 1e-14,
     "q0 = 1e-300"},
    {0, 1e-200, 4, 0.5, -7.568024953079282378260730127805124e-201,
     -6.536436208636119029391188851256634e-201, 6.283185307179586476925286766559006, 1e-14,
     "p0 = 1e-200"},
};

static void check_case(hl_exact_flow *f, const struct closed_case *c, double scale)
{
    hl_error err;
    double z[2] = {c->q0, c->p0}, T = 0;
    int st = hl_exact_flow_period(&T, z, f, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", c->what, err.msg);
    if (st != HL_OK)
        return;
    CHECK_MSG(fabs(T - c->T) < 1e-12 * c->T, "%s: T %.17g vs %.17g", c->what, T, c->T);
    int n = (int)lround(c->t / c->dt);
    for (int i = 0; i < n && st == HL_OK; i++)
        st = hl_exact_flow_step(z, c->dt, f, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", c->what, err.msg);
    double d = fmax(fabs(z[0] - c->q), fabs(z[1] - c->p)) / scale;
    printf("pendulum, %s: T = %.17g, |z(%g) - closed form| = %.3g%s\n", c->what, T, c->t, d,
           scale != 1 ? " (relative)" : "");
    CHECK_MSG(d < c->tol, "%s: z(%g) = (%.17g, %.17g), closed form (%.17g, %.17g)", c->what,
              c->t, z[0], z[1], c->q, c->p);
}

static void test_pendulum_closed_forms(void)
{
    hl_error err;
    hl_system *s = sys_new("p^2/2 - cos(q)");
    for (size_t i = 0; i < sizeof pendulum_cases / sizeof pendulum_cases[0]; i++) {
        hl_exact_flow *f = flow_new(s); /* a fresh flow: no table of another orbit */
        check_case(f, &pendulum_cases[i], 1);
        hl_exact_flow_free(f);
    }
    /* one flow through all cases: each orbit's table, not the last one's */
    hl_exact_flow *g = flow_new(s);
    for (size_t i = 0; i < sizeof pendulum_cases / sizeof pendulum_cases[0]; i++)
        check_case(g, &pendulum_cases[i], 1);
    for (size_t i = 0; i < sizeof tiny_cases / sizeof tiny_cases[0]; i++) {
        const struct closed_case *c = &tiny_cases[i];
        check_case(g, c, fmax(fabs(c->q0), fabs(c->p0)));
    }
    /* the equilibrium stays exactly where it is; its period is the limit 2 pi */
    double eq[2] = {0, 0}, T = 0;
    CHECK(hl_exact_flow_period(&T, eq, g, &err) == HL_OK);
    CHECK_MSG(fabs(T - 2 * M_PI) < 1e-14, "equilibrium: T %.17g", T);
    for (int n = 0; n < 8; n++)
        CHECK(hl_exact_flow_step(eq, 0.5, g, &err) == HL_OK);
    CHECK_MSG(eq[0] == 0 && eq[1] == 0, "equilibrium moved to (%g, %g)", eq[0], eq[1]);
    /* the separatrix itself, and the unstable equilibrium to rounding
     * (sin(M_PI) = 1.2e-16): refused, z unchanged */
    double sep[2] = {0, 2}, top[2] = {M_PI, 0};
    CHECK(hl_exact_flow_step(sep, 0.5, g, &err) == HL_EDOM);
    CHECK(sep[0] == 0 && sep[1] == 2);
    printf("separatrix: %s\n", err.msg);
    CHECK(strstr(err.msg, "separatrix") != NULL);
    CHECK(hl_exact_flow_step(top, 0.5, g, &err) == HL_EDOM);
    CHECK(top[0] == M_PI && top[1] == 0);
    CHECK(strstr(err.msg, "separatrix") != NULL);
    hl_exact_flow_free(g);
    hl_system_free(s);
}

/* Against the Taylor integrator in Arb (24 digits) for systems without a
 * closed form at hand: starts at the bottom, at a turning point, p < 0,
 * inside one well of a double well and above its barrier. */
static void test_other_wells(void)
{
    static const struct {
        const char *H;
        double q0, p0;
    } cases[] = {
        {"p^2/2 + q^4/4", 0, 1},               /* quartic from the bottom */
        {"p^2/2 + q^4/4", 0, -1},
        {"p^2/2 + q^4/4", -1.2, 0},            /* a left turning point */
        {"p^2/2 + (1-exp(-q))^2", 0, 1.2},     /* Morse, E = 0.72 */
        {"p^2/2 + (1-exp(-q))^2", 0.3, -0.9},
        {"p^2/2 + q^4/4 - q^2/2", 1, 0.1},     /* inside the right well */
        {"p^2/2 + q^4/4 - q^2/2", -1, 0.1},    /* inside the left well */
        {"p^2/2 + q^4/4 - q^2/2", -0.5, 0},    /* left well, inner turning point */
        {"p^2/2 + q^4/4 - q^2/2", 0.2, 0.8},   /* above the barrier */
        {"p^2/2 + q^4/4 - q^2/2", 0, -0.8},
    };
    hl_error err;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        hl_system *s = sys_new(cases[i].H);
        hl_exact_flow *f = flow_new(s);
        double z[2] = {cases[i].q0, cases[i].p0}, r[2] = {cases[i].q0, cases[i].p0};
        int st = HL_OK;
        for (int n = 0; n < 40 && st == HL_OK; n++)
            st = hl_exact_flow_step(z, 0.5, f, &err);
        CHECK_MSG(st == HL_OK, "%s from (%g, %g): %s", cases[i].H, r[0], r[1], err.msg);
        reference(r, cases[i].H, 20, 24);
        double d = fmax(fabs(z[0] - r[0]), fabs(z[1] - r[1]));
        printf("%s from (%g, %g): |exact - Arb integrator| at t = 20: %.3g\n", cases[i].H,
               cases[i].q0, cases[i].p0, d);
        CHECK_MSG(d < 1e-13, "%s from (%g, %g): %.3g", cases[i].H, cases[i].q0, cases[i].p0, d);
        hl_exact_flow_free(f);
        hl_system_free(s);
    }
    /* unstable equilibrium of the double well: stays */
    hl_system *s = sys_new("p^2/2 + q^4/4 - q^2/2");
    hl_exact_flow *f = flow_new(s);
    double top[2] = {0, 0};
    CHECK(hl_exact_flow_step(top, 0.5, f, &err) == HL_OK && top[0] == 0 && top[1] == 0);
    hl_exact_flow_free(f);
    hl_system_free(s);
}

/* The double well p^2/2 + q^4/4 - q^2/2 just above its barrier (E = p0^2/2
 * from q = 0): long periods, the orbit creeping over the saddle at q = 0
 * with p = p0.  Periods from python3 + mpmath at 40 digits, tanh-sinh
 * quadrature of T = 4 int_0^q+ dq / sqrt(2 (E - V)), q+^2 = 1 + sqrt(1 + 4E),
 * split at 1e-3, 0.1, 1 (E = mpf(p0)**2/2 of the double p0).  The table
 * starts at the turning point q+, whose rounding to double alone would
 * move E by 1e-16 of an energy of 5e-7 (T off by 1e-11); and p is small
 * where z is: tables of energies an ulp apart are 1e-13 apart there. */
static void test_double_well_near_barrier(void)
{
    static const struct {
        double p0, T;
    } cases[] = {{1e-3, 34.5624824606042925909463289884},
                 {1e-5, 52.9831736637434974350468878638}};
    const char *H = "p^2/2 + q^4/4 - q^2/2";
    hl_system *s = sys_new(H);
    hl_error err;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        hl_exact_flow *f = flow_new(s);
        double z[2] = {0, cases[i].p0}, r[2] = {0, cases[i].p0}, T = 0;
        int st = hl_exact_flow_period(&T, z, f, &err);
        CHECK_MSG(st == HL_OK, "p0 = %g: %s", cases[i].p0, err.msg);
        for (int n = 0; n < 40 && st == HL_OK; n++)
            st = hl_exact_flow_step(z, 0.5, f, &err);
        CHECK_MSG(st == HL_OK, "p0 = %g: %s", cases[i].p0, err.msg);
        reference(r, H, 20, 24);
        double d = fmax(fabs(z[0] - r[0]), fabs(z[1] - r[1]));
        printf("double well just above the barrier, p0 = %g: T = %.17g (%.2g relative), "
               "|exact - Arb integrator| at t = 20: %.3g\n",
               cases[i].p0, T, fabs(T - cases[i].T) / cases[i].T, d);
        CHECK_MSG(fabs(T - cases[i].T) < 1e-14 * cases[i].T, "p0 = %g: T %.17g", cases[i].p0, T);
        CHECK_MSG(d < 1e-13, "p0 = %g: %.3g", cases[i].p0, d);
        hl_exact_flow_free(f);
    }
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

    /* the separatrix refused, z unchanged */
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
    test_pendulum_closed_forms();
    test_other_wells();
    test_double_well_near_barrier();
    test_morse_quartic();
    flint_cleanup();
    return HL_TEST_END();
}
