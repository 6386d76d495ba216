/* hamlie — tapes: expressions compiled into straight-line numeric programs.
 *
 * A tape is built once from an expression DAG with several outputs and the
 * names of its inputs.  Every shared subexpression is computed once (the DAG
 * is hash-consed, so pointer identity is common-subexpression elimination;
 * the compiler also shares identical instructions, e.g. sin(a) and cos(a)
 * become one SINCOS).  Subtrees without inputs are folded into constants.
 *
 * A tape is read three ways:
 *   - in double, by a tight interpreter loop (no allocation per call);
 *   - in Arb, at any precision (bits);
 *   - in Taylor mode: every register holds a truncated power series
 *     x(t) = sum_k x^[k] t^k (normalised Taylor coefficients), in double or
 *     in Arb.  For an autonomous ODE z' = f(z) given as a tape with n inputs
 *     and n outputs, hl_tape_taylor_ode_* gives the Taylor coefficients of the
 *     solution through z0, order by order: z^[k+1] = f(z)^[k] / (k+1).  For
 *     the Hamiltonian vector field this is the numeric Lie series exp(t g) z.
 *
 * Register layout: inputs first, then constants, then one register per
 * instruction.  In Taylor mode register r's coefficients are contiguous.
 *
 * A tape owns its scratch space, so one tape must not be evaluated by two
 * threads at once; build one tape per thread.  It does not keep a reference
 * to the expressions or their pool.
 */
#ifndef HAMLIE_TAPE_H
#define HAMLIE_TAPE_H

#include <arb.h>
#include "hamlie/error.h"
#include "hamlie/expr.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- opcodes ------------------------------------------------------------
 * d = destination register, a, b = operand registers, k = a constant
 * register (its series is k^[0], 0, 0, ...), x = aux register (second
 * result or auxiliary series kept for the recurrence).  The recurrence gives
 * coefficient k of the result from coefficients 0..k of the operands and
 * 0..k-1 of the result (Jorba & Zou 2005; Hairer-Norsett-Wanner I.8).
 * Below, (x*y)^[k] = sum_{j=0..k} x^[j] y^[k-j].
 *
 * Rational factors do not become instructions where they can be carried:
 * the compiler keeps every value as (rational scale) * register, so the
 * (2*p)/2 that differentiation writes compiles to p, and x/3 to a scale of
 * 1/3; a scale becomes a MULK (or NEG) only under a function, a non-integer
 * power, or at an output.  The K-ops below meet constants that are not
 * rational (pi, log 2, ...) or that carry no scale.  A few rewrites tidy
 * what differentiation writes: sqrt(w)^2 -> w, a * (1/u) -> a/u,
 * (x/u)/w -> x/(u w) (u w then shared between components); instructions
 * nobody reads are dropped.  Like any algebraic folding these take x - x,
 * 0*x and sqrt(w)^2 at face value even where x is inf or NaN, or w < 0.
 *
 * Integer powers a^n (|n| <= HL_TAPE_POWI_MAX) are lowered by the compiler
 * to SQR / MUL (and KDIV for n < 0) by binary powering: exact in every mode
 * and stable when a^[0] = 0 (the pow recurrence divides by a^[0]).  A power
 * a^b with non-constant b is lowered to exp(b log a).
 */
typedef enum hl_op {
    /* op        args      value           Taylor coefficient k            */
    HL_OP_NEG,  /* d a      -a              -a[k]                            */
    HL_OP_ADD,  /* d a b    a + b           a[k] + b[k]                      */
    HL_OP_SUB,  /* d a b    a - b           a[k] - b[k]                      */
    HL_OP_MUL,  /* d a b    a * b           (a*b)[k]                         */
    HL_OP_DIV,  /* d a b    a / b           (a[k] - sum_{j=1..k} b[j] d[k-j]) / b[0] */
    HL_OP_SQR,  /* d a      a^2             (a*a)[k], using symmetry         */
    HL_OP_ADDK, /* d a k    a + k           a[k] (+ k at order 0)            */
    HL_OP_SUBK, /* d a k    a - k           a[k] (- k at order 0)            */
    HL_OP_KSUB, /* d a k    k - a           -a[k] (k - a[0] at order 0)      */
    HL_OP_MULK, /* d a k    a * k           k a[k]                           */
    HL_OP_DIVK, /* d a k    a / k           a[k] / k                         */
    HL_OP_KDIV, /* d a k    k / a           -(sum_{j=1..k} a[j] d[k-j]) / a[0], k >= 1 */
    HL_OP_POWK, /* d a k    a^c, c = k real (sum_{j=0..k-1} (c(k-j) - j) a[k-j] d[j]) / (k a[0]) */
    HL_OP_SQRT, /* d a      sqrt(a)         (a[k] - sum_{j=1..k-1} d[j] d[k-j]) / (2 d[0]) */
    HL_OP_EXP,  /* d a      exp(a)          (1/k) sum_{j=1..k} j a[j] d[k-j] */
    HL_OP_LOG,  /* d a      log(a)          (k a[k] - sum_{j=1..k-1} (k-j) a[j] d[k-j]) / (k a[0]) */
    HL_OP_SINCOS, /* d a x  d=sin a, x=cos a  d[k] = (1/k) sum j a[j] x[k-j];
                                              x[k] = -(1/k) sum j a[j] d[k-j]   */
    HL_OP_SINHCOSH, /* d a x d=sinh, x=cosh   as SINCOS without the minus      */
    HL_OP_TAN,  /* d a x    tan a; x=d^2    d[k] = a[k] + (1/k) sum_{j=1..k} j a[j] x[k-j];
                                            then x[k] = (d*d)[k]                 */
    HL_OP_TANH, /* d a x    tanh a; x=d^2   d[k] = a[k] - (1/k) sum_{j=1..k} j a[j] x[k-j]; x[k] = (d*d)[k] */
    HL_OP_ATAN, /* d a x    atan a; x=1+a^2 x[k] = [k=0] + (a*a)[k];
                                            d[k] = (k a[k] - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]) */
    HL_OP_ASIN, /* d a x    asin a; x=sqrt(1-a^2)  x by the SQRT rule on 1-(a*a);
                                            d[k] as ATAN with this x               */
    HL_OP_ACOS, /* d a x    acos a; x=sqrt(1-a^2)  d[k] = -(k a[k] + sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]) */
    HL_OP_ASINH, /* d a x   asinh a; x=sqrt(1+a^2)  x by the SQRT rule on 1+(a*a); d[k] as ASIN */
    HL_OP_ATAN2, /* d a b x atan2(a, b); x=a^2+b^2  x[k] = (a*a)[k] + (b*b)[k];
                                            d[k] = (sum_{j=1..k} j (b[k-j] a[j] - a[k-j] b[j])
                                                    - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]) */
    HL_OP_POW3H, /* d a   a^(3/2) = a sqrt(a)  as POWK with c = 3/2 (w^(3/2), sqrt(w) w) */
    HL_OP_COUNT
} hl_op;

#define HL_TAPE_POWI_MAX 64

typedef struct hl_tape hl_tape;

/* Compile outputs outs[0..nout-1] over inputs named inputs[0..nin-1].  Any
 * other symbol is an error (HL_EINVAL, "unknown symbol 'z'").  Constant
 * subtrees are folded; one that is not finite in double (1/0, log(0)) is
 * HL_EDOM. */
hl_status hl_tape_new(hl_tape **out, const hl_expr *const *outs, int nout,
                      const char *const *inputs, int nin, hl_error *err);
void hl_tape_free(hl_tape *tape); /* NULL is a no-op */

int hl_tape_ninputs(const hl_tape *tape);
int hl_tape_noutputs(const hl_tape *tape);
int hl_tape_nops(const hl_tape *tape);     /* instructions in the body */
int hl_tape_nregs(const hl_tape *tape);
const char *hl_op_name(hl_op op);

/* Print the program, one instruction a line (for debugging and docs).
 * malloc'd. */
char *hl_tape_print(const hl_tape *tape);

/* The Hamiltonian vector field of H with N degrees of freedom: inputs
 * q_1..q_N, p_1..p_N; outputs dH/dp_1..dH/dp_N, -dH/dq_1..-dH/dq_N.  The
 * parameters params[i] are replaced by the expressions vals[i] first. */
hl_status hl_tape_hamiltonian(hl_tape **out, hl_pool *pool, const hl_expr *H, int N,
                              const char *const *q, const char *const *p, int nparams,
                              const char *const *params, const hl_expr *const *vals, hl_error *err);

/* ---- evaluation ------------------------------------------------------- */

/* out[0..nout-1] = f(in[0..nin-1]).  Results may be inf or nan. */
void hl_tape_eval_d(double *out, const double *in, hl_tape *tape);

/* The same in Arb at prec bits (out must hold nout initialised arbs). */
void hl_tape_eval_arb(arb_ptr out, arb_srcptr in, slong prec, hl_tape *tape);

/* Taylor mode.  in[i*(order+1) + k] is coefficient k of input i; writes
 * out[j*(order+1) + k] for output j, k = 0..order. */
void hl_tape_taylor_d(double *out, const double *in, int order, hl_tape *tape);
void hl_tape_taylor_arb(arb_ptr out, arb_srcptr in, int order, slong prec, hl_tape *tape);

/* Taylor coefficients of the solution of z' = f(z) (nin == nout = n):
 * z[i*(order+1) + 0] holds z_i(0) on entry; on return z[i*(order+1) + k]
 * holds z_i^[k] for k = 0..order.  Cost O(order^2) per instruction.
 * HL_EINVAL if the tape is not square. */
hl_status hl_tape_taylor_ode_d(double *z, int order, hl_tape *tape, hl_error *err);
hl_status hl_tape_taylor_ode_arb(arb_ptr z, int order, slong prec, hl_tape *tape, hl_error *err);
/* hl_tape_taylor_ode_d without its copies (they were a tenth of the
 * integrator's cost a step outside the recursion): z[0..n-1] the state,
 * and the coefficients lent from the tape's register file,
 * (*rows)[i*(order+1) + k] = z_i^[k], valid until the next Taylor or
 * native call on the tape (hl_tape_eval_d leaves them).  Fails (*rows
 * NULL) where hl_tape_taylor_ode_d does. */
hl_status hl_tape_taylor_ode_lend(const double **rows, hl_tape *tape, const double *z, int order,
                                  hl_error *err);

/* ---- native code (opt-in) ------------------------------------------------
 * Compile the Taylor-ODE recursion at this order to machine code: one
 * straight-line function (every sum written out, every register index a
 * constant); hl_tape_taylor_ode_d at this order then runs it instead of the
 * interpreter, with the interpreter's results to the last bit (both run the
 * rules of src/rules: the same operations in the same order, no
 * contraction into FMA).  Built
 * in process by libgccjit where hamlie has it (no files), else, or when
 * $HL_CC names a compiler, as C source compiled by the system C compiler
 * ($HL_CC, else "cc", with -march=native: made on and for the machine that
 * runs it) into a temporary shared object and loaded.  Costs one compilation (30-300 ms for
 * the tapes of bench/taylor_flow.c at order 19, growing with tape size
 * times order squared), for a run about twice as fast: it pays for long
 * runs only (hl_tape_compile_pays, HL_COMPILE_TAYLOR).  HL_EUNSUP if neither
 * backend works (the interpreter keeps working); HL_EIO if the temporary
 * files cannot be written; HL_ELIMIT for a program that would be too large
 * (instructions * order^2 / 2 > 4e6 terms). */
hl_status hl_tape_native(hl_tape *tape, int order, hl_error *err);
void hl_tape_native_clear(hl_tape *tape); /* back to the interpreter */

/* ---- machine code for point evaluation (opt-in) ---------------------------
 * Compile the tape's double evaluation to machine code with libgccjit (at
 * -O2, in this process, no files): one function, straight-line, constants
 * as immediates; and for a tape with 1 <= nout <= nin also the loop of
 * hl_tape_iterate.  From then on hl_tape_eval_d runs the machine code
 * instead of the interpreter (one branch; callers change nothing) with
 * bitwise the same results: the same IEEE operations in the same order,
 * the same libm functions, no contraction into FMA.  Evaluation gets 4-7x
 * faster; compiling costs some tens of milliseconds, so it pays only for
 * long runs: see hl_tape_compile_pays.
 * Calling it again recompiles.  HL_EUNSUP if hamlie was built without
 * libgccjit or libgccjit fails (the tape keeps what it had; the
 * interpreter keeps working).  $HL_JIT_FLAGS adds compiler options
 * (space-separated), e.g. "-O3" or "-march=x86-64-v3" ("native" is not
 * understood by libgccjit); options may change the last bits, and an
 * option libgccjit rejects makes it print to stderr and fail.
 * hl_tape_eval_arb and Taylor mode are not affected. */
hl_status hl_tape_jit(hl_tape *tape, hl_error *err);
void hl_tape_jit_clear(hl_tape *tape);          /* back to the interpreter */
int hl_tape_jit_active(const hl_tape *tape);    /* 1 if eval_d runs machine code */
/* 1 if built with libgccjit and loading it (on the first compilation) has
 * not failed; asking does not load it. */
int hl_tape_jit_available(void);
/* Why libgccjit could not be loaded ("libgccjit.so.0 not found: ..."), or
 * NULL if it was not tried or loaded; the command line prints it as a note. */
const char *hl_tape_jit_load_error(void);

/* ---- when compiling pays (one cost model, src/tape/cost.c) -----------------
 * Each compiler costs a fixed time that a run repays by the uses it makes
 * of the machine code.  These functions say, from the tape's length and
 * figures measured by bench/tape_jit.c and bench/run_fixed.c, from how many
 * uses on a compilation pays; the run, scheme and flow drivers ask them and
 * keep no figures of their own.  The choice counts uses, not clocks, so a
 * run makes the same choices everywhere. */
typedef enum hl_compile_kind {
    HL_COMPILE_EVAL,   /* hl_tape_jit; a use is one hl_tape_eval_d */
    HL_COMPILE_LOOP,   /* hl_tape_jit; a use is one step of hl_tape_iterate[_watch]
                        * that replaces a stepper's step (its call and copies too) */
    HL_COMPILE_TAYLOR, /* hl_tape_native; a use is one Taylor step */
} hl_compile_kind;

/* The number of uses from which compiling pays; LONG_MAX where it never
 * does (a tape without instructions; hamlie without libgccjit for
 * hl_tape_jit).  E.g. about 370k evaluations for a 30-instruction
 * Störmer–Verlet step. */
long hl_tape_compile_breakeven(const hl_tape *tape, hl_compile_kind kind);
/* 1 if a run that makes this many uses of the compiled tape should
 * compile it (uses >= the break-even); 0 for a NULL tape. */
int hl_tape_compile_pays(const hl_tape *tape, hl_compile_kind kind, long uses);
/* 1 if the tape's compiled code for kind is in the disk cache and loading
 * it repays itself over this many uses (a hit costs well under a
 * millisecond, about what 500-3000 Taylor steps save): a driver that must
 * otherwise wait to learn its run's length (the flow's probe) asks this
 * first.  hl_tape_compile_pays says yes in these cases as well. */
int hl_tape_compile_kept(const hl_tape *tape, hl_compile_kind kind, long uses);
/* 1 if hl_tape_batch's compiled recursion (this order and lane count)
 * repays itself over member_steps Taylor steps of members in its lanes:
 * kept in the disk cache, or worth compiling (about a second).  0 without
 * libgccjit (the lanes then run one by one: no gain). */
int hl_tape_batch_pays(const hl_tape *tape, int order, int lanes, long member_steps);
/* What a step of the adaptive Taylor integrator (flow.h) on this tape
 * costs at order p, compiled, by the same cost model: c[0] + c[1] p +
 * c[2] p^2 ns (the products' convolutions grow as p^2, linear instructions
 * and the driver's sums over the coefficients as p, the step rule not).
 * The flow chooses its order by it; it counts instructions, never clocks. */
void hl_tape_taylor_step_cost(const hl_tape *tape, double c[3]);
/* The same model's ns a step at this order, with its knee: past a size of
 * the compiled recursion (its products times p^2) a product costs more,
 * as the code outgrows the core's cache of decoded instructions.  The
 * quadratic above is the cost below the knee. */
double hl_tape_taylor_step_ns(const hl_tape *tape, int order);
/* ---- the disk cache of compiled code (`hamlie cache`) ----
 * Compiled code is kept in $HAMLIE_CACHE_DIR, else $XDG_CACHE_HOME/hamlie,
 * else ~/.cache/hamlie (HAMLIE_CACHE=off: not at all).  hamlie's files
 * there are its entries (<hash>.key and <hash>.so) and the temporaries of
 * writers (<hash>.so.tmp<pid>.XXXXXX); any other file is not hamlie's and
 * is neither counted nor removed. */
typedef struct hl_jit_cache_listing {
    char *dir;       /* the directory; NULL when the cache is off or no home is known */
    int exists;      /* the directory exists */
    long entries;    /* key files (each vouches for its object) */
    long files;      /* hamlie's files: keys, objects, temporaries */
    long long bytes; /* their size */
} hl_jit_cache_listing;
/* What the cache holds now.  HL_EIO if the directory exists but cannot be
 * read.  hl_jit_cache_listing_clear frees it. */
hl_status hl_jit_cache_list(hl_jit_cache_listing *listing, hl_error *err);
void hl_jit_cache_listing_clear(hl_jit_cache_listing *listing);
/* Removes hamlie's files from the cache directory: each entry's key
 * before its object (a key never vouches for a missing object; a process
 * that loses an entry it was about to load compiles again), and the
 * temporaries of processes that are gone; a temporary of a running process
 * is left to it (it is being written).  removed (may be NULL) says what
 * went: files, bytes, entries.  HL_EIO, naming the file, if one cannot be
 * removed (one removed meanwhile by another process is not an error). */
hl_status hl_jit_cache_clear(hl_jit_cache_listing *removed, hl_error *err);

/* hl_tape_compile_breakeven(tape, HL_COMPILE_EVAL), its former name. */
long hl_tape_jit_breakeven(const hl_tape *tape);

/* Iterate the tape as a map: n times, in[0..nout-1] = f(in), the inputs
 * from nout on held fixed (a step size, parameters); needs 1 <= nout <= nin.
 * Stops before the first step whose outputs are not all finite and returns
 * the number of steps done (in holds the last state kept); -1 if the tape
 * is not of that shape.  After hl_tape_jit the whole loop is machine code
 * (the state stays in registers, no call per step: a fixed-step run at the
 * speed of hand-written C); else the interpreter, with the same results. */
long hl_tape_iterate(double *in, long n, hl_tape *tape);

/* The same for a tape with nout == nin >= 2 whose last output w is watched
 * rather than fed back: outputs 0..nout-2 replace in[0..nout-2], in[nout-1]
 * is held fixed (a step size), and each step taken raises *dev to
 * |w - w0| if that is larger, w computed at the state the step starts from
 * (e.g. the outputs are a scheme's step and H: the step and the energy of
 * the state it leaves share their subexpressions, and a run checks
 * max |H - H0| without a second tape).  Stops before the first step whose
 * outputs (w included) are not all finite; returns the steps done, -1 if
 * the tape is not of that shape.  After hl_tape_jit the loop is machine
 * code, else the interpreter with the same results. */
long hl_tape_iterate_watch(double *in, long n, double w0, double *dev, hl_tape *tape);

/* ---- simplified Newton's method on tapes --------------------------------
 * Solve F(x, U) = 0 for m unknowns U, x (nx values) held fixed, from
 * U0 = start(x): simplified Newton, the Jacobian dF/dU evaluated and
 * factored (LU, partial pivoting) at the first iteration and again only when
 * the corrections shrink slowly (ratio of successive corrections
 * > HL_NEWTON_REFRESH: an iteration that gains fewer than 3 digits costs
 * more than evaluating F with its Jacobian, one tape, and factoring; the
 * Gonzalez scheme at D = 0.1 on the pendulum, whose unknowns are rates:
 * 6.4 iterations a step with 1/4, 4.3 with 1e-3); done when a correction is at rounding level (max |dU| <= 4 eps
 * max(1, |U|)), or below 1e-12 max(1, |U|) and no longer shrinking (ratio
 * >= 1/2: F's own rounding); or the same test on an output
 * (hl_newton_set_output).  The tapes: start x -> U0 (nx inputs, m
 * outputs), F (x, U) -> F (m outputs), FJ (x, U) -> F then dF/dU row-major
 * (m + m^2 outputs), the same F in both; borrowed, not copied.  The solve
 * allocates nothing; one hl_newton must not be used by two threads. */
#define HL_NEWTON_REFRESH 1e-3

typedef enum hl_newton_status {
    HL_NEWTON_OK = 0,
    HL_NEWTON_START,     /* the starting point is not finite */
    HL_NEWTON_SINGULAR,  /* the Jacobian is singular (at iteration *iters) */
    HL_NEWTON_NONFINITE, /* F, its Jacobian or U not finite (at iteration *iters) */
    HL_NEWTON_NOCONV     /* max_iter iterations; *last: the last correction */
} hl_newton_status;

typedef struct hl_newton hl_newton;

hl_status hl_newton_new(hl_newton **out, hl_tape *start, hl_tape *F, hl_tape *FJ, int max_iter,
                        hl_error *err);

/* Decide convergence on Z(x, U) instead of U (Z: nx + m inputs, any number
 * of outputs, borrowed): done when Z moves by at most 4 eps max(1, |Z|), or
 * by at most 1e-12 max(1, |Z|) while the corrections no longer shrink.  For
 * a scheme Z is the next point: unknowns that are rates (Q - q)/D carry
 * rounding noise 1/D above the point's, which a test on U would chase. */
void hl_newton_set_output(hl_newton *nw, hl_tape *Z);
void hl_newton_free(hl_newton *nw); /* NULL is a no-op */
int hl_newton_unknowns(const hl_newton *nw);

/* With an output tape: its values at the solution after HL_NEWTON_OK (the
 * convergence test computed them there; nz values owned by nw, valid until
 * the next solve), so a caller need not evaluate Z again.  NULL without. */
const double *hl_newton_output(const hl_newton *nw);

/* U (m values) from x; *iters: the iterations taken (the failing one);
 * *last: max |dU| of the last iteration. */
hl_newton_status hl_newton_solve(double *U, int *iters, double *last, const double *x,
                                 hl_newton *nw);

/* The whole solve compiled to one function by libgccjit: the three tapes
 * inlined (constants as immediates, the state in machine registers), the
 * LU factorization written out for this m; from then on hl_newton_solve
 * runs it, with the same results bit for bit (the same operations in the
 * same order).  Costs one compilation (tenths of a second), for tens of
 * nanoseconds a solve: it pays for long runs only (hl_newton_compile_pays).
 * HL_EUNSUP without libgccjit or for m > 16 (the interpreter goes on). */
hl_status hl_newton_jit(hl_newton *nw, hl_error *err);
void hl_newton_jit_clear(hl_newton *nw);
int hl_newton_jit_active(const hl_newton *nw);
/* 1 if a run of this many solves should compile them (the cost model of
 * hl_tape_compile_pays; 0 without libgccjit or for NULL). */
int hl_newton_compile_pays(const hl_newton *nw, long solves);

/* ---- the Taylor-ODE recursion of several members at once (batch) ----------
 * hl_tape_taylor_ode_d for `lanes` states side by side: one recursion over
 * values that are vectors of lanes doubles (SIMD: 4 lanes fill AVX2's
 * registers, 8 AVX-512's), compiled by libgccjit; each lane's coefficients
 * are those of hl_tape_taylor_ode_d for that lane's state, to the last bit
 * (the same operations in the same order, lane by lane).  Without libgccjit
 * (or if it fails) the lanes run one by one through hl_tape_taylor_ode_d,
 * with the same results.  The compiled code goes through the disk cache
 * like the single recursion's.  A batch borrows its tape (which must
 * outlive it) and, without compiled code, its scratch: one thread per
 * batch and tape. */
#define HL_TAPE_BATCH_MAX_LANES 16

typedef struct hl_tape_batch hl_tape_batch;

/* lanes: a power of 2, 1..HL_TAPE_BATCH_MAX_LANES; order >= 0.  HL_EINVAL
 * for a tape that is not square, or lanes or order out of range.  A program
 * too large to compile (instructions * order^2 / 2 > 4e6 terms, as
 * hl_tape_native) or a failed compilation runs lane by lane (HL_OK). */
hl_status hl_tape_batch_new(hl_tape_batch **out, hl_tape *tape, int order, int lanes,
                            hl_error *err);
void hl_tape_batch_free(hl_tape_batch *batch); /* NULL is a no-op */
int hl_tape_batch_lanes(const hl_tape_batch *batch);
int hl_tape_batch_order(const hl_tape_batch *batch);
/* 1 if the recursion runs as compiled SIMD code, 0 if lane by lane. */
int hl_tape_batch_compiled(const hl_tape_batch *batch);

/* The batch's coefficients, owned by it: coefficient k of input i in lane
 * l at z[(i * (order+1) + k) * lanes + l] (lanes side by side).  Set k = 0
 * of every input in every lane, then hl_tape_batch_ode fills k = 1..order.
 * Aligned for the vectors; valid until hl_tape_batch_free. */
double *hl_tape_batch_coefs(hl_tape_batch *batch);
void hl_tape_batch_ode(hl_tape_batch *batch);

/* ---- the watched iteration of several members at once (batch) --------------
 * hl_tape_iterate_watch for `lanes` states side by side: one loop over
 * values that are vectors of lanes doubles (4 fill AVX2's registers),
 * compiled by libgccjit; each lane's outputs, state and *dev are those of
 * hl_tape_iterate_watch for that lane alone, to the last bit (the same
 * operations in the same order, lane by lane; libm's functions called lane
 * by lane).  The lanes step together: the loop stops before the first step
 * at which some lane's outputs (w included) are not all finite, and every
 * lane has then taken the steps returned; the caller finds the lane (its
 * outputs at its state, hl_tape_eval_d) and goes on without it.  Without
 * compiled code (compile 0, no libgccjit, a failed compilation) the lanes
 * step one after the other through the interpreter, with the same results.
 * The compiled code goes through the disk cache.  A batch borrows its tape
 * (which must outlive it; one thread per batch and tape). */
typedef struct hl_tape_iter_batch hl_tape_iter_batch;

/* tape: nout == nin >= 2, as hl_tape_iterate_watch; lanes a power of 2,
 * 1..HL_TAPE_BATCH_MAX_LANES (HL_EINVAL otherwise).  compile: 1 to compile
 * the loop (or load it from the cache; tens of milliseconds the first
 * time, so for long runs: hl_tape_compile_pays), 0 for the interpreter. */
hl_status hl_tape_iter_batch_new(hl_tape_iter_batch **out, hl_tape *tape, int lanes, int compile,
                                 hl_error *err);
void hl_tape_iter_batch_free(hl_tape_iter_batch *batch); /* NULL is a no-op */
int hl_tape_iter_batch_lanes(const hl_tape_iter_batch *batch);
/* 1 if the loop runs as compiled SIMD code, 0 if through the interpreter. */
int hl_tape_iter_batch_compiled(const hl_tape_iter_batch *batch);
/* The lanes' inputs, owned by the batch: input i of lane l at
 * z[i * lanes + l] (the last input, held fixed, is each lane's own).
 * Aligned for the vectors; valid until hl_tape_iter_batch_free. */
double *hl_tape_iter_batch_state(hl_tape_iter_batch *batch);
/* Up to n steps of every lane; w0 and dev: lanes values each (lane l's
 * w0 and *dev of hl_tape_iterate_watch).  Returns the steps every lane
 * took (n, or fewer when one lane's next step is not finite). */
long hl_tape_iter_batch_watch(hl_tape_iter_batch *batch, long n, const double *w0, double *dev);
/* The lanes that fill this machine's vector registers, which the lanes'
 * code is compiled for: 8 with AVX-512, 4 with AVX2, else 2 (SSE2).  The
 * fixed-step batch's default (bench/run_batch.c: Henon-Heiles' Störmer–
 * Verlet step 2.5 ns a member-step at 4 lanes, 1.6 at 8 on AVX-512). */
int hl_tape_lanes_native(void);

#ifdef __cplusplus
}
#endif

#endif
