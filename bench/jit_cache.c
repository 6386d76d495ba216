/* Benchmark: what compiling costs and what the disk cache saves, on the
 * four systems of bench/taylor_flow.c (vector fields from H, as hamlie run
 * makes them).  For the Taylor recursion at order 19 (tol 1e-15) and for
 * the point evaluation (hl_tape_jit):
 *   mem     compiled in memory (HAMLIE_CACHE=off; what every run paid before)
 *   file    compiled into an empty cache (compile_to_file: GCC's assembler
 *           and linker write a shared object; plus hashing, rename, dlopen)
 *   hit     loaded from the cache (no libgccjit context)
 * and, for -O0..-O3 ($HL_JIT_FLAGS="-On", which comes after the site's
 * own level), the compile time and the time of one compiled recursion.
 * Wall times, median of reps; CPU times (this process and its children:
 * GCC's driver runs as and ld as child processes) alongside, which a
 * loaded machine disturbs less.  Argument: [reps] (default 5). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "hamlie/tape.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* this thread's CPU seconds: a preempted loop is not charged its wait */
static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu(void)
{
    struct rusage a, b;
    getrusage(RUSAGE_SELF, &a);
    getrusage(RUSAGE_CHILDREN, &b);
    return a.ru_utime.tv_sec + a.ru_stime.tv_sec + b.ru_utime.tv_sec + b.ru_stime.tv_sec +
           1e-6 *
               (a.ru_utime.tv_usec + a.ru_stime.tv_usec + b.ru_utime.tv_usec + b.ru_stime.tv_usec);
}

static const char *const names[4] = {"oscillator", "pendulum", "henon-heiles", "kepler"};

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
        fprintf(stderr, "jit_cache: %s\n", err.msg);
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

enum { ORDER = 19, MAXREPS = 64 };
static char base[64];
static int reps = 5;

/* A fresh empty cache directory for rep r (cold), or the shared one. */
static void use_cache(const char *how, int r)
{
    char d[128];
    if (strcmp(how, "mem") == 0) {
        setenv("HAMLIE_CACHE", "off", 1);
        return;
    }
    unsetenv("HAMLIE_CACHE");
    if (strcmp(how, "file") == 0)
        snprintf(d, sizeof d, "%s/cold%d-%ld", base, r, (long)(1e6 * now()) % 1000000);
    else
        snprintf(d, sizeof d, "%s/warm", base);
    setenv("HAMLIE_CACHE_DIR", d, 1);
}

/* Compiles (or loads) system s's recursion (taylor) or evaluation;
 * wall and CPU seconds into *w, *c. */
static void one(hl_pool *P, int s, int taylor, double *w, double *c)
{
    hl_tape *t = tape_from_H(P, s);
    hl_error err;
    double c0 = cpu(), t0 = now();
    int st = taylor ? hl_tape_native(t, ORDER, &err) : hl_tape_jit(t, &err);
    *w = now() - t0, *c = cpu() - c0;
    if (st != HL_OK) {
        fprintf(stderr, "jit_cache: %s\n", err.msg);
        exit(1);
    }
    hl_tape_free(t);
}

/* Median wall and CPU ms of reps compilations in mode how. */
static void measure(hl_pool *P, int s, int taylor, const char *how, double *wms, double *cms)
{
    double w[MAXREPS], c[MAXREPS];
    if (strcmp(how, "hit") == 0) { /* fill the entry first */
        use_cache("hit", 0);
        one(P, s, taylor, &w[0], &c[0]);
    }
    for (int r = 0; r < reps; r++) {
        use_cache(how, r);
        one(P, s, taylor, &w[r], &c[r]);
    }
    *wms = 1e3 * median(w, reps), *cms = 1e3 * median(c, reps);
}

/* CPU ns of one compiled recursion at order 19 (best of reps of 20000). */
static double recursion_ns(hl_pool *P, int s)
{
    hl_tape *t = tape_from_H(P, s);
    hl_error err;
    setenv("HAMLIE_CACHE", "off", 1);
    if (hl_tape_native(t, ORDER, &err) != HL_OK)
        return NAN;
    int n = hl_tape_ninputs(t);
    double z[4 * (ORDER + 1)], v[MAXREPS];
    for (int r = 0; r < reps; r++) {
        memset(z, 0, sizeof z);
        for (int i = 0; i < n; i++)
            z[i * (ORDER + 1)] = 0.5 + 0.1 * i;
        double t0 = thread_cpu();
        for (int k = 0; k < 20000; k++) {
            hl_tape_taylor_ode_d(z, ORDER, t, &err);
            z[0] += 1e-9 * z[1]; /* a dependence from one call to the next */
        }
        v[r] = (thread_cpu() - t0) / 20000 * 1e9;
    }
    hl_tape_free(t);
    double best = v[0]; /* the least disturbed run of a loaded machine */
    for (int r = 1; r < reps; r++)
        best = fmin(best, v[r]);
    return best;
}

static void cache_table(hl_pool *P)
{
    printf("compile or load, ms (wall median / CPU incl. as+ld), order %d\n", ORDER);
    printf("%-13s %-9s %17s %17s %17s\n", "system", "site", "mem", "file", "hit");
    for (int s = 0; s < 4; s++)
        for (int taylor = 1; taylor >= 0; taylor--) {
            printf("%-13s %-9s", names[s], taylor ? "taylor" : "eval");
            const char *how[3] = {"mem", "file", "hit"};
            for (int h = 0; h < 3; h++) {
                double w, c;
                measure(P, s, taylor, how[h], &w, &c);
                printf("  %7.2f / %7.2f", w, c);
            }
            printf("\n");
            fflush(stdout);
        }
}

static void opt_table(hl_pool *P)
{
    printf("\nthe Taylor recursion by -O level ($HL_JIT_FLAGS), in memory: compile ms (wall / "
           "CPU), one recursion ns\n");
    printf("%-13s", "system");
    for (int o = 0; o <= 3; o++)
        printf("        -O%d                ", o);
    printf("\n");
    for (int s = 0; s < 4; s++) {
        printf("%-13s", names[s]);
        for (int o = 0; o <= 3; o++) {
            char flag[8];
            snprintf(flag, sizeof flag, "-O%d", o);
            setenv("HL_JIT_FLAGS", flag, 1);
            double w, c;
            measure(P, s, 1, "mem", &w, &c);
            printf("  %6.1f / %6.1f %7.0f ns", w, c, recursion_ns(P, s));
            fflush(stdout);
        }
        unsetenv("HL_JIT_FLAGS");
        printf("\n");
    }
}

int main(int argc, char **argv)
{
    reps = argc > 1 ? atoi(argv[1]) : 5;
    if (reps < 1 || reps > MAXREPS)
        reps = 5;
    if (!hl_tape_jit_available()) {
        printf("hamlie was built without libgccjit\n");
        return 0;
    }
    snprintf(base, sizeof base, "/tmp/hamlie-bench-cache-XXXXXX");
    if (mkdtemp(base) == NULL)
        return 1;
    unsetenv("HL_JIT_FLAGS");
    hl_pool *P = hl_pool_new();
    if (argc <= 2 || strchr(argv[2], 'c'))
        cache_table(P);
    if (argc <= 2 || strchr(argv[2], 'o'))
        opt_table(P);
    hl_pool_free(P);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", base);
    return system(cmd) != 0;
}
