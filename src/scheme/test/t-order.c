/* Every catalog scheme on the pendulum H = p^2/2 - cos(q) and on
 * Henon-Heiles (2 dof): its expansion in D agrees with the exact flow's Lie
 * series exp(D g) z (from hl_lie_terms, a path that does not go through the
 * scheme code or the series solver) up to and including D^order and differs
 * at D^(order+1).  The order is measured here and compared with the
 * textbook order, not read from the catalog table. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/scheme.h"
#include "hl_test.h"

static hl_series *new_series(int k, hl_alg_ctx *ctx)
{
    hl_series *Z = malloc((size_t)k * sizeof *Z);
    for (int i = 0; i < k; i++)
        hl_series_init(&Z[i], 0, ctx);
    return Z;
}

typedef struct want {
    const char *name;
    int order;   /* textbook order */
    int param;
} want;

static int schemes_skip[64];
static const want schemes[] = {
    {"euler", 1, 0},
    {"symplectic-euler-a", 1, 0},
    {"symplectic-euler-b", 1, 0},
    {"stormer-verlet-kdk", 2, 0},
    {"stormer-verlet-dkd", 2, 0},
    {"implicit-midpoint", 2, 0},
    {"rk4", 4, 0},
    {"gauss2", 4, 0},
    {"gauss3", 6, 0},
    {"avf", 2, 0},
    {"gonzalez", 2, 0},
    {"itoh-abe", 1, 0},
    {"lie4", 4, 0},
    {"lie", 3, 3},
    {"lie9", 9, 0},
    {"yoshida4", 4, 0},
    {"paper-euler", 1, 0},
};

/* Measured order: the largest k such that the coefficients 0..k agree with
 * the Lie series, or -1 on error.  *differs: coefficient order+1 differs. */
static int measure(hl_system *sys, const want *w, double *secs)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), n = w->order + 2;
    hl_scheme *s;
    hl_error err;
    clock_t t0 = clock();
    if (hl_scheme_new(&s, w->name, w->param, sys, &err) != HL_OK) {
        fprintf(stderr, "%s: %s\n", w->name, err.msg);
        return -1;
    }
    hl_series *Z = new_series(2 * N, ctx);
    int st = hl_scheme_expand(Z, s, n, &err);
    *secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    int measured = -1;
    if (st != HL_OK)
        fprintf(stderr, "%s: expand: %s\n", w->name, err.msg);
    hl_alg *terms = hl_alg_vec_new(n, ctx);
    hl_alg phi, c;
    hl_alg_init(&phi, ctx);
    hl_alg_init(&c, ctx);
    for (int a = 0; st == HL_OK && a < 2 * N; a++) {
        hl_alg_gen(&phi, a < N ? hl_system_var_q(sys, a) : hl_system_var_p(sys, a - N), ctx);
        CHECK(hl_lie_terms(terms, &phi, n - 1, sys, &err) == HL_OK);
        int k = 0;
        fmpq_t f;
        fmpq_init(f);
        for (; k < n; k++) {
            fmpz_one(fmpq_numref(f));
            fmpz_fac_ui(fmpq_denref(f), (ulong)k);
            hl_alg_scalar_mul_fmpq(&c, &terms[k], f, ctx);
            if (k >= Z[a].n || !hl_alg_equal(&c, &Z[a].c[k], ctx))
                break;
        }
        fmpq_clear(f);
        if (measured < 0 || k - 1 < measured)
            measured = k - 1;
    }
    hl_alg_clear(&phi, ctx);
    hl_alg_clear(&c, ctx);
    hl_alg_vec_free(terms, n, ctx);
    for (int a = 0; a < 2 * N; a++)
        hl_series_clear(&Z[a], ctx);
    free(Z);
    hl_scheme_free(s);
    return measured;
}

/* Itoh-Abe on a separable one-dof H = T(p) + V(q): its quotients are
 * (T(P) - T(p))/(P - p) and (V(Q) - V(q))/(Q - q), exactly the average
 * vector field, which is symmetric, so order 2 there (order 1 in general:
 * Henon-Heiles).  */
static int textbook(const want *w, const char *label)
{
    if (strcmp(w->name, "itoh-abe") == 0 && strcmp(label, "pendulum") == 0)
        return 2;
    return w->order;
}

static void run(const char *H, const char *label)
{
    hl_system *sys;
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    if (hl_system_new(&sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "system: %s\n", err.msg);
        exit(2);
    }
    for (size_t i = 0; i < sizeof schemes / sizeof *schemes; i++) {
        const want *w = &schemes[i];
        if (schemes_skip[i])
            continue;
        double secs = 0;
        int got = measure(sys, w, &secs);
        int o = textbook(w, label);
        printf("%-14s %-20s param %d: order %d (expected %d), %.2f s\n", label, w->name,
               w->param, got, o, secs);
        CHECK_MSG(got == o, "%s on %s: measured order %d, expected %d", w->name, label, got, o);
    }
    hl_system_free(sys);
}

int main(int argc, char **argv)
{
    if (argc > 1) { /* one scheme, for timing: t-order NAME */
        for (size_t i = 0; i < sizeof schemes / sizeof *schemes; i++)
            if (strcmp(schemes[i].name, argv[1]) != 0)
                schemes_skip[i] = 1;
    }
    run("p^2/2 - cos(q)", "pendulum");
    run("(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3", "henon-heiles");
    return HL_TEST_END();
}
