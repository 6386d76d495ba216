/* When compiling pays: the one cost model behind every choice to compile
 * (hamlie/tape.h: hl_tape_compile_pays).  The drivers (run, scheme, flow)
 * ask it and keep no figures of their own.
 *
 * A compilation pays when the time it saves over the run is more than the
 * time it takes: uses * saved_per_use >= compile_time.  The figures are
 * those of bench/tape_jit.c and bench/run_fixed.c (gcc 12, libgccjit at
 * -O2, x86-64, an otherwise idle machine); they are rough (a factor of 2
 * either way between machines), and the choices they make only move time:
 * compiled and interpreted runs give the same results bit for bit
 * (hl_tape_jit, hl_newton_jit), or the same up to the last bits at one
 * known step (hl_tape_native).
 *
 * NOTE: the choice counts uses (evaluations, steps, solves), never clocks,
 * so that a run makes the same choices on every machine and is
 * reproducible. */
#include <limits.h>
#include <math.h>

#include "tape/cost_impl.h"
#include "tape/jit_cache_impl.h"
#include "tape/tape_impl.h"

/* hl_tape_jit: GCC's fixed cost (driver, passes, assembler and loader,
 * in process) and its cost per instruction of straight-line code
 * (bench/tape_jit.c, "compile time against tape length": linear in the
 * tape's length from 50 to 3400 instructions). */
#define JIT_COMPILE_NS 25e6
#define JIT_COMPILE_NS_PER_OP 1e5

/* An evaluation in machine code saves the interpreter's dispatch and its
 * load and store through the register file: about 2.8 ns against 0.4 ns
 * per instruction (bench/tape_jit.c, from 9 to 3400 instructions). */
#define JIT_SAVED_NS_PER_OP 2.4

/* A step of hl_tape_iterate's compiled loop also saves what a stepper
 * does around the evaluation: its call, the copies of the state and the
 * finiteness checks (bench/run_fixed.c, explicit schemes against the loop
 * written by hand). */
#define LOOP_SAVED_NS_PER_STEP 50.0

/* hl_newton_jit compiles three or four tapes and an LU factorization
 * written out: 80-150 ms for the implicit schemes on one degree of freedom,
 * about 400 ms for gauss3 on two, to save about 80 ns a solve (the
 * interpreter and the calls between the tapes).  A million solves is
 * where the smallest of them breaks even (bench/run_fixed.c: the implicit
 * midpoint rule's 10^6 pendulum steps about as fast compiled as not); the
 * larger ones save more per solve as well, so one threshold serves. */
#define NEWTON_BREAKEVEN_SOLVES 1000000L

/* hl_tape_native's recursion: 40-300 ms for the tapes of
 * bench/taylor_flow.c at order 19, for a step about twice as fast; both
 * grow with the tape's length times the order squared, so the break-even
 * hardly depends on the tape: 0.3-0.7 million steps.  The steps of an
 * adaptive run are foreseen from a probe (hl_flow_native_for), not known,
 * hence the margin. */
#define TAYLOR_BREAKEVEN_STEPS 1000000L

/* With the disk cache of compiled code (jit_cache.c) a compilation serves
 * the runs after this one too.  A miss with a usable cache compiles when
 * this run makes a CACHE_RUNS_AHEAD-th of the break-even's uses: the
 * code is counted to serve that many runs of the same program (a rerun,
 * another --t, a parameter study), and the first run pays for them.
 * Kepler to t = 1e4 at tol 1e-15 (55 000 Taylor steps) then compiles on
 * its first run (100-300 ms more; see the NOTE in jit_cache.c on what
 * writing the file adds) and runs native from the second on. */
#define CACHE_RUNS_AHEAD 20

/* A hit is not free: the key file read and compared, the object read and
 * hashed, dlopen and its relocations cost 0.27-0.67 ms of CPU
 * (bench/cached_short.c, bench/jit_cache.c "hit"), about what 500-3000
 * Taylor steps save.  So kept code is loaded when the run's uses save more
 * than that, not for any run: a run of 30 Taylor steps interpreted takes
 * 0.01-0.08 ms, loaded 0.23-0.46 ms. */
#define CACHE_HIT_NS 5e5

/* What a Taylor step saves compiled, per instruction of the tape (+1: the
 * recursion's own loop over the state), at order 19, growing as the
 * square of the order (each coefficient's convolutions): measured 89, 240,
 * 638 and 1400 ns a step on the oscillator, pendulum, Henon-Heiles and
 * Kepler (1, 2, 9 and 8 instructions; bench/cached_short.c), which this
 * puts at 160, 240, 800 and 720 ns: the break-even of a hit within a
 * factor 2 either way (3000, 1800, 850 and 480 steps measured). */
#define TAYLOR_SAVED_NS_PER_OP 80.0
#define TAYLOR_SAVED_AT_ORDER 19

/* The batch recursion (hl_tape_batch, the lanes of hl_flow_batch): about
 * 1.1 s to compile 4 lanes of Henon-Heiles at order 20 (1.3 s the single
 * recursion, on the same loaded machine; bench/taylor_batch.sh "compile").
 * A member's step in 4 lanes then took 135 ns against 868 ns interpreted
 * one member at a time (2671 against 415 members a second of 2776 steps,
 * bench/taylor_batch.sh): 733 ns saved, about what TAYLOR_SAVED_NS_PER_OP
 * puts on the compiled single recursion (800 ns), so that figure serves,
 * and one member-step is one use.  The single run is interpreted in the
 * runs a sweep makes (a few thousand steps each): it is the peer. */
#define BATCH_COMPILE_NS 1.1e9

/* What a compiled Newton solve saves (see NEWTON_BREAKEVEN_SOLVES). */
#define NEWTON_SAVED_NS_PER_SOLVE 80.0

/* What a Taylor step at this order saves compiled. */
static double taylor_saved_ns(const hl_tape *t, int order)
{
    double r = (double)(order + 1) / (TAYLOR_SAVED_AT_ORDER + 1);
    return TAYLOR_SAVED_NS_PER_OP * (hl_tape_nops(t) + 1) * r * r;
}

/* The saved ns per use of kind's compiled code. */
static double saved_ns_per_use(const hl_tape *t, hl_compile_kind kind)
{
    double ops = t->ncode;
    switch (kind) {
    case HL_COMPILE_EVAL:
        return JIT_SAVED_NS_PER_OP * ops;
    case HL_COMPILE_LOOP:
        return JIT_SAVED_NS_PER_OP * ops + LOOP_SAVED_NS_PER_STEP;
    case HL_COMPILE_TAYLOR:
        return taylor_saved_ns(t, t->ts - 1);
    }
    return 0;
}

/* 1 if the cache holds the tape's code for this kind of use.  The Taylor
 * recursion is keyed by its order, which the interpreter has laid the
 * tape out for (t->ts = order + 1) by the time a run asks. */
static int kept_in_cache(const hl_tape *t, hl_compile_kind kind)
{
    if (kind == HL_COMPILE_TAYLOR && t->ts <= 1)
        return 0;
    hl_buf inputs;
    hl_buf_init(&inputs);
    if (kind == HL_COMPILE_TAYLOR)
        hl_jit_inputs_taylor(&inputs, t, t->ts - 1);
    else
        hl_jit_inputs_tape(&inputs, t);
    int has = hl_jit_cache_has(kind == HL_COMPILE_TAYLOR ? HL_JIT_SITE_TAYLOR : HL_JIT_SITE_EVAL,
                               &inputs);
    hl_buf_clear(&inputs);
    return has;
}

/* The choice for a run of uses, given the break-even without a cache. */
static int pays_with_cache(long breakeven, long uses, int kept)
{
    if (breakeven == LONG_MAX || uses <= 0)
        return 0;
    if (uses >= breakeven || kept)
        return 1;
    return hl_jit_cache_on() && uses >= breakeven / CACHE_RUNS_AHEAD;
}

/* 1 if uses repay a load from the cache (the cache is not asked). */
static int hit_repaid(double saved_ns_per_use, long uses)
{
    return (double)uses * saved_ns_per_use >= CACHE_HIT_NS;
}

/* compile_ns / saved_ns, or LONG_MAX if nothing is saved or the quotient
 * does not fit. */
static long uses_to_repay(double compile_ns, double saved_ns)
{
    if (saved_ns <= 0)
        return LONG_MAX;
    double uses = compile_ns / saved_ns;
    return uses >= (double)LONG_MAX ? LONG_MAX : (long)uses;
}

long hl_tape_compile_breakeven(const hl_tape *t, hl_compile_kind kind)
{
    double ops = t->ncode;
    switch (kind) {
    case HL_COMPILE_EVAL:
    case HL_COMPILE_LOOP:
        if (!hl_tape_jit_available() || t->ncode == 0)
            return LONG_MAX;
        return uses_to_repay(JIT_COMPILE_NS + JIT_COMPILE_NS_PER_OP * ops,
                             JIT_SAVED_NS_PER_OP * ops +
                                 (kind == HL_COMPILE_LOOP ? LOOP_SAVED_NS_PER_STEP : 0));
    case HL_COMPILE_TAYLOR:
        return t->ncode == 0 ? LONG_MAX : TAYLOR_BREAKEVEN_STEPS;
    }
    return LONG_MAX;
}

int hl_tape_compile_pays(const hl_tape *t, hl_compile_kind kind, long uses)
{
    if (t == NULL)
        return 0;
    long breakeven = hl_tape_compile_breakeven(t, kind);
    if (breakeven == LONG_MAX || uses <= 0)
        return 0;
    int kept =
        uses < breakeven && hit_repaid(saved_ns_per_use(t, kind), uses) && kept_in_cache(t, kind);
    return pays_with_cache(breakeven, uses, kept);
}

int hl_tape_compile_kept(const hl_tape *t, hl_compile_kind kind, long uses)
{
    if (t == NULL || uses <= 0 || hl_tape_compile_breakeven(t, kind) == LONG_MAX)
        return 0;
    return hit_repaid(saved_ns_per_use(t, kind), uses) && kept_in_cache(t, kind);
}

int hl_newton_compile_pays(const hl_newton *nw, long solves)
{
    if (nw == NULL || !hl_tape_jit_available() || solves <= 0)
        return 0;
    int kept = 0;
    if (solves < NEWTON_BREAKEVEN_SOLVES && hit_repaid(NEWTON_SAVED_NS_PER_SOLVE, solves)) {
        hl_buf inputs;
        hl_buf_init(&inputs);
        hl_jit_inputs_newton(&inputs, nw);
        kept = hl_jit_cache_has(HL_JIT_SITE_NEWTON, &inputs);
        hl_buf_clear(&inputs);
    }
    return pays_with_cache(NEWTON_BREAKEVEN_SOLVES, solves, kept);
}

long hl_tape_jit_breakeven(const hl_tape *t)
{
    return hl_tape_compile_breakeven(t, HL_COMPILE_EVAL);
}

/* 1 if the cache holds the batch recursion of this order and lane count. */
static int batch_kept(const hl_tape *t, int order, int lanes)
{
    hl_buf inputs;
    hl_buf_init(&inputs);
    hl_jit_inputs_batch(&inputs, t, order, lanes);
    int has = hl_jit_cache_has(lanes > 1 ? HL_JIT_SITE_BATCH : HL_JIT_SITE_TAYLOR, &inputs);
    hl_buf_clear(&inputs);
    return has;
}

int hl_tape_batch_pays(const hl_tape *t, int order, int lanes, long member_steps)
{
    if (t == NULL || t->ncode == 0 || member_steps <= 0 || !hl_tape_jit_available())
        return 0;
    double saved = taylor_saved_ns(t, order);
    long breakeven = uses_to_repay(BATCH_COMPILE_NS, saved);
    int kept =
        member_steps < breakeven && hit_repaid(saved, member_steps) && batch_kept(t, order, lanes);
    return pays_with_cache(breakeven, member_steps, kept);
}

/* ---- the cost of a Taylor step against its order ----------------------
 * The adaptive integrator (flow.h) chooses its order by what a step costs
 * (hl_tape_taylor_step_ns) against how far it goes.  The figures are a
 * least-squares fit of the relative misfit (bench/cost_fit.py: ns a step,
 * native, orders 12 to 40, the four systems of bench/work_precision.c and
 * six tapes of the zoo with other mixes of products, libm calls and
 * state; 120 points, the median of two rounds), on a 2-core machine
 * under load: only their ratios matter to the choice.  Median misfit 5 %
 * (without the knee 15 %; the model before session 12, c0 = 40, 4.3 per
 * state and order, 0.18 per product and p^2: 68 %, its c0 and c1 too small
 * against c2 since sessions 10-11 made the driver cheaper and the
 * recursion's code denser).  The linear instructions' share came out 0
 * against the state's (compiled, a sum is folded into the multiply-adds
 * around it); the term is kept, at 0, so that a refit can give it one. */

/* Per product (a convolution) and p^2: the sum over orders 0..p of k
 * multiply-adds */
#define TAYLOR_NS_PER_PRODUCT_P2 0.10
/* NOTE: the knee.  The compiled recursion is one straight-line function
 * whose length grows as its products times p^2; past about
 * TAYLOR_KNEE_PRODUCTS_P2 (some 2500-3500 instructions, session 11's
 * counts scaled by p^2: Kepler between orders 18 and 22, Henon-Heiles
 * between 28 and 32, the 3-D Kepler and FPU tapes between 18 and 20) each
 * further product p^2 costs 2.5 times as much, as the code no longer fits
 * the core's cache of decoded instructions (AMD Zen 5 here; a core with a
 * smaller one has its knee earlier).  The interpreter has no knee.  It
 * moved Kepler's orders at tol 1e-11, 1e-12 from 21, 22 to 18
 * (docs/work-precision.md, session 12). */
#define TAYLOR_KNEE_PRODUCTS_P2 1500.0
#define TAYLOR_NS_PER_PRODUCT_P2_PAST_KNEE 0.145
/* Per linear instruction (a sum, a constant factor) and order */
#define TAYLOR_NS_PER_LINEAR_P 0.0
/* Per state component and order: the driver's Horner sum of the step,
 * the coefficient norms */
#define TAYLOR_NS_PER_STATE_P 0.9
/* Per libm call at order 0 (sin and cos, exp, log, pow, ...) */
#define TAYLOR_NS_PER_CALL 17.0
/* Per step: the step rule (logs and exps), the call of the recursion, the
 * loop's tests and the time's two-sum */
#define TAYLOR_NS_PER_STEP 94.0

/* The products an instruction's recursion costs (in convolutions). */
static double products_of(int op)
{
    switch (op) {
    case HL_OP_MUL:
    case HL_OP_DIV:
    case HL_OP_KDIV:
    case HL_OP_EXP:
    case HL_OP_LOG:
        return 1;
    case HL_OP_SQR:
    case HL_OP_SQRT:
        return 0.5; /* half the terms by symmetry */
    case HL_OP_POWK:
    case HL_OP_POW3H:
        return 1.5; /* a weighted convolution: two products a term */
    case HL_OP_SINCOS:
    case HL_OP_SINHCOSH:
    case HL_OP_TAN:
    case HL_OP_TANH:
    case HL_OP_ATAN:
        return 2;
    case HL_OP_ASIN:
    case HL_OP_ACOS:
    case HL_OP_ASINH:
    case HL_OP_ATAN2:
        return 2.5;
    default:
        return 0; /* linear */
    }
}

/* 1 if the instruction's order 0 is a call of libm (its coefficients past
 * 0 are products); sqrt and a^(3/2) are instructions. */
static int calls_libm(int op)
{
    switch (op) {
    case HL_OP_POWK:
    case HL_OP_EXP:
    case HL_OP_LOG:
    case HL_OP_SINCOS:
    case HL_OP_SINHCOSH:
    case HL_OP_TAN:
    case HL_OP_TANH:
    case HL_OP_ATAN:
    case HL_OP_ASIN:
    case HL_OP_ACOS:
    case HL_OP_ASINH:
    case HL_OP_ATAN2:
        return 1;
    default:
        return 0;
    }
}

void hl_tape_taylor_cost_terms(const hl_tape *t, hl_taylor_cost_terms *terms)
{
    *terms = (hl_taylor_cost_terms){.state = t->nin};
    for (int i = 0; i < t->ncode; i++) {
        double w = products_of(t->code[i].op);
        terms->products += w;
        terms->linear += w == 0;
        terms->calls += calls_libm(t->code[i].op);
    }
}

void hl_tape_taylor_step_cost(const hl_tape *t, double c[3])
{
    hl_taylor_cost_terms n;
    hl_tape_taylor_cost_terms(t, &n);
    c[0] = TAYLOR_NS_PER_STEP + TAYLOR_NS_PER_CALL * n.calls;
    c[1] = TAYLOR_NS_PER_LINEAR_P * n.linear + TAYLOR_NS_PER_STATE_P * n.state;
    c[2] = TAYLOR_NS_PER_PRODUCT_P2 * n.products;
}

double hl_tape_taylor_step_ns(const hl_tape *t, int order)
{
    hl_taylor_cost_terms n;
    hl_tape_taylor_cost_terms(t, &n);
    double c[3], p = order;
    hl_tape_taylor_step_cost(t, c);
    double past = n.products * p * p - TAYLOR_KNEE_PRODUCTS_P2;
    return c[0] + c[1] * p + c[2] * p * p + TAYLOR_NS_PER_PRODUCT_P2_PAST_KNEE * fmax(past, 0);
}
