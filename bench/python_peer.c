/* The C side of bench/python_overhead.py: one fixed-step run through the
 * library from C, every row copied into arrays by the row callback — what
 * the Python binding (python/src/run.c) does for its NumPy arrays — so the
 * two times differ only by what Python adds.  The same settings as
 * hamlie.System(H).run(scheme, dt=, t=, init=): reference on, the run's
 * machine code on, a progress callback (the binding's Ctrl-C check) every
 * 1024 steps.
 * Arguments: H scheme dt t init [reps] [reference 0/1].  Prints the best
 * CPU time of reps runs in milliseconds and the final state. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/run.h"

typedef struct rows {
    long k;
    int n2;
    double *t, *z, *H, *sigma;
} rows;

static int keep(const hl_run_row *row, void *arg)
{
    rows *r = arg;
    long k = r->k++;
    r->t[k] = row->t;
    memcpy(r->z + k * r->n2, row->z, (size_t)r->n2 * sizeof(double));
    r->H[k] = row->H;
    r->sigma[k] = row->sigma;
    return 0;
}

static int progress(double done, double total, void *arg)
{
    return 0;
}

/* CPU time of the process: on a machine shared by other jobs, wall time
 * measures them too (libgccjit compiles in this process, so it counts). */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int fail(const hl_error *err)
{
    fprintf(stderr, "python_peer: %s\n", err->msg);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr, "usage: bench-python_peer H scheme dt t init [reps] [reference]\n");
        return 2;
    }
    double dt = atof(argv[3]), T = atof(argv[4]);
    int reps = argc > 6 ? atoi(argv[6]) : 3, reference = argc > 7 ? atoi(argv[7]) : 1;
    hl_error err;
    hl_error_clear(&err);
    hl_system *sys = NULL;
    hl_scheme *s = NULL;
    hl_system_spec spec = {.H = argv[1]};
    long n = 0;
    double z0[2 * 64];
    if (hl_system_new(&sys, &spec, &err) != HL_OK || hl_scheme_new(&s, argv[2], 4, sys, &err) ||
        hl_run_nsteps(&n, dt, T, &err) != HL_OK ||
        hl_run_init_values(z0, sys, argv[5], &err) != HL_OK)
        return fail(&err);
    rows r = {0, 2 * hl_system_ndof(sys), NULL, NULL, NULL, NULL};
    double best = 1e300;
    for (int i = 0; i < reps; i++) {
        hl_run *run = NULL;
        free(r.t), free(r.z), free(r.H), free(r.sigma);
        double w0 = now();
        /* fresh arrays each time, as the binding returns new ones */
        r.t = malloc((size_t)(n + 1) * sizeof(double));
        r.z = malloc((size_t)(n + 1) * (size_t)r.n2 * sizeof(double));
        r.H = malloc((size_t)(n + 1) * sizeof(double));
        r.sigma = malloc((size_t)(n + 1) * sizeof(double));
        if (hl_run_new(&run, sys, s, &err) != HL_OK)
            return fail(&err);
        hl_run_set_reference(run, reference, 1e-15);
        hl_run_set_jit(run, 1);
        hl_run_set_progress(run, progress, NULL);
        r.k = 0;
        if (hl_run_fixed(run, z0, dt, T, 1, keep, &r, NULL, &err) != HL_OK)
            return fail(&err);
        double w = now() - w0;
        best = w < best ? w : best;
        hl_run_free(run);
    }
    printf("%.3f ms cpu, %ld rows, final %.17g %.17g\n", 1e3 * best, r.k, r.z[(r.k - 1) * r.n2],
           r.z[(r.k - 1) * r.n2 + 1]);
    free(r.t), free(r.z), free(r.H), free(r.sigma);
    hl_scheme_free(s);
    hl_system_free(sys);
    return 0;
}
