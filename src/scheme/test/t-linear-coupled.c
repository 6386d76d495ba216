/* The exact flow of a quadratic H that couples its pairs, in closed form
 * (linear_modes.c, through hl_scheme_linear_flow):
 *  - the closed form at random points and steps D equals exp(D Ã) (z, 1),
 *    Ã = [[A, b], [0, 0]] the augmented field matrix written from H's
 *    derivatives here (q' = H_p, p' = -H_q) and exponentiated by Arb's
 *    arb_mat_exp at 192 bits, to 1e-13 relative: two incommensurate
 *    elliptic modes (frequencies sqrt((5 +- sqrt 13)/2)), a hyperbolic and
 *    an elliptic mode, two hyperbolic modes, a zero mode, a uniform field,
 *    three dof;
 *  - rational frequencies (1 and 3) give a text with no square root, and
 *    frequencies sqrt(2) +- 1 are denested: no sqrt of a perfect square and
 *    no nested sqrt is printed;
 *  - the map composed n times (numerically) is the map at nD;
 *  - the catalog's "exact" equals the Lie series exp(D g) z to D^8;
 *  - a cubic, a defective (Jordan) case, complex (spiral) modes and a
 *    symbolic coefficient are refused with HL_EUNSUP naming the reason. */
#include <math.h>

#include <arb_mat.h>

#include "sch.h"

#define PREC 192

/* The augmented matrix Ã of H's field (independent of linear_modes.c). */
static void field_matrix(arb_mat_t At, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N, nb = hl_alg_ctx_nbase(ctx);
    hl_alg d1, d2;
    hl_error err;
    hl_alg_init(&d1, ctx);
    hl_alg_init(&d2, ctx);
    arb_ptr zero = _arb_vec_init(nb);
    arb_mat_zero(At);
    for (int i = 0; i < M; i++) {
        /* row i: z_i' = dH/dz_{i+N} for i < N, -dH/dz_{i-N} else */
        int src = i < N ? i + N : i - N;
        CHECK(hl_alg_diff(&d1, hl_system_H(sys), src, ctx, &err) == HL_OK);
        for (int k = 0; k < M; k++) {
            CHECK(hl_alg_diff(&d2, &d1, k, ctx, &err) == HL_OK);
            CHECK(hl_alg_eval_arb(arb_mat_entry(At, i, k), &d2, zero, PREC, ctx, &err) ==
                  HL_OK);
        }
        CHECK(hl_alg_eval_arb(arb_mat_entry(At, i, M), &d1, zero, PREC, ctx, &err) == HL_OK);
        if (i >= N)
            for (int k = 0; k <= M; k++)
                arb_neg(arb_mat_entry(At, i, k), arb_mat_entry(At, i, k));
    }
    _arb_vec_clear(zero, nb);
    hl_alg_clear(&d1, ctx);
    hl_alg_clear(&d2, ctx);
}

/* out = the images at the point z (M values) and step D. */
static void eval_images(arb_ptr out, const hl_alg *img, arb_srcptr z, double D, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys), nb = hl_alg_ctx_nbase(ctx);
    arb_ptr v = _arb_vec_init(nb);
    hl_error err;
    for (int i = 0; i < M; i++)
        arb_set(v + i, z + i);
    arb_set_d(v + hl_system_var_D(sys), D);
    for (int i = 0; i < M; i++)
        CHECK_MSG(hl_alg_eval_arb(out + i, &img[i], v, PREC, ctx, &err) == HL_OK, "eval: %s",
                  err.msg);
    _arb_vec_clear(v, nb);
}

/* |a - b| / max(1, |b|), computed in Arb (an upper bound, radii included). */
static double rel_dev(const arb_t a, const arb_t b)
{
    arb_t t;
    arb_init(t);
    arb_sub(t, a, b, PREC);
    double num = arf_get_d(arb_midref(t), ARF_RND_NEAR), rad = mag_get_d(arb_radref(t));
    double y = arf_get_d(arb_midref(b), ARF_RND_NEAR);
    arb_clear(t);
    return (fabs(num) + rad) / fmax(1.0, fabs(y));
}

static double max_dev_seen;

/* The closed form against arb_mat_exp at random points, and the n-fold
 * composition against one step of nD. */
static void check_numeric(const char *H)
{
    hl_system *sys = make_system(H);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys);
    hl_alg *img = hl_alg_vec_new(M, ctx);
    hl_error err;
    int st = hl_scheme_linear_flow(img, sys, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, st == HL_OK ? "" : err.msg);
    CHECK_MSG(hl_scheme_linear_flow_applies(sys), "%s: flow_applies is false", H);
    arb_mat_t At, E;
    arb_mat_init(At, M + 1, M + 1);
    arb_mat_init(E, M + 1, M + 1);
    arb_ptr z = _arb_vec_init(M), got = _arb_vec_init(M), want = _arb_vec_init(M),
            cur = _arb_vec_init(M);
    field_matrix(At, sys);
    flint_rand_t rs;
    flint_randinit(rs);
    double worst = 0;
    for (int trial = 0; st == HL_OK && trial < 8; trial++) {
        double D = 0.05 + 2.5 * (double)n_randint(rs, 1000) / 1000;
        for (int i = 0; i < M; i++)
            arb_set_d(z + i, ((double)n_randint(rs, 2001) - 1000) / 700);
        eval_images(got, img, z, D, sys);
        arb_t Db;
        arb_init(Db);
        arb_set_d(Db, D);
        arb_mat_scalar_mul_arb(E, At, Db, PREC);
        arb_mat_exp(E, E, PREC);
        for (int i = 0; i < M; i++) {
            arb_set(want + i, arb_mat_entry(E, i, M)); /* times the constant 1 */
            for (int k = 0; k < M; k++)
                arb_addmul(want + i, arb_mat_entry(E, i, k), z + k, PREC);
            double dv = rel_dev(got + i, want + i);
            worst = fmax(worst, dv);
        }
        arb_clear(Db);
        /* n steps of D = one step of n D */
        int n = 2 + (int)n_randint(rs, 4);
        _arb_vec_set(cur, z, M);
        for (int s = 0; s < n; s++) {
            eval_images(got, img, cur, D / n, sys);
            _arb_vec_set(cur, got, M);
        }
        eval_images(want, img, z, D, sys);
        for (int i = 0; i < M; i++)
            CHECK_MSG(rel_dev(cur + i, want + i) < 1e-13,
                      "%s: %d steps of D/%d differ from one of D (component %d)", H, n, n, i);
    }
    CHECK_MSG(worst < 1e-13, "%s: closed form differs from arb_mat_exp by %.3g", H, worst);
    max_dev_seen = fmax(max_dev_seen, worst);
    printf("%-60s max rel. deviation from arb_mat_exp %.2e\n", H, worst);
    flint_randclear(rs);
    _arb_vec_clear(z, M);
    _arb_vec_clear(got, M);
    _arb_vec_clear(want, M);
    _arb_vec_clear(cur, M);
    arb_mat_clear(At);
    arb_mat_clear(E);
    hl_alg_vec_free(img, M, ctx);
    hl_system_free(sys);
}

/* The printed map: no sqrt of a perfect square, no nested sqrt; it
 * contains want (NULL: anything) and lacks "sqrt" when no_sqrt. */
static void check_text(const char *H, const char *want, int no_sqrt)
{
    hl_system *sys = make_system(H);
    char *map = NULL;
    hl_error err;
    int st = hl_scheme_linear_flow_map(&map, sys, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, st == HL_OK ? "" : err.msg);
    if (map != NULL) {
        for (const char *s = strstr(map, "sqrt("); s; s = strstr(s + 1, "sqrt(")) {
            const char *a = s + 5;
            CHECK_MSG(strncmp(a, "sqrt(", 5) != 0 && strncmp(a, "-sqrt(", 6) != 0,
                      "%s: nested sqrt in '%.40s'", H, s);
            char *end;
            long v = strtol(a, &end, 10);
            if (end != a && *end == ')') {
                long r = (long)floor(sqrt((double)v) + 0.5);
                CHECK_MSG(r * r != v, "%s: sqrt of the square %ld printed", H, v);
            }
        }
        CHECK_MSG(!no_sqrt || strstr(map, "sqrt") == NULL, "%s: sqrt in %s", H, map);
        CHECK_MSG(want == NULL || strstr(map, want) != NULL, "%s: '%s' not in %s", H, want,
                  map);
    }
    free(map);
    hl_system_free(sys);
}

/* The catalog's "exact" expanded in D equals exp(D g) z to D^8. */
static void check_lie(const char *H)
{
    enum { ORDER = 8 };
    hl_system *sys = make_system(H);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys);
    hl_scheme *s = NULL;
    hl_error err;
    int st = hl_scheme_new(&s, "exact", 0, sys, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, st == HL_OK ? "" : err.msg);
    hl_series *Z = st == HL_OK ? expand(s, ORDER + 1) : NULL;
    CHECK(Z != NULL);
    for (int i = 0; Z != NULL && i < M; i++) {
        hl_alg z, lie;
        hl_series ls;
        hl_alg_init(&z, ctx);
        hl_alg_init(&lie, ctx);
        hl_series_init(&ls, 0, ctx);
        hl_alg_gen(&z, i, ctx);
        int ok = hl_lie_series(&lie, &z, ORDER, sys, &err) == HL_OK &&
                 hl_series_from_alg(&ls, &lie, hl_system_var_D(sys), ORDER + 1, ctx, &err) ==
                     HL_OK;
        for (int k = 0; ok && k <= ORDER; k++)
            ok = hl_alg_equal(&Z[i].c[k], &ls.c[k], ctx);
        CHECK_MSG(ok, "%s: component %d differs from the Lie series", H, i);
        hl_series_clear(&ls, ctx);
        hl_alg_clear(&z, ctx);
        hl_alg_clear(&lie, ctx);
    }
    if (Z)
        free_series(Z, M, ctx);
    hl_scheme_free(s);
    hl_system_free(sys);
}

static void check_refused(const char *H, const char *msg)
{
    hl_system *sys = make_system(H);
    int M = 2 * hl_system_ndof(sys);
    hl_alg *img = hl_alg_vec_new(M, hl_system_ctx(sys));
    hl_error err;
    int st = hl_scheme_linear_flow(img, sys, &err);
    CHECK_MSG(st == HL_EUNSUP && strstr(err.msg, msg) != NULL, "%s: status %d, '%s'", H, st,
              st == HL_OK ? "" : err.msg);
    CHECK(!hl_scheme_linear_flow_applies(sys));
    hl_alg_vec_free(img, M, hl_system_ctx(sys));
    hl_system_free(sys);
}

int main(void)
{
    /* (1) two elliptic modes sqrt((5 +- sqrt 13)/2) */
    check_numeric("(px^2+py^2)/2 + (x^2+4*y^2)/2 + x*y");
    /* (2) hyperbolic: V = -(x^2+y^2)/2 + 2xy has eigenvalues 1, -3: one
     * elliptic mode (1) and one hyperbolic (sqrt 3) */
    check_numeric("(px^2+py^2)/2 - (x^2+y^2)/2 + 2*x*y");
    check_numeric("(px^2+py^2)/2 - (x^2+2*y^2)/2 - x*y"); /* two hyperbolic, sqrt(13) */
    check_numeric("(px^2+py^2)/2 + x*y");                 /* modes 1 and i: cos and cosh */
    check_numeric("(px^2+py^2)/2 + (x^2+y^2)/2 + x*y");   /* a zero mode */
    check_numeric("(px+py)^2/2 + x^2/2");                 /* a free direction */
    check_numeric("(px^2+py^2)/2 + (x^2+4*y^2)/2 + x*y + x + 2*py - y/3"); /* affine */
    check_numeric("(px^2+py^2)/2 + (x^2+9*y^2)/2 + x*py"); /* a magnetic-type x*py */
    check_numeric("px*py + x*y");
    check_numeric("(px^2+py^2+pz^2)/2 + (x^2+2*y^2+3*z^2)/2 + x*y + y*z");
    /* (3) rational frequencies 1 and 3; denested sqrt(3 +- 2 sqrt 2) */
    check_text("(px^2+py^2)/2 + (5*x^2+5*y^2)/2 + 4*x*y", "cos(3*D)", 1);
    check_numeric("(px^2+py^2)/2 + (5*x^2+5*y^2)/2 + 4*x*y");
    check_text("(px^2+py^2)/2 + (x^2+5*y^2)/2 + 2*x*y", "cos(D*sqrt(2) + D)", 0);
    check_numeric("(px^2+py^2)/2 + (x^2+5*y^2)/2 + 2*x*y");
    check_text("(px^2+py^2)/2 + (x^2+4*y^2)/2 + x*y", "sqrt(13)", 0);
    /* the Lie series */
    check_lie("(px^2+py^2)/2 + (x^2+4*y^2)/2 + x*y");
    check_lie("(px^2+py^2)/2 - (x^2+y^2)/2 + 2*x*y + x");
    /* (4) refused, the reason named */
    check_refused("(px^2+py^2+pz^2)/2 + (x^2+2*y^2+4*z^2)/2 + x*y + y*z + x*z",
                  "irreducible polynomial of degree 3");
    check_refused("x*px + y*py + x*py", "not diagonalizable");
    check_refused("(px^2-py^2)/2 + x*y", "complex eigenvalues");
    check_refused("(px^2+py^2)/2 + (x^2+y^2)/2 + k*x*y", "symbolic coefficients");
    printf("max relative deviation from arb_mat_exp over all cases: %.2e\n", max_dev_seen);
    return HL_TEST_END();
}
