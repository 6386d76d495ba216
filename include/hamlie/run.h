/* hamlie — running a scheme: fixed-step trajectories, observers, errors
 * against a reference, observed orders (in the spirit of GSL's odeiv2
 * drivers: the caller owns the state, a callback receives each row).
 *
 *   hl_run *r;
 *   hl_run_new(&r, sys, scheme, err);            // scheme NULL: adaptive Taylor
 *   hl_run_observe(r, "x/p", err);                // any number of observers
 *   hl_run_init_values(z0, sys, "x=1,p=0", err);  // every q_j and p_j named once
 *   hl_run_fixed(r, z0, 0.1, 20, 1, row_fn, arg, &stats, err);
 *   hl_run_free(r);
 *
 * A fixed-step run takes n = t/dt steps of the scheme's numeric stepper
 * (scheme.h) from z0, at t_k = k*dt (computed, not accumulated).  n must be
 * within 1e-9 of an integer ("t = 20 is not reachable with dt = 0.3: 66.67
 * steps"); dt must be positive and finite.  Each row carries t, the state,
 * H, the observers, and sigma = |z_k - z(t_k)|_2^2 where z(t) is the
 * reference trajectory: the Taylor integrator of flow.h (tolerance ref_tol,
 * default 1e-15, absolute and relative) evaluated by dense output exactly at
 * every t_k, without changing its own steps.  Rows are delivered for k = 0,
 * every `every`-th k, and the last step; the statistics (max |H - H0|, max
 * error) are taken over every step.
 *
 * Failures stop the run and are reported with the step and the time: a
 * state that is not finite (HL_EDOM, "blow-up"), a Newton iteration that
 * does not converge (HL_ENOCONV, the stepper's message), a reference that
 * cannot be integrated (the message says it is the reference).  The rows
 * delivered before the failure are valid; stats describe the last good
 * step.  A non-zero return of the callback stops the run and is returned.
 *
 * The adaptive run (scheme NULL) is the Taylor integrator itself at
 * tolerance tol, with rows by dense output at t_k = k*dt (dt is then only
 * the output spacing; sigma is not defined and reported as NaN).
 */
#ifndef HAMLIE_RUN_H
#define HAMLIE_RUN_H

#include <arb.h>

#include "hamlie/error.h"
#include "hamlie/event.h"
#include "hamlie/ham.h"
#include "hamlie/scheme.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_run hl_run;

/* sys and scheme are borrowed (they must outlive the run; scheme NULL for
 * the adaptive Taylor integrator).  Each fixed-step run after the first
 * builds a fresh stepper, so that the step numbers in its messages count
 * from the start of that run.
 * HL_EINVAL for a system without H or with parameters that have no value. */
hl_status hl_run_new(hl_run **out, hl_system *sys, const hl_scheme *scheme, hl_error *err);
void hl_run_free(hl_run *r); /* NULL is a no-op */

/* A run of a stepper that the scheme language does not state (the exact
 * schemes of exact.h, computed by quadrature; a caller's own): step
 * advances z (2N values, q then p) in place by dt and returns nonzero on
 * failure, leaving z as it was and err set.  Everything else — rows, H,
 * observers, sigma against the reference, orders, failures with the step
 * and time — as for a scheme (hl_run_fixed; hl_run_adaptive is not for
 * it).  arg is borrowed. */
typedef hl_status (*hl_run_step_fn)(double *z, double dt, void *arg, hl_error *err);
hl_status hl_run_new_stepper(hl_run **out, hl_system *sys, hl_run_step_fn step, void *arg,
                             hl_error *err);

/* Add an observer: a formula in the system's variables, its parameters and
 * H.  Errors point into formula. */
hl_status hl_run_observe(hl_run *r, const char *formula, hl_error *err);
int hl_run_nobservers(const hl_run *r);

/* The reference trajectory: on (default) or off, and its tolerance
 * (default 1e-15; > 0). */
void hl_run_set_reference(hl_run *r, int on, double tol);

/* Off by default: for a fixed-step run of at least 200000 steps, compile
 * H and the observers to machine code first (hl_tape_jit, tape.h: same
 * results bit for bit, 10-20 ms of compilation; libgccjit's own
 * allocations show as leaks under LeakSanitizer). */
void hl_run_set_jit(hl_run *r, int on);

/* A progress callback (error.h), or NULL: called with the steps done and
 * asked (every 1024 steps of a fixed-step run, or when its compiled loop
 * reaches a row or 65536 steps; for an adaptive run at every output row
 * and, between rows, every ~1024 Taylor steps with a fraction of a row —
 * the integrator then restarts there, which changes the last bits of the
 * rows against a run without a callback); when it returns non-zero the run
 * stops: the rows delivered and the statistics describe the last step (or
 * row) done, and the run returns HL_ESTOP ("stopped at step k of n"). */
void hl_run_set_progress(hl_run *r, hl_progress_fn fn, void *arg);

/* z[0..2N-1] (q then p) from "x=1,p=0" (values are formulas in numbers,
 * pi and set parameters: "q=pi/2").  Every variable must be given exactly
 * once: a missing one is named.  A value that is not finite, or that
 * underflows in double (1e-400, below DBL_MIN but not 0), is refused
 * (HL_EDOM), the error pointing at it in init. */
hl_status hl_run_init_values(double *z, hl_system *sys, const char *init, hl_error *err);

/* The same in Arb at prec bits, from the exact form of each formula. */
hl_status hl_run_init_values_arb(arb_ptr z, hl_system *sys, const char *init, slong prec,
                                 hl_error *err);

/* Is the initial point in H's domain?  HL_EDOM, with the point, when H is
 * not finite there (Kepler at the origin, log(q) at q < 0); the drivers
 * check it before their first row, and a caller that writes anything
 * before the run (a header) checks it first.  The observers may have poles
 * (x/p at p = 0): they are not checked. */
hl_status hl_run_check_start(hl_run *r, const double *z0, hl_error *err);
hl_status hl_run_check_start_arb(hl_run *r, arb_srcptr z0, slong prec, hl_error *err);

/* The number of steps t/dt, with the checks above. */
hl_status hl_run_nsteps(long *n, double dt, double t, hl_error *err);

typedef struct hl_run_row {
    long k;            /* step index */
    double t;          /* k * dt */
    const double *z;   /* 2N values: q then p */
    double H;
    const double *obs; /* the observers' values, in the order added */
    double sigma;      /* |z_k - z(t_k)|^2, NaN without a reference */
    const double *ref; /* z(t_k) (2N values), or NULL */
} hl_run_row;

typedef int (*hl_run_fn)(const hl_run_row *row, void *arg);

typedef struct hl_run_stats {
    long steps;      /* steps completed */
    long nsteps;     /* steps asked for */
    long rows;       /* rows delivered */
    double t;        /* time of the last good step */
    double H0, H;    /* at t = 0 and at t */
    double max_dH;   /* max over steps of |H_k - H0| */
    double sigma;    /* at t (NaN without a reference) */
    double max_err;  /* max over steps of |z_k - z(t_k)|_2 (NaN without one) */
    double err_final;/* |z_n - z(t_n)|_2 at t */
    long ref_steps;  /* steps of the reference integrator */
    int failed;      /* the run stopped on an error */
    long crossings;  /* events found (hl_run_event) */
    double t_crossing; /* the time of the last one (0 if none) */
    int event_stop;  /* the run stopped after hl_run_event's stop_after */
} hl_run_stats;

/* ---- events (event.h) ------------------------------------------------------
 * A surface given as text: "g" (the surface g = 0) or "lhs = rhs" (g = lhs -
 * rhs), a formula in the variables, H, and the parameters with values.
 * hl_run_surface reads it (errors point into the text: a parse error, an
 * unknown symbol, a g that does not depend on the state); var is the index
 * (q_1..q_N, p_1..p_N) of the variable when the surface is "variable =
 * constant" (x = 0, 0 = x), else -1, and value the constant. */
typedef struct hl_run_surface_info {
    const hl_expr *g;
    int var;
    double value;
} hl_run_surface_info;

hl_status hl_run_surface(hl_run_surface_info *out, hl_system *sys, const char *surface,
                         hl_error *err);

typedef struct hl_run_crossing {
    long i;          /* 0, 1, ... in the order of time */
    double t;
    const double *z; /* 2N: the state at the crossing */
    double H;
} hl_run_crossing;

typedef int (*hl_run_crossing_fn)(const hl_run_crossing *c, void *arg);

/* From now on the runs of r deliver the crossings of the surface in the
 * direction dir to fn (NULL: only counted), before the row that follows
 * them.  The adaptive run finds them on the Taylor step's own polynomial,
 * to round-off (hl_run_event_order 0); a fixed-step run on the cubic
 * Hermite interpolant of each step, from the states and the exact vector
 * field at its ends (order 4 local: hl_run_event_order 4), which adds its
 * O(dt^4) to the scheme's own error.  After stop_after crossings (0:
 * never) the run stops and returns HL_OK with stats->event_stop set (its
 * rows and statistics up to the step or row before the last crossing,
 * t_crossing its time); a non-zero return of fn stops the run and is
 * returned.  A fixed-step run with events does not take the compiled
 * fused loop.  Not for the Arb run (HL_EUNSUP). */
hl_status hl_run_event(hl_run *r, const char *surface, hl_event_dir dir, long stop_after,
                       hl_run_crossing_fn fn, void *arg, hl_error *err);

/* 0: crossings on the Taylor polynomial (to round-off); 4: the Hermite
 * cubic's local order for a fixed-step run. */
int hl_run_event_order(const hl_run *r);

/* z0: 2N values (not modified).  stats may be NULL; its z is the run's
 * (hl_run_state). */
hl_status hl_run_fixed(hl_run *r, const double *z0, double dt, double t, long every, hl_run_fn fn,
                       void *arg, hl_run_stats *stats, hl_error *err);

/* ---- many members at once: fixed-step runs in SIMD lanes -------------------
 * The same fixed-step run from B starting points (heyoka's batch mode for
 * the compiled fixed-step loop): member i from z0[i*2N .. i*2N + 2N-1] ends
 * as hl_run_fixed(r, z0_i, dt, t, 1, NULL, NULL, &stats[i], &errs[i]) would
 * take it alone — the same status, message, statistics (max |H - H0| over
 * every step, H at the end) and final state (hl_run_state), to the last bit
 * — with that state in z[i*2N ..] (z may be z0).  Where it pays, `lanes`
 * members step side by side in the SIMD lanes of one compiled loop
 * (tape.h, hl_tape_iter_batch: the explicit step fused with H, as in
 * hl_run_fixed's own fast path): for an explicit scheme, with machine code
 * on (hl_run_set_jit), no reference, events or progress callback, and B *
 * n member-steps enough to repay the loop's compilation (hl_tape_compile_
 * pays; the code is kept in r and in the disk cache).  A lane whose member
 * is done takes the next; a member whose step or H stops being finite
 * leaves its lane and is run again alone by hl_run_fixed, so that its
 * failure reads as there (step, time, message), and the others go on.
 * Otherwise (implicit schemes: Newton's iterations differ from member to
 * member, see docs/sweep.md; without libgccjit; short runs) the members go
 * through hl_run_fixed one after the other, with the same results.
 * stats (B values, may be NULL): a member that cannot start
 * (hl_run_check_start) has them zeroed.  errs (B values, may be NULL):
 * cleared on success.  Returns HL_OK if every member succeeded, else the
 * first failing member's status, err naming it ("member 3: blow-up: ...");
 * the others went on either way.  dt and t as hl_run_fixed (an error there
 * is every member's).  One thread per run, as always. */
hl_status hl_run_fixed_batch(hl_run *r, long B, const double *z0, double dt, double t, double *z,
                             hl_run_stats *stats, hl_status *status, hl_error *errs, hl_error *err);

/* The lanes of hl_run_fixed_batch: 0 for the default (the machine's vector
 * width, hl_tape_lanes_native: 4 with AVX2, 8 with AVX-512), 1 for one
 * member at a time, else a power of 2 up to HL_TAPE_BATCH_MAX_LANES
 * (HL_EINVAL otherwise).  The results do not depend on it. */
hl_status hl_run_set_lanes(hl_run *r, int lanes, hl_error *err);

/* The lanes that hl_run_fixed_batch would use for B members over (dt, t):
 * 1 when they would run one at a time.  Compiles the loop if it would. */
int hl_run_batch_lanes(hl_run *r, long B, double dt, double t);

/* The adaptive Taylor integrator, rows at k*dt (see above). */
hl_status hl_run_adaptive(hl_run *r, const double *z0, double tol, double dt, double t, long every,
                          hl_run_fn fn, void *arg, hl_run_stats *stats, hl_error *err);

/* ---- many adaptive runs side by side (flow.h's batch) ----------------------
 * hl_run_adaptive for B members of one run (its system; no scheme, events
 * or progress callback) at once, their Taylor steps in `lanes` SIMD lanes:
 * each member's stats, status, message and state at the last row are its
 * own hl_run_adaptive's (no rows delivered), bit for bit.  The lanes
 * borrow r (and its scratch: one thread).  Compiling the lanes' recursion
 * costs about a second unless the disk cache holds it: ask
 * hl_run_lanes_pay first. */
typedef struct hl_run_lanes hl_run_lanes;
/* 1 if `members` members to t in `lanes` lanes repay the lanes' compiled
 * code (kept in the disk cache, or compiled), their steps foreseen from
 * the first step at z0 (tape.h's cost model: counts, not clocks). */
int hl_run_lanes_pay(hl_run *r, double tol, int lanes, long members, const double *z0, double t);
hl_status hl_run_lanes_new(hl_run_lanes **out, hl_run *r, double tol, int lanes, hl_error *err);
void hl_run_lanes_free(hl_run_lanes *lanes);          /* NULL is a no-op */
int hl_run_lanes_compiled(const hl_run_lanes *lanes); /* 0: the lanes run one by one */
/* z0, z: B * 2N (z: each member's state at its last row, as hl_run_state);
 * dt: B output spacings; stats, status, errs: B each.  Returns the first
 * failing member's status, or HL_OK. */
hl_status hl_run_adaptive_lanes(hl_run_lanes *lanes, int B, const double *z0, const double *dt,
                                double t, double *z, hl_run_stats *stats, hl_status *status,
                                hl_error *errs);

/* ---- Arb: the adaptive run at about `digits` decimal digits --------------
 * hl_flow_arb (flow.h) with rows at t_k = T k / n (T from its text, exact
 * when it is a decimal), H and the observers evaluated in Arb.  Values are
 * midpoints (no error bound).  stats: max_dH and H as doubles. */
typedef struct hl_run_row_arb {
    long k;
    const arb_struct *t;
    arb_srcptr z;       /* 2N */
    const arb_struct *H;
    arb_srcptr obs;
} hl_run_row_arb;

typedef int (*hl_run_arb_fn)(const hl_run_row_arb *row, void *arg);

hl_status hl_run_adaptive_arb(hl_run *r, arb_srcptr z0, double digits, const char *T, long n,
                              long every, hl_run_arb_fn fn, void *arg, hl_run_stats *stats,
                              hl_error *err);

/* The working precision in bits for `digits` decimal digits (as flow.h's). */
slong hl_run_arb_prec(double digits);

/* x with 17 significant digits in the layout of printf's "%.17g" (reads
 * back as x; "inf", "-inf", "nan"; the last digit may differ from printf's
 * at a near-tie), several times faster than printf.
 * out holds at least 32 bytes; returns the length. */
int hl_run_fmt(char *out, double x);

/* The same with 15 digits when they read back as x (0.1 for 0.1), else 17:
 * for times k*dt. */
int hl_run_fmt_short(char *out, double x);

/* The state after the last hl_run_fixed / hl_run_adaptive (2N values):
 * the last good step, except after a blow-up detected in H (then the state
 * whose H is not finite). */
const double *hl_run_state(const hl_run *r);

/* Observed global order: the scheme run to t with each step dts[i]
 * (reference on), errmax[i] = max over steps of |z_k - z(t_k)|_2 (errfinal[i]
 * the same at the final time; either may be NULL), and for i >= 1
 * order[i] = log(errmax[i-1]/errmax[i]) / log(dts[i-1]/dts[i]) (order[0] = NaN). */
hl_status hl_run_orders(double *errmax, double *errfinal, double *order, hl_run *r,
                        const double *z0, const double *dts, int n, double t, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
