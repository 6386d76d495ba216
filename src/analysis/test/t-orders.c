/* The order of every catalog scheme measured by the error analysis (the
 * least k with v_k != 0, minus one; v_k computed two ways, which must agree)
 * on the pendulum and on Henon-Heiles, against the textbook orders typed
 * here (not read from the catalog).  Also times RK4 on Henon-Heiles and the
 * implicit midpoint rule on the pendulum to order 8. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"
#include "analysis_test.h"

typedef struct want {
    const char *name;
    int order;
} want;

static const want table[] = {
    {"euler", 1}, {"symplectic-euler-a", 1}, {"symplectic-euler-b", 1},
    {"stormer-verlet-kdk", 2}, {"stormer-verlet-dkd", 2}, {"implicit-midpoint", 2},
    {"rk4", 4}, {"gauss2", 4}, {"gauss3", 6}, {"avf", 2}, {"gonzalez", 2},
    {"itoh-abe", 1}, {"lie4", 4}, {"lie2", 2}, {"lie7", 7}, {"yoshida4", 4}, {"paper-euler", 1},
};

/* Errors of scheme `name` to order n; returns the measured order or -1. */
static int measure(hl_system *sys, const char *name, int n, double *secs)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int m = 2 * hl_system_ndof(sys), order = -1;
    hl_scheme *s = NULL;
    hl_error err;
    hl_vfields e;
    hl_series *Z = malloc((size_t)m * sizeof *Z);
    for (int i = 0; i < m; i++)
        hl_series_init(&Z[i], 0, ctx);
    clock_t t0 = clock();
    int st = hl_scheme_new(&s, name, 0, sys, &err);
    if (st == HL_OK)
        st = hl_scheme_expand(Z, s, n + 1, &err);
    e.v = e.vK = NULL;
    e.N = m / 2;
    e.n = n;
    if (st == HL_OK)
        st = hl_vfields_compute(&e, Z, sys, n, &err);
    *secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    if (st != HL_OK)
        fprintf(stderr, "%s: %s\n", name, err.msg);
    else if (!e.agree)
        fprintf(stderr, "%s: v_%d computed two ways disagree\n", name, e.disagree_k);
    else
        order = e.leading ? e.order : 1000;
    hl_vfields_clear(&e, sys);
    for (int i = 0; i < m; i++)
        hl_series_clear(&Z[i], ctx);
    free(Z);
    hl_scheme_free(s);
    return order;
}

int main(void)
{
    const char *systems[] = {"p^2/2 - cos(q)", "(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3"};
    for (int k = 0; k < 2; k++) {
        hl_system *sys = make_system(systems[k]);
        for (size_t i = 0; i < sizeof table / sizeof *table; i++) {
            double t;
            /* Itoh-Abe with one dof and H = T(p) + V(q) uses the difference
             * quotients (V(Q)-V(q))/(Q-q), (T(P)-T(p))/(P-p): symmetric under
             * (q,p,D) <-> (Q,P,-D), so of order 2 on the pendulum. */
            int expect = table[i].order;
            if (k == 0 && strcmp(table[i].name, "itoh-abe") == 0)
                expect = 2;
            int got = measure(sys, table[i].name, expect + 1, &t);
            CHECK_MSG(got == expect, "%s on %s: measured %d, expected %d",
                      table[i].name, systems[k], got, expect);
        }
        hl_system_free(sys);
    }
    /* speed figures */
    double t;
    hl_system *hh = make_system(systems[1]);
    CHECK(measure(hh, "rk4", 8, &t) == 4);
    printf("rk4 on Henon-Heiles to order 8: %.2f s\n", t);
    hl_system_free(hh);
    hl_system *pend = make_system(systems[0]);
    CHECK(measure(pend, "implicit-midpoint", 8, &t) == 2);
    printf("implicit midpoint on the pendulum to order 8: %.2f s\n", t);
    hl_system_free(pend);
    return HL_TEST_END();
}
