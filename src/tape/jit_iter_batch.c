/* hl_tape_iterate_watch for several members at once (tape.h,
 * hl_tape_iter_batch): the loop of jit_eval.c's build_loop with every value
 * a GCC vector of L doubles, one member per lane, compiled through the
 * disk cache; without compiled code the lanes step one after the other
 * through the interpreter, with the same results.
 *
 * Bitwise: a vector's +, -, *, / and negation are the scalar operations
 * lane by lane, so each lane computes what the scalar loop computes for
 * its member, to the last bit; what libgccjit has no vector form of (fma,
 * libm's functions, fabs) runs lane by lane on the lanes' own scalars, read
 * through the vector's address (as jit_taylor.c's lanes do).  A call is
 * made only where its value is stored into a register that something
 * reads, as in the scalar loop, so no lane pays for sin q when only cos q
 * is read.
 *
 * All lanes step together: the loop stops before the first step at which
 * some lane's outputs are not all finite, so that no lane takes a step
 * that the scalar loop would not take; the caller (src/run/batch.c) then
 * finds which lane it was and lets the others go on.
 *
 * NOTE: the loop-carried calls (sin Q of one step is sin q of the next,
 * Störmer–Verlet's two kicks) are found as jit_eval.c's hl_jit_find_carries finds
 * them; the search is repeated here rather than shared so that the scalar
 * loop's file stays as it is. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "rules/unroll.h"
#include "tape/jit_cache_impl.h"
#include "tape/jit_impl.h"
#include "tape/tape_impl.h"

struct hl_tape_iter_batch {
    hl_tape *t;
    int lanes;
    double *z;  /* nin * lanes, z[i * lanes + l], aligned to a vector */
    double *y;  /* the interpreter's outputs, nout * lanes */
    double *in; /* one lane's inputs, for the interpreter */
    void *code; /* the compiled loop (an hl_jit_code), or NULL */
    long (*fn)(double *z, long n, const double *w0, double *dev);
};

#ifdef HAMLIE_HAVE_GCCJIT

/* ---- the point rules over vectors --------------------------------------------- */

typedef struct lem {
    hl_em em;
    gcc_jit_context *c;
    gcc_jit_type *dbl, *dblp, *vt; /* vt: a vector of L doubles */
    int L;
    gcc_jit_function *fun;
    gcc_jit_block *blk;
    const hl_tape *t;
    const hl_instr *in;
    gcc_jit_lvalue **loc; /* by register: its local (vt), NULL for constants */
    unsigned char *read;  /* by register: read by an instruction or an output */
    gcc_jit_function *lib[HL_PFN_COUNT];
    int ntmp;
} lem;

static lem *LE(hl_em *em)
{
    return (lem *)em;
}
static hl_ev ev(gcc_jit_rvalue *r)
{
    return (hl_ev){.p = r};
}
static gcc_jit_rvalue *RV(hl_ev v)
{
    return v.p;
}

/* x in every lane */
static gcc_jit_rvalue *splat(lem *E, double x)
{
    gcc_jit_rvalue *d = gcc_jit_context_new_rvalue_from_double(E->c, E->dbl, x);
    gcc_jit_rvalue *els[HL_TAPE_BATCH_MAX_LANES];
    for (int l = 0; l < E->L; l++)
        els[l] = d;
    return gcc_jit_context_new_rvalue_from_vector(E->c, NULL, E->vt, (size_t)E->L, els);
}

static gcc_jit_rvalue *value(lem *E, int r)
{
    if (E->t->isconst[r])
        return splat(E, E->t->rd[r]);
    return gcc_jit_lvalue_as_rvalue(E->loc[r]);
}

static int slot_reg(const hl_instr *in, hl_slot s)
{
    return s == HL_SLOT_D ? in->d : s == HL_SLOT_A ? in->a : s == HL_SLOT_B ? in->b : in->x;
}

static hl_ev l_num(hl_em *em, long p, long q)
{
    return ev(splat(LE(em), (double)p / (double)q));
}

static hl_ev l_coef(hl_em *em, hl_slot s, int j)
{
    (void)j; /* point rules read coefficient 0 only */
    return ev(value(LE(em), slot_reg(LE(em)->in, s)));
}

/* a register nothing reads is not assigned, so that its calls are not made */
static void l_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    lem *E = LE(em);
    int r = slot_reg(E->in, s);
    (void)j;
    if (E->read[r])
        gcc_jit_block_add_assignment(E->blk, NULL, E->loc[r], RV(v));
}

static hl_ev l_bin(hl_em *em, enum gcc_jit_binary_op op, hl_ev a, hl_ev b)
{
    lem *E = LE(em);
    return ev(gcc_jit_context_new_binary_op(E->c, NULL, op, E->vt, RV(a), RV(b)));
}
static hl_ev l_add(hl_em *em, hl_ev a, hl_ev b)
{
    return l_bin(em, GCC_JIT_BINARY_OP_PLUS, a, b);
}
static hl_ev l_sub(hl_em *em, hl_ev a, hl_ev b)
{
    return l_bin(em, GCC_JIT_BINARY_OP_MINUS, a, b);
}
static hl_ev l_mul(hl_em *em, hl_ev a, hl_ev b)
{
    return l_bin(em, GCC_JIT_BINARY_OP_MULT, a, b);
}
static hl_ev l_div(hl_em *em, hl_ev a, hl_ev b)
{
    return l_bin(em, GCC_JIT_BINARY_OP_DIVIDE, a, b);
}

static hl_ev l_neg(hl_em *em, hl_ev a)
{
    lem *E = LE(em);
    return ev(gcc_jit_context_new_unary_op(E->c, NULL, GCC_JIT_UNARY_OP_MINUS, E->vt, RV(a)));
}

/* a fresh vector local holding v, whose lanes can be read (an assignment
 * nobody reads is dropped by GCC) */
static gcc_jit_lvalue *spill(lem *E, gcc_jit_rvalue *v)
{
    char name[32];
    snprintf(name, sizeof name, "v%d", E->ntmp++);
    gcc_jit_lvalue *l = gcc_jit_function_new_local(E->fun, NULL, E->vt, name);
    gcc_jit_block_add_assignment(E->blk, NULL, l, v);
    return l;
}

/* lane l of the vector local v, read through its address as a double */
static gcc_jit_rvalue *lane(lem *E, gcc_jit_lvalue *v, int l)
{
    gcc_jit_rvalue *p =
        gcc_jit_context_new_cast(E->c, NULL, gcc_jit_lvalue_get_address(v, NULL), E->dblp);
    gcc_jit_type *it = gcc_jit_context_get_type(E->c, GCC_JIT_TYPE_INT);
    return gcc_jit_lvalue_as_rvalue(gcc_jit_context_new_array_access(
        E->c, NULL, p, gcc_jit_context_new_rvalue_from_int(E->c, it, l)));
}

/* f (scalar) on each lane's own arguments, the results a vector again.  The
 * calls are inside the value, not statements: they are made where the value
 * is stored (l_store), and only there. */
static gcc_jit_rvalue *per_lane(lem *E, gcc_jit_function *f, int nargs, const hl_ev *args)
{
    gcc_jit_lvalue *v[3];
    for (int i = 0; i < nargs; i++)
        v[i] = spill(E, RV(args[i]));
    gcc_jit_rvalue *out[HL_TAPE_BATCH_MAX_LANES];
    for (int l = 0; l < E->L; l++) {
        gcc_jit_rvalue *x[3];
        for (int i = 0; i < nargs; i++)
            x[i] = lane(E, v[i], l);
        out[l] = gcc_jit_context_new_call(E->c, NULL, f, nargs, x);
    }
    return gcc_jit_context_new_rvalue_from_vector(E->c, NULL, E->vt, (size_t)E->L, out);
}

static hl_ev l_fma(hl_em *em, hl_ev a, hl_ev b, hl_ev c)
{
    lem *E = LE(em);
    hl_ev args[3] = {a, b, c};
    return ev(per_lane(E, gcc_jit_context_get_builtin_function(E->c, "__builtin_fma"), 3, args));
}

/* libm's functions as opaque imports (jit_common.c says why); sqrt is
 * GCC's builtin, correctly rounded like libm's */
static gcc_jit_function *lib(lem *E, hl_pfn f)
{
    if (E->lib[f] != NULL)
        return E->lib[f];
    if (f == HL_PFN_SQRT) {
        E->lib[f] = gcc_jit_context_get_builtin_function(E->c, "__builtin_sqrt");
    } else {
        gcc_jit_param *p[2] = {gcc_jit_context_new_param(E->c, NULL, E->dbl, "u"),
                               gcc_jit_context_new_param(E->c, NULL, E->dbl, "v")};
        E->lib[f] = gcc_jit_context_new_function(E->c, NULL, GCC_JIT_FUNCTION_IMPORTED, E->dbl,
                                                 hl_pfn_name(f), hl_pfn_arity(f), p, 0);
    }
    return E->lib[f];
}

static hl_ev l_call(hl_em *em, hl_pfn f, hl_ev a, hl_ev b)
{
    lem *E = LE(em);
    hl_ev args[2] = {a, b};
    return ev(per_lane(E, lib(E, f), hl_pfn_arity(f), args));
}

/* point rules keep nothing */
static void l_keep(hl_em *em, int slot, hl_ev v)
{
    (void)em, (void)slot, (void)v;
}
static hl_ev l_kept(hl_em *em, int slot)
{
    (void)slot;
    return ev(splat(LE(em), 0.0));
}

static const hl_em_ops lane_ops = {
    l_num, l_coef, l_store,          l_add,  l_sub, l_mul, l_neg, l_div,
    l_fma, l_call, hl_conv_unrolled, l_keep, l_kept};

static void emit(lem *E, const hl_instr *i)
{
    E->in = i;
    hl_rule_of(i->op)->point(&E->em);
}

/* ---- loop-carried calls (jit_eval.c's hl_jit_find_carries) ---------------------- */

static gcc_jit_lvalue *vlocal(lem *E, const char *prefix, int j)
{
    char name[32];
    snprintf(name, sizeof name, "%s%d", prefix, j);
    return gcc_jit_function_new_local(E->fun, NULL, E->vt, name);
}

/* the carried values at the start, computed from the entry state */
static void carry_start(lem *E, carry *cv, int n)
{
    for (int j = 0; j < n; j++) {
        const hl_instr *i = &E->t->code[cv[j].i];
        emit(E, i);
        cv[j].d = vlocal(E, "cd", j);
        gcc_jit_block_add_assignment(E->blk, NULL, cv[j].d,
                                     E->read[i->d] ? value(E, i->d) : splat(E, 0.0));
        if (i->x >= 0) {
            cv[j].x = vlocal(E, "cx", j);
            gcc_jit_block_add_assignment(E->blk, NULL, cv[j].x,
                                         E->read[i->x] ? value(E, i->x) : splat(E, 0.0));
        }
    }
}

static void carry_use(lem *E, const carry *c)
{
    const hl_instr *i = &E->t->code[c->i];
    if (E->read[i->d])
        gcc_jit_block_add_assignment(E->blk, NULL, E->loc[i->d], gcc_jit_lvalue_as_rvalue(c->d));
    if (i->x >= 0 && E->read[i->x])
        gcc_jit_block_add_assignment(E->blk, NULL, E->loc[i->x], gcc_jit_lvalue_as_rvalue(c->x));
}

static void carry_next(lem *E, gcc_jit_block *blk, const carry *cv, int n)
{
    for (int j = 0; j < n; j++) {
        const hl_instr *i = &E->t->code[cv[j].i], *w = &E->t->code[cv[j].twin];
        if (E->read[i->d])
            gcc_jit_block_add_assignment(blk, NULL, cv[j].d, value(E, w->d));
        if (i->x >= 0 && E->read[i->x])
            gcc_jit_block_add_assignment(blk, NULL, cv[j].x, value(E, w->x));
    }
}

/* ---- the loop ------------------------------------------------------------------- */

/* The function's pieces that build_loop's helpers share. */
typedef struct loop {
    gcc_jit_param *prm[4]; /* z (vectors), n, w0, dev */
    gcc_jit_lvalue **y;    /* the outputs of the step (vectors) */
    gcc_jit_lvalue **m;    /* by lane: max |w - w0| so far */
    gcc_jit_lvalue **w0;   /* by lane: w0 */
    gcc_jit_lvalue *k;     /* steps done */
} loop;

static gcc_jit_rvalue *scalar_at(lem *E, gcc_jit_param *p, int l)
{
    gcc_jit_type *it = gcc_jit_context_get_type(E->c, GCC_JIT_TYPE_INT);
    return gcc_jit_lvalue_as_rvalue(gcc_jit_context_new_array_access(
        E->c, NULL, gcc_jit_param_as_rvalue(p), gcc_jit_context_new_rvalue_from_int(E->c, it, l)));
}

static gcc_jit_lvalue *vector_at(lem *E, gcc_jit_param *p, int i)
{
    gcc_jit_type *it = gcc_jit_context_get_type(E->c, GCC_JIT_TYPE_INT);
    return gcc_jit_context_new_array_access(E->c, NULL, gcc_jit_param_as_rvalue(p),
                                            gcc_jit_context_new_rvalue_from_int(E->c, it, i));
}

static gcc_jit_lvalue *dlocal(lem *E, const char *prefix, int j)
{
    char name[32];
    snprintf(name, sizeof name, "%s%d", prefix, j);
    return gcc_jit_function_new_local(E->fun, NULL, E->dbl, name);
}

/* The sum over outputs and lanes of (y - y): 0 exactly when every output
 * of every lane is finite, NaN otherwise (the scalar loop's test, summed
 * over the lanes after it). */
static gcc_jit_rvalue *all_finite(lem *E, const loop *P)
{
    const hl_tape *t = E->t;
    gcc_jit_rvalue *acc = splat(E, 0.0);
    for (int j = 0; j < t->nout; j++) {
        gcc_jit_rvalue *yv = gcc_jit_lvalue_as_rvalue(P->y[j]);
        acc = gcc_jit_context_new_binary_op(
            E->c, NULL, GCC_JIT_BINARY_OP_PLUS, E->vt, acc,
            gcc_jit_context_new_binary_op(E->c, NULL, GCC_JIT_BINARY_OP_MINUS, E->vt, yv, yv));
    }
    gcc_jit_lvalue *a = spill(E, acc);
    gcc_jit_rvalue *s = lane(E, a, 0);
    for (int l = 1; l < E->L; l++)
        s = gcc_jit_context_new_binary_op(E->c, NULL, GCC_JIT_BINARY_OP_PLUS, E->dbl, s,
                                          lane(E, a, l));
    return gcc_jit_context_new_comparison(E->c, NULL, GCC_JIT_COMPARISON_EQ, s,
                                          gcc_jit_context_zero(E->c, E->dbl));
}

/* In blk: for each lane, e = |w - w0|; if (e > m) m = e (the scalar loop's
 * update, lane by lane).  Returns the block that follows. */
static gcc_jit_block *watch(lem *E, const loop *P, gcc_jit_block *blk)
{
    const hl_tape *t = E->t;
    E->blk = blk;
    gcc_jit_lvalue *w = spill(E, gcc_jit_lvalue_as_rvalue(P->y[t->nout - 1]));
    gcc_jit_function *fabs_ = gcc_jit_context_get_builtin_function(E->c, "__builtin_fabs");
    for (int l = 0; l < E->L; l++) {
        gcc_jit_lvalue *e = dlocal(E, "e", l);
        gcc_jit_rvalue *dw =
            gcc_jit_context_new_binary_op(E->c, NULL, GCC_JIT_BINARY_OP_MINUS, E->dbl,
                                          lane(E, w, l), gcc_jit_lvalue_as_rvalue(P->w0[l]));
        gcc_jit_block_add_assignment(blk, NULL, e,
                                     gcc_jit_context_new_call(E->c, NULL, fabs_, 1, &dw));
        gcc_jit_block *raise = gcc_jit_function_new_block(E->fun, NULL);
        gcc_jit_block *next = gcc_jit_function_new_block(E->fun, NULL);
        gcc_jit_block_end_with_conditional(
            blk, NULL,
            gcc_jit_context_new_comparison(E->c, NULL, GCC_JIT_COMPARISON_GT,
                                           gcc_jit_lvalue_as_rvalue(e),
                                           gcc_jit_lvalue_as_rvalue(P->m[l])),
            raise, next);
        gcc_jit_block_add_assignment(raise, NULL, P->m[l], gcc_jit_lvalue_as_rvalue(e));
        gcc_jit_block_end_with_jump(raise, NULL, next);
        blk = next;
        E->blk = blk;
    }
    return blk;
}

/* The locals and the entry block: the state, w0 and dev into locals, the
 * carried values from the entry state. */
static void loop_entry(lem *E, loop *P, carry *cv, int ncarry)
{
    const hl_tape *t = E->t;
    for (int r = 0; r < t->nregs; r++)
        if (!t->isconst[r])
            E->loc[r] = vlocal(E, "s", r);
    P->y = hl_xmalloc((size_t)t->nout * sizeof *P->y);
    for (int j = 0; j < t->nout; j++)
        P->y[j] = vlocal(E, "y", j);
    P->m = hl_xmalloc((size_t)E->L * sizeof *P->m);
    P->w0 = hl_xmalloc((size_t)E->L * sizeof *P->w0);
    for (int l = 0; l < E->L; l++) {
        P->m[l] = dlocal(E, "m", l);
        P->w0[l] = dlocal(E, "w", l);
        gcc_jit_block_add_assignment(E->blk, NULL, P->m[l], scalar_at(E, P->prm[3], l));
        gcc_jit_block_add_assignment(E->blk, NULL, P->w0[l], scalar_at(E, P->prm[2], l));
    }
    for (int r = 0; r < t->nin; r++)
        gcc_jit_block_add_assignment(E->blk, NULL, E->loc[r],
                                     gcc_jit_lvalue_as_rvalue(vector_at(E, P->prm[0], r)));
    carry_start(E, cv, ncarry);
    gcc_jit_type *lng = gcc_jit_context_get_type(E->c, GCC_JIT_TYPE_LONG);
    P->k = gcc_jit_function_new_local(E->fun, NULL, lng, "k");
    gcc_jit_block_add_assignment(E->blk, NULL, P->k, gcc_jit_context_zero(E->c, lng));
}

/* The step: every instruction (or its carried value), the outputs into y. */
static void loop_body(lem *E, const loop *P, const carry *cv, int ncarry)
{
    const hl_tape *t = E->t;
    for (int i = 0; i < t->ncode; i++) {
        int cj = hl_jit_carried(cv, ncarry, i);
        if (cj >= 0)
            carry_use(E, &cv[cj]);
        else
            emit(E, &t->code[i]);
    }
    for (int j = 0; j < t->nout; j++)
        gcc_jit_block_add_assignment(E->blk, NULL, P->y[j], value(E, t->outreg[j]));
}

/* long hl_jit_watch_lanes(vector *z, long n, const double *w0, double *dev):
 * hl_tape_iterate_watch over the lanes, the state in machine registers. */
static void build_loop(lem *E)
{
    const hl_tape *t = E->t;
    gcc_jit_context *c = E->c;
    gcc_jit_type *lng = gcc_jit_context_get_type(c, GCC_JIT_TYPE_LONG);
    gcc_jit_type *cdblp = gcc_jit_type_get_pointer(gcc_jit_type_get_const(E->dbl));
    loop P = {.prm = {gcc_jit_context_new_param(c, NULL, gcc_jit_type_get_pointer(E->vt), "z"),
                      gcc_jit_context_new_param(c, NULL, lng, "n"),
                      gcc_jit_context_new_param(c, NULL, cdblp, "w0"),
                      gcc_jit_context_new_param(c, NULL, E->dblp, "dev")}};
    E->fun = gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED, lng,
                                          "hl_jit_watch_lanes", 4, P.prm, 0);
    const int nmap = t->nout - 1;
    gcc_jit_block *entry = gcc_jit_function_new_block(E->fun, "entry");
    gcc_jit_block *cond = gcc_jit_function_new_block(E->fun, "cond");
    gcc_jit_block *body = gcc_jit_function_new_block(E->fun, "body");
    gcc_jit_block *latch = gcc_jit_function_new_block(E->fun, "latch");
    gcc_jit_block *done = gcc_jit_function_new_block(E->fun, "done");
    E->blk = entry;
    int ncarry;
    carry *cv = hl_jit_find_carries(E->t, E->read, nmap, &ncarry);
    loop_entry(E, &P, cv, ncarry);
    gcc_jit_block_end_with_jump(entry, NULL, cond);
    gcc_jit_block_end_with_conditional(
        cond, NULL,
        gcc_jit_context_new_comparison(c, NULL, GCC_JIT_COMPARISON_LT,
                                       gcc_jit_lvalue_as_rvalue(P.k),
                                       gcc_jit_param_as_rvalue(P.prm[1])),
        body, done);
    E->blk = body;
    loop_body(E, &P, cv, ncarry);
    gcc_jit_block_end_with_conditional(body, NULL, all_finite(E, &P), latch, done);
    gcc_jit_block *next = watch(E, &P, latch);
    carry_next(E, next, cv, ncarry);
    free(cv);
    for (int j = 0; j < nmap; j++)
        gcc_jit_block_add_assignment(next, NULL, E->loc[j], gcc_jit_lvalue_as_rvalue(P.y[j]));
    gcc_jit_block_add_assignment_op(next, NULL, P.k, GCC_JIT_BINARY_OP_PLUS,
                                    gcc_jit_context_one(c, lng));
    gcc_jit_block_end_with_jump(next, NULL, cond);
    for (int j = 0; j < nmap; j++)
        gcc_jit_block_add_assignment(done, NULL, vector_at(E, P.prm[0], j),
                                     gcc_jit_lvalue_as_rvalue(E->loc[j]));
    gcc_jit_type *it = gcc_jit_context_get_type(c, GCC_JIT_TYPE_INT);
    for (int l = 0; l < E->L; l++)
        gcc_jit_block_add_assignment(
            done, NULL,
            gcc_jit_context_new_array_access(c, NULL, gcc_jit_param_as_rvalue(P.prm[3]),
                                             gcc_jit_context_new_rvalue_from_int(c, it, l)),
            gcc_jit_lvalue_as_rvalue(P.m[l]));
    gcc_jit_block_end_with_return(done, NULL, gcc_jit_lvalue_as_rvalue(P.k));
    free(P.y), free(P.m), free(P.w0);
}

typedef struct lanes_arg {
    const hl_tape *t;
    int lanes;
} lanes_arg;

static void build(gcc_jit_context *c, const void *arg)
{
    const lanes_arg *a = arg;
    lem E = {.em = {&lane_ops}, .c = c, .t = a->t, .L = a->lanes};
    E.dbl = gcc_jit_context_get_type(c, GCC_JIT_TYPE_DOUBLE);
    E.dblp = gcc_jit_type_get_pointer(E.dbl);
    E.vt = gcc_jit_type_get_vector(E.dbl, (size_t)E.L);
    E.loc = hl_xcalloc((size_t)a->t->nregs + 1, sizeof *E.loc);
    E.read = hl_jit_registers_read(a->t);
    build_loop(&E);
    free(E.loc);
    free(E.read);
}

/* The loop for t over lanes, from the disk cache or compiled (the batch
 * site's options: -O2 and the host's vector instructions). */
static hl_status compile_lanes(hl_tape_iter_batch *b, hl_error *err)
{
    hl_buf inputs;
    hl_buf_init(&inputs);
    hl_buf_printf(&inputs, "watch lanes %d\n", b->lanes);
    hl_jit_inputs_tape(&inputs, b->t);
    lanes_arg a = {b->t, b->lanes};
    hl_jit_code *code;
    hl_status st = hl_jit_obtain(&code, HL_JIT_SITE_BATCH, &inputs, build, &a, "hl_jit_watch_lanes",
                                 "the lanes' loop", err);
    hl_buf_clear(&inputs);
    if (st != HL_OK)
        return st;
    b->code = code;
    *(void **)&b->fn = hl_jit_code_sym(code, "hl_jit_watch_lanes");
    return HL_OK;
}

static void release(void *code)
{
    hl_jit_code_free(code);
}

#else /* no libgccjit: the lanes step through the interpreter */

static hl_status compile_lanes(hl_tape_iter_batch *b, hl_error *err)
{
    (void)b;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "hamlie was built without libgccjit");
}

static void release(void *code)
{
    (void)code;
}

#endif

/* ---- the batch object ------------------------------------------------------------ */

int hl_tape_lanes_native(void)
{
    int isa = hl_jit_host_isa(); /* the -march level the lanes are compiled for */
    return isa == 4 ? 8 : isa == 3 ? 4 : 2;
}

static int power_of_two(int x)
{
    return x > 0 && (x & (x - 1)) == 0;
}

/* as hl_xmalloc: allocation failure aborts; aligned to a vector of lanes */
static double *aligned_doubles(size_t n, int lanes)
{
    size_t align = (size_t)lanes * sizeof(double) < 16 ? 16 : (size_t)lanes * sizeof(double);
    size_t bytes = (n * sizeof(double) + align - 1) / align * align;
    double *p = aligned_alloc(align, bytes > 0 ? bytes : align);
    if (p == NULL) {
        fprintf(stderr, "hamlie: out of memory (%zu bytes)\n", bytes);
        abort();
    }
    memset(p, 0, bytes);
    return p;
}

hl_status hl_tape_iter_batch_new(hl_tape_iter_batch **out, hl_tape *t, int lanes, int compile,
                                 hl_error *err)
{
    *out = NULL;
    if (t->nout < 2 || t->nout != t->nin)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "a watched iteration needs a tape with as many outputs as inputs, at "
                            "least 2 (%d inputs, %d outputs)",
                            t->nin, t->nout);
    if (!power_of_two(lanes) || lanes > HL_TAPE_BATCH_MAX_LANES)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "lanes must be a power of 2 from 1 to %d (not %d)",
                            HL_TAPE_BATCH_MAX_LANES, lanes);
    hl_tape_iter_batch *b = hl_xcalloc(1, sizeof *b);
    b->t = t;
    b->lanes = lanes;
    b->z = aligned_doubles((size_t)t->nin * (size_t)lanes, lanes);
    b->y = hl_xcalloc((size_t)t->nout * (size_t)lanes, sizeof *b->y);
    b->in = hl_xcalloc((size_t)t->nin, sizeof *b->in);
    /* one lane is the scalar loop's business (hl_tape_iterate_watch) */
    if (compile && lanes > 1 && hl_tape_jit_available() && compile_lanes(b, NULL) != HL_OK) {
        b->code = NULL;
        b->fn = NULL;
    }
    *out = b;
    return HL_OK;
}

void hl_tape_iter_batch_free(hl_tape_iter_batch *b)
{
    if (b == NULL)
        return;
    release(b->code);
    free(b->z);
    free(b->y);
    free(b->in);
    free(b);
}

int hl_tape_iter_batch_lanes(const hl_tape_iter_batch *b)
{
    return b->lanes;
}
int hl_tape_iter_batch_compiled(const hl_tape_iter_batch *b)
{
    return b->fn != NULL;
}
double *hl_tape_iter_batch_state(hl_tape_iter_batch *b)
{
    return b->z;
}

/* Step k of every lane through the interpreter into b->y; 0 if some
 * output of some lane is not finite. */
static int interpret_step(hl_tape_iter_batch *b)
{
    const hl_tape *t = b->t;
    const int L = b->lanes;
    for (int l = 0; l < L; l++) {
        for (int i = 0; i < t->nin; i++)
            b->in[i] = b->z[(size_t)i * L + l];
        double *y = b->y + (size_t)l * t->nout;
        hl_tape_eval_d(y, b->in, b->t);
        for (int j = 0; j < t->nout; j++)
            if (!isfinite(y[j]))
                return 0;
    }
    return 1;
}

long hl_tape_iter_batch_watch(hl_tape_iter_batch *b, long n, const double *w0, double *dev)
{
    if (n <= 0)
        return 0;
    if (b->fn != NULL)
        return b->fn(b->z, n, w0, dev);
    const hl_tape *t = b->t;
    const int L = b->lanes, nmap = t->nout - 1;
    long k = 0;
    for (; k < n && interpret_step(b); k++)
        for (int l = 0; l < L; l++) {
            const double *y = b->y + (size_t)l * t->nout;
            double e = fabs(y[nmap] - w0[l]);
            if (e > dev[l])
                dev[l] = e;
            for (int i = 0; i < nmap; i++)
                b->z[(size_t)i * L + l] = y[i];
        }
    return k;
}
