/* Benchmark (issue 4): the error fields of RK4 on Hénon–Heiles and of the
 * implicit midpoint rule on the pendulum, to order 8.  The core computation
 * is the scheme's expansion in D (hl_scheme_expand) and the error fields
 * v_2..v_8, timed twice: the direct route alone (hl_vfields_compute_direct:
 * the expansion minus the Lie series, what the SymPy peer
 * bench/errors_sympy.py does), and with the K(D) cross-check that
 * `hamlie errors` runs (hl_vfields_compute).
 * Prints one line per case: name, order, seconds direct, seconds with the
 * cross-check (best of several runs each). */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "hamlie/analysis.h"
#include "hamlie/ham.h"
#include "hamlie/scheme.h"
#include "hamlie/series.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* From the text of H and the scheme's name to v_2..v_order. */
static int run_once(const char *H, const char *scheme, int order, int cross)
{
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_scheme *s = NULL;
    hl_series *psi = NULL;
    hl_vfields e = {0};
    int have_e = 0, m = 0;
    hl_error err;
    hl_error_clear(&err);
    int st = hl_system_new(&sys, &spec, &err);
    if (st == HL_OK)
        st = hl_scheme_new(&s, scheme, 0, sys, &err);
    if (st == HL_OK) {
        hl_alg_ctx *ctx = hl_system_ctx(sys);
        m = 2 * hl_system_ndof(sys);
        psi = malloc((size_t)m * sizeof *psi);
        for (int i = 0; i < m; i++)
            hl_series_init(&psi[i], 0, ctx);
        st = hl_scheme_expand(psi, s, order + 1, &err);
    }
    if (st == HL_OK) {
        have_e = 1;
        st = cross ? hl_vfields_compute(&e, psi, sys, order, &err)
                   : hl_vfields_compute_direct(&e, psi, sys, order, &err);
        if (st == HL_OK && cross && !e.agree)
            fprintf(stderr, "errors_analysis: v_%d disagree\n", e.disagree_k);
    }
    if (st != HL_OK)
        fprintf(stderr, "errors_analysis: %s\n", err.msg);
    if (have_e)
        hl_vfields_clear(&e, sys);
    if (psi != NULL) {
        for (int i = 0; i < m; i++)
            hl_series_clear(&psi[i], hl_system_ctx(sys));
        free(psi);
    }
    hl_scheme_free(s);
    hl_system_free(sys);
    return st != HL_OK;
}

static int bench(const char *name, const char *H, const char *scheme, int order, int repeat)
{
    double best[2] = {1e300, 1e300};
    for (int cross = 0; cross < 2; cross++)
        for (int r = 0; r < repeat; r++) {
            double t0 = now();
            if (run_once(H, scheme, order, cross))
                return 1;
            double t = now() - t0;
            if (t < best[cross])
                best[cross] = t;
        }
    printf("%s %d %.6f %.6f\n", name, order, best[0], best[1]);
    return 0;
}

int main(int argc, char **argv)
{
    int repeat = argc > 1 ? atoi(argv[1]) : 5;
    int bad = 0;
    bad |= bench("rk4-henon-heiles", "(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3", "rk4", 8, repeat);
    bad |= bench("midpoint-pendulum", "p^2/2 - cos(q)", "implicit-midpoint", 8, repeat);
    return bad;
}
