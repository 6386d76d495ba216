/* hamlie — events: where a trajectory crosses a surface g(z) = 0.
 *
 * The surface is a tape g with n inputs (the state, q then p) and one
 * output; a direction says which crossings count:
 *   HL_EVENT_UP    g goes from < 0 to >= 0 (as the integration proceeds),
 *   HL_EVENT_DOWN  g goes from > 0 to <= 0,
 *   HL_EVENT_BOTH  either.
 * A state exactly on the surface (g = 0) at the start of an interval is not
 * a crossing: a run that starts on its section does not record its start,
 * and a crossing that lands exactly at a step's end is counted once.
 *
 * Location.  Between two states known at times 0 and h, the state is a
 * continuous function of tau (an interpolant).  On a Taylor step the roots
 * of g are isolated on g's own series along the step
 * (hl_event_first_taylor), so that crossings close together are found; on
 * other interpolants g is sampled at HL_EVENT_SAMPLES equal sub-intervals
 * (NOTE: there two crossings closer than h / HL_EVENT_SAMPLES cancel and
 * are missed).  A sign change is narrowed by the Illinois variant of false position, with a
 * bisection whenever false position stalls, until the bracket is one
 * rounding of tau wide or g is exactly 0: the crossing is located to
 * round-off ON THE INTERPOLANT.  The interpolants:
 *   - the Taylor integrator (flow.h, hl_flow_set_event): the step's own
 *     polynomial (dense output), valid to the integrator's tolerance over
 *     the whole step;
 *   - fixed-step schemes (hl_event_hermite): the cubic Hermite interpolant
 *     from the states and the vector field at both ends of a step; its
 *     error against the flow through the step's start is O(dt^4) (order 4
 *     local, HL_EVENT_HERMITE_ORDER), on top of the scheme's own error.
 *
 * An event borrows its tape (which must outlive it) and uses the tape's
 * scratch: one thread per event.
 */
#ifndef HAMLIE_EVENT_H
#define HAMLIE_EVENT_H

#include "hamlie/error.h"
#include "hamlie/tape.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hl_event_dir { HL_EVENT_DOWN = -1, HL_EVENT_BOTH = 0, HL_EVENT_UP = 1 } hl_event_dir;

#define HL_EVENT_SAMPLES 4
#define HL_EVENT_HERMITE_ORDER 4

typedef struct hl_event hl_event;

/* g: n inputs, one output.  HL_EINVAL otherwise, or for a direction that is
 * not one of the three. */
hl_status hl_event_new(hl_event **out, hl_tape *g, hl_event_dir dir, hl_error *err);
void hl_event_free(hl_event *ev); /* NULL is a no-op */

int hl_event_dim(const hl_event *ev); /* n */
hl_event_dir hl_event_direction(const hl_event *ev);

/* g(z) */
double hl_event_value(hl_event *ev, const double *z);

/* Does g going from ga to gb count as a crossing (see above)? */
int hl_event_crosses(const hl_event *ev, double ga, double gb);

/* The state at tau in [0, h] of an interpolant: z[0..n-1]. */
typedef void (*hl_event_state_fn)(double *z, double tau, void *arg);

/* The first crossing in (a, b] of g along state(tau), given ga = g at a:
 * 1 with *tau and z (the state there, on the side of the surface the
 * crossing goes to: g(z) >= 0 going up), 0 if there is none. */
int hl_event_first(hl_event *ev, hl_event_state_fn state, void *arg, double a, double b, double ga,
                   double *tau, double *z);

/* Declare g affine, g(z) = g0 + grad . z (n values, copied), as the caller
 * knows from its formula (a section q_j = c): hl_event_first_taylor then
 * takes g's series along a step from the state's directly, without a
 * Taylor-mode pass over the tape (most of the cost of a cheap surface). */
void hl_event_set_affine(hl_event *ev, const double *grad, double g0);

/* The first crossing in (a, h] of g along a Taylor step: the state is the
 * polynomial z_i(u) = sum_k coef[i (p+1) + k] u^k at u = dir tau (tau in
 * [0, h], dir = +-1 the direction of integration), and state(z, tau, arg)
 * evaluates it.  The roots are isolated on g's own Taylor series along the
 * step (g composed with the polynomial by the tape's Taylor mode, as
 * heyoka does): Descartes' rule of signs on (0, 1) after a Moebius map,
 * bisecting while it counts two or more, so that crossings close together
 * are not missed; each isolated root of the right direction is then
 * narrowed on g of the state as hl_event_first.  As hl_event_first
 * otherwise (ga = g at a). */
int hl_event_first_taylor(hl_event *ev, const double *coef, int p, double dir, double h,
                          hl_event_state_fn state, void *arg, double a, double ga, double *tau,
                          double *z);

/* The cubic Hermite interpolant of a step of length dt from (z0, f0 = the
 * vector field at z0) to (z1, f1): the first crossing in (a, dt], as
 * hl_event_first (ga = g at a: g(z0) for a = 0; the state at tau = dt is
 * z1 exactly). */
int hl_event_hermite(hl_event *ev, const double *z0, const double *f0, const double *z1,
                     const double *f1, double dt, double a, double ga, double *tau, double *z);

#ifdef __cplusplus
}
#endif

#endif
