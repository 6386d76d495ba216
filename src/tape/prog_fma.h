/* fma(a, b, c) without a fused multiply-add instruction, for the double
 * interpreter's scalar loop (prog_run.c): the loop of processors without
 * AVX2, which nearly all lack FMA too.  There libm's fma is a software
 * emulation that saves and restores the floating-point environment: about
 * 60-120 ns a call, twenty times the rest of an ODE step (bench/run-interp.sh
 * with glibc's FMA hidden, GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA,-AVX2).  The
 * ODE step z[k+1] = fma(f, hi, f lo) (rule.h) has c tiny next to a b, and
 * for that shape a few exact transformations give fma's bits:
 *
 *   a b = p + e exactly (Dekker's product, Veltkamp's split),
 *   e + c = s + t exactly (Knuth's two-sum; t is needed only at a tie),
 *   p + s = r + u exactly (Dekker's two-sum, as |p| > |s|),
 * so a b + c = r + u + t exactly, and r = fl(p + s) is the correctly
 * rounded a b + c unless p + s is exactly halfway between r and its
 * neighbour n (then t, if not 0, says which of the two is nearer).  When
 * |c| <= 2^-40 |p|, |s| is below 2^-39 |p|, so p + s is a multiple of
 * ulp(s) and so is every halfway point (a multiple of a far larger power of
 * two): p + s off a halfway point is at least ulp(s) from it, and |t| <=
 * ulp(s) / 2 cannot move a b + c across it.  A product a b of 0 is exact,
 * so then fma is p + c.  Outside that shape, or where a product or split
 * could overflow or lose bits to underflow, libm's fma.
 * Needs round-to-nearest and no contraction (prog_run.c is compiled with
 * -ffp-contract=off). */
#ifndef HAMLIE_TAPE_PROG_FMA_H
#define HAMLIE_TAPE_PROG_FMA_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* e with a b = p + e exactly, p = fl(a b) (Dekker): each half of a split
 * has at most 26 bits, so the partial products are exact. */
static inline double prog_product_error(double a, double b, double p)
{
    const double split = 134217729.0; /* 2^27 + 1 */
    double ta = split * a, ah = ta - (ta - a), al = a - ah;
    double tb = split * b, bh = tb - (tb - b), bl = b - bh;
    return ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

/* t with a + b = s + t exactly, s = fl(a + b) (Knuth) */
static inline double prog_sum_error(double a, double b, double s)
{
    double bb = s - a;
    return (a - (s - bb)) + (b - bb);
}

/* The double next to r (not 0, finite) on the side of u. */
static inline double prog_neighbour(double r, double u)
{
    uint64_t bits;
    memcpy(&bits, &r, sizeof bits);
    bits += (u > 0) == (r > 0) ? 1 : (uint64_t)-1; /* away from 0, or towards it */
    double n;
    memcpy(&n, &bits, sizeof n);
    return n;
}

/* Whether a normal u is a power of two (its significand's stored bits 0):
 * the distance to a halfway point is one, so most sums need no more. */
static inline int prog_power_of_two(double u)
{
    uint64_t bits;
    memcpy(&bits, &u, sizeof bits);
    return (bits & 0xfffffffffffffull) == 0;
}

/* fma outside the common shape: a b exactly 0 (half the coefficients of
 * an even or odd series are), where fma is p + c, else libm's. */
static inline double prog_fma_rare(double a, double b, double c, double p)
{
    if ((a == 0 || b == 0) && fabs(a) <= DBL_MAX && fabs(b) <= DBL_MAX)
        return p + c; /* p = a b exactly (+0 or -0), then one rounding */
    return fma(a, b, c);
}

static inline double prog_fma(double a, double b, double c)
{
    const double p = a * b, ap = fabs(p);
    /* NaN and inf fail these tests too */
    if (!(ap >= 0x1p-800 && ap <= 0x1p800 && fabs(a) <= 0x1p900 && fabs(b) <= 0x1p900 &&
          fabs(c) <= ap * 0x1p-40))
        return prog_fma_rare(a, b, c, p);
    const double e = prog_product_error(a, b, p);
    const double s = e + c, r = p + s;
    const double u = s - (r - p); /* p + s = r + u exactly (Dekker's two-sum: |p| > |s|) */
    if (u == 0 || !prog_power_of_two(u))
        return r; /* p + s exact, or not halfway */
    const double n = prog_neighbour(r, u);
    if (n - r != 2 * u)
        return r; /* not halfway either */
    const double t = prog_sum_error(e, c, s);
    return t != 0 && (t > 0) == (u > 0) ? n : r; /* past the halfway point, n is nearer */
}

#endif /* HAMLIE_TAPE_PROG_FMA_H */
