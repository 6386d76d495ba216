/* The discrete gradients' integrals (step.c: Gauss-Legendre or the Taylor
 * series at s = 1/2, whichever is cheaper) against closed forms.
 *
 * Average vector field for a separable H = p^2/2 + V(q):
 *   Q = q + D (p + P)/2,  P = p - D (V(Q) - V(q)) / (Q - q),
 * solved here by bisection on P in long double with the difference quotient
 * written without cancellation:
 *   pendulum V = -cos q: (V(Q) - V(q))/(Q - q) = sin(m) sin(h/2)/(h/2);
 *   V = -cos(3q)/9 (arguments 3 times longer: the long steps leave the
 *     Taylor rule's reach): = sin(3m) sin(3h/2)/(3h/2) / 3;
 *   Morse V = (1 - e^-q)^2: = (e^-q - e^-Q)(2 - e^-q - e^-Q)/(Q - q), with
 *     e^-q - e^-Q = 2 e^-m sinh(h/2);
 *   quartic V = q^4/4: (Q^4 - q^4)/(4 (Q - q)) = (Q^3 + Q^2 q + Q q^2 + q^3)/4
 * (m = (q + Q)/2, h = Q - q).  Steps D = 0.01 to 1.5, several points: the
 * stepper's next point must equal the closed form's to 2e-15 relative
 * (the long steps, beyond the Taylor rule's reach, taken again by the
 * Gauss rule: hl_scheme_stepper_fallbacks; none for D <= 0.3).
 * Kepler (where the Gauss rule is the cheaper) is checked by energy: the
 * average vector field conserves H exactly, so |H(Z) - H(z)| is the rule's
 * error, at most 1e-14.
 *
 * Gonzalez on the pendulum against its closed form: with h = Q - q,
 * v = P - p, m = (q + Q)/2, the remainder is R = sin(m) (2 sin(h/2) - h)
 * and, r = R / sin(m) / (h^2 + v^2),
 *   h = D ((p + P)/2 + sin(m) r v),  v = -D sin(m) (1 + r h),
 * solved by Newton in long double: equal to 2e-15 for D = 0.01, 0.1, 0.3,
 * in at most 3.5, 4.5, 6 Newton iterations a step on average (the
 * remainder as an integral whose Taylor term of order 0 is exactly 0, the
 * rates started at Euler's half step, the Jacobian refreshed when an
 * iteration gains fewer than 3 digits: 5.3, 6.4, 11 before). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/scheme.h"

typedef long double ld;

static ld quot_pendulum(ld q, ld Q)
{
    ld m = (q + Q) / 2, x = (Q - q) / 2;
    return sinl(m) * (x == 0 ? 1 : sinl(x) / x);
}

static ld quot_morse(ld q, ld Q)
{
    ld m = (q + Q) / 2, x = (Q - q) / 2;
    ld shc = x == 0 ? 1 : sinhl(x) / x; /* (e^-q - e^-Q)/(Q - q) = e^-m sinh(x)/x */
    return expl(-m) * shc * (2 - expl(-q) - expl(-Q));
}

/* V = -cos(3q)/9: (V(Q) - V(q))/(Q - q) = sin(3m) sin(3x)/(3x) / 3 */
static ld quot_cos3(ld q, ld Q)
{
    ld m = (q + Q) / 2, x = 3 * (Q - q) / 2;
    return sinl(3 * m) * (x == 0 ? 1 : sinl(x) / x) / 3;
}

static ld quot_quartic(ld q, ld Q)
{
    return (Q * Q * Q + Q * Q * q + Q * q * q + q * q * q) / 4;
}

/* A system, one of its catalog schemes and its stepper, or a failed check. */
typedef struct fixture {
    hl_system *sys;
    hl_scheme *s;
    hl_scheme_stepper *st;
} fixture;

static int fixture_open(fixture *f, const char *H, const char *scheme)
{
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    *f = (fixture){NULL, NULL, NULL};
    if (hl_system_new(&f->sys, &spec, &err) == HL_OK &&
        hl_scheme_new(&f->s, scheme, 0, f->sys, &err) == HL_OK &&
        hl_scheme_stepper_new(&f->st, f->s, &err) == HL_OK)
        return 1;
    CHECK_MSG(0, "%s / %s: %s", H, scheme, err.msg);
    return 0;
}

static void fixture_close(fixture *f)
{
    hl_scheme_stepper_free(f->st);
    hl_scheme_free(f->s);
    hl_system_free(f->sys);
}

/* P from the AVF equation by bisection (F increasing in P for these D). */
static void avf_closed(double *z, double D, ld (*quot)(ld, ld))
{
    ld q = z[0], p = z[1], lo = p - 4 * (fabsl(D) + 1) * 2, hi = p + 4 * (fabsl(D) + 1) * 2;
    for (int i = 0; i < 200; i++) {
        ld P = (lo + hi) / 2, Q = q + D * (p + P) / 2;
        ld F = P - p + D * quot(q, Q);
        if (F > 0)
            hi = P;
        else
            lo = P;
    }
    ld P = (lo + hi) / 2;
    z[0] = (double)(q + D * (p + P) / 2), z[1] = (double)P;
}

static void against_closed_form(const char *H, ld (*quot)(ld, ld), int nsteps,
                                long want_fallbacks)
{
    hl_error err;
    fixture f;
    if (!fixture_open(&f, H, "avf"))
        return;
    hl_scheme_stepper *st = f.st;
    static const double steps[] = {0.01, 0.1, 0.3, 1.0, 1.5};
    static const double pts[][2] = {{1.3, 0}, {0.2, 0.9}, {-0.7, 0.4}, {1e-9, 0.3}};
    double worst = 0;
    long short_fallbacks = 0;
    for (int i = 0; i < nsteps; i++) {
        if (i == 3)
            short_fallbacks = hl_scheme_stepper_fallbacks(st);
        for (int j = 0; j < 4; j++) {
            double a[2] = {pts[j][0], pts[j][1]}, b[2] = {pts[j][0], pts[j][1]};
            CHECK_MSG(hl_scheme_step(st, a, steps[i], 0, &err) == HL_OK, "%s: %s", H, err.msg);
            avf_closed(b, steps[i], quot);
            for (int k = 0; k < 2; k++) {
                double d = fabs(a[k] - b[k]) / fmax(1, fabs(b[k]));
                worst = fmax(worst, d);
                CHECK_MSG(d <= 2e-15, "%s, D = %g, z = (%g, %g): %.17g vs %.17g", H, steps[i],
                          pts[j][0], pts[j][1], a[k], b[k]);
            }
        }
    }
    /* short steps by the Taylor rule alone; long ones (|Q - q| up to 1.4
     * at D = 1.5) partly again by the Gauss rule */
    long fallbacks = hl_scheme_stepper_fallbacks(st);
    CHECK_MSG(short_fallbacks == 0, "%s: %ld steps of D <= 0.3 taken again", H, short_fallbacks);
    CHECK_MSG(fallbacks >= want_fallbacks, "%s: %ld long steps taken again, want %ld", H,
              fallbacks, want_fallbacks);
    printf("%-28s avf = closed form to %.1e; %ld of the %d steps of D >= 1 taken again by the "
           "Gauss rule\n",
           H, worst, fallbacks, 4 * (nsteps - 3));
    fixture_close(&f);
}

/* A run of long steps (V = -cos(3q)/9, D = 1, from q = 0.2, p = 0.7):
 * about three in four beyond the Taylor rule's reach; once the Gauss rules
 * have taken 64 and half of the steps they take all (the last 100 here),
 * and every step equals the closed form's to the Gauss rule's own
 * truncation, about 1.9e-23 |a|^16 (|a| = 3|Q - q| up to 3.6 here). */
static void long_steps(void)
{
    hl_error err;
    fixture f;
    if (!fixture_open(&f, "p^2/2 - cos(3*q)/9", "avf"))
        return;
    hl_scheme_stepper *st = f.st;
    double a[2] = {0.2, 0.7}, worst = 0;
    long at200 = 0;
    for (int k = 0; k < 300; k++) {
        double b[2] = {a[0], a[1]};
        CHECK_MSG(hl_scheme_step(st, a, 1.0, k, &err) == HL_OK, "long steps: %s", err.msg);
        avf_closed(b, 1.0, quot_cos3);
        for (int j = 0; j < 2; j++)
            worst = fmax(worst, fabs(a[j] - b[j]) / fmax(1, fabs(b[j])));
        if (k == 199)
            at200 = hl_scheme_stepper_fallbacks(st);
    }
    long fb = hl_scheme_stepper_fallbacks(st);
    CHECK_MSG(worst <= 5e-14, "long steps: %.3g from the closed form", worst);
    CHECK_MSG(at200 < 200 && fb - at200 == 100, "long steps: %ld of the first 200 and %ld of the "
              "last 100 by the Gauss rule", at200, fb - at200);
    printf("%-28s avf, 300 steps of D = 1: closed form to %.1e, %ld by the Gauss rule\n",
           "p^2/2 - cos(3*q)/9", worst, fb);
    fixture_close(&f);
}

static double kepler_H(const double *z)
{
    return (z[2] * z[2] + z[3] * z[3]) / 2 - 1 / sqrt(z[0] * z[0] + z[1] * z[1]);
}

static void kepler_energy(void)
{
    hl_error err;
    fixture f;
    if (!fixture_open(&f, "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "avf"))
        return;
    hl_scheme_stepper *st = f.st;
    double z[4] = {0.5, 0, 0, 1.7320508075688772}, H0 = kepler_H(z), worst = 0;
    for (int k = 0; k < 200; k++) {
        CHECK_MSG(hl_scheme_step(st, z, 0.05, k * 0.05, &err) == HL_OK, "Kepler: %s", err.msg);
        worst = fmax(worst, fabs(kepler_H(z) - H0));
    }
    CHECK_MSG(worst <= 1e-14, "Kepler avf: |H - H0| up to %.3g", worst);
    printf("%-28s avf, 200 steps of 0.05: |H - H0| <= %.1e\n", "Kepler e = 0.5", worst);
    fixture_close(&f);
}

/* The Gonzalez step of the pendulum from its closed form (Newton with a
 * finite-difference Jacobian in long double). */
static void gonzalez_closed(double *z, double D)
{
    ld q = z[0], p = z[1], Q = q + D * p, P = p - D * sinl(q);
    for (int it = 0; it < 60; it++) {
        ld F[2], J[2][2], U[2] = {Q, P};
        for (int c = -1; c < 2; c++) {
            ld u[2] = {U[0], U[1]}, e = 1e-9L, f[2];
            if (c >= 0)
                u[c] += e;
            ld h = u[0] - q, v = u[1] - p, m = (q + u[0]) / 2, n2 = h * h + v * v;
            ld r = n2 > 0 ? (2 * sinl(h / 2) - h) / n2 : 0;
            f[0] = h - D * ((p + u[1]) / 2 + sinl(m) * r * v);
            f[1] = v + D * sinl(m) * (1 + r * h);
            for (int i = 0; i < 2; i++) {
                if (c < 0)
                    F[i] = f[i];
                else
                    J[i][c] = (f[i] - F[i]) / e;
            }
        }
        ld det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        ld dQ = -(J[1][1] * F[0] - J[0][1] * F[1]) / det;
        ld dP = -(-J[1][0] * F[0] + J[0][0] * F[1]) / det;
        Q += dQ, P += dP;
        if (fabsl(dQ) + fabsl(dP) < 1e-19L)
            break;
    }
    z[0] = (double)Q, z[1] = (double)P;
}

static void gonzalez_against_closed_form(void)
{
    hl_error err;
    fixture f;
    if (!fixture_open(&f, "p^2/2 - cos(q)", "gonzalez"))
        return;
    hl_scheme_stepper *st = f.st;
    static const double steps[] = {0.01, 0.1, 0.3}, max_its[] = {3.5, 4.5, 6};
    double worst = 0;
    for (int i = 0; i < 3; i++) {
        double a[2] = {1.3, 0}, b[2];
        long its = 0;
        for (int k = 0; k < 300; k++) {
            memcpy(b, a, sizeof b);
            CHECK_MSG(hl_scheme_step(st, a, steps[i], 0, &err) == HL_OK, "gonzalez: %s", err.msg);
            its += hl_scheme_stepper_iterations(st);
            gonzalez_closed(b, steps[i]);
            for (int j = 0; j < 2; j++) {
                double d = fabs(a[j] - b[j]) / fmax(1, fabs(b[j]));
                worst = fmax(worst, d);
                CHECK_MSG(d <= 2e-15, "gonzalez, D = %g, step %d: %.17g vs %.17g", steps[i], k,
                          a[j], b[j]);
            }
        }
        CHECK_MSG(its <= max_its[i] * 300, "gonzalez, D = %g: %.2f Newton iterations a step",
                  steps[i],
                  its / 300.0);
        printf("%-28s gonzalez, D = %g: closed form to %.1e, %.2f Newton iterations a step\n",
               "p^2/2 - cos(q)", steps[i], worst, its / 300.0);
    }
    fixture_close(&f);
}

/* Gonzalez's remainder int_0^1 (grad H(z + s d) - grad H(m)).d ds: its
 * Taylor term of order 0 at s = 1/2 is the node 0 (no rounding of O(1)
 * values in R), for H with sin, with powers, with 1/sqrt. */
static void gonzalez_order0(void)
{
    static const char *const Hs[] = {"p^2/2 - cos(q)",
                                      "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
                                      "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "p^4/4 + q^6 + q*p"};
    for (int i = 0; i < 4; i++) {
        hl_error err;
        hl_system_spec spec = {Hs[i], NULL, NULL, NULL, NULL};
        hl_system *sys = NULL;
        hl_scheme *s = NULL;
        if (hl_system_new(&sys, &spec, &err) != HL_OK ||
            hl_scheme_new(&s, "gonzalez", 0, sys, &err) != HL_OK) {
            CHECK_MSG(0, "%s: %s", Hs[i], err.msg);
            continue;
        }
        hl_pool *pool = hl_system_pool(sys);
        const hl_expr *c[2];
        CHECK(s->nint == 1);
        hl_expr_taylor(c, pool, s->int_body[0], HL_SCHEME_S, hl_num_frac(pool, 1, 2), 1);
        CHECK_MSG(c[0] == hl_num_si(pool, 0), "%s: the remainder's term of order 0 is not 0",
                  Hs[i]);
        hl_scheme_free(s);
        hl_system_free(sys);
    }
}

int main(void)
{
    against_closed_form("p^2/2 - cos(q)", quot_pendulum, 5, 0);
    against_closed_form("p^2/2 - cos(3*q)/9", quot_cos3, 4, 2);
    against_closed_form("p^2/2 + (1 - exp(-q))^2", quot_morse, 5, 0);
    against_closed_form("p^2/2 + q^4/4", quot_quartic, 5, 0);
    long_steps();
    kepler_energy();
    gonzalez_against_closed_form();
    gonzalez_order0();
    return HL_TEST_END();
}
