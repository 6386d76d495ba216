/* Machine code for a tape's double evaluation, through libgccjit (opt-in;
 * see hl_tape_jit in hamlie/tape.h).
 *
 * The interpreter pays a dispatch, and a load and a store through the
 * register file, for every instruction.  The tape is a straight-line
 * program, so it translates one to one into a C-like function body: one
 * local per register, constants as immediates, libm calls where the
 * interpreter calls libm.  GCC then keeps the values in machine registers
 * and schedules the arithmetic.
 *
 * Results are bitwise those of the interpreter: each instruction is the
 * same IEEE operation on the same operands in the same order; the library
 * functions are the same libm symbols, called as opaque imports so that GCC
 * cannot rewrite them (pow(x, 2) -> x*x is not exact for glibc's pow);
 * contraction into FMA is switched off (-ffp-contract=off) and no
 * -march is given, so no FMA could be formed anyway.  sqrt is GCC's builtin
 * (sqrtsd, correctly rounded like libm's).
 *
 * Built here: hl_jit_eval (hl_tape_eval_d), hl_jit_iter and hl_jit_watch
 * (hl_tape_iterate[_watch]: the map iterated in one loop, so that a
 * fixed-step run pays no call and no copy per step), hl_jit_newton (the
 * whole simplified Newton solve of newton.c, three tapes inlined); the
 * Taylor-ODE recursion is jit_taylor.c's.  Without libgccjit at build time
 * every entry point here reports HL_EUNSUP and the interpreter runs.
 *
 * Measured (bench/tape_jit.c, gcc 12 -O2): compiling costs about 25 ms plus
 * 0.1 ms per instruction; evaluation is 4-7x faster than the interpreter,
 * and hl_tape_iterate on a Störmer-Verlet step is within 1.2x of the step
 * written by hand in C and inlined into its loop. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "rules/rule.h"
#include "rules/unroll.h"
#include "tape/tape_impl.h"

#ifdef HAMLIE_HAVE_GCCJIT
#include <libgccjit.h>

/* The libm functions the rules call (sqrt: GCC's builtin, set apart). */
static const char *const libm_name[HL_PFN_COUNT] = {
    [HL_PFN_SIN] = "sin",   [HL_PFN_COS] = "cos",   [HL_PFN_TAN] = "tan",
    [HL_PFN_SINH] = "sinh", [HL_PFN_COSH] = "cosh", [HL_PFN_TANH] = "tanh",
    [HL_PFN_EXP] = "exp",   [HL_PFN_LOG] = "log",   [HL_PFN_ATAN] = "atan",
    [HL_PFN_ASIN] = "asin", [HL_PFN_ACOS] = "acos", [HL_PFN_ATAN2] = "atan2",
    [HL_PFN_POW] = "pow",
};

typedef struct jit {
    gcc_jit_context *c;
    gcc_jit_type *dbl, *dblp;
    gcc_jit_block *blk;
    gcc_jit_function *fun;
    gcc_jit_lvalue **loc; /* one local per non-constant register */
    gcc_jit_function *lib[HL_PFN_COUNT]; /* libm imports, by point function */
    gcc_jit_function *sqrt, *sincos;
    const hl_tape *t;
    unsigned char *read; /* by register: read by an instruction or an output */
    int split_sincos;    /* sin and cos as two calls (build_loop) */
} jit;

/* Which registers the body and the outputs read. */
static unsigned char *registers_read(const hl_tape *t)
{
    unsigned char *r = hl_xcalloc((size_t)t->nregs + 1, 1);
    for (int k = 0; k < t->ncode; k++) {
        const hl_instr *i = &t->code[k];
        if (i->a >= 0)
            r[i->a] = 1;
        if (i->b >= 0)
            r[i->b] = 1;
    }
    for (int j = 0; j < t->nout; j++)
        r[t->outreg[j]] = 1;
    return r;
}

static gcc_jit_function *import1(jit *J, const char *name)
{
    gcc_jit_param *x = gcc_jit_context_new_param(J->c, NULL, J->dbl, "x");
    return gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED, J->dbl, name, 1, &x,
                                        0);
}

static gcc_jit_function *import_lib(jit *J, hl_pfn f)
{
    if (f == HL_PFN_SQRT)
        return J->sqrt;
    if (J->lib[f] != NULL)
        return J->lib[f];
    if (f == HL_PFN_POW || f == HL_PFN_ATAN2) { /* pow(x, y), atan2(y, x) */
        gcc_jit_param *p[2] = {gcc_jit_context_new_param(J->c, NULL, J->dbl, "u"),
                               gcc_jit_context_new_param(J->c, NULL, J->dbl, "v")};
        J->lib[f] = gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED, J->dbl,
                                                 libm_name[f], 2, p, 0);
    } else
        J->lib[f] = import1(J, libm_name[f]);
    return J->lib[f];
}

/* sincos(x, &s, &c) */
static gcc_jit_function *import_sincos(jit *J)
{
    if (J->sincos == NULL) {
        gcc_jit_param *p[3] = {gcc_jit_context_new_param(J->c, NULL, J->dbl, "x"),
                               gcc_jit_context_new_param(J->c, NULL, J->dblp, "s"),
                               gcc_jit_context_new_param(J->c, NULL, J->dblp, "c")};
        J->sincos = gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED,
                                                 gcc_jit_context_get_type(J->c, GCC_JIT_TYPE_VOID),
                                                 "sincos", 3, p, 0);
    }
    return J->sincos;
}

/* The value of register r: an immediate for a constant, else its local. */
static gcc_jit_rvalue *val(jit *J, int r)
{
    if (J->t->isconst[r])
        return gcc_jit_context_new_rvalue_from_double(J->c, J->dbl, J->t->rd[r]);
    return gcc_jit_lvalue_as_rvalue(J->loc[r]);
}

static void assign(jit *J, int d, gcc_jit_rvalue *v)
{
    gcc_jit_block_add_assignment(J->blk, NULL, J->loc[d], v);
}

/* ---- point evaluation: the rules' point() at coefficient 0 ------------------
 * An emitter whose values are gccjit trees (hl_ev.p) over the registers'
 * locals.  A register that nothing reads is not assigned, so that its call
 * is not made (the compiler makes every sin a SINCOS, for Taylor mode). */
typedef struct pem {
    hl_em em;
    jit *J;
    const hl_instr *in;
    int fused; /* SINCOS through one sincos call, into D's and X's locals */
} pem;

static jit *PJ(hl_em *em)
{
    return ((pem *)em)->J;
}
static hl_ev ptr(gcc_jit_rvalue *r)
{
    return (hl_ev){.p = r};
}
static gcc_jit_rvalue *RP(hl_ev v)
{
    return v.p;
}

static int slot_reg(const hl_instr *in, hl_slot s)
{
    return s == HL_SLOT_D ? in->d : s == HL_SLOT_A ? in->a : s == HL_SLOT_B ? in->b : in->x;
}

static hl_ev p_num(hl_em *em, long p, long q)
{
    return ptr(
        gcc_jit_context_new_rvalue_from_double(PJ(em)->c, PJ(em)->dbl, (double)p / (double)q));
}

static hl_ev p_coef(hl_em *em, hl_slot s, int j)
{
    (void)j; /* point rules read coefficient 0 only */
    return ptr(val(PJ(em), slot_reg(((pem *)em)->in, s)));
}

static void p_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    pem *P = (pem *)em;
    int r = slot_reg(P->in, s);
    (void)j;
    if (P->J->read[r] && !(P->fused && (s == HL_SLOT_D || s == HL_SLOT_X)))
        assign(P->J, r, RP(v));
}

static hl_ev p_bin(hl_em *em, enum gcc_jit_binary_op op, hl_ev a, hl_ev b)
{
    return ptr(gcc_jit_context_new_binary_op(PJ(em)->c, NULL, op, PJ(em)->dbl, RP(a), RP(b)));
}
static hl_ev p_add(hl_em *em, hl_ev a, hl_ev b)
{
    return p_bin(em, GCC_JIT_BINARY_OP_PLUS, a, b);
}
static hl_ev p_sub(hl_em *em, hl_ev a, hl_ev b)
{
    return p_bin(em, GCC_JIT_BINARY_OP_MINUS, a, b);
}
static hl_ev p_mul(hl_em *em, hl_ev a, hl_ev b)
{
    return p_bin(em, GCC_JIT_BINARY_OP_MULT, a, b);
}
static hl_ev p_div(hl_em *em, hl_ev a, hl_ev b)
{
    return p_bin(em, GCC_JIT_BINARY_OP_DIVIDE, a, b);
}

static hl_ev p_neg(hl_em *em, hl_ev a)
{
    return ptr(
        gcc_jit_context_new_unary_op(PJ(em)->c, NULL, GCC_JIT_UNARY_OP_MINUS, PJ(em)->dbl, RP(a)));
}

static hl_ev p_fma(hl_em *em, hl_ev a, hl_ev b, hl_ev c)
{
    gcc_jit_function *f = gcc_jit_context_get_builtin_function(PJ(em)->c, "__builtin_fma");
    gcc_jit_rvalue *args[3] = {RP(a), RP(b), RP(c)};
    return ptr(gcc_jit_context_new_call(PJ(em)->c, NULL, f, 3, args));
}

/* sin and cos of a SINCOS whose two values are read, outside build_loop:
 * one sincos call (glibc's sincos computes each as sin and cos do, so the
 * bits are the same) */
static int fuse_sincos(const pem *P)
{
    const jit *J = P->J;
    return P->in->op == HL_OP_SINCOS && J->read[P->in->d] && J->read[P->in->x] && !J->split_sincos;
}

static hl_ev p_call(hl_em *em, hl_pfn f, hl_ev a, hl_ev b)
{
    pem *P = (pem *)em;
    jit *J = P->J;
    if ((f == HL_PFN_SIN || f == HL_PFN_COS) && fuse_sincos(P)) {
        if (!P->fused) {
            gcc_jit_rvalue *args[3] = {RP(a), gcc_jit_lvalue_get_address(J->loc[P->in->d], NULL),
                                       gcc_jit_lvalue_get_address(J->loc[P->in->x], NULL)};
            gcc_jit_block_add_eval(J->blk, NULL,
                                   gcc_jit_context_new_call(J->c, NULL, import_sincos(J), 3, args));
            P->fused = 1;
        }
        return ptr(val(J, f == HL_PFN_SIN ? P->in->d : P->in->x));
    }
    gcc_jit_rvalue *args[2] = {RP(a), RP(b)};
    int nargs = f == HL_PFN_POW || f == HL_PFN_ATAN2 ? 2 : 1;
    return ptr(gcc_jit_context_new_call(J->c, NULL, import_lib(J, f), nargs, args));
}

/* point rules keep nothing (keep and kept serve the recurrences) */
static void p_keep(hl_em *em, int slot, hl_ev v)
{
    (void)em, (void)slot, (void)v;
}
static hl_ev p_kept(hl_em *em, int slot)
{
    (void)slot;
    return ptr(gcc_jit_context_zero(PJ(em)->c, PJ(em)->dbl));
}

static const hl_em_ops point_ops = {
    p_num, p_coef, p_store,          p_add,  p_sub, p_mul, p_neg, p_div,
    p_fma, p_call, hl_conv_unrolled, p_keep, p_kept};

/* One instruction, as the interpreter (eval.c) computes it: its rule's
 * point value. */
static void emit(jit *J, const hl_instr *i)
{
    pem P = {.em = {&point_ops}, .J = J, .in = i};
    hl_rule_of(i->op)->point(&P.em);
}

typedef void (*jit_fn)(const double *in, double *out);
typedef long (*jit_iter_fn)(double *z, long n);
typedef long (*jit_watch_fn)(double *z, long n, double w0, double *dev);

/* Fresh locals of J->fun for the registers that are not constants. */
static void new_locals(jit *J, const char *prefix)
{
    const hl_tape *t = J->t;
    for (int r = 0; r < t->nregs; r++) {
        if (t->isconst[r])
            continue;
        char name[32];
        snprintf(name, sizeof name, "%s%d", prefix, r);
        J->loc[r] = gcc_jit_function_new_local(J->fun, NULL, J->dbl, name);
    }
}

static gcc_jit_lvalue *elem(jit *J, gcc_jit_rvalue *base, int i)
{
    gcc_jit_type *ity = gcc_jit_context_get_type(J->c, GCC_JIT_TYPE_INT);
    return gcc_jit_context_new_array_access(J->c, NULL, base,
                                            gcc_jit_context_new_rvalue_from_int(J->c, ity, i));
}

/* void hl_jit_eval(const double *in, double *out): the tape once. */
static void build_eval(jit *J)
{
    const hl_tape *t = J->t;
    gcc_jit_context *c = J->c;
    gcc_jit_type *cdblp = gcc_jit_type_get_pointer(gcc_jit_type_get_const(J->dbl));
    gcc_jit_param *prm[2] = {gcc_jit_context_new_param(c, NULL, cdblp, "in"),
                             gcc_jit_context_new_param(c, NULL, J->dblp, "out")};
    J->fun = gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED,
                                          gcc_jit_context_get_type(c, GCC_JIT_TYPE_VOID),
                                          "hl_jit_eval", 2, prm, 0);
    J->blk = gcc_jit_function_new_block(J->fun, "body");
    new_locals(J, "r");
    gcc_jit_rvalue *in = gcc_jit_param_as_rvalue(prm[0]), *out = gcc_jit_param_as_rvalue(prm[1]);
    /* all inputs are read before any output is written: in and out may alias */
    for (int r = 0; r < t->nin; r++)
        assign(J, r, gcc_jit_lvalue_as_rvalue(elem(J, in, r)));
    for (int k = 0; k < t->ncode; k++)
        emit(J, &t->code[k]);
    for (int j = 0; j < t->nout; j++)
        gcc_jit_block_add_assignment(J->blk, NULL, elem(J, out, j), val(J, t->outreg[j]));
    gcc_jit_block_end_with_void_return(J->blk, NULL);
}

/* Loop-carried calls.  An instruction on an input register that is fed
 * back (sin q) may have a twin, the same op on the register fed back to
 * that input (sin Q): from the second step on, its values are the twin's of
 * the step before, the same bits, and the call is not made again
 * (Stormer-Verlet's two kicks a step, Yoshida's shared forces). */
typedef struct carry {
    int i, twin;              /* instruction indices in t->code */
    gcc_jit_lvalue *d, *x;    /* the carried values (x: the aux, e.g. cos) */
} carry;

static int carried_op(int op)
{
    return op == HL_OP_POWK || (op >= HL_OP_SQRT && op <= HL_OP_ACOS);
}

/* The instructions whose values a loop can carry; nmap inputs fed back.
 * Marks the twins' registers read where the carried ones are. */
static carry *find_carries(jit *J, int nmap, int *n)
{
    const hl_tape *t = J->t;
    carry *cv = hl_xmalloc((size_t)(t->ncode + 1) * sizeof *cv);
    *n = 0;
    for (int k = 0; k < t->ncode; k++) {
        const hl_instr *i = &t->code[k];
        if (!carried_op(i->op) || i->a < 0 || i->a >= nmap || t->outreg[i->a] == i->a)
            continue;
        for (int k2 = 0; k2 < t->ncode; k2++) {
            const hl_instr *w = &t->code[k2];
            if (k2 == k || w->op != i->op || w->b != i->b || w->a != t->outreg[i->a])
                continue;
            J->read[w->d] |= J->read[i->d];
            if (w->x >= 0)
                J->read[w->x] |= J->read[i->x];
            cv[(*n)++] = (carry){k, k2, NULL, NULL};
            break;
        }
    }
    return cv;
}

static int carried(const carry *cv, int n, int k)
{
    for (int j = 0; j < n; j++)
        if (cv[j].i == k)
            return j;
    return -1;
}

/* The carried values from the step's start (entry), and into the body. */
static void carry_start(jit *J, carry *cv, int n)
{
    for (int j = 0; j < n; j++) {
        const hl_instr *i = &J->t->code[cv[j].i];
        emit(J, i);
        char name[32];
        snprintf(name, sizeof name, "cd%d", j);
        cv[j].d = gcc_jit_function_new_local(J->fun, NULL, J->dbl, name);
        gcc_jit_block_add_assignment(J->blk, NULL, cv[j].d, J->read[i->d] ? val(J, i->d)
                                                            : gcc_jit_context_zero(J->c, J->dbl));
        if (i->x >= 0) {
            snprintf(name, sizeof name, "cx%d", j);
            cv[j].x = gcc_jit_function_new_local(J->fun, NULL, J->dbl, name);
            gcc_jit_block_add_assignment(J->blk, NULL, cv[j].x,
                                         J->read[i->x] ? val(J, i->x)
                                                       : gcc_jit_context_zero(J->c, J->dbl));
        }
    }
}

static void carry_use(jit *J, const carry *c)
{
    const hl_instr *i = &J->t->code[c->i];
    if (J->read[i->d])
        assign(J, i->d, gcc_jit_lvalue_as_rvalue(c->d));
    if (i->x >= 0 && J->read[i->x])
        assign(J, i->x, gcc_jit_lvalue_as_rvalue(c->x));
}

/* At the end of a step kept: the twins' values for the next. */
static void carry_next(jit *J, gcc_jit_block *blk, const carry *cv, int n)
{
    for (int j = 0; j < n; j++) {
        const hl_instr *i = &J->t->code[cv[j].i], *w = &J->t->code[cv[j].twin];
        if (J->read[i->d])
            gcc_jit_block_add_assignment(blk, NULL, cv[j].d, val(J, w->d));
        if (i->x >= 0 && J->read[i->x])
            gcc_jit_block_add_assignment(blk, NULL, cv[j].x, val(J, w->x));
    }
}

/* long hl_jit_iter(double *z, long n): hl_tape_iterate as one loop, the
 * state in machine registers between steps.  A step is kept only if its
 * outputs are all finite: sum (y - y) is 0 exactly then, NaN otherwise.
 * With watch, long hl_jit_watch(double *z, long n, double w0, double *dev)
 * for hl_tape_iterate_watch: the last output is not fed back but
 * *dev = max(*dev, |w - w0|) is kept over the steps taken. */
static void build_loop(jit *J, int watch)
{
    const hl_tape *t = J->t;
    gcc_jit_context *c = J->c;
    gcc_jit_type *lng = gcc_jit_context_get_type(c, GCC_JIT_TYPE_LONG);
    gcc_jit_param *prm[4] = {gcc_jit_context_new_param(c, NULL, J->dblp, "z"),
                             gcc_jit_context_new_param(c, NULL, lng, "n"),
                             gcc_jit_context_new_param(c, NULL, J->dbl, "w0"),
                             gcc_jit_context_new_param(c, NULL, J->dblp, "dev")};
    J->fun = gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED, lng,
                                          watch ? "hl_jit_watch" : "hl_jit_iter", watch ? 4 : 2,
                                          prm, 0);
    new_locals(J, "s");
    /* In a loop the step's chain waits for sin q alone where H's cos q is
     * off it: sincos (23 ns here) would hold it longer than sin (19 ns),
     * and the separate cos overlaps (Euler with H watched, 10^6 pendulum
     * steps: 25.2 -> 23.6 ms).  Not in Newton's solve, where both are on
     * the chain (gauss3: 187 -> 204 ms with two calls). */
    J->split_sincos = 1;
    const int nmap = watch ? t->nout - 1 : t->nout;
    gcc_jit_lvalue *k = gcc_jit_function_new_local(J->fun, NULL, lng, "k");
    gcc_jit_lvalue *m = gcc_jit_function_new_local(J->fun, NULL, J->dbl, "m");
    gcc_jit_lvalue *e = gcc_jit_function_new_local(J->fun, NULL, J->dbl, "e");
    gcc_jit_lvalue **y = hl_xmalloc((size_t)t->nout * sizeof *y);
    for (int j = 0; j < t->nout; j++) {
        char name[32];
        snprintf(name, sizeof name, "y%d", j);
        y[j] = gcc_jit_function_new_local(J->fun, NULL, J->dbl, name);
    }
    gcc_jit_rvalue *z = gcc_jit_param_as_rvalue(prm[0]), *n = gcc_jit_param_as_rvalue(prm[1]);
    gcc_jit_block *entry = gcc_jit_function_new_block(J->fun, "entry");
    gcc_jit_block *cond = gcc_jit_function_new_block(J->fun, "cond");
    gcc_jit_block *body = gcc_jit_function_new_block(J->fun, "body");
    gcc_jit_block *latch = gcc_jit_function_new_block(J->fun, "latch");
    gcc_jit_block *done = gcc_jit_function_new_block(J->fun, "done");
    J->blk = entry;
    for (int r = 0; r < t->nin; r++)
        assign(J, r, gcc_jit_lvalue_as_rvalue(elem(J, z, r)));
    int ncarry;
    carry *cv = find_carries(J, nmap, &ncarry);
    carry_start(J, cv, ncarry);
    gcc_jit_block_add_assignment(entry, NULL, k, gcc_jit_context_zero(c, lng));
    if (watch)
        gcc_jit_block_add_assignment(entry, NULL, m,
                                     gcc_jit_lvalue_as_rvalue(gcc_jit_rvalue_dereference(
                                         gcc_jit_param_as_rvalue(prm[3]), NULL)));
    gcc_jit_block_end_with_jump(entry, NULL, cond);
    gcc_jit_block_end_with_conditional(
        cond, NULL,
        gcc_jit_context_new_comparison(c, NULL, GCC_JIT_COMPARISON_LT, gcc_jit_lvalue_as_rvalue(k),
                                       n),
        body, done);
    J->blk = body;
    for (int i = 0; i < t->ncode; i++) {
        int cj = carried(cv, ncarry, i);
        if (cj >= 0)
            carry_use(J, &cv[cj]);
        else
            emit(J, &t->code[i]);
    }
    gcc_jit_rvalue *acc = gcc_jit_context_zero(c, J->dbl);
    for (int j = 0; j < t->nout; j++) {
        gcc_jit_block_add_assignment(body, NULL, y[j], val(J, t->outreg[j]));
        gcc_jit_rvalue *yv = gcc_jit_lvalue_as_rvalue(y[j]);
        acc = gcc_jit_context_new_binary_op(
            c, NULL, GCC_JIT_BINARY_OP_PLUS, J->dbl, acc,
            gcc_jit_context_new_binary_op(c, NULL, GCC_JIT_BINARY_OP_MINUS, J->dbl, yv, yv));
    }
    gcc_jit_block_end_with_conditional(
        body, NULL,
        gcc_jit_context_new_comparison(c, NULL, GCC_JIT_COMPARISON_EQ, acc,
                                       gcc_jit_context_zero(c, J->dbl)),
        latch, done);
    gcc_jit_block *next = latch;
    if (watch) { /* e = |w - w0|; m = e > m ? e : m */
        gcc_jit_rvalue *w = gcc_jit_lvalue_as_rvalue(y[t->nout - 1]);
        gcc_jit_rvalue *dw = gcc_jit_context_new_binary_op(c, NULL, GCC_JIT_BINARY_OP_MINUS, J->dbl,
                                                           w, gcc_jit_param_as_rvalue(prm[2]));
        gcc_jit_function *fabs_ = gcc_jit_context_get_builtin_function(c, "__builtin_fabs");
        gcc_jit_block_add_assignment(latch, NULL, e,
                                     gcc_jit_context_new_call(c, NULL, fabs_, 1, &dw));
        gcc_jit_block *raise = gcc_jit_function_new_block(J->fun, "raise");
        next = gcc_jit_function_new_block(J->fun, "keep");
        gcc_jit_block_end_with_conditional(
            latch, NULL,
            gcc_jit_context_new_comparison(c, NULL, GCC_JIT_COMPARISON_GT,
                                           gcc_jit_lvalue_as_rvalue(e),
                                           gcc_jit_lvalue_as_rvalue(m)),
            raise, next);
        gcc_jit_block_add_assignment(raise, NULL, m, gcc_jit_lvalue_as_rvalue(e));
        gcc_jit_block_end_with_jump(raise, NULL, next);
    }
    carry_next(J, next, cv, ncarry);
    free(cv);
    for (int j = 0; j < nmap; j++)
        gcc_jit_block_add_assignment(next, NULL, J->loc[j], gcc_jit_lvalue_as_rvalue(y[j]));
    gcc_jit_block_add_assignment_op(next, NULL, k, GCC_JIT_BINARY_OP_PLUS,
                                    gcc_jit_context_one(c, lng));
    gcc_jit_block_end_with_jump(next, NULL, cond);
    for (int j = 0; j < nmap; j++)
        gcc_jit_block_add_assignment(done, NULL, elem(J, z, j),
                                     gcc_jit_lvalue_as_rvalue(J->loc[j]));
    if (watch)
        gcc_jit_block_add_assignment(
            done, NULL, gcc_jit_rvalue_dereference(gcc_jit_param_as_rvalue(prm[3]), NULL),
            gcc_jit_lvalue_as_rvalue(m));
    gcc_jit_block_end_with_return(done, NULL, gcc_jit_lvalue_as_rvalue(k));
    free(y);
}

/* The shapes hl_tape_iterate and hl_tape_iterate_watch accept. */
static int iter_shape(const hl_tape *t)
{
    return t->nout >= 1 && t->nout <= t->nin;
}
static int watch_shape(const hl_tape *t)
{
    return t->nout >= 2 && t->nout == t->nin;
}

/* Build the functions and compile them; NULL result on failure (message in
 * the context). */
/* NOTE: libgccjit runs GCC's driver in process, and the driver installs its
 * own handlers for SIGINT, SIGHUP, SIGTERM and SIGPIPE (GCC's fatal_signal,
 * which kills the process) and SIGCHLD, and leaves them there: a caller's
 * Ctrl-C handler (hamlie run stops cleanly on it) was gone after the first
 * compilation.  They are put back after each compilation; the signals that
 * stop a job are held meanwhile and reach the caller's handler after. */
static gcc_jit_result *compile(gcc_jit_context *c)
{
    static const int sigs[] = {SIGINT, SIGHUP, SIGTERM, SIGPIPE, SIGCHLD};
    enum { NSIGS = sizeof sigs / sizeof sigs[0] };
    struct sigaction saved[NSIGS];
    sigset_t hold, prev;
    sigemptyset(&hold);
    sigaddset(&hold, SIGINT);
    sigaddset(&hold, SIGHUP);
    sigaddset(&hold, SIGTERM);
    for (int i = 0; i < NSIGS; i++)
        sigaction(sigs[i], NULL, &saved[i]);
    pthread_sigmask(SIG_BLOCK, &hold, &prev);
    gcc_jit_result *res = gcc_jit_context_compile(c);
    for (int i = 0; i < NSIGS; i++)
        sigaction(sigs[i], &saved[i], NULL);
    pthread_sigmask(SIG_SETMASK, &prev, NULL);
    return res;
}

static gcc_jit_result *build(gcc_jit_context *c, const hl_tape *t)
{
    jit J = {.c = c, .t = t};
    J.dbl = gcc_jit_context_get_type(c, GCC_JIT_TYPE_DOUBLE);
    J.dblp = gcc_jit_type_get_pointer(J.dbl);
    J.sqrt = gcc_jit_context_get_builtin_function(c, "__builtin_sqrt");
    J.loc = hl_xcalloc((size_t)t->nregs + 1, sizeof *J.loc);
    J.read = registers_read(t);
    build_eval(&J);
    if (iter_shape(t))
        build_loop(&J, 0);
    if (watch_shape(t))
        build_loop(&J, 1);
    free(J.loc);
    free(J.read);
    return compile(c);
}

/* Extra options from $HL_JIT_FLAGS (space-separated), for experiments such
 * as -march=native (which may contract into FMA and so change results). */
static void add_env_flags(gcc_jit_context *c)
{
    const char *s = getenv("HL_JIT_FLAGS");
    if (s == NULL)
        return;
    char *copy = hl_xmalloc(strlen(s) + 1), *save = NULL;
    strcpy(copy, s);
    for (char *w = strtok_r(copy, " \t", &save); w != NULL; w = strtok_r(NULL, " \t", &save))
        gcc_jit_context_add_command_line_option(c, w); /* copies w */
    free(copy);
}

/* ---- Newton's method, compiled (hl_newton_jit) ---------------------------
 * int hl_jit_newton(const double *x, double *U, int *iters, double *last,
 *                   double *Z):
 * newton.c's hl_newton_solve as one function, the same operations in the
 * same order: the three tapes inlined (each with its own register locals),
 * U in locals, the LU factors in local arrays (partial pivoting indexes
 * them at run time); with an output tape, its last values in Z (newton.c's
 * zprev, so hl_newton_output reads them after either). */

typedef struct nj {
    gcc_jit_context *c;
    gcc_jit_function *fun;
    gcc_jit_type *dbl, *intt;
    jit T[4]; /* start, F, FJ, and Z (hl_newton_set_output) */
    gcc_jit_rvalue *x, *U, *iters, *last;
    gcc_jit_lvalue **u;                  /* m locals: the iterate */
    gcc_jit_lvalue *A, *b, *dinv, *piv;  /* local arrays */
    gcc_jit_lvalue *it, *fresh, *prev, *ratio, *dn, *un, *r, *tmp;
    gcc_jit_lvalue *zprev, *zd, *zs; /* with Z: its last values, move, size */
    gcc_jit_function *fabs_;
    int m, nx, ntapes;
    int nblk;
} nj;

static gcc_jit_rvalue *ND(nj *N, double v)
{
    return gcc_jit_context_new_rvalue_from_double(N->c, N->dbl, v);
}
static gcc_jit_rvalue *NI(nj *N, int v)
{
    return gcc_jit_context_new_rvalue_from_int(N->c, N->intt, v);
}
static gcc_jit_rvalue *RVL(gcc_jit_lvalue *l)
{
    return gcc_jit_lvalue_as_rvalue(l);
}
static gcc_jit_lvalue *AT(nj *N, gcc_jit_lvalue *arr, gcc_jit_rvalue *i)
{
    return gcc_jit_context_new_array_access(N->c, NULL, RVL(arr), i);
}
static gcc_jit_lvalue *ATI(nj *N, gcc_jit_lvalue *arr, int i)
{
    return AT(N, arr, NI(N, i));
}
static gcc_jit_rvalue *OP(nj *N, enum gcc_jit_binary_op op, gcc_jit_rvalue *a, gcc_jit_rvalue *b)
{
    return gcc_jit_context_new_binary_op(N->c, NULL, op, N->dbl, a, b);
}
static gcc_jit_rvalue *CMP(nj *N, enum gcc_jit_comparison op, gcc_jit_rvalue *a,
                           gcc_jit_rvalue *b)
{
    return gcc_jit_context_new_comparison(N->c, NULL, op, a, b);
}
static gcc_jit_rvalue *FABS(nj *N, gcc_jit_rvalue *a)
{
    return gcc_jit_context_new_call(N->c, NULL, N->fabs_, 1, &a);
}
static gcc_jit_block *BLK(nj *N)
{
    char name[32];
    snprintf(name, sizeof name, "b%d", N->nblk++);
    return gcc_jit_function_new_block(N->fun, name);
}
static void SET(gcc_jit_block *blk, gcc_jit_lvalue *l, gcc_jit_rvalue *v)
{
    gcc_jit_block_add_assignment(blk, NULL, l, v);
}

/* 0.0 exactly when every v[i] is finite (sum of v - v), else NaN */
static gcc_jit_rvalue *finite_sum(nj *N, gcc_jit_rvalue **v, int n)
{
    gcc_jit_rvalue *acc = ND(N, 0);
    for (int i = 0; i < n; i++)
        acc = OP(N, GCC_JIT_BINARY_OP_PLUS, acc, OP(N, GCC_JIT_BINARY_OP_MINUS, v[i], v[i]));
    return acc;
}

/* A block that writes U and returns status: the exits of the solve. */
static gcc_jit_block *exit_block(nj *N, int status)
{
    gcc_jit_block *e = BLK(N);
    for (int i = 0; i < N->m; i++)
        gcc_jit_block_add_assignment(
            e, NULL, gcc_jit_context_new_array_access(N->c, NULL, N->U, NI(N, i)), RVL(N->u[i]));
    gcc_jit_block_end_with_return(e, NULL, NI(N, status));
    return e;
}

/* Continue in a fresh block when cond holds, else go to fail. */
static gcc_jit_block *check(nj *N, gcc_jit_block *blk, gcc_jit_rvalue *cond, gcc_jit_block *fail)
{
    gcc_jit_block *ok = BLK(N);
    gcc_jit_block_end_with_conditional(blk, NULL, cond, ok, fail);
    return ok;
}

/* l = max(l, v) as the C code's ternary: if (v > l) l = v. */
static gcc_jit_block *raise_to(nj *N, gcc_jit_block *blk, gcc_jit_lvalue *l, gcc_jit_rvalue *v)
{
    gcc_jit_block *up = BLK(N), *next = BLK(N);
    gcc_jit_block_end_with_conditional(blk, NULL, CMP(N, GCC_JIT_COMPARISON_GT, v, RVL(l)), up,
                                       next);
    SET(up, l, v);
    gcc_jit_block_end_with_jump(up, NULL, next);
    return next;
}

/* Tape k inlined in blk: inputs x (and U when with_u); returns its outputs
 * (malloc'd array of rvalues). */
static gcc_jit_rvalue **inline_tape(nj *N, int k, gcc_jit_block *blk, int with_u)
{
    jit *J = &N->T[k];
    J->blk = blk;
    for (int i = 0; i < N->nx; i++)
        assign(J, i, RVL(gcc_jit_context_new_array_access(N->c, NULL, N->x, NI(N, i))));
    for (int i = 0; with_u && i < N->m; i++)
        assign(J, N->nx + i, RVL(N->u[i]));
    for (int i = 0; i < J->t->ncode; i++)
        emit(J, &J->t->code[i]);
    gcc_jit_rvalue **out = hl_xmalloc((size_t)J->t->nout * sizeof *out);
    for (int j = 0; j < J->t->nout; j++)
        out[j] = val(J, J->t->outreg[j]);
    /* the imports are shared by the tapes */
    for (int q = 0; q < N->ntapes && q < 4; q++)
        if (q != k) {
            memcpy(N->T[q].lib, J->lib, sizeof J->lib);
            N->T[q].sincos = J->sincos;
        }
    return out;
}

#define A_(i, j) AT(N, N->A, NI(N, (i) * m + (j)))

/* lu_factor of newton.c on the local array A; returns the block after it,
 * jumping to singular when a pivot is 0. */
static gcc_jit_block *build_lu(nj *N, gcc_jit_block *blk, gcc_jit_block *singular)
{
    int m = N->m;
    gcc_jit_rvalue *mm = NI(N, m);
    for (int c = 0; c < m; c++) {
        SET(blk, N->r, NI(N, c));
        for (int i = c + 1; i < m; i++) {
            /* r*m + c */
            gcc_jit_rvalue *rc = gcc_jit_context_new_binary_op(
                N->c, NULL, GCC_JIT_BINARY_OP_PLUS, N->intt,
                gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_MULT, N->intt,
                                              RVL(N->r), mm),
                NI(N, c));
            gcc_jit_block *up = BLK(N), *next = BLK(N);
            gcc_jit_block_end_with_conditional(
                blk, NULL,
                CMP(N, GCC_JIT_COMPARISON_GT, FABS(N, RVL(A_(i, c))), FABS(N, RVL(AT(N, N->A, rc)))),
                up, next);
            SET(up, N->r, NI(N, i));
            gcc_jit_block_end_with_jump(up, NULL, next);
            blk = next;
        }
        SET(blk, ATI(N, N->piv, c), RVL(N->r));
        gcc_jit_rvalue *rm = gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_MULT,
                                                           N->intt, RVL(N->r), mm);
        for (int j = 0; j < m; j++) {
            gcc_jit_lvalue *rj = AT(N, N->A, gcc_jit_context_new_binary_op(
                                                 N->c, NULL, GCC_JIT_BINARY_OP_PLUS, N->intt, rm,
                                                 NI(N, j)));
            SET(blk, N->tmp, RVL(rj));
            SET(blk, rj, RVL(A_(c, j)));
            SET(blk, A_(c, j), RVL(N->tmp));
        }
        blk = check(N, blk, CMP(N, GCC_JIT_COMPARISON_GT, FABS(N, RVL(A_(c, c))), ND(N, 0)),
                    singular);
        SET(blk, ATI(N, N->dinv, c), OP(N, GCC_JIT_BINARY_OP_DIVIDE, ND(N, 1), RVL(A_(c, c))));
        for (int i = c + 1; i < m; i++) {
            SET(blk, N->tmp, OP(N, GCC_JIT_BINARY_OP_MULT, RVL(A_(i, c)), RVL(ATI(N, N->dinv, c))));
            SET(blk, A_(i, c), RVL(N->tmp));
            for (int j = c + 1; j < m; j++)
                SET(blk, A_(i, j),
                    OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(A_(i, j)),
                       OP(N, GCC_JIT_BINARY_OP_MULT, RVL(N->tmp), RVL(A_(c, j)))));
        }
    }
    return blk;
}

/* lu_apply of newton.c: b = A^-1 b. */
static void build_apply(nj *N, gcc_jit_block *blk)
{
    int m = N->m;
    for (int c = 0; c < m; c++) {
        gcc_jit_lvalue *bp = AT(N, N->b, RVL(ATI(N, N->piv, c)));
        SET(blk, N->tmp, RVL(bp));
        SET(blk, bp, RVL(ATI(N, N->b, c)));
        SET(blk, ATI(N, N->b, c), RVL(N->tmp));
        for (int i = c + 1; i < m; i++)
            SET(blk, ATI(N, N->b, i),
                OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(ATI(N, N->b, i)),
                   OP(N, GCC_JIT_BINARY_OP_MULT, RVL(A_(i, c)), RVL(ATI(N, N->b, c)))));
    }
    for (int i = m - 1; i >= 0; i--) {
        SET(blk, N->tmp, RVL(ATI(N, N->b, i)));
        for (int j = i + 1; j < m; j++)
            SET(blk, N->tmp,
                OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(N->tmp),
                   OP(N, GCC_JIT_BINARY_OP_MULT, RVL(A_(i, j)), RVL(ATI(N, N->b, j)))));
        SET(blk, ATI(N, N->b, i), OP(N, GCC_JIT_BINARY_OP_MULT, RVL(N->tmp), RVL(ATI(N, N->dinv, i))));
    }
}

#undef A_

static void build_newton(nj *N, const hl_newton *nw)
{
    gcc_jit_context *c = N->c;
    int m = nw->m;
    gcc_jit_type *cdblp = gcc_jit_type_get_pointer(gcc_jit_type_get_const(N->dbl));
    gcc_jit_type *dblp = gcc_jit_type_get_pointer(N->dbl);
    gcc_jit_param *prm[5] = {gcc_jit_context_new_param(c, NULL, cdblp, "x"),
                             gcc_jit_context_new_param(c, NULL, dblp, "U"),
                             gcc_jit_context_new_param(c, NULL, gcc_jit_type_get_pointer(N->intt),
                                                       "iters"),
                             gcc_jit_context_new_param(c, NULL, dblp, "last"),
                             gcc_jit_context_new_param(c, NULL, dblp, "Z")};
    N->fun = gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED, N->intt,
                                          "hl_jit_newton", 5, prm, 0);
    N->x = gcc_jit_param_as_rvalue(prm[0]), N->U = gcc_jit_param_as_rvalue(prm[1]);
    N->iters = gcc_jit_param_as_rvalue(prm[2]), N->last = gcc_jit_param_as_rvalue(prm[3]);
    static const char *prefix[4] = {"s", "f", "j", "z"};
    for (int k = 0; k < N->ntapes; k++) {
        N->T[k].fun = N->fun;
        new_locals(&N->T[k], prefix[k]);
    }
    N->u = hl_xmalloc((size_t)m * sizeof *N->u);
    for (int i = 0; i < m; i++) {
        char name[32];
        snprintf(name, sizeof name, "u%d", i);
        N->u[i] = gcc_jit_function_new_local(N->fun, NULL, N->dbl, name);
    }
    gcc_jit_type *amm = gcc_jit_context_new_array_type(c, NULL, N->dbl, m * m);
    gcc_jit_type *am = gcc_jit_context_new_array_type(c, NULL, N->dbl, m);
    gcc_jit_type *ai = gcc_jit_context_new_array_type(c, NULL, N->intt, m);
    N->A = gcc_jit_function_new_local(N->fun, NULL, amm, "A");
    N->b = gcc_jit_function_new_local(N->fun, NULL, am, "bv");
    N->dinv = gcc_jit_function_new_local(N->fun, NULL, am, "dinv");
    N->piv = gcc_jit_function_new_local(N->fun, NULL, ai, "piv");
    N->it = gcc_jit_function_new_local(N->fun, NULL, N->intt, "it");
    N->fresh = gcc_jit_function_new_local(N->fun, NULL, N->intt, "fresh");
    N->r = gcc_jit_function_new_local(N->fun, NULL, N->intt, "r");
    N->prev = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "prev");
    N->ratio = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "ratio");
    N->dn = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "dn");
    N->un = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "un");
    N->tmp = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "tmp");
    if (nw->Z != NULL) {
        N->zprev = gcc_jit_param_as_lvalue(prm[4]);
        N->zd = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "zd");
        N->zs = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "zs");
    }
    gcc_jit_lvalue *iters = gcc_jit_rvalue_dereference(N->iters, NULL);
    gcc_jit_lvalue *last = gcc_jit_rvalue_dereference(N->last, NULL);

    /* entry: U0 = start(x) */
    gcc_jit_block *blk = BLK(N);
    SET(blk, iters, NI(N, 0));
    SET(blk, last, ND(N, INFINITY));
    gcc_jit_rvalue **u0 = inline_tape(N, 0, blk, 0);
    for (int i = 0; i < m; i++)
        SET(blk, N->u[i], u0[i]);
    free(u0);
    gcc_jit_rvalue **uv = hl_xmalloc((size_t)m * sizeof *uv);
    for (int i = 0; i < m; i++)
        uv[i] = RVL(N->u[i]);
    blk = check(N, blk, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, uv, m), ND(N, 0)),
                exit_block(N, HL_NEWTON_START));
    if (nw->Z != NULL) { /* Z at the start */
        gcc_jit_rvalue **z0 = inline_tape(N, 3, blk, 1);
        for (int i = 0; i < nw->nz; i++)
            SET(blk, ATI(N, N->zprev, i), z0[i]);
        free(z0);
    }
    SET(blk, N->prev, ND(N, INFINITY));
    SET(blk, N->ratio, ND(N, 0));
    SET(blk, N->fresh, NI(N, 0));
    SET(blk, N->it, NI(N, 0));
    gcc_jit_block *loop = BLK(N), *nonfinite = exit_block(N, HL_NEWTON_NONFINITE);
    gcc_jit_block_end_with_jump(blk, NULL, loop);

    /* loop: it < max_iter, else no convergence */
    blk = check(N, loop, gcc_jit_context_new_comparison(c, NULL, GCC_JIT_COMPARISON_LT,
                                                        RVL(N->it), NI(N, nw->max_iter)),
                exit_block(N, HL_NEWTON_NOCONV));
    gcc_jit_block_add_assignment_op(blk, NULL, N->it, GCC_JIT_BINARY_OP_PLUS, NI(N, 1));
    SET(blk, iters, RVL(N->it));
    gcc_jit_rvalue *refresh = gcc_jit_context_new_binary_op(
        c, NULL, GCC_JIT_BINARY_OP_LOGICAL_OR, gcc_jit_context_get_type(c, GCC_JIT_TYPE_BOOL),
        gcc_jit_context_new_comparison(c, NULL, GCC_JIT_COMPARISON_EQ, RVL(N->it), NI(N, 1)),
        gcc_jit_context_new_binary_op(
            c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND, gcc_jit_context_get_type(c, GCC_JIT_TYPE_BOOL),
            gcc_jit_context_new_comparison(c, NULL, GCC_JIT_COMPARISON_EQ, RVL(N->fresh), NI(N, 0)),
            gcc_jit_context_new_binary_op(
                c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND,
                gcc_jit_context_get_type(c, GCC_JIT_TYPE_BOOL),
                CMP(N, GCC_JIT_COMPARISON_LT, RVL(N->prev), ND(N, INFINITY)),
                CMP(N, GCC_JIT_COMPARISON_GT, RVL(N->ratio), ND(N, HL_NEWTON_REFRESH)))));
    gcc_jit_block *jac = BLK(N), *plain = BLK(N), *after = BLK(N);
    gcc_jit_block_end_with_conditional(blk, NULL, refresh, jac, plain);

    /* F and J, factored */
    gcc_jit_rvalue **fj = inline_tape(N, 2, jac, 1);
    for (int i = 0; i < m; i++)
        SET(jac, ATI(N, N->b, i), gcc_jit_context_new_unary_op(c, NULL, GCC_JIT_UNARY_OP_MINUS,
                                                               N->dbl, fj[i]));
    for (int i = 0; i < m * m; i++)
        SET(jac, ATI(N, N->A, i), fj[m + i]);
    gcc_jit_rvalue **av = hl_xmalloc((size_t)(m * m + m) * sizeof *av);
    for (int i = 0; i < m * m; i++)
        av[i] = RVL(ATI(N, N->A, i));
    jac = check(N, jac, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, av, m * m), ND(N, 0)),
                nonfinite);
    jac = build_lu(N, jac, exit_block(N, HL_NEWTON_SINGULAR));
    SET(jac, N->fresh, NI(N, 1));
    /* F finite (its values are in b, negated) */
    for (int i = 0; i < m; i++)
        av[i] = fj[i];
    jac = check(N, jac, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, av, m), ND(N, 0)), nonfinite);
    gcc_jit_block_end_with_jump(jac, NULL, after);
    free(fj);

    /* F alone */
    gcc_jit_rvalue **fv = inline_tape(N, 1, plain, 1);
    for (int i = 0; i < m; i++)
        SET(plain, ATI(N, N->b, i), gcc_jit_context_new_unary_op(c, NULL, GCC_JIT_UNARY_OP_MINUS,
                                                                 N->dbl, fv[i]));
    SET(plain, N->fresh, NI(N, 0));
    plain = check(N, plain, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, fv, m), ND(N, 0)),
                  nonfinite);
    gcc_jit_block_end_with_jump(plain, NULL, after);
    free(fv);

    /* the correction */
    build_apply(N, after);
    SET(after, N->dn, ND(N, 0));
    SET(after, N->un, ND(N, 1));
    blk = after;
    for (int i = 0; i < m; i++) {
        SET(blk, N->u[i], OP(N, GCC_JIT_BINARY_OP_PLUS, RVL(N->u[i]), RVL(ATI(N, N->b, i))));
        blk = raise_to(N, blk, N->dn, FABS(N, RVL(ATI(N, N->b, i))));
        blk = raise_to(N, blk, N->un, FABS(N, RVL(N->u[i])));
    }
    blk = check(N, blk, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, uv, m), ND(N, 0)), nonfinite);
    SET(blk, last, RVL(N->dn));
    /* ratio = prev < inf && prev > 0 ? dn / prev : 0 */
    gcc_jit_block *div = BLK(N), *zero = BLK(N), *conv = BLK(N);
    gcc_jit_block_end_with_conditional(
        blk, NULL,
        gcc_jit_context_new_binary_op(c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND,
                                      gcc_jit_context_get_type(c, GCC_JIT_TYPE_BOOL),
                                      CMP(N, GCC_JIT_COMPARISON_LT, RVL(N->prev), ND(N, INFINITY)),
                                      CMP(N, GCC_JIT_COMPARISON_GT, RVL(N->prev), ND(N, 0))),
        div, zero);
    SET(div, N->ratio, OP(N, GCC_JIT_BINARY_OP_DIVIDE, RVL(N->dn), RVL(N->prev)));
    gcc_jit_block_end_with_jump(div, NULL, conv);
    SET(zero, N->ratio, ND(N, 0));
    gcc_jit_block_end_with_jump(zero, NULL, conv);
    /* the move: of U (dn, un), or of Z (zd, zs: newton.c's output_move) */
    gcc_jit_lvalue *mv = N->dn, *sz = N->un;
    if (nw->Z != NULL) {
        gcc_jit_rvalue **zv = inline_tape(N, 3, conv, 1);
        SET(conv, N->zd, ND(N, 0));
        SET(conv, N->zs, ND(N, 1));
        for (int i = 0; i < nw->nz; i++) {
            SET(conv, N->tmp, zv[i]);
            conv = raise_to(N, conv, N->zd,
                            FABS(N, OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(N->tmp),
                                       RVL(ATI(N, N->zprev, i)))));
            conv = raise_to(N, conv, N->zs, FABS(N, RVL(N->tmp)));
            SET(conv, ATI(N, N->zprev, i), RVL(N->tmp));
        }
        free(zv);
        mv = N->zd, sz = N->zs;
    }
    /* converged: move <= 4 eps size || (move <= 1e-12 size && ratio >= 0.5) */
    gcc_jit_type *boolt = gcc_jit_context_get_type(c, GCC_JIT_TYPE_BOOL);
    gcc_jit_rvalue *done = gcc_jit_context_new_binary_op(
        c, NULL, GCC_JIT_BINARY_OP_LOGICAL_OR, boolt,
        CMP(N, GCC_JIT_COMPARISON_LE, RVL(mv),
            OP(N, GCC_JIT_BINARY_OP_MULT, ND(N, 4 * DBL_EPSILON), RVL(sz))),
        gcc_jit_context_new_binary_op(
            c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND, boolt,
            CMP(N, GCC_JIT_COMPARISON_LE, RVL(mv),
                OP(N, GCC_JIT_BINARY_OP_MULT, ND(N, 1e-12), RVL(sz))),
            CMP(N, GCC_JIT_COMPARISON_GE, RVL(N->ratio), ND(N, 0.5))));
    gcc_jit_block *again = BLK(N);
    gcc_jit_block_end_with_conditional(conv, NULL, done, exit_block(N, HL_NEWTON_OK), again);
    SET(again, N->prev, RVL(N->dn));
    gcc_jit_block_end_with_jump(again, NULL, loop);
    free(uv), free(av), free(N->u);
}

hl_status hl_newton_jit(hl_newton *nw, hl_error *err)
{
    if (nw->m > 16)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "compiled Newton: %d unknowns (at most 16)", nw->m);
    gcc_jit_context *c = gcc_jit_context_acquire();
    if (c == NULL)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit cannot start");
    gcc_jit_context_set_int_option(c, GCC_JIT_INT_OPTION_OPTIMIZATION_LEVEL, 2);
    gcc_jit_context_set_bool_option(c, GCC_JIT_BOOL_OPTION_DEBUGINFO, 0);
    gcc_jit_context_set_bool_print_errors_to_stderr(c, 0);
    gcc_jit_context_add_command_line_option(c, "-ffp-contract=off");
    add_env_flags(c);
    nj N = {.c = c, .m = nw->m, .nx = nw->nx, .ntapes = nw->Z != NULL ? 4 : 3};
    N.dbl = gcc_jit_context_get_type(c, GCC_JIT_TYPE_DOUBLE);
    N.intt = gcc_jit_context_get_type(c, GCC_JIT_TYPE_INT);
    N.fabs_ = gcc_jit_context_get_builtin_function(c, "__builtin_fabs");
    hl_tape *tapes[4] = {nw->start, nw->F, nw->FJ, nw->Z};
    for (int k = 0; k < N.ntapes; k++) {
        jit *J = &N.T[k];
        J->c = c, J->t = tapes[k], J->dbl = N.dbl, J->dblp = gcc_jit_type_get_pointer(N.dbl);
        J->sqrt = gcc_jit_context_get_builtin_function(c, "__builtin_sqrt");
        J->loc = hl_xcalloc((size_t)tapes[k]->nregs + 1, sizeof *J->loc);
        J->read = registers_read(tapes[k]);
    }
    build_newton(&N, nw);
    for (int k = 0; k < N.ntapes; k++)
        free(N.T[k].loc), free(N.T[k].read);
    gcc_jit_result *res = compile(c);
    void *fn = res != NULL ? gcc_jit_result_get_code(res, "hl_jit_newton") : NULL;
    int status = HL_OK;
    if (fn == NULL) {
        const char *why = gcc_jit_context_get_first_error(c);
        status = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit failed on Newton%s%s",
                              why ? ": " : "", why ? why : "");
        if (res != NULL)
            gcc_jit_result_release(res);
    }
    gcc_jit_context_release(c);
    if (status != HL_OK)
        return status;
    hl_newton_jit_clear(nw);
    nw->jit_result = res;
    *(void **)&nw->jit_fn = fn;
    return HL_OK;
}

hl_status hl_tape_jit(hl_tape *t, hl_error *err)
{
    gcc_jit_context *c = gcc_jit_context_acquire();
    if (c == NULL)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit cannot start");
    gcc_jit_context_set_int_option(c, GCC_JIT_INT_OPTION_OPTIMIZATION_LEVEL, 2);
    gcc_jit_context_set_bool_option(c, GCC_JIT_BOOL_OPTION_DEBUGINFO, 0);
    /* its diagnostics are not ours to print; the first comes back in err */
    gcc_jit_context_set_bool_print_errors_to_stderr(c, 0);
    gcc_jit_context_add_command_line_option(c, "-ffp-contract=off");
    add_env_flags(c);
    gcc_jit_result *res = build(c, t);
    jit_fn fn = NULL;
    jit_iter_fn iter = NULL;
    jit_watch_fn watch = NULL;
    if (res != NULL) {
        *(void **)&fn = gcc_jit_result_get_code(res, "hl_jit_eval");
        if (iter_shape(t))
            *(void **)&iter = gcc_jit_result_get_code(res, "hl_jit_iter");
        if (watch_shape(t))
            *(void **)&watch = gcc_jit_result_get_code(res, "hl_jit_watch");
    }
    int status = HL_OK;
    if (fn == NULL) {
        const char *why = gcc_jit_context_get_first_error(c);
        status = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit failed on the tape%s%s",
                              why ? ": " : "", why ? why : "");
        if (res != NULL)
            gcc_jit_result_release(res);
    }
    /* the result owns the code; the context is no longer needed */
    gcc_jit_context_release(c);
    if (status != HL_OK)
        return status;
    hl_tape_jit_clear(t);
    t->jit_result = res;
    t->jit_fn = fn;
    t->jit_iter = iter;
    t->jit_watch = watch;
    return HL_OK;
}

void hl_tape_jit_clear(hl_tape *t)
{
    if (t->jit_result != NULL)
        gcc_jit_result_release(t->jit_result);
    t->jit_result = NULL;
    t->jit_fn = NULL;
    t->jit_iter = NULL;
    t->jit_watch = NULL;
}

int hl_tape_jit_available(void)
{
    return 1;
}

#if defined(__SANITIZE_ADDRESS__)
/* libgccjit keeps some 5-10 kB of compiler state per compilation that
 * gcc_jit_context_release and gcc_jit_result_release do not free; in
 * sanitizer builds LeakSanitizer would fail every program that compiles a
 * tape.  Only allocations made inside libgccjit are suppressed. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libgccjit.so\nleak:libfontconfig.so\n";
}
#endif

#else /* no libgccjit */

hl_status hl_newton_jit(hl_newton *nw, hl_error *err)
{
    (void)nw;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "hamlie was built without libgccjit");
}

hl_status hl_tape_jit(hl_tape *t, hl_error *err)
{
    (void)t;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "hamlie was built without libgccjit");
}

void hl_tape_jit_clear(hl_tape *t)
{
    (void)t;
}

int hl_tape_jit_available(void)
{
    return 0;
}

#endif

int hl_tape_jit_active(const hl_tape *t)
{
    return t->jit_fn != NULL;
}

int hl_newton_jit_active(const hl_newton *nw)
{
    return nw->jit_fn != NULL;
}

void hl_newton_jit_clear(hl_newton *nw)
{
#ifdef HAMLIE_HAVE_GCCJIT
    if (nw->jit_result != NULL)
        gcc_jit_result_release(nw->jit_result);
#endif
    nw->jit_result = NULL;
    nw->jit_fn = NULL;
}

/* Figures from bench/tape_jit.c (gcc 12, -O2, x86-64): compile time
 * 25 ms + 0.1 ms per instruction; interpreter about 2.8 ns and compiled
 * code about 0.4 ns per instruction and evaluation. */
long hl_tape_jit_breakeven(const hl_tape *t)
{
    if (!hl_tape_jit_available() || t->ncode == 0)
        return LONG_MAX;
    double compile_ns = 25e6 + 1e5 * t->ncode, gain_ns = 2.4 * t->ncode;
    return (long)(compile_ns / gain_ns);
}

static int all_finite(const double *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

long hl_tape_iterate(double *in, long n, hl_tape *t)
{
    if (t->nout < 1 || t->nout > t->nin)
        return -1;
    if (n <= 0)
        return 0;
    if (t->jit_iter != NULL)
        return t->jit_iter(in, n);
    double *y = hl_xmalloc((size_t)t->nout * sizeof *y);
    long k = 0;
    for (; k < n; k++) {
        hl_tape_eval_d(y, in, t);
        if (!all_finite(y, t->nout))
            break;
        memcpy(in, y, (size_t)t->nout * sizeof *y);
    }
    free(y);
    return k;
}

long hl_tape_iterate_watch(double *in, long n, double w0, double *dev, hl_tape *t)
{
    if (t->nout < 2 || t->nout != t->nin)
        return -1;
    if (n <= 0)
        return 0;
    if (t->jit_watch != NULL)
        return t->jit_watch(in, n, w0, dev);
    const int nmap = t->nout - 1;
    double *y = hl_xmalloc((size_t)t->nout * sizeof *y);
    long k = 0;
    for (; k < n; k++) {
        hl_tape_eval_d(y, in, t);
        if (!all_finite(y, t->nout))
            break;
        double e = fabs(y[nmap] - w0);
        if (e > *dev)
            *dev = e;
        memcpy(in, y, (size_t)nmap * sizeof *y);
    }
    free(y);
    return k;
}
