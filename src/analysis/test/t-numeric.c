/* Numeric error analysis at a point (numerr.h) against the symbolic one:
 * at random points, v_k (k = 2..n) and the coefficients of K(D) from
 * hl_numerr_compute must equal the symbolic v_k (hl_vfields_compute) and the
 * symbolic K series (hl_series_scheme_K), each evaluated at the point with
 * Arb, to 1e-12 relative (plus a round-off allowance k! 1e-14 scale for
 * fields that vanish); on the oscillator, the pendulum, Henon-Heiles and
 * Kepler, for explicit, implicit (implicit midpoint, gauss2), integral (avf)
 * and user-written schemes.  The numeric order must be the textbook order
 * typed here.  Also times RK4 to order 8 numerically on Henon-Heiles and
 * Kepler (printed, not checked). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/analysis.h"
#include "hamlie/numerr.h"
#include "hamlie/scheme.h"
#include "hl_test.h"
#include "analysis_test.h"

typedef struct cse {
    const char *H;
    const char *scheme; /* catalog name, or NULL */
    const char *text;   /* scheme language (from_text), or NULL */
    const char *eqs;    /* --equations, or NULL */
    int n, order;       /* order n of the comparison; textbook order */
} cse;

static const cse cases[] = {
    {"(p^2+q^2)/2", "euler", NULL, NULL, 5, 1},
    {"(p^2+q^2)/2", "implicit-midpoint", NULL, NULL, 5, 2},
    {"p^2/2 - cos(q)", "stormer-verlet-kdk", NULL, NULL, 5, 2},
    {"p^2/2 - cos(q)", "rk4", NULL, NULL, 6, 4},
    {"p^2/2 - cos(q)", "implicit-midpoint", NULL, NULL, 5, 2},
    {"p^2/2 - cos(q)", "gauss2", NULL, NULL, 6, 4},
    {"p^2/2 - cos(q)", "avf", NULL, NULL, 4, 2},
    {"p^2/2 - cos(q)", NULL, NULL, "(Q-q)/D = (P+p)/2; (P-p)/D = -sin((q+Q)/2)", 5, 2},
    {"(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3", "rk4", NULL, NULL, 6, 4},
    {"(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3", "implicit-midpoint", NULL, NULL, 4, 2},
    {"(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3", NULL,
     "(Q-q)/D = Hp(q, P); (P-p)/D = -Hq(q, P)", NULL, 4, 1},
    {"(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "stormer-verlet-kdk", NULL, NULL, 4, 2},
    {"(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "rk4", NULL, NULL, 5, 4},
};

static double rnd(double a, double b) { return a + (b - a) * rand() / (double)RAND_MAX; }

static double eval_alg(const hl_alg *a, arb_srcptr vals, hl_system *sys)
{
    arb_t r;
    arb_init(r);
    hl_error err;
    double x = NAN;
    if (hl_alg_eval_arb(r, a, vals, 128, hl_system_ctx(sys), &err) == HL_OK)
        x = arf_get_d(arb_midref(r), ARF_RND_NEAR);
    arb_clear(r);
    return x;
}

static int make_scheme(hl_scheme **s, const cse *c, hl_system *sys, hl_error *err)
{
    if (c->scheme)
        return hl_scheme_new(s, c->scheme, 0, sys, err);
    if (c->text)
        return hl_scheme_from_text(s, c->text, sys, err);
    return hl_scheme_from_equations(s, c->eqs, sys, err);
}

static void run_case(const cse *c)
{
    hl_system *sys = make_system(c->H);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), m = 2 * N, n = c->n;
    const char *label = c->scheme ? c->scheme : c->text ? c->text : c->eqs;
    hl_scheme *s = NULL;
    hl_error err;
    int st = make_scheme(&s, c, sys, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", label, err.msg);
    if (st != HL_OK) {
        hl_system_free(sys);
        return;
    }
    hl_series *Z = malloc((size_t)m * sizeof *Z), *Ks = malloc((size_t)m * sizeof *Ks);
    for (int i = 0; i < m; i++)
        hl_series_init(&Z[i], 0, ctx), hl_series_init(&Ks[i], 0, ctx);
    hl_vfields e;
    memset(&e, 0, sizeof e);
    int vars[64];
    for (int i = 0; i < m; i++)
        vars[i] = i;
    st = hl_scheme_expand(Z, s, n + 1, &err);
    if (st == HL_OK)
        st = hl_vfields_compute(&e, Z, sys, n, &err);
    if (st == HL_OK)
        st = hl_series_scheme_K(Ks, m, Z, vars, hl_system_var_D(sys), ctx, &err);
    CHECK_MSG(st == HL_OK, "%s symbolic: %s", label, err.msg);
    int nb = hl_alg_ctx_nbase(ctx);
    arb_ptr vals = _arb_vec_init(nb);
    for (int trial = 0; trial < 3 && st == HL_OK; trial++) {
        double z[64];
        for (int i = 0; i < m; i++) {
            z[i] = rnd(-0.9, 0.9);
            if (strstr(c->H, "sqrt") && i < N)
                z[i] = rnd(0.5, 1.2); /* Kepler: away from the origin */
            arb_set_d(vals + i, z[i]);
        }
        hl_numerr r;
        int st2 = hl_numerr_compute(&r, s, z, n, &err);
        CHECK_MSG(st2 == HL_OK, "%s numeric: %s", label, err.msg);
        if (st2 == HL_OK) {
            double fact = 1;
            for (int k = 1; k <= n; k++) {
                fact *= k;
                if (k < 2)
                    continue;
                double sym[64], big = 0, scale = 0;
                for (int i = 0; i < m; i++) {
                    sym[i] = eval_alg(hl_vfields_v(&e, k) + i, vals, sys);
                    big = fmax(big, fabs(sym[i]));
                    scale = fmax(scale, fabs(r.flow[k * m + i]) + fabs(r.psi[k * m + i]));
                }
                for (int i = 0; i < m; i++) {
                    double d = fabs(r.v[k * m + i] - sym[i]);
                    double tol = 1e-12 * fmax(big, 1e-300) + 1e-14 * fact * scale;
                    CHECK_MSG(d <= tol, "%s on %s: v_%d[%d] numeric %.17g symbolic %.17g",
                              label, c->H, k, i, r.v[k * m + i], sym[i]);
                }
            }
            for (int k = 0; k < n && k < Ks[0].n; k++) {
                double sym[64], big = 0;
                for (int i = 0; i < m; i++) {
                    sym[i] = eval_alg(&Ks[i].c[k], vals, sys);
                    big = fmax(big, fabs(sym[i]));
                }
                for (int i = 0; i < m; i++) {
                    double d = fabs(r.K[k * m + i] - sym[i]);
                    CHECK_MSG(d <= 1e-12 * fmax(big, 1) * (k + 1),
                              "%s on %s: K_%d[%d] numeric %.17g symbolic %.17g", label, c->H,
                              k, i, r.K[k * m + i], sym[i]);
                }
            }
            CHECK_MSG(r.order == c->order, "%s on %s: numeric order %d, expected %d", label,
                      c->H, r.order, c->order);
            CHECK_MSG(r.order == e.order, "%s on %s: numeric order %d, symbolic %d", label,
                      c->H, r.order, e.order);
        }
        hl_numerr_clear(&r);
    }
    _arb_vec_clear(vals, nb);
    if (e.v != NULL)
        hl_vfields_clear(&e, sys);
    for (int i = 0; i < m; i++)
        hl_series_clear(&Z[i], ctx), hl_series_clear(&Ks[i], ctx);
    free(Z);
    free(Ks);
    hl_scheme_free(s);
    hl_system_free(sys);
}

static void timing(const char *H, const double *z, int n)
{
    hl_system *sys = make_system(H);
    hl_scheme *s = NULL;
    hl_error err;
    hl_numerr r;
    CHECK(hl_scheme_new(&s, "rk4", 0, sys, &err) == HL_OK);
    clock_t t0 = clock();
    int st = hl_numerr_compute(&r, s, z, n, &err);
    double t = (double)(clock() - t0) / CLOCKS_PER_SEC;
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    CHECK_MSG(st != HL_OK || r.order == 4, "rk4 on %s: order %d at n = %d", H, r.order, n);
    printf("rk4 numeric to order %d on %s: %.1f ms\n", n, H, 1e3 * t);
    hl_numerr_clear(&r);
    hl_scheme_free(s);
    hl_system_free(sys);
}

/* The order-by-order solver against plain evaluation: the same explicit
 * scheme solved as if it were implicit (a shallow copy with all_explicit
 * cleared) must give the same coefficients, here to order 55 on Kepler near the centre,
 * whose coefficients grow like 2^k (the probes must not be lost in
 * rounding against them). */
static void solver_vs_evaluation(const char *name, int n)
{
    hl_system *sys = make_system("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)");
    hl_scheme *s = NULL;
    hl_error err;
    CHECK(hl_scheme_new(&s, name, 0, sys, &err) == HL_OK);
    hl_scheme imp = *s;
    imp.all_explicit = 0;
    double z[4] = {0.3, 0.05, -0.2, 1.9};
    hl_numerr a, b;
    int sa = hl_numerr_compute(&a, s, z, n, &err);
    int sb = hl_numerr_compute(&b, &imp, z, n, &err);
    CHECK_MSG(sa == HL_OK && sb == HL_OK, "%s: %s", name, err.msg);
    for (int k = 0; sa == HL_OK && sb == HL_OK && k <= n; k++) {
        double big = 0;
        for (int i = 0; i < 4; i++)
            big = fmax(big, fabs(a.psi[k * 4 + i]));
        for (int i = 0; i < 4; i++)
            CHECK_MSG(fabs(a.psi[k * 4 + i] - b.psi[k * 4 + i]) <= 1e-11 * big,
                      "%s: psi_%d[%d] evaluated %.17g solved %.17g", name, k, i,
                      a.psi[k * 4 + i], b.psi[k * 4 + i]);
        for (int i = 0; k < n && i < 4; i++)
            CHECK_MSG(fabs(a.K[k * 4 + i] - b.K[k * 4 + i]) <=
                          1e-11 * fmax(fabs(a.K[k * 4 + i]), 1e-300) + 1e-11 * (k + 1) * big,
                      "%s: K_%d[%d] evaluated %.17g solved %.17g", name, k, i, a.K[k * 4 + i],
                      b.K[k * 4 + i]);
    }
    hl_numerr_clear(&a);
    hl_numerr_clear(&b);
    hl_scheme_free(s);
    hl_system_free(sys);
}

int main(void)
{
    solver_vs_evaluation("rk4", 55);
    solver_vs_evaluation("stormer-verlet-kdk", 55);
    srand(12345);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        run_case(&cases[i]);
    double hh[4] = {0.1, -0.2, 0.3, 0.25}, kep[4] = {0.5, 0, 0, 1.7320508075688772};
    timing("(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3", hh, 8);
    timing("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", kep, 8);
    /* a bad order is an error, not a crash */
    hl_system *sys = make_system("p^2/2 - cos(q)");
    hl_scheme *s = NULL;
    hl_error err;
    hl_numerr r;
    double z[2] = {1.3, 0};
    CHECK(hl_scheme_new(&s, "rk4", 0, sys, &err) == HL_OK);
    CHECK(hl_numerr_compute(&r, s, z, 1, &err) == HL_ELIMIT);
    hl_numerr_clear(&r);
    hl_scheme_free(s);
    hl_system_free(sys);
    return HL_TEST_END();
}
