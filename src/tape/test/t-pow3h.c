/* w^(3/2), the tape op POW3H (src/rules/pow3h.c), against mpmath and SymPy:
 *   compiling: w^(3/2), sqrt(w)*w and w*sqrt(w) all become one POW3H (no
 *     SQRT, no POWK left);
 *   point values at hard arguments (tiny, subnormal, huge, near overflow,
 *     0, -0, negative, inf, NaN): the interpreter and the libgccjit code
 *     bitwise w*sqrt(w) from libm, within 1.3 ulp of mpmath's value (the
 *     worst seen is 1.27 ulp, bench/pow3h_ulp.py; the bound from two
 *     roundings is 2 ulp), or inf where mpmath's exceeds DBL_MAX; the Arb
 *     interpreter a ball around mpmath's value;
 *   Taylor coefficients of w(t)^(3/2) for two polynomials w(t), against
 *     SymPy's series: the double interpreter (1e-14 relative to the largest
 *     coefficient, as a recurrence's error grows with the coefficients
 *     before it), Arb (1e-25), and the expression layer's own series of
 *     x^(3/2) (hl_expr_taylor, not the tape: the symbolic side unchanged). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"

static hl_pool *P;
static const char *const wname[] = {"w"};

static const hl_expr *parse(const char *s)
{
    const hl_expr *e = NULL;
    hl_error err;
    CHECK_MSG(hl_parse(&e, P, s, &err) == HL_OK, "%s: %s", s, err.msg);
    return e;
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static hl_tape *tape_of(const char *f)
{
    const hl_expr *e = parse(f);
    hl_tape *t = NULL;
    hl_error err;
    CHECK_MSG(hl_tape_new(&t, &e, 1, wname, 1, &err) == HL_OK, "%s: %s", f, err.msg);
    return t;
}

static void test_compiles_to_one_op(void)
{
    const char *forms[] = {"w^(3/2)", "sqrt(w)*w", "w*sqrt(w)", "sqrt(w)^3"};
    for (size_t i = 0; i < sizeof forms / sizeof *forms; i++) {
        hl_tape *t = tape_of(forms[i]);
        if (t == NULL)
            continue;
        char *s = hl_tape_print(t);
        CHECK_MSG(hl_tape_nops(t) == 1 && strstr(s, "= POW3H r0") != NULL, "%s:\n%s", forms[i], s);
        free(s);
        hl_tape_free(t);
    }
}

/* mpmath: mpf(w) ** mpf(1.5) at 40 digits, printed to 30 */
static const struct {
    double w;
    const char *mp;
} hard[] = {
    {0.3, "1.64316767251549824915678018108e-1"},
    {2.0, "2.82842712474619009760337744842"},
    {4.0, "8.0"},
    {1.564091062758839, "1.95610900198819509226860875948"},  /* 1.24 ulp */
    {1.5839130040029725, "1.99341162494828611465697902411"}, /* the worst seen: 1.27 ulp */
    {1e-200, "9.99999999999999973150393598624e-301"},
    {5e-206, "1.11803398874989485001636966915e-308"},                  /* a subnormal result */
    {4.9406564584124654e-324, "1.09818873711362634127465406532e-485"}, /* subnormal w */
    {2.2250738585072014e-308, "3.31907179776661314462300125441e-462"},
    {1e200, "9.99999999999999954599683318766e+299"},
    {3.1e205, "1.72600695247730694120591174737e+308"}, /* just below DBL_MAX */
    {3.2e205, "1.81019335983756163197103204257e+308"}, /* just above: inf */
    {DBL_MAX, "2.41031242692103218718246366985e+462"},
};

/* |got - exact| in ulps of exact rounded to double (subnormal spacing
 * included); exact beyond DBL_MAX must give inf */
static double ulps_off(double got, const arb_t exact)
{
    double ex = arf_get_d(arb_midref(exact), ARF_RND_NEAR);
    if (!isfinite(ex))
        return isinf(got) && got > 0 ? 0 : INFINITY;
    if (!isfinite(got))
        return INFINITY;
    double ulp = nextafter(fabs(ex), INFINITY) - fabs(ex);
    if (!isfinite(ulp)) /* ex = DBL_MAX */
        ulp = fabs(ex) - nextafter(fabs(ex), 0);
    arb_t d;
    arb_init(d);
    arb_set_d(d, got);
    arb_sub(d, d, exact, 256);
    double off = fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR)) / ulp;
    arb_clear(d);
    return off;
}

static void check_point(hl_tape *t, hl_tape *tj, double w, const char *mp)
{
    double want = w * sqrt(w), got = NAN, gotj = NAN;
    hl_tape_eval_d(&got, &w, t);
    if (tj != NULL)
        hl_tape_eval_d(&gotj, &w, tj);
    CHECK_MSG(same_bits(got, want) && (tj == NULL || same_bits(gotj, want)),
              "w = %a: interpreter %a, jit %a, w*sqrt(w) %a", w, got, gotj, want);
    if (mp == NULL)
        return;
    arb_t exact, in, out;
    arb_init(exact), arb_init(in), arb_init(out);
    arb_set_str(exact, mp, 256);
    double off = ulps_off(got, exact);
    CHECK_MSG(off <= 1.3, "w = %.17g: %.17g is %.3f ulp off mpmath's %s", w, got, off, mp);
    arb_set_d(in, w);
    hl_tape_eval_arb(out, in, 128, t);
    arb_t rel;
    arb_init(rel);
    arb_sub(rel, out, exact, 256);
    arb_div(rel, rel, exact, 256); /* mpmath's 30 digits: 1e-29 relative */
    double r = arf_get_d(arb_midref(rel), ARF_RND_NEAR), rad = mag_get_d(arb_radref(rel));
    CHECK_MSG(fabs(r) < 1e-29 && rad < 1e-35, "Arb at w = %.17g: %s, mpmath %s", w,
              arb_get_str(out, 30, 0), mp);
    arb_clear(rel);
    arb_clear(exact), arb_clear(in), arb_clear(out);
}

static void test_points(void)
{
    hl_tape *t = tape_of("w^(3/2)"), *tj = tape_of("w^(3/2)");
    hl_error err;
    if (hl_tape_jit(tj, &err) != HL_OK) {
        printf("jit skipped: %s\n", err.msg);
        hl_tape_free(tj);
        tj = NULL;
    }
    for (size_t i = 0; i < sizeof hard / sizeof *hard; i++)
        check_point(t, tj, hard[i].w, hard[i].mp);
    /* outside the finite positives: as pow (+-0 -> +0, w < 0 -> NaN, inf),
     * but -inf -> NaN (pow: +inf) */
    const double odd[] = {0.0,      -0.0,      -1.0, -1e-300, -4.9406564584124654e-324,
                          INFINITY, -INFINITY, NAN};
    const double want[] = {0.0, 0.0, NAN, NAN, NAN, INFINITY, NAN, NAN};
    for (size_t i = 0; i < sizeof odd / sizeof *odd; i++) {
        double got = -1;
        check_point(t, tj, odd[i], NULL);
        hl_tape_eval_d(&got, &odd[i], t);
        CHECK_MSG(isnan(want[i]) ? isnan(got) : same_bits(got, want[i]), "w = %g: %g, want %g",
                  odd[i], got, want[i]);
    }
    hl_tape_free(t);
    hl_tape_free(tj);
}

/* SymPy: series(w(t)**Rational(3, 2), t, 0, 13), coefficients to 30 digits */
enum { K = 12, S = K + 1 };
static const struct {
    const char *w;    /* w(t) for the expression layer */
    double wc[4];     /* its coefficients */
    const char *c[S]; /* SymPy's */
} poly[] = {
    {"2 + 3*t - t^2 + t^3/2",
     {2, 3, -1, 0.5},
     {"2.82842712474619009760337744842", "6.36396103067892771960759925894",
      "0.265165042944955321650316635789", "-1.12695143251606011701384570210",
      "1.99288102588317983927816096585", "-1.46151513904426546425233114492",
      "1.37446470095507684384727114258", "-1.49857739175080524004452017665",
      "1.82595624071966145989621744555", "-2.36840582148627372561332079176",
      "3.21460669633639863379182276316", "-4.51719677757978250319044480640",
      "6.52380283890511281917085033775"}},
    {"1/64 + t/8 + t^2", /* w0 small: the coefficients grow as 8^k */
     {1.0 / 64, 0.125, 1, 0},
     {"0.001953125", "0.0234375", "0.234375", "0.6875", "1.6875", "-6.75", "13.5", "54", "-621",
      "2052", "7560", "-118368", "467424"}},
};

static void check_series(const char *what, const double *got, const char *const *c, double tol)
{
    double want[S], scale = 0;
    for (int k = 0; k < S; k++) {
        want[k] = strtod(c[k], NULL);
        scale = fmax(scale, fabs(want[k]));
        CHECK_MSG(fabs(got[k] - want[k]) <= tol * scale, "%s, t^%d: %.17g, SymPy %s", what, k,
                  got[k], c[k]);
    }
}

static void test_taylor(void)
{
    hl_tape *t = tape_of("w^(3/2)");
    hl_error err;
    arb_ptr ain = _arb_vec_init(S), aout = _arb_vec_init(S);
    for (size_t i = 0; i < sizeof poly / sizeof *poly; i++) {
        double in[S] = {0}, out[S], arbd[S], ex[S];
        for (int k = 0; k < 4; k++)
            in[k] = poly[i].wc[k];
        hl_tape_taylor_d(out, in, K, t);
        check_series("tape, double", out, poly[i].c, 1e-14);
        for (int k = 0; k < S; k++)
            arb_set_d(ain + k, in[k]);
        hl_tape_taylor_arb(aout, ain, K, 128, t);
        for (int k = 0; k < S; k++)
            arbd[k] = arf_get_d(arb_midref(aout + k), ARF_RND_NEAR);
        check_series("tape, Arb", arbd, poly[i].c, 1e-25);
        char src[96];
        snprintf(src, sizeof src, "(%s)^(3/2)", poly[i].w);
        const hl_expr *c[S];
        hl_expr_taylor(c, P, parse(src), "t", hl_num_si(P, 0), K);
        for (int k = 0; k < S; k++)
            CHECK(hl_expr_eval_d(&ex[k], c[k], 0, NULL, NULL, &err) == HL_OK);
        check_series("expression layer", ex, poly[i].c, 1e-15);
    }
    _arb_vec_clear(ain, S);
    _arb_vec_clear(aout, S);
    hl_tape_free(t);
}

int main(void)
{
    P = hl_pool_new();
    test_compiles_to_one_op();
    test_points();
    test_taylor();
    hl_pool_free(P);
    return HL_TEST_END();
}
