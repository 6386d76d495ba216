/* Benchmark: when loading a cached Taylor recursion pays for a short run
 * (issue 17; the figures behind CACHE_HIT_NS and TAYLOR_SAVED_NS_PER_OP in
 * src/tape/cost.c).  On the four systems of bench/taylor_flow.c (vector
 * fields from H, as hamlie run makes them), at tol 1e-15, runs of about N
 * Taylor steps (N = 30 ... 10000), two ways:
 *   interp  the interpreter alone;
 *   hit     the recursion loaded from a warm disk cache (hl_tape_native:
 *           key check, dlopen) before the run, then the run native.
 * CPU ms of the whole (the load included), median of reps, each on a fresh
 * tape (a tape keeps its loaded code).  Also: the tape's length, the load
 * alone, and the time per step each way on a long run, whose difference
 * and the load give the break-even in steps.  Argument: [reps] (default 7). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "hamlie/flow.h"
#include "hamlie/expr.h"
#include "hamlie/tape.h"

static double cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *const names[4] = {"oscillator", "pendulum", "henon-heiles", "kepler"};
static const double z0s[4][4] = {
    {1, 0}, {1.3, 0}, {0.1, -0.1, 0.05, 0.1}, {0.5, 0, 0, 1.7320508075688772}};

static hl_tape *tape_from_H(hl_pool *P, int which)
{
    static const char *const Hs[4] = {"(q^2 + p^2)/2", "p^2/2 - cos(q)",
                                      "(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3",
                                      "(px^2 + py^2)/2 - 1/sqrt(x^2 + y^2)"};
    const char *q1[] = {"q"}, *p1[] = {"p"}, *q2[] = {"x", "y"}, *p2[] = {"px", "py"};
    const hl_expr *H;
    hl_tape *t = NULL;
    hl_error err;
    int two = which >= 2;
    if (hl_parse(&H, P, Hs[which], &err) != HL_OK ||
        hl_tape_hamiltonian(&t, P, H, two ? 2 : 1, two ? q2 : q1, two ? p2 : p1, 0, NULL, NULL,
                            &err) != HL_OK) {
        fprintf(stderr, "cached_short: %s\n", err.msg);
        exit(1);
    }
    return t;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

enum { MAXREPS = 64 };
#define TOL 1e-15

/* CPU seconds of a run of system s to time T on a fresh tape, loaded from
 * the cache first if hit; *steps the steps taken, *load the load alone. */
static double run(hl_pool *P, int s, double T, int hit, long *steps, double *load)
{
    hl_tape *t = tape_from_H(P, s);
    hl_flow *fl;
    hl_error err;
    if (hl_flow_new(&fl, t, TOL, TOL, &err) != HL_OK) {
        fprintf(stderr, "cached_short: %s\n", err.msg);
        exit(1);
    }
    double z[4], tt = 0;
    memcpy(z, z0s[s], sizeof z);
    double c0 = cpu();
    if (hit && hl_tape_native(t, hl_flow_order(fl), &err) != HL_OK) {
        fprintf(stderr, "cached_short: %s\n", err.msg);
        exit(1);
    }
    double c1 = cpu();
    if (hl_flow_evolve(fl, &tt, T, z, &err) != HL_OK) {
        fprintf(stderr, "cached_short: %s\n", err.msg);
        exit(1);
    }
    double c2 = cpu();
    *steps = hl_flow_nsteps(fl);
    if (load)
        *load = c1 - c0;
    hl_flow_free(fl);
    hl_tape_free(t);
    return c2 - c0;
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 7;
    reps = reps < 1 ? 1 : reps > MAXREPS ? MAXREPS : reps;
    char dir[] = "/tmp/hamlie-cached-short-XXXXXX";
    if (mkdtemp(dir) == NULL)
        return 1;
    setenv("HAMLIE_CACHE_DIR", dir, 1);
    unsetenv("HAMLIE_CACHE");
    hl_pool *P = hl_pool_new();
    static const long Ns[] = {30, 100, 300, 1000, 3000, 10000};
    printf("CPU ms, median of %d; tol %g; hit = load from a warm cache + native run\n", reps, TOL);
    printf("%-13s %5s %9s %9s %9s %7s\n", "system", "ops", "steps", "interp", "hit", "ratio");
    for (int s = 0; s < 4; s++) {
        long steps;
        double v[MAXREPS], w[MAXREPS], l[MAXREPS];
        /* the mean step, and the cache filled */
        double Tlong = 2000;
        run(P, s, Tlong, 1, &steps, NULL);
        double mean = Tlong / (double)steps;
        double per_i[MAXREPS], per_n[MAXREPS];
        for (int r = 0; r < reps; r++) {
            per_i[r] = run(P, s, Tlong, 0, &steps, NULL) / (double)steps;
            per_n[r] = (run(P, s, Tlong, 1, &steps, &l[r]) - l[r]) / (double)steps;
        }
        double pi = median(per_i, reps), pn = median(per_n, reps), load = median(l, reps);
        hl_tape *t = tape_from_H(P, s);
        long ops = hl_tape_nops(t);
        hl_tape_free(t);
        for (size_t k = 0; k < sizeof Ns / sizeof *Ns; k++) {
            double T = mean * (double)Ns[k];
            for (int r = 0; r < reps; r++) {
                v[r] = run(P, s, T, 0, &steps, NULL);
                w[r] = run(P, s, T, 1, &steps, NULL);
            }
            double a = median(v, reps), b = median(w, reps);
            printf("%-13s %5ld %9ld %9.3f %9.3f %7.2f\n", names[s], ops, steps, 1e3 * a, 1e3 * b,
                   a / b);
        }
        printf("%-13s per step: interp %.0f ns, native %.0f ns, saved %.0f ns; load %.3f ms; "
               "break-even %.0f steps; saved per op %.2f ns\n",
               names[s], 1e9 * pi, 1e9 * pn, 1e9 * (pi - pn), 1e3 * load,
               load / (pi - pn), 1e9 * (pi - pn) / (double)ops);
        fflush(stdout);
    }
    hl_pool_free(P);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    return system(cmd) == 0 ? 0 : 1;
}
