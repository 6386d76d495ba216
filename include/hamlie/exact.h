/* hamlie — exact schemes for integrable systems (§3 of the paper).
 *
 * An exact scheme maps z to the flow exp(D g) z for every step D, so it has
 * no discretization error at all.  Two numeric constructions:
 *
 *   quadratic H (any N):  z' = A z + b with A = J Hess(H), b = J grad H(0)
 *                         constant; the step is the matrix exponential of
 *                         [[A, b], [0, 0]] times dt, computed with Arb
 *                         (arb_mat_exp, 128 bits) and rounded to double.
 *   1 dof:                the orbit through z is tabulated once over one
 *                         period T (Taylor polynomials of the flow at
 *                         samples, see flow.c); a step finds the time
 *                         t(q,p) since the table's start (the angle is
 *                         2 pi t / T), advances it by dt mod T and maps
 *                         back.  The orbit is found by following the flow
 *                         from z: a libration (bounded, in the well z is
 *                         in) between the turning points on either side of
 *                         z; a rotation when H is 2 pi-periodic in q and q
 *                         advances by 2 pi without turning (q then grows
 *                         by 2 pi a period); the table is rebuilt when z is
 *                         not on the current one, to rounding of the
 *                         orbit's own size (so tiny orbits are told apart).
 *                         An equilibrium (grad H = 0) stays where it is;
 *                         an orbit so small that the vector field is linear
 *                         to rounding over it follows the linearised flow,
 *                         the limit of small orbits.
 *
 * Requirements of the 1-dof construction: H(q,p) = H(q,-p) (time-reversal
 * symmetric, true for p^2/2m + V(q)).  Refused with HL_EDOM naming the
 * reason: unbounded orbits (an escape over a Morse well), and the
 * separatrix — an orbit whose energy is within rounding (2^-40 of the
 * orbit's energy scale) of an unstable equilibrium's, where the period is
 * infinite or cannot be told from rounding.  Near it (the pendulum from
 * q = 3.14, or p = 1.99 at q = 0) the orbits are computed, their long
 * periods included.
 */
#ifndef HAMLIE_EXACT_H
#define HAMLIE_EXACT_H

#include <arb.h>

#include "hamlie/error.h"
#include "hamlie/alg.h"
#include "hamlie/ham.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The closed form for a quadratic H is the scheme layer's
 * hl_scheme_linear_flow (scheme.h): the catalog's "exact". */

/* ---- a user's action-angle map (1 dof) ---------------------------------- */

/* "theta = f(q,p); I = g(q,p); q = r(theta,I); p = s(theta,I); nu = n(I)"
 * (the coordinate and momentum under their own names).  Borrowed from the
 * system's pool. */
typedef struct hl_exact_aa {
    const hl_expr *theta, *I, *q, *p, *nu;
} hl_exact_aa;

hl_status hl_exact_aa_read(hl_exact_aa *aa, hl_system *sys, const char *spec, hl_error *err);

/* *ok = 0 and why = the first failing condition of: {theta, I} = 1;
 * {I, H} = 0; {theta, H} = nu(I); q, p the inverse (numerically at points in
 * all four quadrants and on the axes: an angle atan(q/p) fails for p < 0,
 * atan2(q, p) holds everywhere). */
hl_status hl_exact_aa_verify(int *ok, char *why, size_t whylen, const hl_exact_aa *aa,
                             hl_system *sys, hl_error *err);

/* The exact scheme Q = r(theta(q,p) + nu D, I(q,p)), P = s(...), unsimplified. */
hl_status hl_exact_aa_scheme(hl_alg *images, const hl_exact_aa *aa, hl_system *sys, hl_error *err);

/* ---- numeric exact flow ------------------------------------------------ */

typedef struct hl_exact_flow hl_exact_flow;

/* quadratic H: exp(D A); otherwise 1 dof: quadrature along the orbit.
 * Symbolic parameters must have values.  HL_EUNSUP for N > 1 non-quadratic. */
hl_status hl_exact_flow_new(hl_exact_flow **out, hl_system *sys, hl_error *err);
void hl_exact_flow_free(hl_exact_flow *f); /* NULL is a no-op */

/* z (2N) advanced in place by dt (any sign); flow is an hl_exact_flow.
 * Nonzero on failure (unbounded orbit, separatrix), z unchanged. */
hl_status hl_exact_flow_step(double *z, double dt, void *flow, hl_error *err);

/* The Taylor coefficients in D of the exact step at z, as the scheme builds
 * the step: coef[k*2N + i] = [D^k] psi_D(z)_i, k = 0..n.
 *
 * 1 dof: the step is a time shift along the tabulated orbit, psi_D(z) =
 * P(s + D) with P the table's polynomial piece (degree
 * HL_EXACT_SERIES_DEGREE in time, centred at a sample) holding z's time
 * t(z) and s the offset of t(z) in it, so the series is P re-expanded at s:
 * [D^k] = sum_{j>=k} binom(j,k) c_j s^(j-k).  It is not Taylor mode at z:
 * compared with the flow's series at z it checks the action-angle map (z's
 * time on the table) and the table's pieces at every order.  n is at most
 * HL_EXACT_SERIES_DEGREE (HL_EUNSUP beyond: the pieces stop there), and
 * coefficient k carries the piece's truncation, which grows with k: within
 * about 1e-13 relative of the flow's for k <= HL_EXACT_SERIES_ACCURATE,
 * up to 1e-11 at k = 9, 5e-9 at k = 10, 2e-7 at k = 12, O(1) near the
 * degree (measured at 2000 points along orbits of the pendulum, Morse and
 * quartic oscillators of several energies; hl_numerr_from_series's |v_k|
 * stays below 2e-4 of its threshold to k = 8, 0.04 to k = 9, and exceeds
 * it at some points at k = 10.  The ratio of the sample spacing to the
 * radius of convergence is fixed by the table's step rule, so this does
 * not depend on the energy.)  The map itself is right to round-off for
 * every step: only its high derivatives in D show the pieces.
 *
 * Quadratic H: (A^k (z, 1))/k! of the augmented matrix, any n.  Errors as
 * hl_exact_flow_step's. */
#define HL_EXACT_SERIES_DEGREE 20
#define HL_EXACT_SERIES_ACCURATE 8
hl_status hl_exact_flow_series(double *coef, const double *z, int n, hl_exact_flow *f,
                               hl_error *err);

/* 1 if the flow is the linear (matrix exponential) kind. */
int hl_exact_flow_is_linear(const hl_exact_flow *f);

/* Period T of the orbit through z (1-dof kind; the quadratic kind gives
 * HL_EUNSUP): a rotation's is the time q takes to advance by 2 pi; at a
 * stable equilibrium (and on the orbits small enough for the linearised
 * flow), the limit of small orbits 2 pi / omega; at an unstable one,
 * +inf.  Builds the orbit table for that orbit. */
hl_status hl_exact_flow_period(double *T, const double *z, hl_exact_flow *f, hl_error *err);

/* ---- the 1-dof exact scheme in high precision --------------------------
 * The period T of the orbit through z in Arb at about `digits` digits
 * (16..1000), and z advanced by dt of any size in the time of less than a
 * period: psi_dt(z) = the Arb Taylor integrator (flow.h) over dt mod T (on
 * a rotation, plus 2 pi for each period in dt).  T comes from Newton's
 * method on the turning point (H(q,0) = E) and on p(T/2) = 0 for a
 * libration, on q(T) = q + 2 pi for a rotation, started from the double
 * exact flow's orbit (flow.c), and is kept for the energy of the last
 * point.  The digits the orbit's small size takes away from absolute
 * tolerances and from E - H(q,0) are added.  An equilibrium stays, its
 * period the limit of small orbits (as hl_exact_flow_period).  Multiprecision floating point,
 * not validated enclosures (as flow.h's Arb integrator).  HL_EUNSUP for
 * N > 1 or a quadratic H (its exact scheme is a closed form); errors of the
 * orbit as hl_exact_flow_step's. */
typedef struct hl_exact_arb hl_exact_arb;

hl_status hl_exact_arb_new(hl_exact_arb **out, hl_system *sys, double digits, hl_error *err);
void hl_exact_arb_free(hl_exact_arb *f); /* NULL is a no-op */
hl_status hl_exact_arb_period(arb_t T, arb_srcptr z, hl_exact_arb *f, hl_error *err);
hl_status hl_exact_arb_step(arb_ptr z, const arb_t dt, hl_exact_arb *f, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
