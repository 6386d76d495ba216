/* hamlie — the Taylor (Lie-series) integrator.
 *
 * Integrates an autonomous ODE z' = f(z) given as a square tape (n inputs,
 * n outputs; for a Hamiltonian see hl_tape_hamiltonian, then each step is a
 * numeric Lie series exp(h g) z).  Each step computes the Taylor coefficients
 * z^[0..p] at the current point (hl_tape_taylor_ode_*), picks the step from
 * them and sums the polynomial.  Order and step follow Jorba & Zou,
 * Experiment. Math. 14 (2005) 99-117, as heyoka takes them:
 *
 *   p = ceil(-ln(tol) / 2) + 1,           tol = min(atol, rtol)
 *   s = max(atol, rtol * |z|_inf) / tol   (1 in absolute mode, |z| in relative)
 *   rho = min_{k = p-1, p} (s / |z^[k]|_inf)^(1/k)   (the radius of convergence)
 *   h = rho * exp(-2) * exp(-0.7 / (p - 1))
 *
 * so that a step's last two terms are under tol s e^-2.7 and tol s e^-0.7,
 * and its truncation error about a hundredth of tol s: tol bounds a step's
 * error, not a run's (docs/tolerance.md says what a run makes of it).
 * In double at tol 1e-9 .. 1e-13 the order is raised where the tape's cost
 * model (hl_tape_taylor_step_cost) says a step of higher order is cheaper
 * per unit time, with a step whose tail past the order is a tenth of the
 * one above (src/flow/rule.c); the Arb integrator keeps the rule above.
 * The state is added to the step's increment last, its rounding carried
 * to the next step (compensated summation, reset at each evolve).
 *
 * The step is made safe where orders of the series vanish by symmetry (at
 * q = 0 in the well q^4/4 the last two can both be 0), eps = tol s: the
 * orders p-5..p-2 also bound the step, |z^[k]| h^k <= eps e^(3.5 (p-1-k)),
 * which leaves an ordinary orbit's step as it is; where they shorten it, or all of the
 * last six orders are 0, the step is checked by its defect
 * |P'(h) - f(P(h))| (P the step's polynomial) and shortened until the
 * tail it implies is under eps (so are the first step of each run or
 * evolve, and every step below order 10: tolerances above 1.5e-8).  The equilibrium, all of whose
 * orders past 0 vanish, stays put in one step.  (src/flow/flow_impl.h says why, and what it cannot
 * see.)
 *
 * Dense output: the polynomial of a step is valid over the whole step, so
 * outputs at given times are evaluated on it, without shortening steps (only
 * the last step is cut to land exactly on the final time).  Time is carried
 * in double-double, so that thousands of steps do not drift by rounding t.
 *
 * Errors name the time: a step that produces a NaN or an infinity
 * (HL_EDOM), or a step size that underflows (HL_ENOCONV).  On error z and t
 * hold the last good step.
 *
 * A flow borrows its tape (which must outlive it) and uses the tape's
 * scratch: one thread per flow and tape.  For long runs in double, compile
 * the tape's recursion first: hl_tape_native(f, hl_flow_order(flow), err)
 * (tape.h), or let the flow decide (hl_flow_native_for); the flow then runs
 * the machine code.
 */
#ifndef HAMLIE_FLOW_H
#define HAMLIE_FLOW_H

#include <arb.h>
#include <float.h>
#include "hamlie/error.h"
#include "hamlie/event.h"
#include "hamlie/tape.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- double ------------------------------------------------------------ */

typedef struct hl_flow hl_flow;

/* atol, rtol > 0, rtol >= HL_FLOW_MIN_RTOL (a quarter of double's epsilon:
 * smaller cannot be reached in double).  HL_EINVAL if the tape is not
 * square or a tolerance is out of range. */
#define HL_FLOW_MIN_RTOL (DBL_EPSILON / 4)
hl_status hl_flow_new(hl_flow **out, hl_tape *f, double atol, double rtol, hl_error *err);
void hl_flow_free(hl_flow *flow); /* NULL is a no-op */

int hl_flow_order(const hl_flow *flow);
long hl_flow_nsteps(const hl_flow *flow); /* steps taken since creation */

/* Long runs: after HL_FLOW_NATIVE_PROBE steps, if the steps foreseen to
 * t_end (the time left over the mean step so far) are enough for the
 * compilation to pay (tape.h: hl_tape_compile_pays, HL_COMPILE_TAYLOR),
 * compile the tape's recursion to machine code (hl_tape_native) and go on
 * with it.  The decision counts steps, not clocks, so a run is
 * reproducible, and the compiled recursion gives the interpreter's bits,
 * so the switch does not change the results.  A failure to compile leaves
 * the interpreter.  A recursion kept in the disk cache is loaded after
 * 100 steps, before the probe's end, when the steps foreseen at the step's
 * length then repay the load (hl_tape_compile_kept). */
#define HL_FLOW_NATIVE_PROBE 1000
void hl_flow_native_for(hl_flow *flow, double t_end);
int hl_flow_native_active(const hl_flow *flow);

/* Integrate from *t to t1 (either direction); z (n values) in and out.
 * On success *t == t1. */
hl_status hl_flow_evolve(hl_flow *flow, double *t, double t1, double *z, hl_error *err);

/* Called at each output time with the state there; a non-zero return stops
 * the run, and hl_flow_run returns that value. */
typedef int (*hl_flow_fn)(double t, const double *z, void *arg);

/* Events (event.h): from now on, hl_flow_evolve and hl_flow_run call fn at
 * each crossing of ev's surface, located on the step's own polynomial to
 * round-off, in the order of time with the output times (an output at the
 * same time first).  The steps are not shortened for it.  A non-zero
 * return stops the integration there and is returned: z and *t (evolve)
 * are then the crossing's.  ev NULL: no events.  ev is borrowed.  HL_EINVAL
 * if ev's dimension is not the flow's. */
hl_status hl_flow_set_event(hl_flow *flow, hl_event *ev, hl_flow_fn fn, void *arg, hl_error *err);

/* Start at (t0, z0) and call fn at ts[0..n-1], which must be monotone in
 * the direction of ts[n-1] - t0 (ts[0] may equal t0). */
hl_status hl_flow_run(hl_flow *flow, double t0, const double *z0, const double *ts, int n,
                      hl_flow_fn fn, void *arg, hl_error *err);

/* The same, storing out[i*dim + j] = z_j(ts[i]). */
hl_status hl_flow_eval_at(hl_flow *flow, double t0, const double *z0, const double *ts, int n,
                          double *out, hl_error *err);

/* ---- batch: many members, side by side in SIMD lanes -----------------------
 * The same integrator for B members of one system at once (heyoka's batch
 * mode): the Taylor recursions of `lanes` members run as one compiled
 * recursion over vectors (tape.h, hl_tape_batch; 4 lanes fill AVX2's
 * registers), and each lane picks its own step by the single integrator's
 * rule from its own coefficients, with its own start and end time.  Each
 * member ends exactly where hl_flow_evolve would have taken it: the same
 * steps, the same coefficients, the same bits (hl_flow_native_for's
 * choice never changes those).  A lane whose member is done, or fails,
 * takes the next member; one that blows up stops alone.  Without
 * libgccjit the lanes' recursions run one by one (the same results).
 * Compiling costs what hl_tape_native does (once per tape, order and lane
 * count; kept in the disk cache), so a batch pays for ensembles of long
 * runs.  No outputs at given times and no events: final states only.  A
 * batch borrows its tape and its scratch: one thread per batch and tape. */
typedef struct hl_flow_batch hl_flow_batch;

/* Tolerances as hl_flow_new; lanes a power of 2 up to
 * HL_TAPE_BATCH_MAX_LANES (4 for AVX2, 8 for AVX-512).  Compiles the
 * recursion (or finds it in the disk cache). */
hl_status hl_flow_batch_new(hl_flow_batch **out, hl_tape *f, double atol, double rtol, int lanes,
                            hl_error *err);
void hl_flow_batch_free(hl_flow_batch *batch); /* NULL is a no-op */
/* The probe before hl_flow_batch_new, which compiles: 1 if `members`
 * members to |t| repay the batch's compiled recursion (tape.h,
 * hl_tape_batch_pays: kept in the disk cache, or worth compiling), their
 * steps foreseen from the first step's length at z0 (one Taylor
 * recursion, interpreted).  Counts, not clocks: the same answer on every
 * machine with the same cache. */
int hl_flow_batch_pays(hl_tape *f, double atol, double rtol, int lanes, long members,
                       const double *z0, double t);
int hl_flow_batch_order(const hl_flow_batch *batch);
int hl_flow_batch_lanes(const hl_flow_batch *batch);
int hl_flow_batch_compiled(const hl_flow_batch *batch); /* 1: SIMD code, 0: lane by lane */

/* Integrate member i (i < B, any B >= 0) from t[i] to t1[i] (either
 * direction): z[i*n .. i*n + n-1] in and out, t[i] == t1[i] on success.
 * status[i] (B values) is each member's outcome, as hl_flow_evolve's; a
 * member that fails keeps its last good step in z and t, with its error in
 * errs[i] when errs is not NULL (B values, cleared on success).  nsteps[i],
 * if not NULL: the member's steps.  Returns HL_OK if every member reached
 * its end, else the first failing member's status, err naming it
 * ("member 3: ..."); the others went on either way. */
hl_status hl_flow_batch_evolve(hl_flow_batch *batch, int B, double *t, const double *t1, double *z,
                               hl_status *status, long *nsteps, hl_error *errs, hl_error *err);

/* Outputs on a grid, as hl_run_adaptive asks for them (run.h): member i
 * starts at t = k0[i] * dt[i] from z[i*n ..] and is called back at each
 * t_k = (double)k * dt[i], k = k0[i]+1 .. k1[i], with its state there,
 * evaluated on the step's polynomial as hl_flow_run's outputs (the steps
 * are not shortened; the last lands on t_k1).  Every `segment` outputs
 * (0: never) the member starts afresh from its state at the last output,
 * as a new hl_flow_run call over the next `segment` times would (with the
 * same flow: its stall watch goes on): every output is then the bits of
 * hl_flow_run's over the same times, called in those segments.  dt[i] >
 * 0.  fn's non-zero return stops member i alone, with that return as its
 * status; fn fills err (the member's errs[i]) when it returns non-zero.
 * z is then each member's last state, status, nsteps, errs and the
 * return as hl_flow_batch_evolve's.  fn is called from the caller's
 * thread, member by member in no fixed order across members (each
 * member's outputs in order). */
typedef int (*hl_flow_batch_fn)(int member, long k, double t, const double *z, hl_error *err,
                                void *arg);
hl_status hl_flow_batch_grid(hl_flow_batch *batch, int B, const double *dt, const long *k0,
                             const long *k1, long segment, double *z, hl_flow_batch_fn fn,
                             void *arg, hl_status *status, long *nsteps, hl_error *errs,
                             hl_error *err);

/* ---- Arb ---------------------------------------------------------------
 * The same integrator in Arb at about digits decimal digits (tolerance
 * 10^-digits, absolute and relative; precision digits*log2(10) + 32 bits).
 * This is multiprecision floating point, not a validated integrator: the
 * truncation error is not enclosed, and only midpoints are carried from
 * step to step (the radii of interval arithmetic would otherwise grow with
 * every step); output balls are exact midpoints. */

typedef struct hl_flow_arb hl_flow_arb;

hl_status hl_flow_arb_new(hl_flow_arb **out, hl_tape *f, double digits, hl_error *err);
void hl_flow_arb_free(hl_flow_arb *flow); /* NULL is a no-op */

int hl_flow_arb_order(const hl_flow_arb *flow);
slong hl_flow_arb_prec(const hl_flow_arb *flow);
long hl_flow_arb_nsteps(const hl_flow_arb *flow);

hl_status hl_flow_arb_evolve(hl_flow_arb *flow, arb_t t, const arb_t t1, arb_ptr z, hl_error *err);

typedef int (*hl_flow_arb_fn)(const arb_t t, arb_srcptr z, void *arg);

hl_status hl_flow_arb_run(hl_flow_arb *flow, const arb_t t0, arb_srcptr z0, arb_srcptr ts, int n,
                          hl_flow_arb_fn fn, void *arg, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
