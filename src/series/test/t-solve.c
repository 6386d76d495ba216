/* Schemes solved order by order:
 *  - the paper's discrete gradient, written (X-x)/D = (P+p)/2 and in the
 *    paper's own form (P^2-p^2)/(P-p), and implicit midpoint on the
 *    oscillator: all the map (4x + 4Dp - D^2 x)/(4 + D^2), ... (§4.1.3);
 *  - explicit maps (Euler, the exact rotation with sin D, cos D);
 *  - symplectic Euler on the pendulum: exact, P = p - D sin q,
 *    Q = q + D p - D^2 sin q;
 *  - implicit midpoint on the pendulum: residual O(D^n) by substitution,
 *    the D^2 coefficients by hand (Q_2 = -sin(q)/2, P_2 = -p cos(q)/2), and
 *    the truncated series against a fixed-point solution in double;
 *  - the errors for inconsistent and singular schemes. */
#include <math.h>

#include "sr.h"

enum { VX, VQ, VP, VD };

static int solve(hl_series *Z, const char *src, const char *u0, const char *u1, const char *z0a,
                 const char *z0b, int n, hl_error *err)
{
    hl_eqn eqs[4];
    int m;
    const char *unk[2] = {u0, u1};
    if (hl_parse_list(eqs, 4, &m, pool, src, err) != HL_OK || m != 2) {
        fprintf(stderr, "cannot parse '%s'\n", src);
        exit(2);
    }
    hl_alg z0[2];
    hl_alg_init(&z0[0], ctx);
    hl_alg_init(&z0[1], ctx);
    rd(&z0[0], z0a);
    rd(&z0[1], z0b);
    int st = hl_series_solve(Z, 2, eqs, unk, z0, "D", n, ctx, err);
    if (st != HL_OK)
        fprintf(stderr, "%s: %s\n", src, err->msg);
    hl_alg_clear(&z0[0], ctx);
    hl_alg_clear(&z0[1], ctx);
    return st;
}

/* Z (X, P) against the expansions of closed forms fx, fp in D. */
static void check_map(const hl_series *Z, const char *fx, const char *fp, int n)
{
    hl_series s;
    hl_alg a;
    hl_error err;
    hl_series_init(&s, 0, ctx);
    hl_alg_init(&a, ctx);
    rd(&a, fx);
    CHECK(hl_series_from_alg(&s, &a, VD, n, ctx, &err) == HL_OK);
    CHECK_SERIES(&Z[0], &s, n);
    rd(&a, fp);
    CHECK(hl_series_from_alg(&s, &a, VD, n, ctx, &err) == HL_OK);
    CHECK_SERIES(&Z[1], &s, n);
    hl_series_clear(&s, ctx);
    hl_alg_clear(&a, ctx);
}

static void oscillator(hl_series *Z)
{
    hl_error err;
    const char *dgx = "(4*x + 4*D*p - D^2*x)/(4 + D^2)";
    const char *dgp = "(4*p - 4*D*x - D^2*p)/(4 + D^2)";
    CHECK(solve(Z, "(X-x)/D = (P+p)/2; (P-p)/D = -(X+x)/2", "X", "P", "x", "p", 10, &err) == HL_OK);
    CHECK(Z[0].n == 10 && Z[1].n == 10);
    check_map(Z, dgx, dgp, 10);
    /* the paper's form of the discrete gradient */
    CHECK(solve(Z, "(X-x)/D = (1/2)*(P^2-p^2)/(P-p); (P-p)/D = -(1/2)*(X^2-x^2)/(X-x)", "X", "P",
                "x", "p", 10, &err) == HL_OK);
    check_map(Z, dgx, dgp, 10);
    /* implicit midpoint, equations in the other order */
    CHECK(solve(Z, "P = p - D*(x+X)/2; X = x + D*(p+P)/2", "X", "P", "x", "p", 10, &err) == HL_OK);
    check_map(Z, dgx, dgp, 10);
    /* explicit Euler and the exact rotation */
    CHECK(solve(Z, "X = x + D*p; P = p - D*x", "X", "P", "x", "p", 6, &err) == HL_OK);
    check_map(Z, "x + D*p", "p - D*x", 6);
    CHECK(solve(Z, "X = x*cos(D) + p*sin(D); P = p*cos(D) - x*sin(D)", "X", "P", "x", "p", 9,
                &err) == HL_OK);
    CHECK_COEF(&Z[0], 2, "-x/2");
    CHECK_COEF(&Z[0], 3, "-p/6");
    CHECK_COEF(&Z[1], 8, "p/40320");
    /* a power of D dividing the whole equation: D*(X - x - D*p) = 0 */
    CHECK(solve(Z, "D*(X - x - D*p) = 0; D^2*P = D^2*p - D^3*x", "X", "P", "x", "p", 5, &err) ==
          HL_OK);
    check_map(Z, "x + D*p", "p - D*x", 5);
    /* ... and a factor D hidden in an atom: sin(D) and exp(D) - 1 */
    CHECK(solve(Z, "sin(D)*(X - x - D*p) = 0; (exp(D) - 1)*(P - p) = -D*x*(exp(D) - 1)", "X", "P",
                "x", "p", 6, &err) == HL_OK);
    check_map(Z, "x + D*p", "p - D*x", 6);
}

static void pendulum(hl_series *Z)
{
    hl_error err;
    /* symplectic Euler: exact and finite */
    CHECK(solve(Z, "Q = q + D*P; P = p - D*sin(q)", "Q", "P", "q", "p", 7, &err) == HL_OK);
    CHECK_COEF(&Z[0], 0, "q");
    CHECK_COEF(&Z[0], 1, "p");
    CHECK_COEF(&Z[0], 2, "-sin(q)");
    CHECK_COEF(&Z[1], 0, "p");
    CHECK_COEF(&Z[1], 1, "-sin(q)");
    for (int k = 3; k < 7; k++)
        CHECK_COEF(&Z[0], k, "0");
    for (int k = 2; k < 7; k++)
        CHECK_COEF(&Z[1], k, "0");

    /* implicit midpoint */
    const int n = 8;
    const char *src = "Q = q + D*(p+P)/2; P = p - D*sin((q+Q)/2)";
    CHECK(solve(Z, src, "Q", "P", "q", "p", n, &err) == HL_OK);
    CHECK_COEF(&Z[0], 1, "p");
    CHECK_COEF(&Z[1], 1, "-sin(q)");
    CHECK_COEF(&Z[0], 2, "-sin(q)/2");
    CHECK_COEF(&Z[1], 2, "-p*cos(q)/2");

    /* residual: substitute back into lhs - rhs */
    const char *names[] = {"q", "p", "D", "Q", "P"};
    hl_series vals[5], r;
    hl_alg g;
    hl_alg_init(&g, ctx);
    for (int i = 0; i < 5; i++)
        hl_series_init(&vals[i], 0, ctx);
    hl_alg_gen(&g, VQ, ctx);
    hl_series_set_alg(&vals[0], &g, n, ctx);
    hl_alg_gen(&g, VP, ctx);
    hl_series_set_alg(&vals[1], &g, n, ctx);
    hl_alg_zero(&g, ctx);
    hl_series_set_var(&vals[2], &g, n, ctx);
    hl_series_set(&vals[3], &Z[0], ctx);
    hl_series_set(&vals[4], &Z[1], ctx);
    hl_series_init(&r, 0, ctx);
    hl_eqn eqs[2];
    int m;
    CHECK(hl_parse_list(eqs, 2, &m, pool, src, &err) == HL_OK);
    for (int i = 0; i < 2; i++) {
        const hl_expr *f = hl_sub(pool, eqs[i].lhs, eqs[i].rhs);
        CHECK(hl_series_eval_expr(&r, f, 5, names, vals, n, ctx, &err) == HL_OK);
        CHECK(r.n == n);
        CHECK_MSG(hl_series_is_zero(&r, ctx), "residual of equation %d", i + 1);
    }

    /* numerically: the truncated series at D = 0.05 against fixed-point
     * iteration of the scheme in double; the difference is O(D^8) ~ 4e-11 */
    double q = 0.7, p = 0.3, D = 0.05, Q = q, P = p;
    for (int it = 0; it < 200; it++) {
        Q = q + D * (p + P) / 2;
        P = p - D * sin((q + Q) / 2);
    }
    arb_ptr pt = _arb_vec_init(4);
    arb_t y, s, dk;
    arb_init(y);
    arb_init(s);
    arb_init(dk);
    arb_set_d(pt + VX, 0.0);
    arb_set_d(pt + VQ, q);
    arb_set_d(pt + VP, p);
    arb_set_d(pt + VD, D);
    for (int j = 0; j < 2; j++) {
        arb_zero(s);
        arb_one(dk);
        for (int k = 0; k < n; k++) {
            CHECK(hl_alg_eval_arb(y, &Z[j].c[k], pt, 128, ctx, &err) == HL_OK);
            arb_addmul(s, y, dk, 128);
            arb_set_d(y, D);
            arb_mul(dk, dk, y, 128);
        }
        double v = arf_get_d(arb_midref(s), ARF_RND_NEAR), want = j ? P : Q;
        CHECK_MSG(fabs(v - want) < 1e-9, "%s: series %.15g, fixed point %.15g", j ? "P" : "Q", v,
                  want);
    }
    arb_clear(y);
    arb_clear(s);
    arb_clear(dk);
    _arb_vec_clear(pt, 4);
    for (int i = 0; i < 5; i++)
        hl_series_clear(&vals[i], ctx);
    hl_series_clear(&r, ctx);
    hl_alg_clear(&g, ctx);
}

/* One unknown: X = x + D X^2 has X = (1 - sqrt(1 - 4 D x))/(2D), whose
 * coefficients are the Catalan numbers times x^(k+1). */
static void catalan(void)
{
    hl_eqn eq;
    int m;
    hl_error err;
    const char *unk[] = {"X"};
    hl_alg z0;
    hl_series Z;
    hl_alg_init(&z0, ctx);
    hl_series_init(&Z, 0, ctx);
    hl_alg_gen(&z0, VX, ctx);
    CHECK(hl_parse_list(&eq, 1, &m, pool, "X = x + D*X^2", &err) == HL_OK);
    CHECK(hl_series_solve(&Z, 1, &eq, unk, &z0, "D", 9, ctx, &err) == HL_OK);
    const char *want[] = {"x",      "x^2",     "2*x^3",   "5*x^4",   "14*x^5",
                          "42*x^6", "132*x^7", "429*x^8", "1430*x^9"};
    for (int k = 0; k < 9; k++)
        CHECK_COEF(&Z, k, want[k]);
    /* n = 1: just the starting point */
    CHECK(hl_series_solve(&Z, 1, &eq, unk, &z0, "D", 1, ctx, &err) == HL_OK);
    CHECK(Z.n == 1);
    CHECK_COEF(&Z, 0, "x");
    hl_alg_clear(&z0, ctx);
    hl_series_clear(&Z, ctx);
}

/* The step need not be a symbol of the context: here "h" with ctx (q, p). */
static void foreign_step(void)
{
    hl_alg_ctx *saved = ctx;
    const char *names[] = {"q", "p"};
    ctx = hl_alg_ctx_new(2, names, 0);
    hl_eqn eqs[2];
    int m;
    hl_error err;
    const char *unk[] = {"Q", "P"};
    hl_alg z0[2];
    hl_series Z[2];
    for (int i = 0; i < 2; i++) {
        hl_alg_init(&z0[i], ctx);
        hl_alg_gen(&z0[i], i, ctx);
        hl_series_init(&Z[i], 0, ctx);
    }
    CHECK(hl_parse_list(eqs, 2, &m, pool, "Q = q + h*P; P = p - h*sin(q)", &err) == HL_OK);
    CHECK(hl_series_solve(Z, 2, eqs, unk, z0, "h", 4, ctx, &err) == HL_OK);
    CHECK_COEF(&Z[0], 2, "-sin(q)");
    CHECK_COEF(&Z[1], 1, "-sin(q)");
    CHECK_COEF(&Z[1], 2, "0");
    for (int i = 0; i < 2; i++) {
        hl_alg_clear(&z0[i], ctx);
        hl_series_clear(&Z[i], ctx);
    }
    hl_alg_ctx_free(ctx);
    ctx = saved;
}

static void errors(hl_series *Z)
{
    hl_error err;
    /* a domain error while expanding: log(P - p) at D = 0 */
    CHECK(solve(Z, "X = x + D*log(P - p); P = p - D*x", "X", "P", "x", "p", 4, &err) == HL_EDOM);
    CHECK(solve(Z, "X = x + 1; P = p", "X", "P", "x", "p", 4, &err) == HL_EINVAL);
    CHECK_MSG(strstr(err.msg, "not the identity at D = 0") != NULL, "%s", err.msg);
    CHECK(solve(Z, "X + P = x + p; X + P = x + p", "X", "P", "x", "p", 4, &err) == HL_EINVAL);
    CHECK_MSG(strstr(err.msg, "does not determine (X, P) at D = 0") != NULL, "%s", err.msg);
    /* Euler written without the D: X - x = p has X = x + p at D = 0 */
    CHECK(solve(Z, "X - x = p; P - p = -x", "X", "P", "x", "p", 4, &err) == HL_EINVAL);
    CHECK_MSG(strstr(err.msg, "not the identity") != NULL, "%s", err.msg);
    /* an equation that says nothing */
    CHECK(solve(Z, "X = X; P = p - D*x", "X", "P", "x", "p", 4, &err) == HL_EINVAL);
    CHECK_MSG(strstr(err.msg, "holds for every value") != NULL, "%s", err.msg);
    /* a symbol the system does not know */
    CHECK(solve(Z, "X = x + D*y; P = p", "X", "P", "x", "p", 4, &err) == HL_EINVAL);
    CHECK_MSG(strstr(err.msg, "'y'") != NULL, "%s", err.msg);
    /* an unknown that is a phase variable */
    CHECK(solve(Z, "q = x + D*p; P = p", "q", "P", "x", "p", 4, &err) == HL_EINVAL);
    CHECK_MSG(strstr(err.msg, "'q'") != NULL, "%s", err.msg);
}

int main(void)
{
    const char *names[] = {"x", "q", "p", "D"};
    setup(4, names);
    hl_series Z[2];
    hl_series_init(&Z[0], 0, ctx);
    hl_series_init(&Z[1], 0, ctx);
    oscillator(Z);
    pendulum(Z);
    catalan();
    foreign_step();
    errors(Z);
    hl_series_clear(&Z[0], ctx);
    hl_series_clear(&Z[1], ctx);
    teardown();
    flint_cleanup();
    return HL_TEST_END();
}
