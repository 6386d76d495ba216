/* Benchmark: the double Taylor interpreter alone, hl_tape_taylor_ode_d at
 * order 19 (the flow's order at tolerance 1e-15) on the vector fields of
 * bench/taylor_flow.c written by hand (1 pendulum, 2 Henon-Heiles,
 * 3 Kepler), so that builds whose flows take different step counts compare
 * per call.  Uses only the public API that the old interpreter (a4ae1ce,
 * issue 14's "before") has too, so the same file builds against both:
 *   cc -O2 bench/taylor_interp.c -I OLD/include OLD/build/libhamlie.a \
 *      -lflint-arb -lflint -lmpfr -lgmp -lm -ldl
 * Arguments: [rounds] [calls per round] [system 1..3 or 0 for all].
 * Prints per system: ns per call, the best round's (a loaded machine only
 * ever adds time), and a checksum of the coefficients (equal across builds
 * that compute the same bits). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/expr.h"
#include "hamlie/tape.h"

#define ORDER 19

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static hl_tape *make_tape(hl_pool *P, int which, const double **z0, int *n)
{
    static const double zp[] = {1.3, 0}, zh[] = {0.1, -0.2, 0.3, 0.25}, zk[] = {0.5, 0, 0, 1.5};
    const hl_expr *two = hl_num_si(P, 2);
    const hl_expr *x = hl_sym(P, "x"), *y = hl_sym(P, "y");
    const hl_expr *px = hl_sym(P, "px"), *py = hl_sym(P, "py");
    const char *n2[] = {"x", "px"}, *n4[] = {"x", "y", "px", "py"};
    const hl_expr *f[4];
    *n = 4;
    if (which == 1) {
        f[0] = px, f[1] = hl_neg(P, hl_call(P, HL_SIN, x)), *n = 2, *z0 = zp;
    } else if (which == 2) {
        f[0] = px, f[1] = py, *z0 = zh;
        f[2] = hl_sub(P, hl_neg(P, x), hl_mul(P, hl_mul(P, two, x), y));
        f[3] = hl_add(P, hl_sub(P, hl_neg(P, y), hl_pow(P, x, two)), hl_pow(P, y, two));
    } else {
        const hl_expr *r3i =
            hl_pow(P, hl_add(P, hl_pow(P, x, two), hl_pow(P, y, two)), hl_num_frac(P, -3, 2));
        f[0] = px, f[1] = py, *z0 = zk;
        f[2] = hl_neg(P, hl_mul(P, x, r3i));
        f[3] = hl_neg(P, hl_mul(P, y, r3i));
    }
    hl_tape *t = NULL;
    hl_error err;
    if (hl_tape_new(&t, f, *n, *n == 2 ? n2 : n4, *n, &err) != HL_OK) {
        fprintf(stderr, "taylor_interp: %s\n", err.msg);
        exit(1);
    }
    return t;
}

/* a sum that changes with any bit of any coefficient */
static unsigned long long checksum(const double *z, int m)
{
    unsigned long long h = 1469598103934665603ull;
    for (int i = 0; i < m; i++) {
        unsigned long long b;
        memcpy(&b, &z[i], sizeof b);
        h = (h ^ b) * 1099511628211ull;
    }
    return h;
}

static void bench_system(hl_pool *P, int which, int rounds, long calls)
{
    static const char *const names[] = {"", "pendulum", "henon-heiles", "kepler"};
    const double *z0;
    int n;
    hl_tape *t = make_tape(P, which, &z0, &n);
    double z[4 * (ORDER + 1)] = {0}, best = 1e300;
    for (int i = 0; i < n; i++)
        z[i * (ORDER + 1)] = z0[i];
    hl_error err;
    for (int r = 0; r < rounds; r++) {
        double t0 = now();
        for (long c = 0; c < calls; c++)
            hl_tape_taylor_ode_d(z, ORDER, t, &err);
        double dt = (now() - t0) / (double)calls;
        best = dt < best ? dt : best;
    }
    printf("%-13s %8.1f ns/call  checksum %016llx\n", names[which], 1e9 * best,
           checksum(z, n * (ORDER + 1)));
    hl_tape_free(t);
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 5;
    long calls = argc > 2 ? atol(argv[2]) : 20000;
    int only = argc > 3 ? atoi(argv[3]) : 0;
    hl_pool *P = hl_pool_new();
    for (int s = 1; s <= 3; s++)
        if (only == 0 || only == s)
            bench_system(P, s, rounds, calls);
    hl_pool_free(P);
    return 0;
}
