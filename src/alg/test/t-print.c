/* hl_alg_to_expr: the text a person would write.  Every expected string is
 * worked out by hand from the rules at the top of print.c (the derivations
 * of the computed ones are written beside them); every printed element must
 * also round-trip, from_expr(to_expr(a)) == a (same num and den), and its
 * text must parse back to the very DAG that was built (so what is shown is
 * exactly what was built).  Random elements with square roots check the
 * round trip with and without the series symbol. */
#include <stdlib.h>

#include "hamlie/alg.h"
#include "hl_test.h"
#include "alg_test.h"


enum { X, Y, Q, P, PX, PY, D, NBASE };


/* from_expr(to_expr(a)) has the same num and den as a, and so does the
 * element read back from the printed text; the text parses to the same DAG. */
static int round_trip(const hl_alg *a)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    hl_alg b, c;
    hl_error err;
    hl_alg_init(&b, ctx);
    hl_alg_init(&c, ctx);
    const hl_expr *e = hl_alg_to_expr(a, ctx, pool), *back = NULL;
    char *s = hl_expr_print(e, HL_STYLE_TEXT);
    int ok = hl_alg_from_expr(&b, e, ctx, &err) == HL_OK && fmpz_mpoly_equal(a->num, b.num, mc)
             && fmpz_mpoly_equal(a->den, b.den, mc);
    int same_dag = hl_parse(&back, pool, s, &err) == HL_OK && back == e;
    ok = ok && same_dag && hl_alg_from_expr(&c, back, ctx, &err) == HL_OK
         && fmpz_mpoly_equal(a->num, c.num, mc) && fmpz_mpoly_equal(a->den, c.den, mc);
    if (!ok)
        fprintf(stderr, "round trip failed for %s%s\n", s,
                same_dag ? "" : " (text parses to another DAG)");
    free(s);
    hl_alg_clear(&b, ctx);
    hl_alg_clear(&c, ctx);
    return ok;
}

static void check_alg(const hl_alg *a, const char *what, const char *want)
{
    char *s = hl_expr_print(hl_alg_to_expr(a, ctx, pool), HL_STYLE_TEXT);
    CHECK_MSG(strcmp(s, want) == 0, "%s: got \"%s\", want \"%s\"", what, s, want);
    free(s);
    CHECK_MSG(round_trip(a), "%s", what);
}

static void check_print(const char *in, const char *want)
{
    hl_alg a;
    hl_alg_init(&a, ctx);
    if (rd(&a, in) != HL_OK)
        CHECK_MSG(0, "'%s' did not read", in);
    else
        check_alg(&a, in, want);
    hl_alg_clear(&a, ctx);
}

/* r = {f, g} in the pairs (x, px), (y, py), (q, p); r may alias f or g. */
static void bracket(hl_alg *r, const hl_alg *f, const hl_alg *g)
{
    static const int qs[] = {X, Y, Q}, ps[] = {PX, PY, P};
    hl_alg a, b, t, s;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&s, ctx);
    for (int j = 0; j < 3; j++) {
        hl_alg_diff(&a, f, qs[j], ctx, NULL);
        hl_alg_diff(&b, g, ps[j], ctx, NULL);
        hl_alg_mul(&t, &a, &b, ctx);
        hl_alg_add(&s, &s, &t, ctx);
        hl_alg_diff(&a, g, qs[j], ctx, NULL);
        hl_alg_diff(&b, f, ps[j], ctx, NULL);
        hl_alg_mul(&t, &a, &b, ctx);
        hl_alg_sub(&s, &s, &t, ctx);
    }
    hl_alg_swap(r, &s, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    hl_alg_clear(&t, ctx);
}

/* Without a series symbol: the stored order (total degree descending). */
static void no_step(void)
{
    hl_alg_ctx_set_step(ctx, -1);
    CHECK(hl_alg_ctx_step(ctx) == -1);
    check_print("-x*sqrt(x^2+y^2)/(x^2+y^2)^2", "-x/(x^2 + y^2)^(3/2)");
    check_print("-x/(x^2+y^2)^(3/2)", "-x/(x^2 + y^2)^(3/2)");
    check_print("x/sqrt(x^2+y^2)", "x/sqrt(x^2 + y^2)");
    check_print("1/sqrt(x^2+y^2)", "1/sqrt(x^2 + y^2)");
    check_print("sqrt(x^2+y^2)", "sqrt(x^2 + y^2)");
    check_print("(x^2+y^2)^(-5/2)*y", "y/(x^2 + y^2)^(5/2)");
    check_print("-sin(q)", "-sin(q)");
    check_print("p^2/2 - cos(q)", "p^2/2 - cos(q)");
    check_print("1 + D^2", "D^2 + 1");
    check_print("x + D*p", "p*D + x");
    check_print("x/(1 + D^2)", "x/(D^2 + 1)");
    check_print("x/((x^2+y^2)^2*(x+1))", "x/((x + 1)*(x^2 + y^2)^2)");
    check_print("(x^2 - y^2)/(x^2 + 2*x*y + y^2)", "(x - y)/(x + y)");
    check_print("x/2 + 3*y/4 - 1", "x/2 + 3*y/4 - 1");
    check_print("-x + y", "-x + y");
    check_print("(x + y)^2", "x^2 + 2*x*y + y^2");
    check_print("sin(q)^2", "-cos(q)^2 + 1");
    check_print("tan(q)", "sin(q)/cos(q)");
    check_print("x^(2/3)", "x^(2/3)");
    check_print("2*pi", "2*pi");
    check_print("sqrt(2)*x", "x*sqrt(2)");
    check_print("exp(2*x)*sin(sqrt(x^2+y^2))", "exp(2*x)*sin(sqrt(x^2 + y^2))");
    check_print("0", "0");
    check_print("-3/4", "-3/4");
    /* rule 2 without the setting: the sign on the first factor */
    check_print("-x*D", "-x*D");
    check_print("-p^4*sin(q)", "-p^4*sin(q)");
}

/* With the series symbol D. */
static void with_step(void)
{
    hl_alg_ctx_set_step(ctx, D);
    CHECK(hl_alg_ctx_step(ctx) == D);

    /* rule 1: ascending powers of D, then total degree descending; D first */
    check_print("x + D*p", "x + D*p");
    check_print("p - D*x", "p - D*x");
    check_print("D^2 + 1", "1 + D^2");
    check_print("x/(1 + D^2)", "x/(1 + D^2)");
    check_print("p^2/2 - cos(q)", "p^2/2 - cos(q)");
    check_print("x*D^2*p", "D^2*x*p");
    check_print("3*x*D/2", "3*D*x/2");
    check_print("D*x + x^3 + D*x^2 + 1", "x^3 + 1 + D*x^2 + D*x");
    check_print("q + D*p - D^2*sin(q)/2", "q + D*p - D^2*sin(q)/2");
    check_print("1/(D^2*x + x)", "1/(x*(1 + D^2))");

    /* rule 2: no "-(a*b)" */
    check_print("-x*D", "-D*x");
    check_print("-p*cos(q)", "-p*cos(q)");
    check_print("-p^4*sin(q)", "-p^4*sin(q)");
    check_print("-3*x*y/2", "-3*x*y/2");
    check_print("-x^2*y + x", "-x^2*y + x");
    check_print("-1/(x^2+y^2)", "-1/(x^2 + y^2)");
    check_print("-7", "-7");
    check_print("-3*x/(x^2+y^2)", "-3*x/(x^2 + y^2)");
    check_print("-3*(x + y)/(x^2+y^2)", "-(3*x + 3*y)/(x^2 + y^2)"); /* 3*(x + y): a tie */
    check_print("-D/(1 + D^2)", "-D/(1 + D^2)");

    /* rule 3: split by square roots; sqrt(u)/u^k = 1/u^(k-1/2) */
    check_print("-(x^3*px*py - x^2*y*px^2 + x*y^2*px*py - y^3*px^2 + y*sqrt(x^2 + y^2))"
                "/(x^2 + y^2)",
                "-x*px*py + y*px^2 - y/sqrt(x^2 + y^2)");
    check_print("(x + sqrt(x^2+y^2))/(x^2+y^2)", "x/(x^2 + y^2) + 1/sqrt(x^2 + y^2)");
    check_print("(x*(x^2+y^2) + y*sqrt(x^2+y^2))/((x^2+y^2)^2*(x+1))",
                "x/((x + 1)*(x^2 + y^2)) + y/((x + 1)*(x^2 + y^2)^(3/2))");
    check_print("-y/(x^2+y^2)^(5/2)", "-y/(x^2 + y^2)^(5/2)");
    check_print("1/sqrt(x^2+y^2) + 1/sqrt(x^2+1)", "1/sqrt(x^2 + y^2) + 1/sqrt(x^2 + 1)");
    check_print("sqrt(x^2+y^2)/sqrt(x^2+1)", "sqrt(x^2 + y^2)/sqrt(x^2 + 1)");
    check_print("sqrt(x^2+y^2)/x", "sqrt(x^2 + y^2)/x");

    /* rule 4: a common factor only when the text gets shorter */
    check_print("x/3 + y/3 + q/3", "(x + y + q)/3");    /* 13 < 15 characters */
    check_print("-x/3 - y/3 - q/3", "-(x + y + q)/3");  /* 14 < 16 */
    check_print("2*x + 2*y + 2*q", "2*(x + y + q)");    /* 13 < 15 */
    check_print("x/2 + y/2", "x/2 + y/2");              /* a tie: 9 = 9 */
    check_print("x/2 + 3*y/4 - 1", "x/2 + 3*y/4 - 1");  /* (2*x + 3*y - 4)/4 is longer */
    check_print("-(x+y)/(2*(x^2+y^2))", "-(x + y)/(2*(x^2 + y^2))");
    check_print("(2*x + 4*y)/(x^2 + y^2)", "(2*x + 4*y)/(x^2 + y^2)"); /* a tie */

    /* a rational function with a factored denominator */
    check_print("x/((x^2+y^2)^2*(x+1))", "x/((x + 1)*(x^2 + y^2)^2)");
    check_print("(x^2 - y^2)/(x^2 + 2*x*y + y^2)", "(x - y)/(x + y)");
    check_print("(x + D)/(x^3*y - x*y^3)", "(x + D)/(x*y*(x + y)*(x - y))");
}

/* Kepler H = (px^2 + py^2)/2 - 1/r, r = sqrt(x^2 + y^2), L = x*py - y*px,
 * A = py*L - x/r.  By hand, with dr/dx = x/r:
 *   dA/dx = py^2 - 1/r + x^2/r^3 = py^2 - y^2/r^3,  dA/dy = -px*py + x*y/r^3,
 *   dA/dpx = -y*py,  dA/dpy = 2*x*py - y*px,
 *   {L, A} = py*(-y*py) - (py^2 - y^2/r^3)*(-y) + (-px)*(2*x*py - y*px)
 *            - (-px*py + x*y/r^3)*x
 *          = -x*px*py + y*px^2 - y*(x^2 + y^2)/r^3 = -x*px*py + y*px^2 - y/r.
 * Generator: -dH/dx = -x/r^3, -dH/dy = -y/r^3. */
static void kepler(void)
{
    hl_alg H, L, A, r;
    hl_alg_init(&H, ctx);
    hl_alg_init(&L, ctx);
    hl_alg_init(&A, ctx);
    hl_alg_init(&r, ctx);
    CHECK(rd(&H, "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)") == HL_OK);
    CHECK(rd(&L, "x*py - y*px") == HL_OK);
    CHECK(rd(&A, "py*(x*py - y*px) - x/sqrt(x^2+y^2)") == HL_OK);
    bracket(&r, &L, &A);
    check_alg(&r, "{L, A}", "-x*px*py + y*px^2 - y/sqrt(x^2 + y^2)");
    hl_alg_diff(&r, &H, X, ctx, NULL);
    hl_alg_neg(&r, &r, ctx);
    check_alg(&r, "-dH/dx", "-x/(x^2 + y^2)^(3/2)");
    hl_alg_diff(&r, &H, Y, ctx, NULL);
    hl_alg_neg(&r, &r, ctx);
    check_alg(&r, "-dH/dy", "-y/(x^2 + y^2)^(3/2)");
    check_alg(&H, "H", "px^2/2 + py^2/2 - 1/sqrt(x^2 + y^2)");
    hl_alg_clear(&H, ctx);
    hl_alg_clear(&L, ctx);
    hl_alg_clear(&A, ctx);
    hl_alg_clear(&r, ctx);
}

/* Pendulum H = p^2/2 - cos q, g f = {f, H} = p df/dq - sin q df/dp, s = sin q,
 * c = cos q, s^2 = 1 - c^2 (the canonical form keeps s to degree 1):
 *   g q = p, g^2 q = -s, g^3 q = -p*c, g^4 q = p*(p*s) - s*(-c) = p^2*s + s*c,
 *   g^5 q = p*(p^2*c + c^2 - s^2) - s*(2*p*s) = p^3*c + 4*p*c^2 - 3*p,
 *   g^6 q = p*(-p^3*s - 8*p*c*s) - s*(3*p^2*c + 4*c^2 - 3)
 *         = -p^4*s - 11*p^2*s*c - 4*s*c^2 + 3*s. */
static void pendulum(void)
{
    static const char *want[] = {
        "q", "p", "-sin(q)", "-p*cos(q)", "p^2*sin(q) + sin(q)*cos(q)",
        "p^3*cos(q) + 4*p*cos(q)^2 - 3*p",
        "-p^4*sin(q) - 11*p^2*sin(q)*cos(q) - 4*sin(q)*cos(q)^2 + 3*sin(q)",
    };
    hl_alg H, f;
    hl_alg_init(&H, ctx);
    hl_alg_init(&f, ctx);
    CHECK(rd(&H, "p^2/2 - cos(q)") == HL_OK);
    hl_alg_gen(&f, Q, ctx);
    for (int k = 0; k <= 6; k++) {
        char what[16];
        snprintf(what, sizeof what, "g^%d q", k);
        check_alg(&f, what, want[k]);
        bracket(&f, &f, &H);
    }
    hl_alg_clear(&H, ctx);
    hl_alg_clear(&f, ctx);
}

/* A random polynomial in x, y, D (others absent). */
static void rand_poly(hl_alg *a, flint_rand_t state, const ulong *bounds)
{
    hl_alg_one(a, ctx);
    fmpz_mpoly_randtest_bounds(a->num, state, 5, 6, (ulong *)bounds, hl_alg_ctx_mpoly(ctx));
}

/* Round trips of (P0 + P1*r1 + P2*r2 + P3*r1*r2) / (Q*u1^k), r1 = sqrt(u1),
 * u1 = x^2 + y^2, r2 = sqrt(x + 2), with and without the series symbol. */
static void random_round_trips(void)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    flint_rand_t state;
    flint_randinit(state);
    int nv = (int)mc->minfo->nvars;
    ulong *bounds = malloc((size_t)nv * sizeof *bounds);
    for (int v = 0; v < nv; v++)
        bounds[v] = v == X || v == Y ? 4 : v == D ? 3 : 1;
    hl_alg r1, r2, u1, num, t, den;
    hl_alg_init(&r1, ctx);
    hl_alg_init(&r2, ctx);
    hl_alg_init(&u1, ctx);
    hl_alg_init(&num, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&den, ctx);
    rd(&r1, "sqrt(x^2 + y^2)");
    rd(&r2, "sqrt(x + 2)");
    rd(&u1, "x^2 + y^2");
    int bad = 0, runs = 0, split = 0;
    for (int i = 0; i < 300; i++) {
        hl_alg_ctx_set_step(ctx, i % 2 ? D : -1);
        rand_poly(&num, state, bounds);
        rand_poly(&t, state, bounds);
        hl_alg_mul(&t, &t, &r1, ctx);
        hl_alg_add(&num, &num, &t, ctx);
        if (i % 3 == 0) {
            rand_poly(&t, state, bounds);
            hl_alg_mul(&t, &t, &r2, ctx);
            hl_alg_add(&num, &num, &t, ctx);
            rand_poly(&t, state, bounds);
            hl_alg_mul(&t, &t, &r1, ctx);
            hl_alg_mul(&t, &t, &r2, ctx);
            hl_alg_add(&num, &num, &t, ctx);
        }
        rand_poly(&den, state, bounds);
        if (fmpz_mpoly_is_zero(den.num, mc))
            continue;
        hl_alg_pow_si(&t, &u1, i % 4, ctx, NULL);
        hl_alg_mul(&den, &den, &t, ctx);
        hl_alg_div(&num, &num, &den, ctx, NULL);
        runs++;
        split += !fmpz_mpoly_is_fmpz(num.den, mc);
        bad += !round_trip(&num);
    }
    CHECK_MSG(bad == 0, "%d of %d random round trips failed", bad, runs);
    CHECK_MSG(runs > 250 && split > 150, "only %d runs, %d with a denominator", runs, split);
    hl_alg_clear(&r1, ctx);
    hl_alg_clear(&r2, ctx);
    hl_alg_clear(&u1, ctx);
    hl_alg_clear(&num, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&den, ctx);
    free(bounds);
    flint_randclear(state);
}

int main(void)
{
    const char *names[NBASE] = {"x", "y", "q", "p", "px", "py", "D"};
    pool = hl_pool_new();
    ctx = hl_alg_ctx_new(NBASE, names, 0);
    CHECK(hl_alg_ctx_step(ctx) == -1); /* off by default */
    no_step();
    with_step();
    kepler();
    pendulum();
    random_round_trips();
    hl_alg_ctx_set_step(ctx, NBASE); /* out of range: off */
    CHECK(hl_alg_ctx_step(ctx) == -1);
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
    return HL_TEST_END();
}
