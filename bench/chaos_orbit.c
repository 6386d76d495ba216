/* Benchmark (issue 15 part 3): the cost of one orbit's chaos indicators,
 * the per-member cost of a chaos map.  Henon-Heiles at E = 1/6 from
 * x = 0, y = -0.1, py = 0 (chaotic), t = 1000, tol 1e-13:
 *   chaos   hl_chaos_run (orbit + variational equations + MEGNO integrals,
 *           12 components), the hl_chaos built once outside the timing;
 *   orbit   the orbit alone by hl_flow_evolve (4 components), same tol;
 * the median CPU time of 7 runs of each, interleaved (the machine is shared), their
 * Taylor steps and the ratio chaos / orbit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "hamlie/chaos.h"
#include "hamlie/flow.h"
#include "hamlie/tape.h"

#define RUNS 7

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); /* CPU time: the machine is shared */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(void)
{
    hl_system_spec spec = {"(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_chaos *chaos = NULL;
    hl_tape *tape = NULL;
    hl_error err;
    const char *q[2] = {"x", "y"}, *p[2] = {"px", "py"};
    double y = -0.1, T = 1000, tol = 1e-13;
    double z0[4] = {0, y, sqrt(2 * (1.0 / 6 - (y * y / 2 - y * y * y / 3))), 0};
    if (hl_system_new(&sys, &spec, &err) != HL_OK ||
        hl_chaos_new(&chaos, sys, tol, &err) != HL_OK ||
        hl_tape_hamiltonian(&tape, hl_system_pool(sys), hl_system_H_expr(sys), 2, q, p, 0, NULL,
                            NULL, &err) != HL_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    double tc[RUNS], to[RUNS];
    long steps_chaos = 0, steps_orbit = 0;
    for (int r = 0; r < RUNS; r++) {
        hl_chaos_result res;
        double t0 = now();
        if (hl_chaos_run(chaos, z0, NULL, T, 0, NULL, NULL, &res, &err) != HL_OK)
            return fprintf(stderr, "%s\n", err.msg), 1;
        tc[r] = now() - t0;
        steps_chaos = res.nsteps;
        hl_flow *flow = NULL;
        double z[4] = {z0[0], z0[1], z0[2], z0[3]}, t = 0;
        t0 = now();
        if (hl_flow_new(&flow, tape, tol, tol, &err) != HL_OK ||
            hl_flow_evolve(flow, &t, T, z, &err) != HL_OK)
            return fprintf(stderr, "%s\n", err.msg), 1;
        to[r] = now() - t0;
        steps_orbit = hl_flow_nsteps(flow);
        hl_flow_free(flow);
    }
    qsort(tc, RUNS, sizeof *tc, by_value);
    qsort(to, RUNS, sizeof *to, by_value);
    printf("chaos  %8.2f ms  %ld steps\n", 1e3 * tc[RUNS / 2], steps_chaos);
    printf("orbit  %8.2f ms  %ld steps\n", 1e3 * to[RUNS / 2], steps_orbit);
    printf("ratio  %8.2f   (tape of the orbit: %d instructions)\n", tc[RUNS / 2] / to[RUNS / 2],
           hl_tape_nops(tape));
    hl_tape_free(tape);
    hl_chaos_free(chaos);
    hl_system_free(sys);
    return 0;
}
