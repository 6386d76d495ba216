/* Benchmark: hl_run_fixed (the scheme's stepper tape, H evaluated at every
 * step for max |H - H0|, no rows written) against the same scheme written
 * by hand in C, in the same process, on the pendulum H = p^2/2 - cos(q) from
 * (1.3, 0), dt = 0.01, 10^6 steps.  Two hand-written figures: the step
 * alone, and the step plus H at every step (what the driver computes).
 * Also: the driver with the reference trajectory on (sigma at every step).
 * Prints milliseconds (best of reps) and the ratios; the final states must
 * agree (checked: |difference| < 1e-9, else exit 1).
 * Arguments: [reps] (default 5) [jit] (hl_run_set_jit: H compiled by
 * libgccjit, as the CLI does). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/run.h"

#define DT 0.01
#define NSTEPS 1000000L

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* volatile sink so the compiler keeps the H evaluations */
static volatile double sink;

static void euler(double *z, int withH)
{
    double q = z[0], p = z[1], H0 = p * p / 2 - cos(q), m = 0;
    for (long k = 0; k < NSTEPS; k++) {
        double Q = q + DT * p, P = p - DT * sin(q);
        q = Q, p = P;
        if (withH)
            m = fmax(m, fabs(p * p / 2 - cos(q) - H0));
    }
    z[0] = q, z[1] = p, sink = m;
}

static void verlet(double *z, int withH)
{
    double q = z[0], p = z[1], H0 = p * p / 2 - cos(q), m = 0;
    for (long k = 0; k < NSTEPS; k++) {
        double ph = p - DT / 2 * sin(q);
        q = q + DT * ph;
        p = ph - DT / 2 * sin(q);
        if (withH)
            m = fmax(m, fabs(p * p / 2 - cos(q) - H0));
    }
    z[0] = q, z[1] = p, sink = m;
}

static void rk4(double *z, int withH)
{
    double q = z[0], p = z[1], H0 = p * p / 2 - cos(q), m = 0;
    for (long k = 0; k < NSTEPS; k++) {
        double k1q = p, k1p = -sin(q);
        double k2q = p + DT / 2 * k1p, k2p = -sin(q + DT / 2 * k1q);
        double k3q = p + DT / 2 * k2p, k3p = -sin(q + DT / 2 * k2q);
        double k4q = p + DT * k3p, k4p = -sin(q + DT * k3q);
        q += DT / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
        p += DT / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
        if (withH)
            m = fmax(m, fabs(p * p / 2 - cos(q) - H0));
    }
    z[0] = q, z[1] = p, sink = m;
}

static double best_hand(void (*f)(double *, int), int withH, int reps, double *z)
{
    double best = 1e300;
    for (int r = 0; r < reps; r++) {
        z[0] = 1.3, z[1] = 0;
        double t0 = now();
        f(z, withH);
        best = fmin(best, now() - t0);
    }
    return best;
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 5, bad = 0;
    int jit = argc > 2 && strcmp(argv[2], "jit") == 0;
    const char *names[] = {"euler", "stormer-verlet-kdk", "rk4"};
    void (*hand[])(double *, int) = {euler, verlet, rk4};
    hl_error err;
    hl_system_spec spec = {"p^2/2 - cos(q)", NULL, NULL, NULL};
    hl_system *sys = NULL;
    if (hl_system_new(&sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "run_fixed: %s\n", err.msg);
        return 1;
    }
    printf("pendulum, dt = %g, %ld steps, best of %d (ms)%s\n", DT, NSTEPS, reps,
           jit ? ", H by libgccjit" : "");
    printf("%-20s %9s %9s %9s %7s %7s %12s\n", "scheme", "hand", "hand+H", "hl_run", "ratio",
           "ratioH", "hl_run+ref");
    for (int i = 0; i < 3; i++) {
        hl_scheme *s = NULL;
        hl_run *run = NULL;
        if (hl_scheme_new(&s, names[i], 0, sys, &err) != HL_OK ||
            hl_run_new(&run, sys, s, &err) != HL_OK) {
            fprintf(stderr, "run_fixed: %s\n", err.msg);
            return 1;
        }
        double zh[2], zhh[2], z0[2] = {1.3, 0};
        double th = best_hand(hand[i], 0, reps, zh), thh = best_hand(hand[i], 1, reps, zhh);
        double td = 1e300, tr = 1e300;
        hl_run_set_reference(run, 0, 0);
        hl_run_set_jit(run, jit);
        for (int r = 0; r < reps; r++) {
            double t0 = now();
            if (hl_run_fixed(run, z0, DT, NSTEPS * DT, 1, NULL, NULL, NULL, &err) != HL_OK) {
                fprintf(stderr, "run_fixed: %s\n", err.msg);
                return 1;
            }
            td = fmin(td, now() - t0);
        }
        const double *z = hl_run_state(run);
        double diff = fmax(fabs(z[0] - zh[0]), fabs(z[1] - zh[1]));
        if (!(diff < 1e-9)) {
            fprintf(stderr, "run_fixed: %s: states differ by %.3g\n", names[i], diff);
            bad = 1;
        }
        hl_run_set_reference(run, 1, 1e-15);
        for (int r = 0; r < (reps > 2 ? 2 : reps); r++) {
            double t0 = now();
            hl_run_fixed(run, z0, DT, NSTEPS * DT, 1, NULL, NULL, NULL, &err);
            tr = fmin(tr, now() - t0);
        }
        printf("%-20s %9.1f %9.1f %9.1f %7.2f %7.2f %12.1f\n", names[i], 1e3 * th, 1e3 * thh,
               1e3 * td, td / th, td / thh, 1e3 * tr);
        hl_run_free(run);
        hl_scheme_free(s);
    }
    hl_system_free(sys);
    return bad;
}
