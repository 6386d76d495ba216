/* The integrals of the discrete gradients (step.c: Gauss-Legendre or the
 * Taylor series at s = 1/2, whichever is cheaper) against closed forms.
 *
 * Average vector field for a separable H = p^2/2 + V(q):
 *   Q = q + D (p + P)/2,  P = p - D (V(Q) - V(q)) / (Q - q),
 * solved here by bisection on P in long double with the difference quotient
 * written without cancellation:
 *   pendulum V = -cos q: (V(Q) - V(q))/(Q - q) = sin(m) sin(h/2)/(h/2);
 *   Morse V = (1 - e^-q)^2: = (e^-q - e^-Q)(2 - e^-q - e^-Q)/(Q - q), with
 *     e^-q - e^-Q = 2 e^-m sinh(h/2);
 *   quartic V = q^4/4: (Q^4 - q^4)/(4 (Q - q)) = (Q^3 + Q^2 q + Q q^2 + q^3)/4
 * (m = (q + Q)/2, h = Q - q).  Steps D = 0.01 to 1, several points: the
 * stepper's next point must equal the closed form's to 2e-15 relative.
 * Kepler (where the Gauss rule is the cheaper) is checked by energy: the
 * average vector field conserves H exactly, so |H(Z) - H(z)| is the rule's
 * error, at most 1e-14. */
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

static ld quot_quartic(ld q, ld Q)
{
    return (Q * Q * Q + Q * Q * q + Q * q * q + q * q * q) / 4;
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

static void against_closed_form(const char *H, ld (*quot)(ld, ld))
{
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_scheme *s = NULL;
    hl_scheme_stepper *st = NULL;
    if (hl_system_new(&sys, &spec, &err) != HL_OK || hl_scheme_new(&s, "avf", 0, sys, &err) != HL_OK ||
        hl_scheme_stepper_new(&st, s, &err) != HL_OK) {
        CHECK_MSG(0, "%s: %s", H, err.msg);
        return;
    }
    static const double steps[] = {0.01, 0.1, 0.3, 1.0};
    static const double pts[][2] = {{1.3, 0}, {0.2, 0.9}, {-0.7, 0.4}, {1e-9, 0.3}};
    double worst = 0;
    for (int i = 0; i < 4; i++)
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
    printf("%-28s avf = closed form to %.1e\n", H, worst);
    hl_scheme_stepper_free(st);
    hl_scheme_free(s);
    hl_system_free(sys);
}

static double kepler_H(const double *z)
{
    return (z[2] * z[2] + z[3] * z[3]) / 2 - 1 / sqrt(z[0] * z[0] + z[1] * z[1]);
}

static void kepler_energy(void)
{
    hl_error err;
    hl_system_spec spec = {"(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_scheme *s = NULL;
    hl_scheme_stepper *st = NULL;
    if (hl_system_new(&sys, &spec, &err) != HL_OK || hl_scheme_new(&s, "avf", 0, sys, &err) != HL_OK ||
        hl_scheme_stepper_new(&st, s, &err) != HL_OK) {
        CHECK_MSG(0, "Kepler: %s", err.msg);
        return;
    }
    double z[4] = {0.5, 0, 0, 1.7320508075688772}, H0 = kepler_H(z), worst = 0;
    for (int k = 0; k < 200; k++) {
        CHECK_MSG(hl_scheme_step(st, z, 0.05, k * 0.05, &err) == HL_OK, "Kepler: %s", err.msg);
        worst = fmax(worst, fabs(kepler_H(z) - H0));
    }
    CHECK_MSG(worst <= 1e-14, "Kepler avf: |H - H0| up to %.3g", worst);
    printf("%-28s avf, 200 steps of 0.05: |H - H0| <= %.1e\n", "Kepler e = 0.5", worst);
    hl_scheme_stepper_free(st);
    hl_scheme_free(s);
    hl_system_free(sys);
}

int main(void)
{
    against_closed_form("p^2/2 - cos(q)", quot_pendulum);
    against_closed_form("p^2/2 + (1 - exp(-q))^2", quot_morse);
    against_closed_form("p^2/2 + q^4/4", quot_quartic);
    kepler_energy();
    return HL_TEST_END();
}
