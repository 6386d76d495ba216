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
 * whole simplified Newton solve of newton.c, three tapes inlined) and, for
 * hl_tape_native in native.c, the Taylor-ODE recursion at one order.  Without libgccjit at build time
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
#include "tape/tape_impl.h"

#ifdef HAMLIE_HAVE_GCCJIT
#include <libgccjit.h>

/* The libm functions the ops call, by op; NULL where the op is arithmetic. */
static const char *const libm_name[HL_OP_COUNT] = {
    [HL_OP_POWK] = "pow",      [HL_OP_EXP] = "exp",       [HL_OP_LOG] = "log",
    [HL_OP_SINCOS] = "sincos", [HL_OP_SINHCOSH] = "sinh", [HL_OP_TAN] = "tan",
    [HL_OP_TANH] = "tanh",     [HL_OP_ATAN] = "atan",     [HL_OP_ASIN] = "asin",
    [HL_OP_ACOS] = "acos",     [HL_OP_ATAN2] = "atan2",
};

typedef struct jit {
    gcc_jit_context *c;
    gcc_jit_type *dbl, *dblp;
    gcc_jit_block *blk;
    gcc_jit_function *fun;
    gcc_jit_lvalue **loc; /* one local per non-constant register */
    gcc_jit_function *lib[HL_OP_COUNT];
    gcc_jit_function *cosh, *sqrt, *sin, *cos;
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

static gcc_jit_function *import_lib(jit *J, int op)
{
    if (J->lib[op] != NULL)
        return J->lib[op];
    if (op == HL_OP_POWK || op == HL_OP_ATAN2) { /* pow(x, y), atan2(y, x) */
        gcc_jit_param *p[2] = {gcc_jit_context_new_param(J->c, NULL, J->dbl, "u"),
                               gcc_jit_context_new_param(J->c, NULL, J->dbl, "v")};
        J->lib[op] = gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED, J->dbl,
                                                  libm_name[op], 2, p, 0);
    } else if (op == HL_OP_SINCOS) {
        gcc_jit_param *p[3] = {gcc_jit_context_new_param(J->c, NULL, J->dbl, "x"),
                               gcc_jit_context_new_param(J->c, NULL, J->dblp, "s"),
                               gcc_jit_context_new_param(J->c, NULL, J->dblp, "c")};
        J->lib[op] = gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED,
                                                  gcc_jit_context_get_type(J->c, GCC_JIT_TYPE_VOID),
                                                  "sincos", 3, p, 0);
    } else
        J->lib[op] = import1(J, libm_name[op]);
    return J->lib[op];
}

/* The value of register r: an immediate for a constant, else its local. */
static gcc_jit_rvalue *val(jit *J, int r)
{
    if (J->t->isconst[r])
        return gcc_jit_context_new_rvalue_from_double(J->c, J->dbl, J->t->rd[r]);
    return gcc_jit_lvalue_as_rvalue(J->loc[r]);
}

static gcc_jit_rvalue *binop(jit *J, enum gcc_jit_binary_op op, int a, int b)
{
    return gcc_jit_context_new_binary_op(J->c, NULL, op, J->dbl, val(J, a), val(J, b));
}

static gcc_jit_rvalue *call1(jit *J, gcc_jit_function *f, int a)
{
    gcc_jit_rvalue *x = val(J, a);
    return gcc_jit_context_new_call(J->c, NULL, f, 1, &x);
}

static void assign(jit *J, int d, gcc_jit_rvalue *v)
{
    gcc_jit_block_add_assignment(J->blk, NULL, J->loc[d], v);
}

/* One instruction, as the interpreter (eval.c) computes it. */
static void emit(jit *J, const hl_instr *i)
{
    gcc_jit_rvalue *v = NULL;
    switch ((hl_op)i->op) {
    case HL_OP_NEG:
        v = gcc_jit_context_new_unary_op(J->c, NULL, GCC_JIT_UNARY_OP_MINUS, J->dbl, val(J, i->a));
        break;
    case HL_OP_ADD:
    case HL_OP_ADDK:
        v = binop(J, GCC_JIT_BINARY_OP_PLUS, i->a, i->b);
        break;
    case HL_OP_SUB:
    case HL_OP_SUBK:
        v = binop(J, GCC_JIT_BINARY_OP_MINUS, i->a, i->b);
        break;
    case HL_OP_KSUB:
        v = binop(J, GCC_JIT_BINARY_OP_MINUS, i->b, i->a);
        break;
    case HL_OP_MUL:
    case HL_OP_MULK:
        v = binop(J, GCC_JIT_BINARY_OP_MULT, i->a, i->b);
        break;
    case HL_OP_DIV:
    case HL_OP_DIVK:
        v = binop(J, GCC_JIT_BINARY_OP_DIVIDE, i->a, i->b);
        break;
    case HL_OP_KDIV:
        v = binop(J, GCC_JIT_BINARY_OP_DIVIDE, i->b, i->a);
        break;
    case HL_OP_SQR:
        v = binop(J, GCC_JIT_BINARY_OP_MULT, i->a, i->a);
        break;
    case HL_OP_POWK:
    case HL_OP_ATAN2: {
        gcc_jit_rvalue *args[2] = {val(J, i->a), val(J, i->b)};
        v = gcc_jit_context_new_call(J->c, NULL, import_lib(J, i->op), 2, args);
        break;
    }
    case HL_OP_SQRT:
        v = call1(J, J->sqrt, i->a);
        break;
    case HL_OP_SINCOS: {
        /* sin or cos alone when the other is not read (the compiler makes
         * every sin a SINCOS, for Taylor mode): glibc's sincos computes
         * each as sin and cos do, so the bits are the same */
        if (!J->read[i->x] || !J->read[i->d] || J->split_sincos) {
            if (J->sin == NULL)
                J->sin = import1(J, "sin"), J->cos = import1(J, "cos");
            if (J->read[i->d])
                assign(J, i->d, call1(J, J->sin, i->a));
            if (J->read[i->x])
                assign(J, i->x, call1(J, J->cos, i->a));
            return;
        }
        gcc_jit_rvalue *args[3] = {val(J, i->a), gcc_jit_lvalue_get_address(J->loc[i->d], NULL),
                                   gcc_jit_lvalue_get_address(J->loc[i->x], NULL)};
        gcc_jit_block_add_eval(J->blk, NULL,
                               gcc_jit_context_new_call(J->c, NULL, import_lib(J, i->op), 3, args));
        return;
    }
    case HL_OP_SINHCOSH:
        assign(J, i->d, call1(J, import_lib(J, i->op), i->a));
        if (J->cosh == NULL)
            J->cosh = import1(J, "cosh");
        v = call1(J, J->cosh, i->a);
        assign(J, i->x, v);
        return;
    case HL_OP_EXP:
    case HL_OP_LOG:
    case HL_OP_TAN:
    case HL_OP_TANH:
    case HL_OP_ATAN:
    case HL_OP_ASIN:
    case HL_OP_ACOS:
        v = call1(J, import_lib(J, i->op), i->a);
        break;
    case HL_OP_COUNT:
        return;
    }
    assign(J, i->d, v);
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

/* The vector instructions of the machine that runs the code (libgccjit
 * does not understand -march=native).  Contraction into FMA stays off, so
 * the results are those of plain SSE2 code; the wider registers let GCC
 * pair the recurrences' independent products (bench/taylor_flow.c: Kepler's
 * recursion 30% faster with AVX-512). */
static int add_host_isa(gcc_jit_context *c)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    int v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
             __builtin_cpu_supports("bmi2");
    int v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
    if (v4)
        gcc_jit_context_add_command_line_option(c, "-march=x86-64-v4");
    else if (v3)
        gcc_jit_context_add_command_line_option(c, "-march=x86-64-v3");
    return v3; /* FMA instructions */
#else
    (void)c;
    return 0;
#endif
}

/* ---- the Taylor-ODE recursion (hl_tape_native's backend) ------------------
 * The same straight-line program native.c prints as C, built as trees: every
 * sum balanced in the same way, every operation in the same order, so both
 * backends give the same coefficients. */

typedef struct tj {
    jit J;
    gcc_jit_rvalue *R; /* the register file, the function's parameter */
    int S;             /* stride: order + 1 */
    gcc_jit_rvalue **term; /* a sum's terms known a round ago */
    int n, cap;
    gcc_jit_rvalue *fresh[2]; /* and those that read coefficient k (j = 0, k) */
    int fresh_reg[2], nfresh;
    const char *fname[16]; /* the libm functions imported so far */
    gcc_jit_function *fimp[16];
    int nf;
    gcc_jit_lvalue **inv; /* by instruction: 1 / its divisor's coefficient 0 */
    gcc_jit_lvalue **inv2; /* DIV, KDIV: d[0] / that divisor */
    gcc_jit_lvalue **coef; /* the locals of the coefficients (RL) */
    int fma;               /* the machine code may use FMA instructions */
    int *def;              /* by register: the instruction that writes it, or -1 */
} tj;

/* Coefficient j of register reg: constants are read from the register
 * file R (read only); every other coefficient is a local, so that GCC need
 * not assume that a store through R changes what it has loaded (the
 * recurrences are load-bound); the inputs' coefficients go back to R at the
 * end. */
static gcc_jit_lvalue *RL(tj *T, int reg, int j)
{
    if (T->J.t->isconst[reg]) {
        gcc_jit_type *lng = gcc_jit_context_get_type(T->J.c, GCC_JIT_TYPE_LONG);
        return gcc_jit_context_new_array_access(
            T->J.c, NULL, T->R,
            gcc_jit_context_new_rvalue_from_long(T->J.c, lng, (long)reg * T->S + j));
    }
    gcc_jit_lvalue **l = &T->coef[(long)reg * T->S + j];
    if (*l == NULL) {
        char name[32];
        snprintf(name, sizeof name, "c%d_%d", reg, j);
        *l = gcc_jit_function_new_local(T->J.fun, NULL, T->J.dbl, name);
    }
    return *l;
}
static gcc_jit_rvalue *RV(tj *T, int reg, int j)
{
    return gcc_jit_lvalue_as_rvalue(RL(T, reg, j));
}
/* R[reg * S + j] itself */
static gcc_jit_lvalue *RMEM(tj *T, int reg, int j)
{
    gcc_jit_type *lng = gcc_jit_context_get_type(T->J.c, GCC_JIT_TYPE_LONG);
    return gcc_jit_context_new_array_access(
        T->J.c, NULL, T->R, gcc_jit_context_new_rvalue_from_long(T->J.c, lng, (long)reg * T->S + j));
}
static gcc_jit_rvalue *NUM(tj *T, double x)
{
    return gcc_jit_context_new_rvalue_from_double(T->J.c, T->J.dbl, x);
}
static gcc_jit_rvalue *BIN(tj *T, enum gcc_jit_binary_op op, gcc_jit_rvalue *a, gcc_jit_rvalue *b)
{
    return gcc_jit_context_new_binary_op(T->J.c, NULL, op, T->J.dbl, a, b);
}
#define ADD_(a, b) BIN(T, GCC_JIT_BINARY_OP_PLUS, a, b)
#define SUB_(a, b) BIN(T, GCC_JIT_BINARY_OP_MINUS, a, b)
#define MUL_(a, b) BIN(T, GCC_JIT_BINARY_OP_MULT, a, b)
#define DIV_(a, b) BIN(T, GCC_JIT_BINARY_OP_DIVIDE, a, b)
static gcc_jit_rvalue *NEG_(tj *T, gcc_jit_rvalue *a)
{
    return gcc_jit_context_new_unary_op(T->J.c, NULL, GCC_JIT_UNARY_OP_MINUS, T->J.dbl, a);
}

/* A term is fresh when it reads a coefficient k computed in this round
 * (j = 0 or j = k in a convolution); the others were known a round ago.
 * fresh: the register whose coefficient k the term reads, else -1. */
static void tterm(tj *T, gcc_jit_rvalue *v, int fresh)
{
    if (fresh >= 0 && T->nfresh < 2) { /* a convolution has at most two */
        T->fresh[T->nfresh] = v;
        T->fresh_reg[T->nfresh++] = fresh;
        return;
    }
    if (T->n == T->cap) {
        T->cap = T->cap ? 2 * T->cap : 64;
        T->term = hl_xrealloc(T->term, (size_t)T->cap * sizeof *T->term);
    }
    T->term[T->n++] = v;
}

static gcc_jit_rvalue *tsum_range(tj *T, int lo, int hi)
{
    if (hi - lo == 1)
        return T->term[lo];
    int mid = (lo + hi) / 2;
    return ADD_(tsum_range(T, lo, mid), tsum_range(T, mid, hi));
}

/* The collected terms as native.c's sum: the known terms as a balanced
 * tree, then the fresh ones added one by one, the one computed last (the
 * higher register) last, so that the chain from one order to the next
 * goes through one multiplication and one addition per instruction rather
 * than through the whole tree; 0.0 if there are none. */
static gcc_jit_rvalue *tsum(tj *T)
{
    gcc_jit_rvalue *v = T->n == 0 ? NULL : tsum_range(T, 0, T->n);
    if (T->nfresh == 2 && T->fresh_reg[0] > T->fresh_reg[1]) {
        gcc_jit_rvalue *f = T->fresh[0];
        T->fresh[0] = T->fresh[1], T->fresh[1] = f;
    }
    for (int i = 0; i < T->nfresh; i++)
        v = v == NULL ? T->fresh[i] : ADD_(v, T->fresh[i]);
    T->n = T->nfresh = 0;
    return v == NULL ? NUM(T, 0.0) : v;
}

/* which register's coefficient k the term x[j] y[k-j] reads, or -1 */
static int fresh_of(int x, int y, int j, int k)
{
    return j == k ? x : j == 0 ? y : -1;
}

static void tconv(tj *T, int x, int y, int lo, int hi, int k)
{
    for (int j = lo; j <= hi; j++)
        tterm(T, MUL_(RV(T, x, j), RV(T, y, k - j)), fresh_of(x, y, j, k));
}

/* (w x[j]) y[k-j]; for the fresh x[k] (w y[0]) x[k], one product on the
 * chain */
static void twconv(tj *T, int x, int y, int lo, int hi, int k, int wa, int wb)
{
    for (int j = lo; j <= hi; j++) {
        gcc_jit_rvalue *w = NUM(T, wa * j + wb);
        gcc_jit_rvalue *v = j == k && k > 0 ? MUL_(MUL_(w, RV(T, y, k - j)), RV(T, x, j))
                                            : MUL_(MUL_(w, RV(T, x, j)), RV(T, y, k - j));
        tterm(T, v, fresh_of(x, y, j, k));
    }
}

/* the terms j = lo..k-lo of (x*x)[k], using symmetry */
static void tsqr_from(tj *T, int x, int k, int lo)
{
    for (int j = lo; 2 * j < k; j++)
        tterm(T, MUL_(MUL_(NUM(T, 2.0), RV(T, x, j)), RV(T, x, k - j)), j == 0 ? x : -1);
    if (k % 2 == 0 && k / 2 >= lo)
        tterm(T, MUL_(RV(T, x, k / 2), RV(T, x, k / 2)), k == 0 ? x : -1);
}

static void tsqr(tj *T, int x, int k)
{
    tsqr_from(T, x, k, 0);
}

static gcc_jit_rvalue *tcall(tj *T, const char *name, gcc_jit_rvalue *x)
{
    gcc_jit_function *f = NULL;
    if (strcmp(name, "sqrt") == 0)
        f = T->J.sqrt;
    for (int i = 0; i < T->nf && f == NULL; i++)
        if (strcmp(T->fname[i], name) == 0)
            f = T->fimp[i];
    if (f == NULL) { /* at most the 11 functions of temit */
        f = import1(&T->J, name);
        T->fname[T->nf] = name;
        T->fimp[T->nf++] = f;
    }
    return gcc_jit_context_new_call(T->J.c, NULL, f, 1, &x);
}

static void tset(tj *T, int reg, int k, gcc_jit_rvalue *v)
{
    gcc_jit_block_add_assignment(T->J.blk, NULL, RL(T, reg, k), v);
}

/* The recurrences divide every coefficient by the same coefficient 0 of a
 * series (and by k): at k = 0 its reciprocal is kept in a local, and later
 * coefficients multiply by it and by the constant 1/k.  A division costs
 * 4-5 times a multiplication and lies on the chain from one order to the
 * next; the result differs from the quotient by an ulp or two. */
static void keep_inverse(tj *T, int i, gcc_jit_rvalue *divisor)
{
    char name[32];
    snprintf(name, sizeof name, "inv%d", i);
    T->inv[i] = gcc_jit_function_new_local(T->J.fun, NULL, T->J.dbl, name);
    gcc_jit_block_add_assignment(T->J.blk, NULL, T->inv[i], DIV_(NUM(T, 1.0), divisor));
}
static gcc_jit_rvalue *INV(tj *T, int i)
{
    return gcc_jit_lvalue_as_rvalue(T->inv[i]);
}
/* DIV and KDIV: d[0] times that reciprocal, so that the fresh term b[k] d[0]
 * of d[k] = (a[k] - sum_j b[j] d[k-j]) / b[0] enters as b[k] (d[0]/b[0]):
 * one product and one subtraction on the chain */
static void keep_ratio(tj *T, int i, gcc_jit_rvalue *d0)
{
    char name[32];
    snprintf(name, sizeof name, "rat%d", i);
    T->inv2[i] = gcc_jit_function_new_local(T->J.fun, NULL, T->J.dbl, name);
    gcc_jit_block_add_assignment(T->J.blk, NULL, T->inv2[i], MUL_(d0, INV(T, i)));
}
static gcc_jit_rvalue *RATIO(tj *T, int i)
{
    return gcc_jit_lvalue_as_rvalue(T->inv2[i]);
}
/* v / k as v * (1/k) */
static gcc_jit_rvalue *OVER_K(tj *T, gcc_jit_rvalue *v, int k)
{
    return MUL_(v, NUM(T, 1.0 / k));
}

/* One instruction (number i) at coefficient k: native.c's gen_instr, as
 * trees. */
static void temit(tj *T, const hl_instr *in, int i, int k)
{
    const int d = in->d, a = in->a, b = in->b, x = in->x, op = in->op;
    const double K = k;
    switch (op) {
    case HL_OP_NEG:
        tset(T, d, k, NEG_(T, RV(T, a, k)));
        return;
    case HL_OP_ADD:
        tset(T, d, k, ADD_(RV(T, a, k), RV(T, b, k)));
        return;
    case HL_OP_SUB:
        tset(T, d, k, SUB_(RV(T, a, k), RV(T, b, k)));
        return;
    case HL_OP_MUL: {
        int w = hl_tape_sqrt_times_(T->J.t, T->def, in);
        if (w >= 0) { /* sqrt(w) w as w^(3/2): see hl_tape_sqrt_times_ */
            if (k == 0) {
                tconv(T, a, b, 0, 0, 0);
                tset(T, d, 0, tsum(T));
                keep_inverse(T, i, RV(T, w, 0));
                keep_ratio(T, i, MUL_(NUM(T, 1.5), RV(T, d, 0)));
                return;
            }
            for (int m = 1; m < k; m++)
                tterm(T, MUL_(MUL_(NUM(T, 2.5 * m - k), RV(T, w, m)), RV(T, d, k - m)), -1);
            tset(T, d, k,
                 ADD_(OVER_K(T, MUL_(tsum(T), INV(T, i)), k), MUL_(RV(T, w, k), RATIO(T, i))));
            return;
        }
        tconv(T, a, b, 0, k, k);
        tset(T, d, k, tsum(T));
        return;
    }
    case HL_OP_SQR:
        tsqr(T, a, k);
        tset(T, d, k, tsum(T));
        return;
    case HL_OP_DIV:
        if (k == 0) {
            tset(T, d, k, DIV_(RV(T, a, 0), RV(T, b, 0)));
            keep_inverse(T, i, RV(T, b, 0));
            keep_ratio(T, i, RV(T, d, 0));
            return;
        }
        tconv(T, b, d, 1, k - 1, k); /* the known terms */
        tset(T, d, k,
             SUB_(MUL_(SUB_(RV(T, a, k), tsum(T)), INV(T, i)), MUL_(RV(T, b, k), RATIO(T, i))));
        return;
    case HL_OP_ADDK:
    case HL_OP_SUBK:
    case HL_OP_KSUB:
        if (k == 0 && op == HL_OP_KSUB)
            tset(T, d, k, SUB_(RV(T, b, 0), RV(T, a, 0)));
        else if (k == 0)
            tset(T, d, k,
                 op == HL_OP_ADDK ? ADD_(RV(T, a, 0), RV(T, b, 0))
                                  : SUB_(RV(T, a, 0), RV(T, b, 0)));
        else
            tset(T, d, k, op == HL_OP_KSUB ? NEG_(T, RV(T, a, k)) : RV(T, a, k));
        return;
    case HL_OP_MULK:
        tset(T, d, k, MUL_(RV(T, a, k), RV(T, b, 0)));
        return;
    case HL_OP_DIVK:
        tset(T, d, k, DIV_(RV(T, a, k), RV(T, b, 0)));
        return;
    case HL_OP_KDIV:
        if (k == 0) {
            tset(T, d, k, DIV_(RV(T, b, 0), RV(T, a, 0)));
            keep_inverse(T, i, RV(T, a, 0));
            keep_ratio(T, i, RV(T, d, 0));
            return;
        }
        tconv(T, a, d, 1, k - 1, k); /* the known terms */
        tset(T, d, k,
             SUB_(MUL_(NEG_(T, tsum(T)), INV(T, i)), MUL_(RV(T, a, k), RATIO(T, i))));
        return;
    case HL_OP_POWK:
        if (k == 0) {
            gcc_jit_rvalue *args[2] = {RV(T, a, 0), RV(T, b, 0)};
            tset(T, d, k,
                 gcc_jit_context_new_call(T->J.c, NULL, import_lib(&T->J, HL_OP_POWK), 2, args));
            keep_inverse(T, i, RV(T, a, 0));
            return;
        }
        for (int m = 1; m <= k; m++)
            tterm(T,
                  MUL_(MUL_(SUB_(MUL_(ADD_(RV(T, b, 0), NUM(T, 1.0)), NUM(T, m)), NUM(T, K)),
                            RV(T, a, m)),
                       RV(T, d, k - m)),
                  m == k ? a : -1);
        tset(T, d, k, OVER_K(T, MUL_(tsum(T), INV(T, i)), k));
        return;
    case HL_OP_SQRT:
        if (k == 0) {
            tset(T, d, k, tcall(T, "sqrt", RV(T, a, 0)));
            keep_inverse(T, i, MUL_(NUM(T, 2.0), RV(T, d, 0)));
            return;
        }
        tsqr_from(T, d, k, 1);
        tset(T, d, k, MUL_(SUB_(RV(T, a, k), tsum(T)), INV(T, i)));
        return;
    case HL_OP_EXP:
        if (k == 0) {
            tset(T, d, k, tcall(T, "exp", RV(T, a, 0)));
            return;
        }
        twconv(T, a, d, 1, k, k, 1, 0);
        tset(T, d, k, OVER_K(T, tsum(T), k));
        return;
    case HL_OP_LOG:
        if (k == 0) {
            tset(T, d, k, tcall(T, "log", RV(T, a, 0)));
            keep_inverse(T, i, RV(T, a, 0));
            return;
        }
        twconv(T, a, d, 1, k - 1, k, -1, k);
        tset(T, d, k,
             OVER_K(T, MUL_(SUB_(MUL_(NUM(T, K), RV(T, a, k)), tsum(T)), INV(T, i)), k));
        return;
    case HL_OP_SINCOS:
    case HL_OP_SINHCOSH: {
        int trig = op == HL_OP_SINCOS;
        if (k == 0) {
            tset(T, d, 0, tcall(T, trig ? "sin" : "sinh", RV(T, a, 0)));
            tset(T, x, 0, tcall(T, trig ? "cos" : "cosh", RV(T, a, 0)));
            return;
        }
        twconv(T, a, x, 1, k, k, 1, 0);
        tset(T, d, k, OVER_K(T, tsum(T), k));
        twconv(T, a, d, 1, k, k, 1, 0);
        gcc_jit_rvalue *s = tsum(T);
        tset(T, x, k, OVER_K(T, trig ? NEG_(T, s) : s, k));
        return;
    }
    case HL_OP_TAN:
    case HL_OP_TANH: {
        int tn = op == HL_OP_TAN;
        if (k == 0) {
            tset(T, d, 0, tcall(T, tn ? "tan" : "tanh", RV(T, a, 0)));
        } else {
            twconv(T, a, x, 1, k, k, 1, 0);
            gcc_jit_rvalue *q = OVER_K(T, tsum(T), k);
            tset(T, d, k, tn ? ADD_(RV(T, a, k), q) : SUB_(RV(T, a, k), q));
        }
        tsqr(T, d, k);
        tset(T, x, k, tsum(T));
        return;
    }
    case HL_OP_ATAN:
    case HL_OP_ASIN:
    case HL_OP_ACOS:
        /* first the aux series x, then d */
        if (op == HL_OP_ATAN) {
            tconv(T, a, a, 0, k, k);
            gcc_jit_rvalue *s = tsum(T);
            tset(T, x, k, k == 0 ? ADD_(NUM(T, 1.0), s) : s);
        } else if (k == 0) {
            tset(T, x, 0, tcall(T, "sqrt", SUB_(NUM(T, 1.0), MUL_(RV(T, a, 0), RV(T, a, 0)))));
        } else {
            tconv(T, a, a, 0, k, k);
            gcc_jit_rvalue *s1 = tsum(T);
            tconv(T, x, x, 1, k - 1, k);
            gcc_jit_rvalue *s2 = tsum(T);
            tset(T, x, k, MUL_(MUL_(SUB_(NEG_(T, s1), s2), INV(T, i)), NUM(T, 0.5)));
        }
        if (k == 0) {
            tset(T, d, 0,
                 tcall(T,
                       op == HL_OP_ATAN   ? "atan"
                       : op == HL_OP_ASIN ? "asin"
                                          : "acos",
                       RV(T, a, 0)));
            keep_inverse(T, i, RV(T, x, 0));
            return;
        }
        twconv(T, x, d, 1, k - 1, k, -1, k);
        tset(T, d, k,
             OVER_K(T,
                    MUL_(SUB_(MUL_(NUM(T, op == HL_OP_ACOS ? -K : K), RV(T, a, k)), tsum(T)),
                         INV(T, i)),
                    k));
        return;
    case HL_OP_ATAN2: { /* x = a^2 + b^2 first, then d */
        tconv(T, a, a, 0, k, k);
        tconv(T, b, b, 0, k, k);
        tset(T, x, k, tsum(T));
        if (k == 0) {
            gcc_jit_rvalue *args[2] = {RV(T, a, 0), RV(T, b, 0)};
            tset(T, d, 0,
                 gcc_jit_context_new_call(T->J.c, NULL, import_lib(&T->J, HL_OP_ATAN2), 2, args));
            keep_inverse(T, i, RV(T, x, 0));
            return;
        }
        twconv(T, a, b, 1, k, k, 1, 0);
        gcc_jit_rvalue *g1 = tsum(T);
        twconv(T, b, a, 1, k, k, 1, 0);
        gcc_jit_rvalue *g2 = tsum(T);
        twconv(T, x, d, 1, k - 1, k, -1, k);
        tset(T, d, k, OVER_K(T, MUL_(SUB_(SUB_(g1, g2), tsum(T)), INV(T, i)), k));
        return;
    }
    }
}

/* f / n as fma(f, r_hi, f r_lo) with r_hi + r_lo = 1/n to twice double
 * precision (hl_tape_recip_split): the quotient rounded once, so the bits
 * of the division (but for f/n within 2^-105 of a rounding boundary), in a
 * multiplication and an FMA (8 cycles) instead of a division (13-14) on
 * the chain from one order to the next.  f * fl(1/n) alone is not enough:
 * 1/n's rounding error has a fixed sign and drifts the phase (the
 * oscillator's energy error at t = 1e4 grows tenfold).  Without FMA in the
 * machine (fma would be a call), the division. */
static gcc_jit_rvalue *over_k1(tj *T, gcc_jit_rvalue *f, int n)
{
    double hi, lo;
    hl_tape_recip_split(&hi, &lo, n);
    if (lo == 0)
        return MUL_(f, NUM(T, hi)); /* n a power of 2: exact */
    if (!T->fma)
        return DIV_(f, NUM(T, n));
    gcc_jit_function *fma_ = gcc_jit_context_get_builtin_function(T->J.c, "__builtin_fma");
    gcc_jit_rvalue *args[3] = {f, NUM(T, hi), MUL_(f, NUM(T, lo))};
    return gcc_jit_context_new_call(T->J.c, NULL, fma_, 3, args);
}

int hl_tape_jit_taylor(void **result, void (**fn)(double *R), const hl_tape *t, int order,
                       hl_error *err)
{
    gcc_jit_context *c = gcc_jit_context_acquire();
    if (c == NULL)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit cannot start");
    /* -O1 as native.c: -O2's scheduling costs much compile time on these
     * long blocks for little gain */
    gcc_jit_context_set_int_option(c, GCC_JIT_INT_OPTION_OPTIMIZATION_LEVEL, 1);
    gcc_jit_context_set_bool_option(c, GCC_JIT_BOOL_OPTION_DEBUGINFO, 0);
    gcc_jit_context_set_bool_print_errors_to_stderr(c, 0);
    gcc_jit_context_add_command_line_option(c, "-ffp-contract=off");
    int fma = add_host_isa(c);
    add_env_flags(c);
    tj Tv = {.J = {.c = c, .t = t}, .S = order + 1, .fma = fma}, *T = &Tv;
    T->J.dbl = gcc_jit_context_get_type(c, GCC_JIT_TYPE_DOUBLE);
    T->J.dblp = gcc_jit_type_get_pointer(T->J.dbl);
    T->J.sqrt = gcc_jit_context_get_builtin_function(c, "__builtin_sqrt");
    gcc_jit_param *prm = gcc_jit_context_new_param(c, NULL, T->J.dblp, "R");
    T->J.fun = gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED,
                                            gcc_jit_context_get_type(c, GCC_JIT_TYPE_VOID),
                                            "hl_native", 1, &prm, 0);
    T->R = gcc_jit_param_as_rvalue(prm);
    T->J.blk = gcc_jit_function_new_block(T->J.fun, "body");
    T->def = hl_tape_defs_(t);
    T->inv = hl_xcalloc((size_t)t->ncode + 1, sizeof *T->inv);
    T->inv2 = hl_xcalloc((size_t)t->ncode + 1, sizeof *T->inv2);
    T->coef = hl_xcalloc((size_t)t->nregs * (size_t)T->S, sizeof *T->coef);
    for (int i = 0; i < t->nin; i++)
        tset(T, i, 0, gcc_jit_lvalue_as_rvalue(RMEM(T, i, 0)));
    for (int k = 0; k < order; k++) {
        for (int i = 0; i < t->ncode; i++)
            temit(T, &t->code[i], i, k);
        for (int i = 0; i < t->nin; i++)
            tset(T, i, k + 1, over_k1(T, RV(T, t->outreg[i], k), k + 1));
    }
    for (int i = 0; i < t->nin; i++)
        for (int k = 1; k <= order; k++)
            gcc_jit_block_add_assignment(T->J.blk, NULL, RMEM(T, i, k), RV(T, i, k));
    gcc_jit_block_end_with_void_return(T->J.blk, NULL);
    free(T->term);
    free(T->inv);
    free(T->inv2);
    free(T->def);
    free(T->coef);
    gcc_jit_result *res = compile(c);
    void *f = res ? gcc_jit_result_get_code(res, "hl_native") : NULL;
    int status = HL_OK;
    if (f == NULL) {
        const char *why = gcc_jit_context_get_first_error(c);
        status = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit failed on the recursion%s%s",
                              why ? ": " : "", why ? why : "");
        if (res)
            gcc_jit_result_release(res);
    }
    gcc_jit_context_release(c);
    if (status != HL_OK)
        return status;
    *result = res;
    *(void **)fn = f;
    return HL_OK;
}

void hl_tape_jit_release(void *result)
{
    if (result != NULL)
        gcc_jit_result_release(result);
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
            N->T[q].cosh = J->cosh, N->T[q].sin = J->sin, N->T[q].cos = J->cos;
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

int hl_tape_jit_taylor(void **result, void (**fn)(double *R), const hl_tape *t, int order,
                       hl_error *err)
{
    (void)result, (void)fn, (void)t, (void)order;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "hamlie was built without libgccjit");
}

void hl_tape_jit_release(void *result)
{
    (void)result;
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
