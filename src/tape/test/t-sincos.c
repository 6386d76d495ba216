/* sin and cos at order 0, which the back ends compute differently: the
 * double interpreter joins SINCOS's two calls into one sincos() (prog.c
 * rec_call), the compiled recursion calls sin() and cos() (jit_taylor.c:
 * one sincos was measured slower there, docs/work-precision.md, session
 * 12).  They agree to the bit only because glibc's sincos computes each
 * value as sin and cos do; this checks that, on the libm the tests run
 * with:
 *   - sincos(x) against (sin x, cos x), memcmp, over arguments that reach
 *     every path of glibc's code: random bit patterns, uniform in
 *     [-3, 3] (the ranges |x| < 0.855 and < 2.426 take different
 *     reductions) and [-1000, 1000], random magnitudes 2^-100 .. 2^100 of
 *     both signs, the ulps around k pi/2 (|k| <= 10^4, where the reduced
 *     argument cancels), around glibc's range edges (2^-27, 0.855469,
 *     2.426265, 105414350, where the reduction changes), 2^1023, and the
 *     special values (+-0, subnormals, DBL_MAX, +-inf, NaN);
 *   - the pendulum's recursion (p' = -sin q) at order 3, native against
 *     the interpreter, memcmp, from q among those arguments (skipped
 *     without libgccjit).
 * About 0.3 s; fewer arguments under the sanitizers. */
#define _GNU_SOURCE /* sincos */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"

#if defined(__SANITIZE_ADDRESS__)
#define SCALE 10 /* a tenth of the arguments: the CI's time */
#else
#define SCALE 1
#endif
#define NRANDOM (2000000 / SCALE)
#define NPI2 (10000 / SCALE)  /* multiples of pi/2 on each side of 0 */
#define NEDGE (20000 / SCALE) /* ulps on each side of an edge */
#define ORDER 3
#define NSTATES (4000 / SCALE)

static long nchecked, ndiffer;
static double first_differ;

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static void check_sincos(double x)
{
    double s, c;
    sincos(x, &s, &c);
    /* volatile: GCC may itself turn sin(x), cos(x) into one sincos */
    volatile double sv = sin(x), cv = cos(x);
    nchecked++;
    if (!same_bits(s, sv) || !same_bits(c, cv)) {
        if (ndiffer++ == 0)
            first_differ = x;
    }
}

static uint64_t rng = 0x9e3779b97f4a7c15ULL;
static uint64_t next_random(void) /* xorshift64 */
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}
static double unit_random(void) /* [0, 1) */
{
    return (double)(next_random() >> 11) * 0x1p-53;
}

static double random_argument(long i)
{
    uint64_t r = next_random();
    double x;
    switch (i % 4) {
    case 0: /* any bits but NaN's */
        memcpy(&x, &r, sizeof x);
        return isnan(x) ? 0.5 : x;
    case 1:
        return 6 * unit_random() - 3;
    case 2:
        return 2000 * unit_random() - 1000;
    default:
        x = ldexp(0.5 + unit_random(), (int)(r % 201) - 100);
        return r >> 63 ? -x : x;
    }
}

/* x and the n doubles on either side of it, and their negatives */
static void check_around(double x, int n)
{
    double up = x, down = x;
    for (int i = 0; i < n; i++) {
        check_sincos(up);
        check_sincos(-up);
        check_sincos(down);
        check_sincos(-down);
        up = nextafter(up, INFINITY);
        down = nextafter(down, -INFINITY);
    }
}

static const double edges[] = {0x1p-27, 0x1p-26, 0.855469, 2.426265, 105414350.0, 0x1p1023};
static const double specials[] = {0.0,     -0.0,     DBL_MIN,  -DBL_MIN,  0x1p-1074, -0x1p-1074,
                                  DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, NAN};

static void libm_sincos(void)
{
    for (long i = 0; i < NRANDOM; i++)
        check_sincos(random_argument(i));
    for (int k = 0; k <= NPI2; k++)
        check_around(k * M_PI_2, 3);
    for (size_t e = 0; e < sizeof edges / sizeof *edges; e++)
        check_around(edges[e], NEDGE);
    for (size_t i = 0; i < sizeof specials / sizeof *specials; i++) {
        double s, c;
        sincos(specials[i], &s, &c);
        double sv = sin(specials[i]), cv = cos(specials[i]);
        /* NaN's payload may differ; NaN against NaN is enough */
        CHECK_MSG((same_bits(s, sv) || (isnan(s) && isnan(sv))) &&
                      (same_bits(c, cv) || (isnan(c) && isnan(cv))),
                  "sincos(%a) = (%a, %a), sin, cos = (%a, %a)", specials[i], s, c, sv, cv);
    }
    CHECK_MSG(ndiffer == 0, "sincos differs from (sin, cos) at %ld of %ld arguments, first %a",
              ndiffer, nchecked, first_differ);
    printf("libm: sincos == (sin, cos) at %ld arguments\n", nchecked - ndiffer);
}

/* q' = p, p' = -sin q: the interpreter's coefficients (tape a) and the
 * native code's (tape b, the same program) from each q of a list
 * (p = 0.25), all bits */
static void pendulum_native(void)
{
    hl_pool *P = hl_pool_new();
    const char *vars[2] = {"q", "p"};
    const hl_expr *q = hl_sym(P, "q"), *p = hl_sym(P, "p");
    const hl_expr *f[2] = {p, hl_neg(P, hl_call(P, HL_SIN, q))};
    hl_tape *ta = NULL, *tb = NULL;
    hl_error err;
    CHECK(hl_tape_new(&ta, f, 2, vars, 2, &err) == HL_OK);
    CHECK(hl_tape_new(&tb, f, 2, vars, 2, &err) == HL_OK);
    int st = hl_tape_native(tb, ORDER, &err);
    if (st != HL_OK) {
        CHECK_MSG(st == HL_EUNSUP, "native: %s", err.msg);
        printf("native: skipped: %s\n", err.msg);
    } else {
        const int S = ORDER + 1;
        long differ = 0;
        for (long i = 0; i < NSTATES; i++) {
            /* half random, half the multiples of pi/2 and their next doubles */
            double q0 = i < NSTATES / 2 ? random_argument(i) : (i - NSTATES / 2 - 20) * M_PI_2;
            if (i >= NSTATES / 2 && i % 2)
                q0 = nextafter(q0, INFINITY);
            double a[2 * (ORDER + 1)] = {q0}, b[2 * (ORDER + 1)] = {q0};
            a[S] = b[S] = 0.25;
            CHECK(hl_tape_taylor_ode_d(a, ORDER, ta, &err) == HL_OK);
            CHECK(hl_tape_taylor_ode_d(b, ORDER, tb, &err) == HL_OK);
            if (memcmp(a, b, sizeof a) != 0 && differ++ == 0)
                fprintf(stderr, "q = %a: interpreter and native differ\n", q0);
        }
        CHECK_MSG(differ == 0, "the pendulum's coefficients differ at %ld of %d states", differ,
                  NSTATES);
        printf("native: the interpreter's bits at %ld states\n", NSTATES - differ);
    }
    hl_tape_free(ta);
    hl_tape_free(tb);
    hl_pool_free(P);
}

int main(void)
{
    unsetenv("HL_CC"); /* libgccjit, the back end under test */
    libm_sincos();
    pendulum_native();
    flint_cleanup();
    return HL_TEST_END();
}
