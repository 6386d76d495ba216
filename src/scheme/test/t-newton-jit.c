/* The compiled Newton solve (tape.h: hl_newton_jit, through
 * hl_scheme_stepper_jit) takes the interpreter's steps bit for bit: every
 * implicit scheme of the catalog on the pendulum, on the non-separable
 * H = (p^2 + q^2)^2/4 + q p (where even the symplectic Euler methods and
 * Stormer-Verlet are implicit) and on Henon-Heiles, 500 steps, the same
 * states and the same Newton iteration counts; and the same failure (gauss3
 * with D = 50: no convergence, the same message). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/scheme.h"
#include "hamlie/tape.h"

static void compare(const char *H, const char *name, const double *z0, int n2, double D)
{
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_scheme *s = NULL;
    hl_scheme_stepper *a = NULL, *b = NULL;
    if (hl_system_new(&sys, &spec, &err) != HL_OK || hl_scheme_new(&s, name, 0, sys, &err) != HL_OK ||
        hl_scheme_stepper_new(&a, s, &err) != HL_OK || hl_scheme_stepper_new(&b, s, &err) != HL_OK) {
        CHECK_MSG(0, "%s / %s: %s", H, name, err.msg);
        return;
    }
    int compiled = hl_scheme_stepper_jit(b, 1000000000L);
    double za[8], zb[8];
    memcpy(za, z0, (size_t)n2 * sizeof *za);
    memcpy(zb, z0, (size_t)n2 * sizeof *zb);
    int bad = 0, its = 0;
    for (int k = 0; k < 500 && !bad; k++) {
        int sa = hl_scheme_step(a, za, D, k * D, &err);
        int sb = hl_scheme_step(b, zb, D, k * D, &err);
        its += hl_scheme_stepper_iterations(a);
        bad = sa != HL_OK || sb != HL_OK || memcmp(za, zb, (size_t)n2 * sizeof *za) != 0 ||
              hl_scheme_stepper_iterations(a) != hl_scheme_stepper_iterations(b);
        if (bad)
            printf("%s / %s: step %d: %d %d, %.17g vs %.17g\n", H, name, k + 1, sa, sb, za[0],
                   zb[0]);
    }
    CHECK_MSG(!bad, "%s / %s differs", H, name);
    printf("%-28s %-20s %d tapes compiled, 500 steps bitwise equal, %.2f iterations/step\n", H,
           name, compiled, its / 500.0);
    hl_scheme_stepper_free(a);
    hl_scheme_stepper_free(b);
    hl_scheme_free(s);
    hl_system_free(sys);
}

static void failure(void)
{
    hl_error ea, eb;
    hl_system_spec spec = {"p^2/2 - cos(q)", NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_scheme *s = NULL;
    hl_scheme_stepper *a = NULL, *b = NULL;
    CHECK(hl_system_new(&sys, &spec, &ea) == HL_OK && hl_scheme_new(&s, "gauss3", 0, sys, &ea) == HL_OK &&
          hl_scheme_stepper_new(&a, s, &ea) == HL_OK && hl_scheme_stepper_new(&b, s, &ea) == HL_OK);
    hl_scheme_stepper_jit(b, 1000000000L);
    double za[2] = {1.3, 0}, zb[2] = {1.3, 0};
    int sa = hl_scheme_step(a, za, 50, 0, &ea), sb = hl_scheme_step(b, zb, 50, 0, &eb);
    CHECK_MSG(sa == HL_ENOCONV && sb == HL_ENOCONV && strcmp(ea.msg, eb.msg) == 0,
              "%d %d\n  %s\n  %s", sa, sb, ea.msg, eb.msg);
    CHECK(za[0] == 1.3 && zb[0] == 1.3 && za[1] == 0 && zb[1] == 0);
    printf("failure: %s\n", eb.msg);
    hl_scheme_stepper_free(a);
    hl_scheme_stepper_free(b);
    hl_scheme_free(s);
    hl_system_free(sys);
}

int main(void)
{
    if (!hl_tape_jit_available()) {
        printf("no libgccjit: nothing to compare\n");
        return HL_TEST_END();
    }
    static const char *implicit[] = {"implicit-midpoint", "gauss2", "gauss3", "avf",
                                      "gonzalez", "itoh-abe"};
    double zp[2] = {1.3, 0.2}, zn[2] = {0.6, -0.3}, zh[4] = {0.1, -0.2, 0.3, 0.25};
    for (int i = 0; i < 6; i++) {
        compare("p^2/2 - cos(q)", implicit[i], zp, 2, 0.05);
        compare("(p^2 + q^2)^2/4 + q*p", implicit[i], zn, 2, 0.02);
        compare("(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", implicit[i], zh, 4, 0.05);
    }
    static const char *split[] = {"symplectic-euler-a", "symplectic-euler-b",
                                  "stormer-verlet-kdk", "stormer-verlet-dkd"};
    for (int i = 0; i < 4; i++)
        compare("(p^2 + q^2)^2/4 + q*p", split[i], zn, 2, 0.02);
    failure();
    return HL_TEST_END();
}
