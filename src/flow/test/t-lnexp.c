/* The step rule's ln and exp (src/flow/lnexp.h) against long double's
 * logl and expl (64-bit significands: 2^11 times finer than the bounds
 * checked) over the whole range: every binade of the normal doubles, at
 * the table's subinterval boundaries and at pseudo-random significands;
 * exp at every multiple of ln(2)/128 (the reduction's ties) and random
 * points of [-708, 708].  A few values against mpmath (40 digits).  The
 * AVX2+FMA build of both (the flow's loops are built so, flow_poly.h) gives
 * the same bits as the plain one: this file is compiled with
 * -ffp-contract=off, as the flow's are.  And libm's exp outside the fast
 * range: inf, NaN, overflow, subnormal results as before. */
#include <float.h>
#include <math.h>
#include <stdint.h>

#include "flow/flow_poly.h"
#include "flow/lnexp.h"
#include "hl_test.h"

/* the bounds stated in lnexp.h */
static long double ln_bound(long double lnx)
{
    return 2e-16L + 2.5e-16L * fabsl(lnx);
}
#define EXP_BOUND 4e-16L

static uint64_t rng = 0x9e3779b97f4a7c15u;
static uint64_t next_u64(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

#if defined(__x86_64__) && defined(__GNUC__)
static HL_FLOW_VEC double ln_vec(double x)
{
    return hl_flow_ln_normal(x);
}
static HL_FLOW_VEC double exp_vec(double y)
{
    return hl_flow_exp(y);
}
#define HAVE_VEC 1
#else
#define HAVE_VEC 0
#endif

typedef struct worst {
    long n, bad, twins_differ;
    double at;
    long double ratio; /* the worst error over its bound */
} worst;

static void ln_one(worst *w, double x)
{
    double got = hl_flow_ln_normal(x);
    long double want = logl((long double)x), r = fabsl(got - want) / ln_bound(want);
    w->n++;
    if (r > w->ratio) {
        w->ratio = r;
        w->at = x;
    }
    w->bad += !(r <= 1);
    if (HAVE_VEC && hl_flow_vec_ok() && hl_flow_bits_of(ln_vec(x)) != hl_flow_bits_of(got))
        w->twins_differ++;
}

static void exp_one(worst *w, double y)
{
    double got = hl_flow_exp(y);
    long double want = expl((long double)y), r = fabsl(got / want - 1) / EXP_BOUND;
    w->n++;
    if (r > w->ratio) {
        w->ratio = r;
        w->at = y;
    }
    w->bad += !(r <= 1);
    if (HAVE_VEC && hl_flow_vec_ok() && hl_flow_bits_of(exp_vec(y)) != hl_flow_bits_of(got))
        w->twins_differ++;
}

#if defined(__SANITIZE_ADDRESS__)
#define PER_BINADE 40
#define EXP_RANDOM 100000
#else
#define PER_BINADE 200
#define EXP_RANDOM 1000000
#endif

/* every binade: its ends, the table's 128 subinterval boundaries (and
 * their neighbours), PER_BINADE random significands */
static void test_ln_range(void)
{
    worst w = {0};
    for (uint64_t e = 1; e <= 2046; e++) {
        uint64_t b = e << 52;
        ln_one(&w, hl_flow_double_of(b));
        ln_one(&w, hl_flow_double_of(b | ((UINT64_C(1) << 52) - 1)));
        for (uint64_t i = 0; i < 128; i++) {
            uint64_t edge = (0x3fe6000000000000 + (i << 45)) & ((UINT64_C(1) << 52) - 1);
            ln_one(&w, hl_flow_double_of(b | edge));
            ln_one(&w, hl_flow_double_of(b | ((edge + 1) & ((UINT64_C(1) << 52) - 1))));
            ln_one(&w, hl_flow_double_of(b | ((edge - 1) & ((UINT64_C(1) << 52) - 1))));
        }
        for (int j = 0; j < PER_BINADE; j++)
            ln_one(&w, hl_flow_double_of(b | (next_u64() >> 12)));
    }
    /* near 1, where ln x is small and the bound absolute */
    for (int j = -2000; j <= 2000; j++)
        ln_one(&w, 1 + j * DBL_EPSILON * 0.5);
    printf("ln: %ld points, worst error %.3Lf of the bound at %a\n", w.n, w.ratio, w.at);
    CHECK_MSG(w.bad == 0, "%ld points over the bound, worst %.3Lf of it at %a", w.bad, w.ratio,
              w.at);
    CHECK_MSG(w.twins_differ == 0, "the AVX2+FMA build differs at %ld points", w.twins_differ);
}

static void test_exp_range(void)
{
    worst w = {0};
    /* m ln(2)/128 for every m reaching +-708: the reduction's rounding ties */
    for (long m = -130800; m <= 130800; m++) {
        double y = m * 0x1.62e42fefa39efp-8;
        if (fabs(y) <= 708)
            exp_one(&w, y);
    }
    for (int j = 0; j < EXP_RANDOM; j++)
        exp_one(&w, ((double)(next_u64() >> 11) * 0x1p-53 * 2 - 1) * 708);
    /* small arguments, every binade down to the subnormals */
    for (double y = 1; y > 0; y *= 0.5) {
        exp_one(&w, y);
        exp_one(&w, -y);
    }
    exp_one(&w, 708);
    exp_one(&w, -708);
    printf("exp: %ld points, worst error %.3Lf of the bound at %a\n", w.n, w.ratio, w.at);
    CHECK_MSG(w.bad == 0, "%ld points over the bound, worst %.3Lf of it at %a", w.bad, w.ratio,
              w.at);
    CHECK_MSG(w.twins_differ == 0, "the AVX2+FMA build differs at %ld points", w.twins_differ);
}

/* mpmath at 40 digits, rounded to 22 */
static void test_mpmath(void)
{
    static const struct {
        double x;
        long double ln;
    } L[] = {
        {2.2250738585072014e-308, -708.3964185322641062244L},
        {1.7976931348623157e+308, 709.7827128933839967322L},
        {3, 1.098612288668109691395L},
        {0.1, -2.302585092994045628507L},
        {1e-300, -690.7755278982137051803L},
        {1e+300, 690.7755278982137052579L},
        {0.6875, -0.374693449441410693607L},
        {1.375, 0.3184537311185346158102L},
        {1.0000000000000002, 2.220446049250312834328e-16L},
        {0.9999999999999999, -1.110223024625156602053e-16L},
    };
    static const struct {
        double y;
        long double e;
    } E[] = {
        {708, 3.023383144276055014776e+307L},
        {-708, 3.307553003638407996201e-308L},
        {1, 2.71828182845904523536L},
        {-2.0350877192982457, 0.1306690198065626303493L},
        {0.5, 1.648721270700128146849L},
        {-0.0054, 0.9946145537913911703745L},
        {123.456, 4.132944352778106135834e+53L},
    };
    for (size_t i = 0; i < sizeof L / sizeof *L; i++) {
        long double d = fabsl(hl_flow_ln_normal(L[i].x) - L[i].ln);
        CHECK_MSG(d <= ln_bound(L[i].ln), "ln %a: off by %Lg", L[i].x, d);
    }
    for (size_t i = 0; i < sizeof E / sizeof *E; i++) {
        long double d = fabsl(hl_flow_exp(E[i].y) / E[i].e - 1);
        CHECK_MSG(d <= EXP_BOUND, "exp %a: off by %Lg", E[i].y, d);
    }
}

/* outside |y| <= 708: libm's exp, bit for bit */
static void test_exp_outside(void)
{
    const double ys[] = {708.5,  709.78, 710,  1e300,  INFINITY,
                         -708.5, -745,   -746, -1e300, -INFINITY};
    for (size_t i = 0; i < sizeof ys / sizeof *ys; i++)
        CHECK_MSG(hl_flow_bits_of(hl_flow_exp(ys[i])) == hl_flow_bits_of(exp(ys[i])),
                  "exp(%g) = %a, libm %a", ys[i], hl_flow_exp(ys[i]), exp(ys[i]));
    CHECK(isnan(hl_flow_exp(NAN)));
    CHECK(hl_flow_exp(INFINITY) == INFINITY && hl_flow_exp(-INFINITY) == 0);
}

/* hl_flow_ln: lnexp's for normal positive x, libm's log bit for bit else */
static void test_ln_outside(void)
{
    const double xs[] = {0,        -0.0, 4.9e-324, 1e-310, DBL_MIN * (1 - DBL_EPSILON),
                         INFINITY, -1,   -INFINITY};
    for (size_t i = 0; i < sizeof xs / sizeof *xs; i++)
        CHECK_MSG(hl_flow_bits_of(hl_flow_ln(xs[i])) == hl_flow_bits_of(log(xs[i])),
                  "ln(%g) = %a, libm %a", xs[i], hl_flow_ln(xs[i]), log(xs[i]));
    CHECK(isnan(hl_flow_ln(NAN)));
    const double normal[] = {DBL_MIN, 0.5, 1, 3, DBL_MAX};
    for (size_t i = 0; i < sizeof normal / sizeof *normal; i++)
        CHECK(hl_flow_bits_of(hl_flow_ln(normal[i])) ==
              hl_flow_bits_of(hl_flow_ln_normal(normal[i])));
}

int main(void)
{
    test_ln_range();
    test_exp_range();
    test_mpmath();
    test_exp_outside();
    test_ln_outside();
    return HL_TEST_END();
}
