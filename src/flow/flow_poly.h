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

/* sum_{k>=1} c[k] h^k, h2 = h^2, as h O(h^2) + h^2 E(h^2): the odd and the
 * even coefficients by Horner in h^2, two chains of p/2 multiply-adds that
 * the processor runs side by side, where one Horner chain of p was a fifth
 * of a step of Kepler's problem.  The step is one chain of dependences
 * (state, recursion, step size, state), so that these chains' latency
 * counts, not their instructions: four sums of c[k] h^k from the powers of
 * h (one AVX2 vector, 5 % fewer instructions a step of Kepler's problem)
 * took 9 % longer on the pendulum, for the powers and the sums' reduction
 * lengthen the chain.  p >= 2. */
HL_FLOW_INLINE double increment(const double *c, int p, double h, double h2)
{
    const int top_e = p & ~1, top_o = (p - 1) | 1;
    double e = c[top_e], o = top_o <= p ? c[top_o] : 0;
    for (int k = top_e - 2; k >= 2; k -= 2)
        e = fma(e, h2, c[k]);
    for (int k = top_o - 2; k >= 1; k -= 2)
        o = fma(o, h2, c[k]);
    return fma(h, o, h2 * e);
}

/* z_i = sum_k c_i[k] h^k, the state c_i[0] added last: one rounding at the
 * state's scale (see advance) */
HL_FLOW_INLINE void horner(double *z, const double *coef, int n, int p, double h)
{
    const int S = p + 1;
    for (int i = 0; i < n; i++)
        z[i] = coef[(size_t)i * S] + increment(coef + (size_t)i * S, p, h, h * h);
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
static HL_FLOW_VEC __attribute__((unused)) void horner_vec(double *z, const double *coef, int n,
                                                           int p, double h)
{
    horner(z, coef, n, p, h);
}
static __attribute__((unused)) void horner_plain(double *z, const double *coef, int n, int p,
                                                 double h)
{
    horner(z, coef, n, p, h);
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

/* the polynomial (or its derivative) at h, by the build vec chose */
static inline void poly_at(int vec, double *z, const double *coef, int n, int p, double h)
{
    (vec ? horner_vec : horner_plain)(z, coef, n, p, h);
}
static inline void poly_derivative_at(int vec, double *dz, const double *coef, int n, int p,
                                      double h)
{
    (vec ? horner_derivative_vec : horner_derivative_plain)(dz, coef, n, p, h);
}

#endif
