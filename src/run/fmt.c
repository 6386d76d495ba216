/* Doubles for the CSV: 17 significant digits (always enough to read the
 * same double back), in the layout of printf's %.17g, without printf.
 *
 * glibc's %.17g converts exactly (big integers) and costs about 400 ns a
 * number: a million-row CSV spent 90% of its time there.  Here the double
 * is scaled by a power of ten in long double (64-bit mantissa: relative
 * error about 1e-19) and rounded to a 17-digit integer.  The result is
 * within 0.5 unit of the 17th digit plus 1e-19 relative of x, well inside
 * half the spacing of doubles (>= 1.1e-16 relative), so strtod gives x back;
 * it may differ from %.17g by one in the last digit when the 18th digit is
 * a near-tie (about 0.2% of random doubles).  Checked against strtod and
 * %.17g in src/run/test/t-fmt.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hamlie/run.h"


/* 10^0 .. 10^27: exact in long double (5^27 < 2^64) */
static const long double P10[28] = {
    1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,  1e7L,  1e8L,  1e9L,
    1e10L, 1e11L, 1e12L, 1e13L, 1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L,
    1e20L, 1e21L, 1e22L, 1e23L, 1e24L, 1e25L, 1e26L, 1e27L};

/* y * 10^k: exact factors, one rounding each (at most 13 for |k| <= 340) */
static long double scale(long double y, int k)
{
    int a = k < 0 ? -k : k;
    long double f = P10[a % 27];
    for (a /= 27; a > 0; a--)
        f *= P10[27];
    return k < 0 ? y / f : y * f;
}

/* x with prec (1..17) significant digits, %.<prec>g's layout. */
static int fmt_prec(char *out, double x, int prec)
{
    char *s = out;
    if (isnan(x)) {
        strcpy(out, signbit(x) ? "-nan" : "nan");
        return (int)strlen(out);
    }
    if (signbit(x))
        *s++ = '-', x = -x;
    if (isinf(x)) {
        memcpy(s, "inf", 4);
        return (int)(s - out) + 3;
    }
    if (x == 0) {
        *s++ = '0', *s = '\0';
        return (int)(s - out);
    }
    int e = (int)floor(ilogb(x) * 0.30102999566398120); /* may be one low */
    unsigned long long m = 0;
    for (int tries = 0; tries < 4; tries++) {
        long double y = scale((long double)x, prec - 1 - e);
        long double r = rintl(y); /* ties to even, as printf */
        if (r < P10[prec - 1]) {
            e--;
            continue;
        }
        if (r >= P10[prec]) {
            e++;
            continue;
        }
        m = (unsigned long long)r;
        break;
    }
    char d[18];
    for (int i = prec - 1; i >= 0; i--)
        d[i] = (char)('0' + m % 10), m /= 10;
    int nd = prec;
    while (nd > 1 && d[nd - 1] == '0')
        nd--;
    if (e >= -4 && e < prec) {
        if (e >= 0) {
            for (int i = 0; i <= e; i++)
                *s++ = i < nd ? d[i] : '0';
            if (nd > e + 1) {
                *s++ = '.';
                for (int i = e + 1; i < nd; i++)
                    *s++ = d[i];
            }
        } else {
            *s++ = '0', *s++ = '.';
            for (int i = 0; i < -e - 1; i++)
                *s++ = '0';
            for (int i = 0; i < nd; i++)
                *s++ = d[i];
        }
    } else {
        *s++ = d[0];
        if (nd > 1) {
            *s++ = '.';
            for (int i = 1; i < nd; i++)
                *s++ = d[i];
        }
        *s++ = 'e';
        *s++ = e < 0 ? '-' : '+';
        int a = e < 0 ? -e : e;
        if (a >= 100)
            *s++ = (char)('0' + a / 100);
        *s++ = (char)('0' + a / 10 % 10);
        *s++ = (char)('0' + a % 10);
    }
    *s = '\0';
    return (int)(s - out);
}

int hl_run_fmt(char *out, double x) { return fmt_prec(out, x, 17); }

int hl_run_fmt_short(char *out, double x)
{
    int n = fmt_prec(out, x, 15);
    if (!isfinite(x) || strtod(out, NULL) == x)
        return n;
    return fmt_prec(out, x, 17);
}
