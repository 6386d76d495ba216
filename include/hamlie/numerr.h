/* hamlie — numeric error analysis at a point (issue 5, part 5).
 *
 * The error fields v_k (psi_D(z) - exp(D g)(z) = sum_k D^k/k! v_k(z)) and the
 * Taylor coefficients of K(D) = (d/dD psi_D)(psi_{-D}(z)) evaluated at one
 * point z in double precision, without any symbolic expansion: the scheme's
 * equations (expression DAGs) are evaluated in truncated power series in D
 * with double coefficients, implicit schemes solved order by order, and the
 * exact flow's coefficients g^k z / k! come from Taylor mode on the
 * Hamiltonian vector field's tape.  The method is described in
 * src/analysis/numeric.c.
 */
#ifndef HAMLIE_NUMERR_H
#define HAMLIE_NUMERR_H

#include "hamlie/error.h"
#include "hamlie/scheme.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_NUMERR_MAX_ORDER 60

/* The round-off threshold: v_k counts as non-zero when
 * |v_k(z)|_inf > HL_NUMERR_REL_TOL * k! * max_i(|psi_k,i| + |g^k z_i / k!|, 1e-300):
 * v_k is k! times a difference of two coefficients of that size, each
 * computed with a relative error of a few hundred ulps at most. */
#define HL_NUMERR_REL_TOL 1e-10

typedef struct hl_numerr {
    int N, n;        /* dof; v_k for k = 2..n, K to D^(n-1) */
    double *psi;     /* psi[k*2N + i]: [D^k] psi_D(z)_i, k = 0..n */
    double *flow;    /* flow[k*2N + i] = (g^k z_i)/k!, k = 0..n */
    double *v;       /* v[k*2N + i] = k! (psi - flow), k = 0..n (0 for k < 2) */
    double *K;       /* K[k*2N + i] = [D^k] K(D)_i, k = 0..n-1 */
    double *vnorm;   /* |v_k|_inf, k = 0..n */
    double *thresh;  /* the round-off threshold for v_k, k = 0..n */
    int leading;     /* least k >= 2 with vnorm[k] > thresh[k], 0 if none */
    int order;       /* leading - 1, or n when none */
} hl_numerr;

/* z: 2N values (q_1..q_N, p_1..p_N).  2 <= n <= HL_NUMERR_MAX_ORDER.  The
 * scheme's system must have H, every parameter a value.  HL_EDOM when a
 * value is not finite or a division meets a series vanishing at D = 0 that
 * the numerator does not cancel; HL_ENOCONV when an implicit scheme's linear
 * system at some order is singular at z.  Fills r (hl_numerr_clear after,
 * also on failure). */
hl_status hl_numerr_compute(hl_numerr *r, const hl_scheme *s, const double *z, int n,
                            hl_error *err);
void hl_numerr_clear(hl_numerr *r);

/* The same analysis for a stepper that is not a scheme of the scheme
 * language but gives its own series at z: psi[k*2N + i] = [D^k] psi_D(z)_i,
 * k = 0..n (e.g. hl_exact_flow_series).  The flow's coefficients, v_k,
 * leading and order as hl_numerr_compute's, except the thresholds: such a
 * series is not exact where a coefficient vanishes at z by symmetry, so
 * the size of order k in the threshold is at least the upper concave hull
 * of log max_i(|psi_k,i| + |flow_k,i|) over k = 0..n (the same where that
 * is concave in k, as for geometric or factorial decay).  K needs the
 * stepper at points other than z and is not computed: r->K is NaN. */
hl_status hl_numerr_from_series(hl_numerr *r, hl_system *sys, const double *z, const double *psi,
                                int n, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
