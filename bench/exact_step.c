/* Benchmark (issue 6): the numeric exact scheme of the pendulum
 * H = p^2/2 - cos(q) from q = 1.3, p = 0, step D = 0.5.
 * Prints ns per call, best of 5 runs:
 *   setup      hl_exact_flow_new + the orbit table (turning point, period
 *              refined in Arb, samples of the half period in Arb);
 *   step       one exact step chained from its own output (time carried);
 *   step-find  one exact step from a point it did not produce (the time on
 *              the orbit is found by Newton on the table polynomial);
 *   lie        one step of D = 0.5 of the Taylor (Lie-series) integrator at
 *              tol 1e-15, interpreted tape (what `hamlie run` uses as the
 *              reference);
 * and the ratios lie / step, lie / step-find. */
#include <math.h>
#include <stdio.h>
#include <time.h>

#include "hamlie/exact.h"
#include "hamlie/flow.h"
#include "hamlie/tape.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    hl_system_spec spec = {"p^2/2 - cos(q)", NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_error err;
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        return fprintf(stderr, "%s\n", err.msg), 1;
    double best_setup = INFINITY, best_step = INFINITY, best_find = INFINITY,
           best_lie = INFINITY;
    const int nstep = 20000;
    for (int rep = 0; rep < 5; rep++) {
        hl_exact_flow *f = NULL, *g = NULL;
        double z[2] = {1.3, 0};
        double t0 = now();
        hl_exact_flow_new(&f, sys, &err);
        double T;
        hl_exact_flow_period(&T, z, f, &err);
        best_setup = fmin(best_setup, now() - t0);
        hl_exact_flow_new(&g, sys, &err);
        hl_exact_flow_period(&T, z, g, &err);
        t0 = now();
        for (int i = 0; i < nstep; i++)
            hl_exact_flow_step(z, 0.5, f, &err);
        best_step = fmin(best_step, (now() - t0) / nstep);
        /* alternate two flows: each sees a point the other produced */
        t0 = now();
        for (int i = 0; i < nstep; i++)
            hl_exact_flow_step(z, 0.5, i % 2 ? f : g, &err);
        best_find = fmin(best_find, (now() - t0) / nstep);
        hl_exact_flow_free(f);
        hl_exact_flow_free(g);

        hl_tape *tape = NULL;
        hl_flow *fl = NULL;
        const char *q = "q", *p = "p";
        hl_tape_hamiltonian(&tape, hl_system_pool(sys), hl_system_H_expr(sys), 1, &q, &p, 0,
                            NULL, NULL, &err);
        hl_flow_new(&fl, tape, 1e-15, 1e-15, &err);
        double w[2] = {1.3, 0}, t = 0;
        const int nl = 2000;
        t0 = now();
        for (int i = 1; i <= nl; i++)
            hl_flow_evolve(fl, &t, 0.5 * i, w, &err);
        best_lie = fmin(best_lie, (now() - t0) / nl);
        hl_flow_free(fl);
        hl_tape_free(tape);
    }
    printf("setup      %12.0f ns\n", best_setup * 1e9);
    printf("step       %12.1f ns\n", best_step * 1e9);
    printf("step-find  %12.1f ns\n", best_find * 1e9);
    printf("lie        %12.1f ns\n", best_lie * 1e9);
    printf("lie/step %.1f  lie/step-find %.1f  setup/lie %.1f\n", best_lie / best_step,
           best_lie / best_find, best_setup / best_lie);
    hl_system_free(sys);
    return 0;
}
