/* The arithmetic on a Taylor step's polynomials that the single (flow.c)
 * and the batch (batch.c) integrators share, so that a batch lane gives
 * the single run's bits by construction: time as a two-sum, the increment
 * of a step, the polynomial and its derivative at h. */
#ifndef HAMLIE_FLOW_POLY_H
#define HAMLIE_FLOW_POLY_H

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
 * of a step of Kepler's problem.  p >= 2. */
static inline double increment(const double *c, int p, double h, double h2)
{
    const int top_e = p & ~1, top_o = (p - 1) | 1;
    double e = c[top_e], o = top_o <= p ? c[top_o] : 0;
    for (int k = top_e - 2; k >= 2; k -= 2)
        e = e * h2 + c[k];
    for (int k = top_o - 2; k >= 1; k -= 2)
        o = o * h2 + c[k];
    return h * o + h2 * e;
}

/* z_i = sum_k c_i[k] h^k, the state c_i[0] added last: one rounding at the
 * state's scale (see advance) */
static inline void horner(double *z, const double *coef, int n, int p, double h)
{
    const int S = p + 1;
    for (int i = 0; i < n; i++)
        z[i] = coef[(size_t)i * S] + increment(coef + (size_t)i * S, p, h, h * h);
}

/* dz_i = sum_k k c_i[k] h^(k-1), the derivative of the step's polynomial */
static inline void horner_derivative(double *dz, const double *coef, int n, int p, double h)
{
    for (int i = 0; i < n; i++) {
        const double *c = coef + (size_t)i * (p + 1);
        double d = p * c[p];
        for (int k = p - 1; k >= 1; k--)
            d = d * h + k * c[k];
        dz[i] = d;
    }
}

#endif
