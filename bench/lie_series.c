/* Benchmark: the Lie series exp(D g) z of every coordinate z, to order 12 for
 * Hénon–Heiles and to order 8 for planar Kepler (issue 3).  The peer is the
 * same computation in SymPy (bench/lie_sympy.py); bench/run-lie.sh runs both
 * and prints the ratio.  Prints one line per system: name, order, seconds
 * (best of several runs), and the total number of terms of the result. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/ham.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One full computation, from the text of H to the series of every coordinate:
 * the set-up (parsing, context) is part of what a user waits for. */
static int run_once(const char *H, int order, long *terms)
{
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_error err;
    hl_error_clear(&err);
    if (hl_system_new(&sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "lie_series: %s\n", err.msg);
        return 1;
    }
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int n = hl_system_ndof(sys);
    hl_alg z, s;
    hl_alg_init(&z, ctx);
    hl_alg_init(&s, ctx);
    *terms = 0;
    int status = HL_OK;
    for (int v = 0; v < 2 * n && status == HL_OK; v++) {
        hl_alg_gen(&z, v, ctx);
        status = hl_lie_series(&s, &z, order, sys, &err);
        *terms += hl_alg_length(&s, ctx);
    }
    if (status != HL_OK)
        fprintf(stderr, "lie_series: %s\n", err.msg);
    hl_alg_clear(&z, ctx);
    hl_alg_clear(&s, ctx);
    hl_system_free(sys);
    return status != HL_OK;
}

static int bench(const char *name, const char *H, int order, int repeat)
{
    double best = 1e300;
    long terms = 0;
    for (int r = 0; r < repeat; r++) {
        double t0 = now();
        if (run_once(H, order, &terms))
            return 1;
        double t = now() - t0;
        if (t < best)
            best = t;
    }
    printf("%s %d %.6f %ld\n", name, order, best, terms);
    return 0;
}

int main(int argc, char **argv)
{
    int repeat = argc > 1 ? atoi(argv[1]) : 5;
    int bad = 0;
    bad |= bench("henon-heiles", "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", 12, repeat);
    bad |= bench("kepler", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", 8, repeat);
    return bad;
}
