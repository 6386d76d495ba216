/* Benchmark: fixed-step runs of an ensemble, one member at a time against
 * the batch (hl_run_fixed_batch: the members' fused step-and-H loop side by
 * side in SIMD lanes).  Störmer–Verlet (or the scheme given), dt = 0.01,
 * 10^5 steps, 64 members near a base point of each system, in one process:
 *   single-interp  hl_run_fixed per member, machine code off (the stepper)
 *   single-jit     hl_run_fixed per member, machine code on: the compiled
 *                  scalar loop (hl_tape_iterate_watch), the fastest path
 *                  one member at a time
 *   batch-L        hl_run_fixed_batch with L lanes (2, 4, 8)
 * For each system (the pendulum: libm's sin and cos, called lane by lane;
 * Henon-Heiles: a polynomial, all vector arithmetic; Kepler: a square root
 * and divisions) it prints per mode: CPU seconds (the best of reps,
 * CLOCK_PROCESS_CPUTIME_ID: the machine is shared), members per second,
 * member-steps per second (ns per member-step), the time of the first call
 * (which compiles or loads the code; wall clock, as the compilation runs
 * in a child process), and whether every member's final state and max
 * |H - H0| are bit for bit single-interp's (they must be).
 * Arguments: [members 64] [steps 100000] [reps 3] [scheme stormer-verlet-kdk]
 * [system: all|pendulum|henon|kepler] [mode: all|single-interp|...].
 * CSV on stdout: system,scheme,mode,members,steps,cpu_s,members_per_s,
 * ns_per_member_step,first_call_ms,identical.
 *
 * Measured 2026-11-28 (commit 15e2188, AMD EPYC with AVX-512, 2 cores
 * shared by several jobs, load 17-21; `bench-run_batch 64 100000 3
 * <scheme>` with a fresh cache; ns a member-step, CPU, the best of 3;
 * every member bit for bit single-interp's in every mode):
 *                  interp  single-jit  batch-2  batch-4  batch-8
 *   Stormer-Verlet
 *     pendulum      112      25.0       19.5     21.4     20.4
 *     Henon-Heiles  106       9.5        4.1      2.5      1.55
 *     Kepler        186      50.5       47.0     36.8     28.2
 *   RK4
 *     pendulum      171      55.0       49.7     50.3     49.4
 *     Henon-Heiles  180      18.2        9.2      4.6      3.1
 *     Kepler        282      90.5       57.0     49.2     47.0
 *   symplectic Euler (a)
 *     pendulum       86      21.5       21.4     19.5     19.3
 *     Henon-Heiles   88       7.9        3.5      2.25     1.46
 *     Kepler        141      39.0       23.3     17.5     13.9
 * Lanes pay where the step is arithmetic (Henon-Heiles: 3.5-4x at 4
 * lanes, 5-6x at 8); libm's functions are called lane by lane, so the
 * pendulum (sin and cos: one of each a step even with the carried sin, H
 * is watched) gains 10-20 % and Kepler (libm's pow for r^(-3/2)) 1.3-2.8x.
 * The first call (compiling the lanes' loop, wall clock on the loaded
 * machine) took 0.5-2.6 s; a cached entry loads in under a millisecond. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/run.h"

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

static const struct {
    const char *name, *H, *init;
    double spread;
} systems[] = {
    {"pendulum", "p^2/2 - cos(q)", "q=1.3,p=0.1", 0.5},
    {"henon", "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", "x=0,y=0.1,px=0.3,py=0.05", 0.1},
    {"kepler", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "x=1,y=0,px=0,py=1.1", 0.2},
};

typedef struct bench {
    hl_system *sys;
    hl_scheme *sch;
    hl_run *run;
    int n2, B;
    long steps;
    double *z0, *z, *dH;
} bench;

static void die(const char *what, const hl_error *err)
{
    fprintf(stderr, "run_batch: %s: %s\n", what, err->msg);
    exit(1);
}

/* member i: the base point moved along a curve through the box of size
 * `spread` (all different) */
static void bench_new(bench *b, int s, const char *scheme, int B, long steps)
{
    hl_error err;
    hl_system_spec spec = {systems[s].H, NULL, NULL, NULL, NULL};
    if (hl_system_new(&b->sys, &spec, &err) != HL_OK ||
        hl_scheme_new(&b->sch, scheme, 0, b->sys, &err) != HL_OK ||
        hl_run_new(&b->run, b->sys, b->sch, &err) != HL_OK)
        die(systems[s].name, &err);
    hl_run_set_reference(b->run, 0, 0);
    b->n2 = 2 * hl_system_ndof(b->sys);
    b->B = B;
    b->steps = steps;
    b->z0 = malloc((size_t)(B * b->n2) * sizeof *b->z0);
    b->z = malloc((size_t)(B * b->n2) * sizeof *b->z);
    b->dH = malloc((size_t)B * sizeof *b->dH);
    double base[4];
    if (hl_run_init_values(base, b->sys, systems[s].init, &err) != HL_OK)
        die("init", &err);
    for (int i = 0; i < B; i++)
        for (int c = 0; c < b->n2; c++)
            b->z0[i * b->n2 + c] =
                base[c] + systems[s].spread * sin(0.7 * i * (c + 1) + c) * (i + 1) / B;
}

static void bench_free(bench *b)
{
    hl_run_free(b->run);
    hl_scheme_free(b->sch);
    hl_system_free(b->sys);
    free(b->z0), free(b->z), free(b->dH);
}

typedef struct result {
    double cpu, first_ms;
    int ok;
} result;

static result run_single(bench *b, int jit)
{
    result r = {0, 0, 1};
    hl_run_set_jit(b->run, jit);
    double t = 0.01 * (double)b->steps, c0 = cpu();
    for (int i = 0; i < b->B; i++) {
        hl_run_stats s;
        hl_error err;
        double w0 = wall();
        r.ok &= hl_run_fixed(b->run, b->z0 + i * b->n2, 0.01, t, 1, NULL, NULL, &s, &err) == HL_OK;
        if (i == 0) /* the compilation (or the cache's load) is in the first member */
            r.first_ms = 1e3 * (wall() - w0);
        memcpy(b->z + i * b->n2, hl_run_state(b->run), (size_t)b->n2 * sizeof *b->z);
        b->dH[i] = s.max_dH;
    }
    r.cpu = cpu() - c0;
    return r;
}

/* the batch's loop compiled (or loaded) by a first call outside the timing */
static result run_batch(bench *b, int lanes)
{
    result r = {0, 0, 1};
    hl_run_set_jit(b->run, 1);
    hl_run_set_lanes(b->run, lanes, NULL);
    double t = 0.01 * (double)b->steps;
    double w0 = wall();
    int used = hl_run_batch_lanes(b->run, b->B, 0.01, t);
    r.first_ms = 1e3 * (wall() - w0);
    if (used != lanes)
        fprintf(stderr, "run_batch: %d lanes asked, %d used\n", lanes, used);
    hl_run_stats *s = malloc((size_t)b->B * sizeof *s);
    hl_status *st = malloc((size_t)b->B * sizeof *st);
    double c0 = cpu();
    r.ok = hl_run_fixed_batch(b->run, b->B, b->z0, 0.01, t, b->z, s, st, NULL, NULL) == HL_OK;
    r.cpu = cpu() - c0;
    for (int i = 0; i < b->B; i++)
        b->dH[i] = s[i].max_dH;
    free(s), free(st);
    return r;
}

static result run_mode(bench *b, const char *mode)
{
    if (!strcmp(mode, "single-interp"))
        return run_single(b, 0);
    if (!strcmp(mode, "single-jit"))
        return run_single(b, 1);
    return run_batch(b, atoi(mode + strlen("batch-")));
}

int main(int argc, char **argv)
{
    int B = argc > 1 ? atoi(argv[1]) : 64, reps = argc > 3 ? atoi(argv[3]) : 3;
    long steps = argc > 2 ? atol(argv[2]) : 100000;
    const char *scheme = argc > 4 ? argv[4] : "stormer-verlet-kdk";
    const char *only_sys = argc > 5 ? argv[5] : "all", *only = argc > 6 ? argv[6] : "all";
    static const char *const modes[] = {"single-interp", "single-jit", "batch-2", "batch-4",
                                        "batch-8"};
    printf("system,scheme,mode,members,steps,cpu_s,members_per_s,ns_per_member_step,"
           "first_call_ms,identical\n");
    for (int s = 0; s < 3; s++) {
        if (strcmp(only_sys, "all") && strcmp(only_sys, systems[s].name))
            continue;
        bench b;
        bench_new(&b, s, scheme, B, steps);
        size_t nz = (size_t)(B * b.n2);
        double *ref = malloc(nz * sizeof *ref), *refdH = malloc((size_t)B * sizeof *refdH);
        run_mode(&b, "single-interp"); /* the reference bits */
        memcpy(ref, b.z, nz * sizeof *ref);
        memcpy(refdH, b.dH, (size_t)B * sizeof *refdH);
        for (size_t m = 0; m < sizeof modes / sizeof *modes; m++) {
            if (strcmp(only, "all") && strcmp(only, modes[m]))
                continue;
            result best = {INFINITY, 0, 0};
            double first_ms = 0;
            for (int r = 0; r < reps; r++) {
                result x = run_mode(&b, modes[m]);
                if (r == 0) /* the later reps find the code in the run */
                    first_ms = x.first_ms;
                if (x.cpu < best.cpu)
                    best = x;
            }
            int same = best.ok && memcmp(b.z, ref, nz * sizeof *ref) == 0 &&
                       memcmp(b.dH, refdH, (size_t)B * sizeof *refdH) == 0;
            printf("%s,%s,%s,%d,%ld,%.4f,%.1f,%.2f,%.1f,%s\n", systems[s].name, scheme, modes[m], B,
                   steps, best.cpu, B / best.cpu, 1e9 * best.cpu / ((double)B * steps), first_ms,
                   same ? "yes" : "NO");
            fflush(stdout);
        }
        free(ref), free(refdH);
        bench_free(&b);
    }
    return 0;
}
