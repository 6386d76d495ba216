/* hl_run_fmt against strtod and printf: 2 * 10^6 doubles from random bit
 * patterns (every exponent, subnormals) and from random values in [0, 100]
 * read back exactly; the string equals printf's "%.17g" but for near-ties
 * in the 18th digit, where the long double product is not exact (about 0.2%
 * of random doubles; allowed 0.5%): the 17th digit is then one off, which
 * still reads back; special values and the layout at the switch to
 * exponents equal printf's. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <math.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/run.h"

static uint64_t state = 0x9E3779B97F4A7C15u;

static uint64_t next(void) /* xorshift64* */
{
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return state * 2685821657736338717u;
}

int main(void)
{
    char a[32], b[40];
    long differ = 0, bad = 0, n = 2000000;
    for (long i = 0; i < n; i++) {
        double x;
        if (i % 2) {
            uint64_t u = next();
            memcpy(&x, &u, sizeof x);
            if (!isfinite(x))
                continue;
        } else
            x = (double)(next() >> 11) * 0x1p-53 * 100;
        hl_run_fmt(a, x);
        snprintf(b, sizeof b, "%.17g", x);
        if (strtod(a, NULL) != x || (x == 0 && signbit(x) != signbit(strtod(a, NULL)))) {
            if (bad++ < 5)
                fprintf(stderr, "%.17g printed as %s\n", x, a);
        }
        if (strcmp(a, b) != 0 && differ++ < 3)
            printf("differs from printf: %s vs %s\n", a, b);
    }
    printf("%ld doubles: %ld do not read back, %ld differ from %%.17g\n", n, bad, differ);
    CHECK(bad == 0);
    CHECK(differ <= n / 200);
    const double xs[] = {0.0, -0.0, 1, -1, 0.5, 0.1, 1e16, 1e17, 123456789012345678.0, 1e-4,
                         1e-5, 0.00012345, 9.9999999999999995e-05, 1e300, 5e-324, 2.5e-310,
                         1.7976931348623157e308, 0.30000000000000004, 20, 1e22, 100};
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++) {
        hl_run_fmt(a, xs[i]);
        snprintf(b, sizeof b, "%.17g", xs[i]);
        CHECK_STR(a, b);
    }
    /* 15 digits where they suffice, as printf's %.15g */
    const double ts[] = {0.1, 0.30000000000000004, 1e4, 2.5, 1e-7, 123.456, 1e20, 0.7};
    for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) {
        hl_run_fmt_short(a, ts[i]);
        snprintf(b, sizeof b, "%.15g", ts[i]);
        if (strtod(b, NULL) != ts[i])
            snprintf(b, sizeof b, "%.17g", ts[i]);
        CHECK_STR(a, b);
    }
    for (long k = 0; k < 100000; k++) { /* t = k dt reads back */
        double t = (double)k * 0.01;
        hl_run_fmt_short(a, t);
        CHECK(strtod(a, NULL) == t || (printf("%s\n", a), 0));
    }
    hl_run_fmt(a, INFINITY);
    CHECK_STR(a, "inf");
    hl_run_fmt(a, -INFINITY);
    CHECK_STR(a, "-inf");
    hl_run_fmt(a, NAN);
    CHECK_STR(a, "nan");
    return HL_TEST_END();
}
