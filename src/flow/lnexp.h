/* ln and exp for the step rule (flow_impl.h), inlined, without libm.
 *
 * WHY: the rule h = r min_k (s/N_k)^(1/k) takes two logs and an exp a
 * step, on the step's chain of dependences (state, recursion, step,
 * state); libm's, through the PLT and its wrappers, were about 210 of the
 * 1000 instructions a pendulum step spends outside the recursion (callgrind,
 * docs/work-precision.md).  The rule is a heuristic radius times a safety
 * factor: it needs neither libm's half ulp nor its special cases, only a
 * stated bound, which the rule then covers by shortening the step
 * (HL_FLOW_LNEXP_DELTA, flow_impl.h).
 *
 * The same bits on every x86-64: integer operations and double products
 * and sums only, no fma(), in files compiled with -ffp-contract=off
 * (CMakeLists.txt), and tables rounded once from 60 digits
 * (scripts/gen-flow-lnexp.py, lnexp_tab.c), not computed by the libm at
 * hand.
 *
 * Bounds (src/flow/test/t-lnexp.c checks them against long double's logl
 * and expl over the whole range, and against mpmath at a few points):
 *   hl_flow_ln_normal:  |ln~ x - ln x| <= 2e-16 + 2.5e-16 |ln x|, for
 *                       normal positive x (so <= 1.8e-13 over the range);
 *                       (hl_flow_ln: libm's log for other x);
 *   hl_flow_exp:        |exp~ y / e^y - 1| <= 4e-16 for |y| <= 708, libm's
 *                       exp outside (inf, NaN, overflow, subnormal). */
#ifndef HAMLIE_FLOW_LNEXP_H
#define HAMLIE_FLOW_LNEXP_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define HL_FLOW_LN_BITS 7 /* 128 subintervals: |r| <= 0.0040 */
#define HL_FLOW_LN_N (1 << HL_FLOW_LN_BITS)
#define HL_FLOW_EXP_BITS 6 /* 2^(j/64): |r| <= ln(2)/128 */
#define HL_FLOW_EXP_N (1 << HL_FLOW_EXP_BITS)

/* lnexp_tab.c; hidden: read directly, not through the shared library's GOT */
extern const double hl_flow_ln_tab[HL_FLOW_LN_N][2] __attribute__((visibility("hidden")));
extern const double hl_flow_exp_tab[HL_FLOW_EXP_N] __attribute__((visibility("hidden")));

static inline uint64_t hl_flow_bits_of(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static inline double hl_flow_double_of(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* ln x for x normal and positive (DBL_MIN <= x <= DBL_MAX; else garbage):
 * x = 2^k z, z in [0.6875, 1.375) (the offset keeps z near 1 on both sides),
 * z = c (1 + r) with 1/c from a table of 128 by z's leading bits, so
 * ln x = k ln 2 + ln c + log1p(r), |r| <= 0.0040, log1p by its Taylor
 * series to r^6 (the rest below 3e-18).  r = z/c - 1 is z (1/c) rounded
 * once (then 1 off exactly): 1.1e-16.  ln 2 in two parts, the first with
 * 42 bits so that k ln2_hi is exact for any exponent. */
static inline double hl_flow_ln_normal(double x)
{
    const uint64_t off = 0x3fe6000000000000; /* 0.6875 */
    const double ln2_hi = 0x1.62e42fefa3800p-1, ln2_lo = 0x1.ef35793c76730p-45;
    uint64_t ix = hl_flow_bits_of(x), tmp = ix - off;
    int i = (int)((tmp >> (52 - HL_FLOW_LN_BITS)) % HL_FLOW_LN_N);
    double k = (double)((int64_t)tmp >> 52); /* arithmetic shift: floor */
    double z = hl_flow_double_of(ix - (tmp & (UINT64_C(0xfff) << 52)));
    double r = z * hl_flow_ln_tab[i][0] - 1, r2 = r * r;
    double hi = k * ln2_hi + hl_flow_ln_tab[i][1];
    /* -r^2/2 + r^3/3 - ... - r^6/6, in pairs: a shorter chain than Horner */
    double tail = r2 * ((-0.5 + r * (1.0 / 3)) + r2 * ((-0.25 + r * 0.2) + r2 * (-1.0 / 6)));
    return hi + (r + (k * ln2_lo + tail));
}

/* ln x: hl_flow_ln_normal for normal positive x, libm's log for the rest
 * (0, subnormal, inf, NaN, negative: as libm).  One unsigned comparison of
 * the bits: below DBL_MIN they wrap around. */
static inline double hl_flow_ln(double x)
{
    const uint64_t min = 0x0010000000000000, span = 0x7ff0000000000000 - min; /* DBL_MIN, inf */
    return hl_flow_bits_of(x) - min < span ? hl_flow_ln_normal(x) : log(x);
}

/* e^y: y = (n + j/64) ln 2 + r, n, j integers, 0 <= j < 64, |r| <= ln(2)/128
 * (plus the rounding of y 64/ln 2), e^y = 2^n 2^(j/64) e^r, 2^(j/64) from a
 * table, e^r - 1 by its Taylor series to r^5 (the rest below 4e-17).  The
 * nearest integer to y 64/ln 2 by adding 1.5 2^52 (its low bits are then
 * the integer, two's complement).  r = y - m ln2/64 in two parts: the first
 * with 36 bits, exact times m (|m| <= 65400, 17 bits), and y less it exact
 * (they are within a factor 2: Sterbenz). */
static inline double hl_flow_exp(double y)
{
    if (!(fabs(y) <= 708)) /* also NaN; 2^n stays normal below */
        return exp(y);
    const double shift = 0x1.8p52, inv_ln2_64 = 0x1.71547652b82fep+6;
    const double ln2_64_hi = 0x1.62e42fefa0000p-7, ln2_64_lo = 0x1.cf79abc9e3b3ap-46;
    double md = y * inv_ln2_64 + shift;
    int64_t m = (int64_t)(hl_flow_bits_of(md) - hl_flow_bits_of(shift));
    md -= shift;
    double r = (y - md * ln2_64_hi) - md * ln2_64_lo, r2 = r * r;
    uint64_t top = (uint64_t)(m >> HL_FLOW_EXP_BITS) << 52; /* 2^n: added to the exponent */
    double scale =
        hl_flow_double_of(hl_flow_bits_of(hl_flow_exp_tab[m & (HL_FLOW_EXP_N - 1)]) + top);
    double em1 = r + r2 * ((0.5 + r * (1.0 / 6)) + r2 * ((1.0 / 24) + r * (1.0 / 120)));
    return scale + scale * em1;
}

#endif
