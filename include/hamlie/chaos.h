/* hamlie — chaos indicators of one orbit: MEGNO, the fast Lyapunov
 * indicator and the maximal Lyapunov exponent.
 *
 * Along an orbit z(t) of z' = f(z) = J grad H, a tangent vector delta obeys
 * the variational equations delta' = Df(z) delta.  With
 * r(s) = delta . delta' / delta . delta (= d/ds log |delta|):
 *
 *   MEGNO (Cincotta & Simo 2000)  Y(t)   = (2/t) int_0^t s r(s) ds
 *                                  <Y>(t) = (1/t) int_0^t Y(s) ds
 *   mLCE estimate                  (1/t) log(|delta(t)| / |delta(0)|)
 *   FLI (Froeschle et al. 1997)    sup_{s <= t} log(|delta(s)| / |delta(0)|)
 *
 * <Y> -> 0 for isochronous orbits (harmonic oscillators), -> 2 for
 * quasi-periodic ones, and grows like lambda t / 2 for chaotic ones
 * (lambda the maximal Lyapunov exponent).
 *
 * The variational equations are differentiated symbolically from H
 * (hl_expr_diff) and integrated with the orbit and the two integrals of
 * MEGNO as one ODE by the Taylor integrator (flow.h), so all of them are
 * computed to the integrator's tolerance.  delta is renormalised to length 1
 * at checkpoints (the log of each factor is summed), so an exponent of any
 * size does not overflow; the FLI's sup is taken over those checkpoints.
 *
 * An hl_chaos is built once per system (its tapes compiled once) and runs
 * any number of orbits; it borrows the system (which must outlive it) and
 * is used by one thread at a time: build one per thread.
 */
#ifndef HAMLIE_CHAOS_H
#define HAMLIE_CHAOS_H

#include "hamlie/error.h"
#include "hamlie/ham.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_chaos hl_chaos;

/* The indicators at time t (an output time, or where a run stopped). */
typedef struct hl_chaos_result {
    double t;
    double megno;      /* Y(t) */
    double megno_mean; /* <Y>(t) */
    double fli;        /* sup of log(|delta| / |delta0|) over the checkpoints */
    double mlce;       /* log(|delta(t)| / |delta0|) / t (0 at t = 0) */
    long nsteps;       /* Taylor steps so far */
    hl_status status;  /* HL_OK, or why the run stopped (t is where) */
} hl_chaos_result;

/* Build for sys (which needs H and numeric values for all its parameters)
 * with the Taylor integrator's tolerance tol (absolute and relative,
 * >= HL_FLOW_MIN_RTOL).  HL_EINVAL without H, with a symbolic parameter
 * (named), or a tolerance out of range. */
hl_status hl_chaos_new(hl_chaos **out, hl_system *sys, double tol, hl_error *err);
void hl_chaos_free(hl_chaos *chaos); /* NULL is a no-op */

/* Called at each output time; a non-zero return stops the run (HL_ESTOP). */
typedef int (*hl_chaos_fn)(const hl_chaos_result *r, const double *z, void *arg);

/* Run one orbit from z0 (2N values: q then p) with the tangent vector delta0
 * (2N values, not all 0; NULL: a fixed generic direction) from t = 0 to
 * t_end > 0.  With every > 0, fn (may be NULL) is called at every multiple
 * of every below t_end and at t_end.  res (may be NULL) gets the
 * indicators at t_end, or where the run stopped, with the status.  Errors:
 * HL_EINVAL for delta0 = 0, a t_end or every not positive and finite, a z0
 * not finite; HL_EDOM / HL_ENOCONV from the integrator (blow-up) with the
 * time. */
hl_status hl_chaos_run(hl_chaos *chaos, const double *z0, const double *delta0, double t_end,
                       double every, hl_chaos_fn fn, void *arg, hl_chaos_result *res,
                       hl_error *err);

/* fn(t, t_end, arg) (error.h's hl_progress_fn) is called between two
 * chunks of a run (about once per e-fold of |delta|, at most every 64 time
 * units): a non-zero return stops the run with HL_ESTOP ("interrupted at
 * t = .."), res holding the indicators there.  Chunks restart the
 * integrator anyway, so the callback changes no bit of the results.  NULL
 * (the default): none. */
void hl_chaos_set_progress(hl_chaos *chaos, hl_progress_fn fn, void *arg);

#ifdef __cplusplus
}
#endif

#endif
