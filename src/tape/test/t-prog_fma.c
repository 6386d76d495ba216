/* prog_fma (src/tape/prog_fma.h), the scalar loop's fma without the fma
 * instruction, against libm's fma (correctly rounded, by the instruction or
 * by glibc's emulation) bit for bit:
 *   - the ODE step's shape fma(f, hi, f lo), hi + lo = 1/n from
 *     hl_rule_recip_split, for n = 2..300 and f of every sign and of
 *     magnitudes 2^-300..2^300, and 0;
 *   - ties: a b exactly halfway between two doubles and c far below its
 *     last bit, so that only c decides; the test checks that the naive
 *     sum goes wrong on many of them (the correction is reached);
 *   - other shapes and special values (c as large as a b, 0, inf, NaN,
 *     subnormals, near overflow), which take libm's fma or p + c.
 * Compiled with -ffp-contract=off (CMakeLists.txt), as prog_run.c. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "rules/rule.h"
#include "tape/prog_fma.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;

static uint64_t rnd(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return rng_state;
}

/* a random double with a full significand, sign s (+-1, or 0 for either),
 * exponent in [lo, hi] */
static double random_double(int lo, int hi)
{
    double m = 1.0 + (double)(rnd() >> 12) * 0x1p-52;
    int e = lo + (int)(rnd() % (uint64_t)(hi - lo + 1));
    return (rnd() & 1 ? -1 : 1) * ldexp(m, e);
}

static int same(double a, double b)
{
    return (isnan(a) && isnan(b)) || memcmp(&a, &b, sizeof a) == 0;
}

static void check_ode_shape(void)
{
    for (int n = 2; n <= 300; n++) {
        double hi, lo;
        hl_rule_recip_split(&hi, &lo, n);
        int bad = 0;
        for (int i = 0; i < 2000; i++) {
            double f = i < 2 ? (i ? -0.0 : 0.0) : random_double(-300, 300);
            bad += !same(prog_fma(f, hi, f * lo), fma(f, hi, f * lo));
        }
        CHECK_MSG(bad == 0, "n = %d: %d of 2000 differ from fma", n, bad);
    }
}

/* a b exactly halfway between two doubles: odd A, B of 27 bits whose
 * product has 54, times powers of two; then c, far below a b's last bit,
 * alone decides the rounding, which the naive fl(p + fl(e + c)) misses
 * (p + fl(e + c) is a tie, rounded to even). */
static void check_ties(void)
{
    int bad = 0, naive_wrong = 0, tried = 0;
    while (tried < 100000) {
        uint64_t A = (rnd() >> 37) | (1ull << 26) | 1, B = (rnd() >> 37) | (1ull << 26) | 1;
        if (A * B < (1ull << 53))
            continue;
        double a = ldexp((double)A, (int)(rnd() % 80) - 40) * (rnd() & 1 ? -1 : 1);
        double b = ldexp((double)B, (int)(rnd() % 80) - 40) * (rnd() & 1 ? -1 : 1);
        double p = a * b, e = fma(a, b, -p);
        double c = random_double(ilogb(p) - 120, ilogb(p) - 55);
        double want = fma(a, b, c), got = prog_fma(a, b, c);
        tried++;
        bad += !same(got, want);
        naive_wrong += !same(p + (e + c), want);
    }
    CHECK_MSG(bad == 0, "%d of %d ties differ from fma", bad, tried);
    CHECK_MSG(naive_wrong > tried / 20, "only %d of %d ties need the correction", naive_wrong,
              tried);
}

static void check_other_shapes(void)
{
    static const double special[] = {0.0,       -0.0,     1.0,      -1.0,     INFINITY,
                                     -INFINITY, NAN,      DBL_MIN,  -DBL_MIN, DBL_TRUE_MIN,
                                     DBL_MAX,   -DBL_MAX, 0x1p-800, 0x1p900,  0x1p-1000,
                                     0x1p511,   3.0,      1.0 / 3.0};
    const int ns = (int)(sizeof special / sizeof *special);
    int bad = 0;
    for (int i = 0; i < ns; i++)
        for (int j = 0; j < ns; j++)
            for (int k = 0; k < ns; k++)
                bad += !same(prog_fma(special[i], special[j], special[k]),
                             fma(special[i], special[j], special[k]));
    CHECK_MSG(bad == 0, "%d special triples differ from fma", bad);
    bad = 0;
    for (int i = 0; i < 200000; i++) {
        double a = random_double(-600, 600), b = random_double(-600, 600);
        /* c from far below a b's last bit to far above it */
        double c = random_double(-1074, 1000) * (i % 7 == 0 ? 0 : 1);
        if (i % 3 == 0)
            c = a * b * random_double(-60, 0);
        bad += !same(prog_fma(a, b, c), fma(a, b, c));
    }
    CHECK_MSG(bad == 0, "%d random triples differ from fma", bad);
}

int main(void)
{
    check_ode_shape();
    check_ties();
    check_other_shapes();
    return HL_TEST_END();
}
