/* The arithmetic on a Taylor step's polynomials that the single (flow.c)
 * and the batch (batch.c) integrators share, so that a batch lane gives
 * the single run's bits by construction: time as a two-sum, the increment
 * of a step, the polynomial and its derivative at h.
 *
 * The multiply-adds are fma(): one rounding, not two, and the same
 * correctly rounded result on every machine.  Where the processor has FMA
 * the callers' hot loops are compiled twice (HL_FLOW_VEC and plain, chosen
 * by hl_flow_vec_ok): then fma() is one instruction, else a call of libm's.
 * Either way the bits are the same, and the same for every back end of the
 * recursion (interpreted or compiled), which only fill the coefficients. */
#ifndef HAMLIE_FLOW_POLY_H
#define HAMLIE_FLOW_POLY_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(__x86_64__) && defined(__GNUC__)
/* the files that use it are compiled with -ffp-contract=off
 * (CMakeLists.txt): no a * b + c but the written fma() is fused, so that
 * the two builds of a loop give the same bits */
#define HL_FLOW_VEC __attribute__((target("avx2,fma")))
static inline int hl_flow_vec_ok(void)
{
    const char *no = getenv("HAMLIE_NO_AVX2"); /* as the interpreter: for the tests */
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
           (no == NULL || no[0] == '\0' || strcmp(no, "0") == 0);
}
#else
#define HL_FLOW_VEC
static inline int hl_flow_vec_ok(void)
{
    return 0;
}
#endif

#define HL_FLOW_INLINE static inline __attribute__((always_inline))

/* Time as an unevaluated sum hi + lo (Knuth's two-sum). */
static inline void time_add(double *hi, double *lo, double h)
{
    double s = *hi + h, bv = s - *hi;
    double e = (*hi - (s - bv)) + (h - bv) + *lo;
    *hi = s + e;
    *lo = e - (*hi - s);
}

/* The room hl_flow_powers needs at order p */
#define HL_FLOW_POWERS(p) ((size_t)(p) + 8)

/* H[k] = h^k for k = 0..p (and past it, to p + 7 at most): four chains,
 * h^(k+4) = h^k h^4, that run side by side (one chain of p products was
 * as long as the step's sums); h^k carries some k/4 + 2 roundings. */
HL_FLOW_INLINE void hl_flow_powers(double *H, int p, double h)
{
    const double h2 = h * h, h4 = h2 * h2;
    H[0] = 1;
    H[1] = h;
    H[2] = h2;
    H[3] = h2 * h;
    for (int k = 4; k <= p; k += 4)
        for (int j = 0; j < 4; j++)
            H[k + j] = H[k + j - 4] * h4;
}

/* sum_{k>=1} c[k] h^k from H = hl_flow_powers(h): the orders r+1..p
 * (r = p mod 4) in four sums, one for each order mod 4, from the highest
 * order down (the smallest terms first); those added from the smallest;
 * then the orders r..1 one by one.  Where one Horner chain of p
 * multiply-adds (and then two of p/2) was the step's longest wait, the
 * four sums run side by side, in one vector where the processor has them;
 * the error is as Horner's, a few roundings of the first term.  p >= 1. */
HL_FLOW_INLINE double increment(const double *c, int p, const double *H)
{
    const int r = p % 4;
    double a[4] = {0, 0, 0, 0};
    for (int k = p - 3; k > r; k -= 4)
        for (int j = 0; j < 4; j++)
            a[j] = fma(c[k + j], H[k + j], a[j]);
    double s = ((a[3] + a[2]) + a[1]) + a[0];
    for (int k = r; k >= 1; k--)
        s = fma(c[k], H[k], s);
    return s;
}

/* z_i = sum_k c_i[k] h^k, the state c_i[0] added last: one rounding at the
 * state's scale (see advance).  H: room for hl_flow_powers. */
HL_FLOW_INLINE void horner(double *z, double *H, const double *coef, int n, int p, double h)
{
    const int S = p + 1;
    hl_flow_powers(H, p, h);
    for (int i = 0; i < n; i++)
        z[i] = coef[(size_t)i * S] + increment(coef + (size_t)i * S, p, H);
}

/* dz_i = sum_k k c_i[k] h^(k-1), the derivative of the step's polynomial */
HL_FLOW_INLINE void horner_derivative(double *dz, const double *coef, int n, int p, double h)
{
    for (int i = 0; i < n; i++) {
        const double *c = coef + (size_t)i * (p + 1);
        double d = p * c[p];
        for (int k = p - 1; k >= 1; k--)
            d = fma(d, h, k * c[k]);
        dz[i] = d;
    }
}

/* horner and horner_derivative built twice, for hl_flow_vec_ok's choice */
static HL_FLOW_VEC __attribute__((unused)) void horner_vec(double *z, double *H, const double *coef,
                                                           int n, int p, double h)
{
    horner(z, H, coef, n, p, h);
}
static __attribute__((unused)) void horner_plain(double *z, double *H, const double *coef, int n,
                                                 int p, double h)
{
    horner(z, H, coef, n, p, h);
}
static HL_FLOW_VEC __attribute__((unused)) void
horner_derivative_vec(double *dz, const double *coef, int n, int p, double h)
{
    horner_derivative(dz, coef, n, p, h);
}
static __attribute__((unused)) void horner_derivative_plain(double *dz, const double *coef, int n,
                                                            int p, double h)
{
    horner_derivative(dz, coef, n, p, h);
}

/* the polynomial (or its derivative) at h, by the build vec chose; H:
 * room for hl_flow_powers */
static inline void poly_at(int vec, double *z, double *H, const double *coef, int n, int p,
                           double h)
{
    (vec ? horner_vec : horner_plain)(z, H, coef, n, p, h);
}
static inline void poly_derivative_at(int vec, double *dz, const double *coef, int n, int p,
                                      double h)
{
    (vec ? horner_derivative_vec : horner_derivative_plain)(dz, coef, n, p, h);
}

#endif
