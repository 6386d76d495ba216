/* Machine code for a tape's double evaluation, through libgccjit (opt-in;
 * see hl_tape_jit in hamlie/tape.h).
 *
 * The interpreter pays a dispatch, and a load and a store through the
 * register file, for every instruction.  The tape is a straight-line
 * program, so it translates one to one into a C-like function body: one
 * local per register, constants as immediates, libm calls where the
 * interpreter calls libm.  GCC then keeps the values in machine registers
 * and schedules the arithmetic.  The results are bitwise the interpreter's
 * (jit_common.c says how).
 *
 * Built here: hl_jit_eval (hl_tape_eval_d), hl_jit_iter and hl_jit_watch
 * (hl_tape_iterate[_watch]: the map iterated in one loop, so that a
 * fixed-step run pays no call and no copy per step), and the emitter of
 * one instruction that jit_newton.c also uses.  Without libgccjit
 * hl_tape_jit reports HL_EUNSUP and hl_tape_iterate runs the interpreter.
 * When compiling pays: cost.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "rules/unroll.h"
#include "tape/jit_cache_impl.h"
#include "tape/jit_impl.h"
#include "tape/tape_impl.h"

#ifdef HAMLIE_HAVE_GCCJIT

unsigned char *hl_jit_registers_read(const hl_tape *t)
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

gcc_jit_rvalue *hl_jit_val(jit *J, int r)
{
    if (J->t->isconst[r])
        return gcc_jit_context_new_rvalue_from_double(J->c, J->dbl, J->t->rd[r]);
    return gcc_jit_lvalue_as_rvalue(J->loc[r]);
}

void hl_jit_assign(jit *J, int d, gcc_jit_rvalue *v)
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
    return ptr(hl_jit_val(PJ(em), slot_reg(((pem *)em)->in, s)));
}

static void p_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    pem *P = (pem *)em;
    int r = slot_reg(P->in, s);
    (void)j;
    if (P->J->read[r] && !(P->fused && (s == HL_SLOT_D || s == HL_SLOT_X)))
        hl_jit_assign(P->J, r, RP(v));
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
            gcc_jit_block_add_eval(
                J->blk, NULL,
                gcc_jit_context_new_call(J->c, NULL, hl_jit_import_sincos(J), 3, args));
            P->fused = 1;
        }
        return ptr(hl_jit_val(J, f == HL_PFN_SIN ? P->in->d : P->in->x));
    }
    gcc_jit_rvalue *args[2] = {RP(a), RP(b)};
    int nargs = f == HL_PFN_POW || f == HL_PFN_ATAN2 ? 2 : 1;
    return ptr(gcc_jit_context_new_call(J->c, NULL, hl_jit_import_lib(J, f), nargs, args));
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
void hl_jit_emit(jit *J, const hl_instr *i)
{
    pem P = {.em = {&point_ops}, .J = J, .in = i};
    hl_rule_of(i->op)->point(&P.em);
}

void hl_jit_new_locals(jit *J, const char *prefix)
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
    hl_jit_new_locals(J, "r");
    gcc_jit_rvalue *in = gcc_jit_param_as_rvalue(prm[0]), *out = gcc_jit_param_as_rvalue(prm[1]);
    /* all inputs are read before any output is written: in and out may alias */
    for (int r = 0; r < t->nin; r++)
        hl_jit_assign(J, r, gcc_jit_lvalue_as_rvalue(elem(J, in, r)));
    for (int k = 0; k < t->ncode; k++)
        hl_jit_emit(J, &t->code[k]);
    for (int j = 0; j < t->nout; j++)
        gcc_jit_block_add_assignment(J->blk, NULL, elem(J, out, j), hl_jit_val(J, t->outreg[j]));
    gcc_jit_block_end_with_void_return(J->blk, NULL);
}

/* Loop-carried calls.  An instruction on an input register that is fed
 * back (sin q) may have a twin, the same op on the register fed back to
 * that input (sin Q): from the second step on, its values are the twin's of
 * the step before, the same bits, and the call is not made again
 * (Stormer-Verlet's two kicks a step, Yoshida's shared forces). */
static int carried_op(int op)
{
    return op == HL_OP_POWK || op == HL_OP_POW3H || (op >= HL_OP_SQRT && op <= HL_OP_ACOS);
}

/* The instructions whose values a loop can carry; nmap inputs fed back.
 * Marks the twins' registers read where the carried ones are. */
carry *hl_jit_find_carries(const hl_tape *t, unsigned char *read, int nmap, int *n)
{
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
            read[w->d] |= read[i->d];
            if (w->x >= 0)
                read[w->x] |= read[i->x];
            cv[(*n)++] = (carry){k, k2, NULL, NULL};
            break;
        }
    }
    return cv;
}

int hl_jit_carried(const carry *cv, int n, int k)
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
        hl_jit_emit(J, i);
        char name[32];
        snprintf(name, sizeof name, "cd%d", j);
        cv[j].d = gcc_jit_function_new_local(J->fun, NULL, J->dbl, name);
        gcc_jit_block_add_assignment(J->blk, NULL, cv[j].d,
                                     J->read[i->d] ? hl_jit_val(J, i->d)
                                                   : gcc_jit_context_zero(J->c, J->dbl));
        if (i->x >= 0) {
            snprintf(name, sizeof name, "cx%d", j);
            cv[j].x = gcc_jit_function_new_local(J->fun, NULL, J->dbl, name);
            gcc_jit_block_add_assignment(J->blk, NULL, cv[j].x,
                                         J->read[i->x] ? hl_jit_val(J, i->x)
                                                       : gcc_jit_context_zero(J->c, J->dbl));
        }
    }
}

static void carry_use(jit *J, const carry *c)
{
    const hl_instr *i = &J->t->code[c->i];
    if (J->read[i->d])
        hl_jit_assign(J, i->d, gcc_jit_lvalue_as_rvalue(c->d));
    if (i->x >= 0 && J->read[i->x])
        hl_jit_assign(J, i->x, gcc_jit_lvalue_as_rvalue(c->x));
}

/* At the end of a step kept: the twins' values for the next. */
static void carry_next(jit *J, gcc_jit_block *blk, const carry *cv, int n)
{
    for (int j = 0; j < n; j++) {
        const hl_instr *i = &J->t->code[cv[j].i], *w = &J->t->code[cv[j].twin];
        if (J->read[i->d])
            gcc_jit_block_add_assignment(blk, NULL, cv[j].d, hl_jit_val(J, w->d));
        if (i->x >= 0 && J->read[i->x])
            gcc_jit_block_add_assignment(blk, NULL, cv[j].x, hl_jit_val(J, w->x));
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
    J->fun =
        gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED, lng,
                                     watch ? "hl_jit_watch" : "hl_jit_iter", watch ? 4 : 2, prm, 0);
    hl_jit_new_locals(J, "s");
    /* NOTE: in a loop the step's chain often waits for sin q alone while
     * cos q (in H, watched) is off it: sincos is slower than sin and would
     * hold the chain, where a separate cos overlaps with the next step.
     * Not in Newton's solve, where both are on the chain and one sincos
     * is cheaper than two calls. */
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
        hl_jit_assign(J, r, gcc_jit_lvalue_as_rvalue(elem(J, z, r)));
    int ncarry;
    carry *cv = hl_jit_find_carries(J->t, J->read, nmap, &ncarry);
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
        int cj = hl_jit_carried(cv, ncarry, i);
        if (cj >= 0)
            carry_use(J, &cv[cj]);
        else
            hl_jit_emit(J, &t->code[i]);
    }
    gcc_jit_rvalue *acc = gcc_jit_context_zero(c, J->dbl);
    for (int j = 0; j < t->nout; j++) {
        gcc_jit_block_add_assignment(body, NULL, y[j], hl_jit_val(J, t->outreg[j]));
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

/* The functions the tape's shape allows, in context c (hl_jit_build_fn). */
static void build(gcc_jit_context *c, const void *arg)
{
    const hl_tape *t = arg;
    jit J = {0};
    hl_jit_init(&J, c, t);
    J.loc = hl_xcalloc((size_t)t->nregs + 1, sizeof *J.loc);
    J.read = hl_jit_registers_read(t);
    build_eval(&J);
    if (iter_shape(t))
        build_loop(&J, 0);
    if (watch_shape(t))
        build_loop(&J, 1);
    free(J.loc);
    free(J.read);
}

hl_status hl_tape_jit(hl_tape *t, hl_error *err)
{
    hl_buf inputs;
    hl_buf_init(&inputs);
    hl_jit_inputs_tape(&inputs, t);
    hl_jit_code *code;
    hl_status st =
        hl_jit_obtain(&code, HL_JIT_SITE_EVAL, &inputs, build, t, "hl_jit_eval", "the tape", err);
    hl_buf_clear(&inputs);
    if (st != HL_OK)
        return st;
    hl_tape_jit_clear(t);
    t->jit_result = code;
    *(void **)&t->jit_fn = hl_jit_code_sym(code, "hl_jit_eval");
    if (iter_shape(t))
        *(void **)&t->jit_iter = hl_jit_code_sym(code, "hl_jit_iter");
    if (watch_shape(t))
        *(void **)&t->jit_watch = hl_jit_code_sym(code, "hl_jit_watch");
    return HL_OK;
}

void hl_tape_jit_clear(hl_tape *t)
{
    hl_jit_code_free(t->jit_result);
    t->jit_result = NULL;
    t->jit_fn = NULL;
    t->jit_iter = NULL;
    t->jit_watch = NULL;
}

#else /* no libgccjit */

hl_status hl_tape_jit(hl_tape *t, hl_error *err)
{
    (void)t;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "hamlie was built without libgccjit");
}

void hl_tape_jit_clear(hl_tape *t)
{
    (void)t;
}

#endif

int hl_tape_jit_active(const hl_tape *t)
{
    return t->jit_fn != NULL;
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
