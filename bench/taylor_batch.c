/* Benchmark: the Taylor integrator on an ensemble, one member at a time
 * against the batch mode (hl_flow_batch: the members' recursions side by
 * side in SIMD lanes).  Henon-Heiles, tol 1e-15, t = 1000, 64 members
 * seeded on the section x = 0 (px > 0) at E = 1/12, 1/8 and 1/6 (from
 * invariant curves to the chaotic sea), in one process:
 *   single-interp  hl_flow_evolve per member, the recursion interpreted
 *   single-native  the same with the recursion compiled (hl_tape_native)
 *   batch-L        hl_flow_batch_evolve with L lanes (2, 4, 8)
 * Prints per mode: CPU seconds (the best of reps, CLOCK_PROCESS_CPUTIME_ID:
 * the machine is shared), members per second, steps per second, the
 * compile/load time outside the timing (wall clock: the compilation runs
 * in a child process; the first rep of a mode compiles, later reps load
 * the disk cache, so the setup printed is the best rep's), and whether every member's final
 * state is bit for bit the interpreted single run's (it must be).
 * Arguments: [members 64] [T 1000] [reps 3] [mode: all|single-interp|
 * single-native|batch-2|batch-4|batch-8] [noref] (one mode alone, and
 * noref: without the reference run, for callgrind; identical is then "-").
 * CSV on stdout: mode,members,T,cpu_s,members_per_s,steps,steps_per_s,
 * setup_ms,identical.  bench/taylor_batch.sh runs it beside heyoka's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/flow.h"

#define TOL 1e-15

/* wall time, for the compilation (in a child process when the cache is on) */
static double wall(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* member i of B: energy E from {1/12, 1/8, 1/6} by thirds, y spread over
 * the section's allowed range at that energy, x = py = 0, px > 0 from H */
static void seed(double *z, int i, int B)
{
    static const double E[3] = {1.0 / 12, 1.0 / 8, 1.0 / 6};
    int g = i % 3, j = i / 3, nj = (B + 2 - g) / 3;
    double e = E[g];
    /* at x = px = py = 0, H = y^2/2 - y^3/3 = E: y from -ymax to +ymax, inside */
    double lo = -0.95 * (g == 0 ? 0.36 : g == 1 ? 0.42 : 0.48), hi = 0.95 * (g == 2 ? 0.72 : 0.5);
    double y = nj > 1 ? lo + (hi - lo) * j / (nj - 1) : 0.1;
    double u = 2 * e - y * y + 2 * y * y * y / 3;
    z[0] = 0;
    z[1] = y;
    z[2] = sqrt(u > 0 ? u : 0);
    z[3] = 0;
}

static hl_tape *henon_heiles(void)
{
    hl_pool *P = hl_pool_new();
    const char *q[] = {"x", "y"}, *p[] = {"px", "py"};
    const hl_expr *H;
    hl_error err;
    hl_tape *t = NULL;
    if (hl_parse(&H, P, "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", &err) != HL_OK ||
        hl_tape_hamiltonian(&t, P, H, 2, q, p, 0, NULL, NULL, &err) != HL_OK) {
        fprintf(stderr, "taylor_batch: %s\n", err.msg);
        exit(1);
    }
    hl_pool_free(P);
    return t;
}

typedef struct result {
    double cpu, setup_ms;
    long steps;
    int ok;
} result;

/* one member at a time; native: the recursion compiled first */
static result run_single(hl_tape *t, int B, double T, double *z, int native)
{
    result r = {0};
    hl_flow *f = NULL;
    hl_error err;
    if (hl_flow_new(&f, t, TOL, TOL, &err) != HL_OK)
        exit(1);
    double c0 = wall();
    if (native && hl_tape_native(t, hl_flow_order(f), &err) != HL_OK)
        fprintf(stderr, "taylor_batch: no native recursion: %s\n", err.msg);
    r.setup_ms = 1e3 * (wall() - c0);
    c0 = cpu();
    r.ok = 1;
    for (int i = 0; i < B; i++) {
        double t0 = 0;
        long before = hl_flow_nsteps(f);
        r.ok &= hl_flow_evolve(f, &t0, T, z + 4 * (size_t)i, &err) == HL_OK;
        r.steps += hl_flow_nsteps(f) - before;
    }
    r.cpu = cpu() - c0;
    if (native)
        hl_tape_native_clear(t);
    hl_flow_free(f);
    return r;
}

static result run_batch(hl_tape *t, int B, double T, double *z, int lanes)
{
    result r = {0};
    hl_flow_batch *b = NULL;
    hl_error err;
    double c0 = wall();
    if (hl_flow_batch_new(&b, t, TOL, TOL, lanes, &err) != HL_OK) {
        fprintf(stderr, "taylor_batch: %s\n", err.msg);
        exit(1);
    }
    r.setup_ms = 1e3 * (wall() - c0);
    if (!hl_flow_batch_compiled(b))
        fprintf(stderr, "taylor_batch: %d lanes not compiled (lane by lane)\n", lanes);
    double *t0 = calloc((size_t)B, sizeof *t0), *t1 = malloc((size_t)B * sizeof *t1);
    long *steps = calloc((size_t)B, sizeof *steps);
    hl_status *st = calloc((size_t)B, sizeof *st);
    for (int i = 0; i < B; i++)
        t1[i] = T;
    c0 = cpu();
    r.ok = hl_flow_batch_evolve(b, B, t0, t1, z, st, steps, NULL, &err) == HL_OK;
    r.cpu = cpu() - c0;
    for (int i = 0; i < B; i++)
        r.steps += steps[i];
    free(t0), free(t1), free(steps), free(st);
    hl_flow_batch_free(b);
    return r;
}

static result run_mode(const char *mode, hl_tape *t, int B, double T, double *z)
{
    for (int i = 0; i < B; i++)
        seed(z + 4 * (size_t)i, i, B);
    if (!strcmp(mode, "single-interp"))
        return run_single(t, B, T, z, 0);
    if (!strcmp(mode, "single-native"))
        return run_single(t, B, T, z, 1);
    return run_batch(t, B, T, z, atoi(mode + strlen("batch-")));
}

int main(int argc, char **argv)
{
    int B = argc > 1 ? atoi(argv[1]) : 64, reps = argc > 3 ? atoi(argv[3]) : 3;
    double T = argc > 2 ? atof(argv[2]) : 1000;
    const char *only = argc > 4 ? argv[4] : "all";
    static const char *const modes[] = {"single-interp", "single-native", "batch-2", "batch-4",
                                        "batch-8"};
    hl_tape *t = henon_heiles();
    double *ref = malloc(4 * (size_t)B * sizeof *ref), *z = malloc(4 * (size_t)B * sizeof *z);
    int noref = argc > 5 && !strcmp(argv[5], "noref");
    if (!noref) {
        run_mode("single-interp", t, 1 < B ? B : 1, 0, ref); /* warm up: layout */
        run_mode("single-interp", t, B, T, ref);             /* the reference bits */
    }
    printf("mode,members,T,cpu_s,members_per_s,steps,steps_per_s,setup_ms,identical\n");
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++) {
        if (strcmp(only, "all") && strcmp(only, modes[m]))
            continue;
        result best = {INFINITY, 0, 0, 0};
        for (int r = 0; r < reps; r++) {
            result x = run_mode(modes[m], t, B, T, z);
            if (x.cpu < best.cpu)
                best = x;
        }
        int same = best.ok && memcmp(z, ref, 4 * (size_t)B * sizeof *z) == 0;
        printf("%s,%d,%g,%.4f,%.1f,%ld,%.0f,%.1f,%s\n", modes[m], B, T, best.cpu, B / best.cpu,
               best.steps, best.steps / best.cpu, best.setup_ms,
               noref  ? "-"
               : same ? "yes"
                      : "NO");
        fflush(stdout);
    }
    free(ref), free(z);
    hl_tape_free(t);
    return 0;
}
