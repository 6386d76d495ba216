/* The Taylor-ODE recursion compiled in process by libgccjit (the default
 * back end of hl_tape_native where hamlie has libgccjit; emit_c.c prints
 * the same program as C for the system compiler otherwise).
 *
 * The rules of src/rules run at each coefficient k through an emitter whose
 * values are gcc_jit_rvalue trees: every sum written out, every index a
 * constant.  The trees are the interpreter's operations in its order
 * (rule.h) and GCC runs with -ffp-contract=off, so the coefficients are the
 * interpreter's to the last bit.  Every coefficient but the constants' is a
 * local, so that GCC need not assume that a store through the register
 * file changes what it has loaded (the recurrences are load-bound); the
 * inputs' coefficients go back to the register file at the end, which is
 * all hl_tape_taylor_ode_d reads.
 *
 * Lanes (hl_tape_batch, jit_batch.c): the same emitter with every value a
 * GCC vector of L doubles (L = 2, 4, 8, 16), one member of a batch per
 * lane.  A vector's +, -, *, / and negation are the scalar operations lane
 * by lane, so each lane's coefficients are the single member's to the last
 * bit; what has no vector form in libgccjit 12 (fma, libm's functions)
 * runs lane by lane on scalars read through the vector's address and is
 * put back together (calls are made at k = 0 only; fma is the ODE step's
 * division).  The register file is then R[(reg * S + j) * L + lane]. */
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
#include "tape/gccjit_api.h"

/* ---- the emitter: values are gccjit trees ------------------------------------- */

/* A value, and the number itself when it is known now (known numbers are
 * folded here, with the machine's rounding, so that a convolution's weights
 * are immediates). */
typedef struct gval {
    gcc_jit_rvalue *r;
    double v;
    int isnum;
    gcc_jit_rvalue *neg; /* r is -neg (or NULL): see fold_negation */
} gval;

typedef struct gem {
    hl_em em;
    gcc_jit_context *c;
    gcc_jit_type *dbl, *dblp;
    gcc_jit_type *vt; /* a value's type: dbl, or a vector of L doubles */
    int L;            /* lanes (1: the single member's recursion) */
    gcc_jit_function *fun;
    gcc_jit_block *blk;
    gcc_jit_rvalue *R; /* the register file, the function's parameter */
    const hl_tape *t;
    const hl_instr *in;
    int i, S;              /* the instruction's index; order + 1 */
    gcc_jit_lvalue **coef; /* by register * S + j: the coefficients' locals */
    gcc_jit_lvalue **keep; /* by instruction * 2 + slot: kept values */
    gcc_jit_rvalue **negof; /* by register * S + j: the local is -this (or NULL) */
    gcc_jit_function *lib[HL_PFN_COUNT];
    gval *v; /* the values made for the current instruction */
    int n, cap, ntmp;
} gem;

static gem *GE(hl_em *em)
{
    return (gem *)em;
}

static hl_ev push(gem *E, gcc_jit_rvalue *r, int isnum, double v)
{
    if (E->n == E->cap) {
        E->cap = E->cap ? 2 * E->cap : 64;
        E->v = hl_xrealloc(E->v, (size_t)E->cap * sizeof *E->v);
    }
    E->v[E->n] = (gval){r, v, isnum, NULL};
    return (hl_ev){.i = E->n++};
}

static const gval *V(gem *E, hl_ev a)
{
    return &E->v[a.i];
}
static gcc_jit_rvalue *RV(gem *E, hl_ev a)
{
    return E->v[a.i].r;
}

/* x in every lane */
static gcc_jit_rvalue *immediate(gem *E, double x)
{
    gcc_jit_rvalue *d = gcc_jit_context_new_rvalue_from_double(E->c, E->dbl, x);
    if (E->L == 1)
        return d;
    gcc_jit_rvalue *els[HL_TAPE_BATCH_MAX_LANES];
    for (int l = 0; l < E->L; l++)
        els[l] = d;
    return gcc_jit_context_new_rvalue_from_vector(E->c, NULL, E->vt, (size_t)E->L, els);
}

static hl_ev number(gem *E, double x)
{
    return push(E, immediate(E, x), 1, x);
}

static hl_ev g_num(hl_em *em, long p, long q)
{
    return number(GE(em), (double)p / (double)q);
}

static int reg_of(const hl_instr *in, hl_slot s)
{
    return s == HL_SLOT_D ? in->d : s == HL_SLOT_A ? in->a : s == HL_SLOT_B ? in->b : in->x;
}

/* R[reg * S + j] itself */
static gcc_jit_lvalue *cell(gem *E, int reg, int j)
{
    gcc_jit_type *lng = gcc_jit_context_get_type(E->c, GCC_JIT_TYPE_LONG);
    return gcc_jit_context_new_array_access(
        E->c, NULL, E->R, gcc_jit_context_new_rvalue_from_long(E->c, lng, (long)reg * E->S + j));
}

static gcc_jit_lvalue *local_of(gem *E, int reg, int j)
{
    gcc_jit_lvalue **l = &E->coef[(long)reg * E->S + j];
    if (*l == NULL) {
        char name[32];
        snprintf(name, sizeof name, "c%d_%d", reg, j);
        *l = gcc_jit_function_new_local(E->fun, NULL, E->vt, name);
    }
    return *l;
}

/* a constant's coefficients (c, 0, 0, ...) are immediates */
static hl_ev g_coef(hl_em *em, hl_slot s, int j)
{
    gem *E = GE(em);
    int reg = reg_of(E->in, s);
    if (E->t->isconst[reg])
        return number(E, j == 0 ? E->t->rd[reg] : 0.0);
    hl_ev v = push(E, gcc_jit_lvalue_as_rvalue(local_of(E, reg, j)), 0, 0);
    E->v[v.i].neg = E->negof[(long)reg * E->S + j];
    return v;
}

static gcc_jit_rvalue *temporary(gem *E, gcc_jit_type *type, gcc_jit_rvalue *v);

static void g_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    gem *E = GE(em);
    int reg = reg_of(E->in, s);
    gcc_jit_rvalue *neg = V(E, v)->neg, *r = RV(E, v);
    if (neg != NULL) { /* the negated value once, in a local its readers share */
        neg = temporary(E, E->vt, neg);
        r = gcc_jit_context_new_unary_op(E->c, NULL, GCC_JIT_UNARY_OP_MINUS, E->vt, neg);
    }
    gcc_jit_block_add_assignment(E->blk, NULL, local_of(E, reg, j), r);
    E->negof[(long)reg * E->S + j] = neg;
}

static int both_known(gem *E, hl_ev a, hl_ev b)
{
    return V(E, a)->isnum && V(E, b)->isnum;
}

/* Negation folded into a known factor: (-a) c = a (-c), (-a)/c = a/(-c),
 * c/(-a) = (-c)/a, exactly (rounding to nearest is symmetric), so that the
 * negations of the rules (cos's -sum, the -sin of a pendulum's force) cost
 * no instruction on the chain from one order to the next.  *op_a and *op_b
 * become the operands to use; 0 when nothing folds. */
static int fold_negation(gem *E, enum gcc_jit_binary_op op, hl_ev a, hl_ev b, gcc_jit_rvalue **op_a,
                         gcc_jit_rvalue **op_b)
{
    if (op != GCC_JIT_BINARY_OP_MULT && op != GCC_JIT_BINARY_OP_DIVIDE)
        return 0;
    if (V(E, a)->neg != NULL && V(E, b)->isnum) {
        *op_a = V(E, a)->neg;
        *op_b = immediate(E, -V(E, b)->v);
        return 1;
    }
    if (V(E, b)->neg != NULL && V(E, a)->isnum) {
        *op_a = immediate(E, -V(E, a)->v);
        *op_b = V(E, b)->neg;
        return 1;
    }
    return 0;
}

static hl_ev binary(gem *E, enum gcc_jit_binary_op op, hl_ev a, hl_ev b)
{
    gcc_jit_rvalue *fa, *fb;
    if (fold_negation(E, op, a, b, &fa, &fb))
        return push(E, gcc_jit_context_new_binary_op(E->c, NULL, op, E->vt, fa, fb), 0, 0);
    if (both_known(E, a, b)) {
        double x = V(E, a)->v, y = V(E, b)->v;
        return number(E, op == GCC_JIT_BINARY_OP_PLUS    ? x + y
                         : op == GCC_JIT_BINARY_OP_MINUS ? x - y
                         : op == GCC_JIT_BINARY_OP_MULT  ? x * y
                                                         : x / y);
    }
    return push(E, gcc_jit_context_new_binary_op(E->c, NULL, op, E->vt, RV(E, a), RV(E, b)), 0, 0);
}

static hl_ev g_add(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(GE(em), GCC_JIT_BINARY_OP_PLUS, a, b);
}
static hl_ev g_sub(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(GE(em), GCC_JIT_BINARY_OP_MINUS, a, b);
}
static hl_ev g_mul(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(GE(em), GCC_JIT_BINARY_OP_MULT, a, b);
}
static hl_ev g_div(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(GE(em), GCC_JIT_BINARY_OP_DIVIDE, a, b);
}

static hl_ev g_neg(hl_em *em, hl_ev a)
{
    gem *E = GE(em);
    if (V(E, a)->isnum)
        return number(E, -V(E, a)->v);
    if (V(E, a)->neg != NULL) /* -(-x) = x */
        return push(E, V(E, a)->neg, 0, 0);
    hl_ev v = push(
        E, gcc_jit_context_new_unary_op(E->c, NULL, GCC_JIT_UNARY_OP_MINUS, E->vt, RV(E, a)), 0, 0);
    E->v[v.i].neg = RV(E, a);
    return v;
}

/* a fresh local named t<n> holding v (of type type): a call is made once
 * however often a rule reads its value */
static gcc_jit_rvalue *temporary(gem *E, gcc_jit_type *type, gcc_jit_rvalue *v)
{
    char name[32];
    snprintf(name, sizeof name, "t%d", E->ntmp++);
    gcc_jit_lvalue *l = gcc_jit_function_new_local(E->fun, NULL, type, name);
    gcc_jit_block_add_assignment(E->blk, NULL, l, v);
    return gcc_jit_lvalue_as_rvalue(l);
}

/* a fresh vector local holding v, whose lanes can be read */
static gcc_jit_lvalue *spill(gem *E, gcc_jit_rvalue *v)
{
    char name[32];
    snprintf(name, sizeof name, "v%d", E->ntmp++);
    gcc_jit_lvalue *l = gcc_jit_function_new_local(E->fun, NULL, E->vt, name);
    gcc_jit_block_add_assignment(E->blk, NULL, l, v);
    return l;
}

/* Lane l of the vector local v, read through its address as a double. */
static gcc_jit_rvalue *lane(gem *E, gcc_jit_lvalue *v, int l)
{
    gcc_jit_rvalue *p =
        gcc_jit_context_new_cast(E->c, NULL, gcc_jit_lvalue_get_address(v, NULL), E->dblp);
    gcc_jit_type *it = gcc_jit_context_get_type(E->c, GCC_JIT_TYPE_INT);
    return gcc_jit_lvalue_as_rvalue(gcc_jit_context_new_array_access(
        E->c, NULL, p, gcc_jit_context_new_rvalue_from_int(E->c, it, l)));
}

/* f (scalar) applied to args: with lanes, once per lane on the lanes' own
 * scalars (a known number stays an immediate), the results made a vector
 * again.  The value is a temporary: the calls are made once. */
static gcc_jit_rvalue *call_per_lane(gem *E, gcc_jit_function *f, int nargs, const hl_ev *args)
{
    gcc_jit_rvalue *x[3];
    if (E->L == 1) {
        for (int i = 0; i < nargs; i++)
            x[i] = RV(E, args[i]);
        return temporary(E, E->dbl, gcc_jit_context_new_call(E->c, NULL, f, nargs, x));
    }
    gcc_jit_lvalue *v[3] = {NULL, NULL, NULL};
    for (int i = 0; i < nargs; i++)
        if (!V(E, args[i])->isnum)
            v[i] = spill(E, RV(E, args[i]));
    gcc_jit_rvalue *out[HL_TAPE_BATCH_MAX_LANES];
    for (int l = 0; l < E->L; l++) {
        for (int i = 0; i < nargs; i++)
            x[i] = v[i] != NULL
                       ? lane(E, v[i], l)
                       : gcc_jit_context_new_rvalue_from_double(E->c, E->dbl, V(E, args[i])->v);
        out[l] = temporary(E, E->dbl, gcc_jit_context_new_call(E->c, NULL, f, nargs, x));
    }
    return temporary(E, E->vt,
                     gcc_jit_context_new_rvalue_from_vector(E->c, NULL, E->vt, (size_t)E->L, out));
}

/* GCC's fma: one instruction where the machine has FMA (add_host_isa),
 * libm's fma otherwise; the same bits either way */
static hl_ev g_fma(hl_em *em, hl_ev a, hl_ev b, hl_ev c)
{
    gem *E = GE(em);
    if (both_known(E, a, b) && V(E, c)->isnum)
        return number(E, fma(V(E, a)->v, V(E, b)->v, V(E, c)->v));
    gcc_jit_function *f = gcc_jit_context_get_builtin_function(E->c, "__builtin_fma");
    if (V(E, a)->neg != NULL && V(E, b)->isnum) { /* fma(-s, h, z) = fma(s, -h, z) exactly */
        a = push(E, V(E, a)->neg, 0, 0);
        b = number(E, -V(E, b)->v);
    }
    hl_ev args[3] = {a, b, c};
    return push(E, call_per_lane(E, f, 3, args), 0, 0);
}


/* libm's functions as opaque imports, so that GCC cannot rewrite them
 * (pow(x, 2) -> x*x is not exact for glibc's pow); sqrt is GCC's builtin
 * (sqrtsd, correctly rounded like libm's) */
static gcc_jit_function *lib(gem *E, hl_pfn f)
{
    if (E->lib[f] != NULL)
        return E->lib[f];
    if (f == HL_PFN_SQRT) {
        E->lib[f] = gcc_jit_context_get_builtin_function(E->c, "__builtin_sqrt");
    } else {
        int two = hl_pfn_arity(f) == 2;
        gcc_jit_param *p[2] = {gcc_jit_context_new_param(E->c, NULL, E->dbl, "u"),
                               gcc_jit_context_new_param(E->c, NULL, E->dbl, "v")};
        E->lib[f] = gcc_jit_context_new_function(E->c, NULL, GCC_JIT_FUNCTION_IMPORTED, E->dbl,
                                                 hl_pfn_name(f), two ? 2 : 1, p, 0);
    }
    return E->lib[f];
}

static hl_ev g_call(hl_em *em, hl_pfn f, hl_ev a, hl_ev b)
{
    gem *E = GE(em);
    hl_ev args[2] = {a, b};
    int nargs = f == HL_PFN_ATAN2 || f == HL_PFN_POW ? 2 : 1;
    return push(E, call_per_lane(E, lib(E, f), nargs, args), 0, 0);
}

/* kept values: locals set at k = 0 */
static void g_keep(hl_em *em, int slot, hl_ev v)
{
    gem *E = GE(em);
    char name[32];
    snprintf(name, sizeof name, "k%d_%d", E->i, slot);
    gcc_jit_lvalue *l = gcc_jit_function_new_local(E->fun, NULL, E->vt, name);
    gcc_jit_block_add_assignment(E->blk, NULL, l, RV(E, v));
    E->keep[2 * E->i + slot] = l;
}

static hl_ev g_kept(hl_em *em, int slot)
{
    gem *E = GE(em);
    return push(E, gcc_jit_lvalue_as_rvalue(E->keep[2 * E->i + slot]), 0, 0);
}

static const hl_em_ops g_ops = {g_num, g_coef, g_store,          g_add,  g_sub, g_mul, g_neg, g_div,
                                g_fma, g_call, hl_conv_unrolled, g_keep, g_kept};

/* ---- the program -------------------------------------------------------------- */

/* z[k+1] = f[k] / (k+1) for every input, as every double back end divides
 * (hl_tape_ode_source): fma(c, hi, c lo), or c hi where the reciprocal is
 * exact (lo = 0), which is the same number for every finite c and one
 * operation less on the chain from one order to the next (the oscillator's
 * recursion is that chain alone) */
static void ode_step(gem *E, int k)
{
    for (int i = 0; i < E->t->nin; i++) {
        hl_ode_source src;
        hl_tape_ode_source(&src, E->t, i, k);
        E->in = &(hl_instr){.d = i, .a = src.reg, .b = -1, .x = -1};
        hl_ev f = g_coef(&E->em, HL_SLOT_A, src.k), h = number(E, src.hi);
        hl_ev v = src.lo == 0 ? g_mul(&E->em, f, h)
                              : g_fma(&E->em, f, h, g_mul(&E->em, f, number(E, src.lo)));
        g_store(&E->em, HL_SLOT_D, k + 1, v);
        E->n = 0;
    }
}

/* void hl_native(double *R): the recursion of hl_tape_taylor_ode_d */
static void build_recursion(gem *E, int order)
{
    const hl_tape *t = E->t;
    for (int i = 0; i < t->nin; i++)
        gcc_jit_block_add_assignment(E->blk, NULL, local_of(E, i, 0),
                                     gcc_jit_lvalue_as_rvalue(cell(E, i, 0)));
    for (int k = 0; k < order; k++) {
        for (int i = 0; i < t->ncode; i++) {
            E->in = &t->code[i];
            E->i = i;
            hl_rule_of(E->in->op)->taylor(&E->em, k);
            E->n = 0;
        }
        ode_step(E, k);
    }
    for (int i = 0; i < t->nin; i++)
        for (int k = 1; k <= order; k++)
            gcc_jit_block_add_assignment(E->blk, NULL, cell(E, i, k),
                                         gcc_jit_lvalue_as_rvalue(local_of(E, i, k)));
    gcc_jit_block_end_with_void_return(E->blk, NULL);
}

typedef struct recursion {
    const hl_tape *t;
    int order, lanes;
} recursion;

/* void hl_native(double *R) in context c (hl_jit_build_fn); with lanes, R
 * points to vectors of L doubles. */
static void build(gcc_jit_context *c, const void *arg)
{
    const recursion *r = arg;
    const hl_tape *t = r->t;
    gem E = {.em = {&g_ops}, .c = c, .t = t, .S = r->order + 1, .L = r->lanes};
    E.dbl = gcc_jit_context_get_type(c, GCC_JIT_TYPE_DOUBLE);
    E.dblp = gcc_jit_type_get_pointer(E.dbl);
    E.vt = E.L == 1 ? E.dbl : gcc_jit_type_get_vector(E.dbl, (size_t)E.L);
    gcc_jit_param *prm = gcc_jit_context_new_param(c, NULL, gcc_jit_type_get_pointer(E.vt), "R");
    E.fun = gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED,
                                         gcc_jit_context_get_type(c, GCC_JIT_TYPE_VOID),
                                         "hl_native", 1, &prm, 0);
    E.R = gcc_jit_param_as_rvalue(prm);
    E.blk = gcc_jit_function_new_block(E.fun, "body");
    E.coef = hl_xcalloc((size_t)t->nregs * (size_t)E.S, sizeof *E.coef);
    E.negof = hl_xcalloc((size_t)t->nregs * (size_t)E.S, sizeof *E.negof);
    E.keep = hl_xcalloc(2 * ((size_t)t->ncode + 1), sizeof *E.keep);
    build_recursion(&E, r->order);
    free(E.coef);
    free(E.negof);
    free(E.keep);
    free(E.v);
}

/* The site's options (-O1: -O2's scheduling costs much compile time on
 * these long blocks for little gain; the host's vector instructions, so
 * that GCC pairs the independent products) are in jit_cache.c's table. */
hl_status hl_tape_jit_taylor(void **result, void (**fn)(double *R), const hl_tape *t, int order,
                             hl_error *err)
{
    return hl_tape_jit_taylor_lanes(result, fn, t, order, 1, err);
}

hl_status hl_tape_jit_taylor_lanes(void **result, void (**fn)(double *R), const hl_tape *t,
                                   int order, int lanes, hl_error *err)
{
    hl_buf inputs;
    hl_buf_init(&inputs);
    hl_jit_inputs_batch(&inputs, t, order, lanes);
    hl_jit_code *code;
    recursion r = {t, order, lanes};
    hl_status status =
        hl_jit_obtain(&code, lanes > 1 ? HL_JIT_SITE_BATCH : HL_JIT_SITE_TAYLOR, &inputs, build, &r,
                      "hl_native", lanes > 1 ? "the batch recursion" : "the recursion", err);
    hl_buf_clear(&inputs);
    if (status != HL_OK)
        return status;
    *result = code;
    *(void **)fn = hl_jit_code_sym(code, "hl_native");
    return HL_OK;
}

void hl_tape_jit_release(void *result)
{
    hl_jit_code_free(result);
}

#else /* no libgccjit */

hl_status hl_tape_jit_taylor(void **result, void (**fn)(double *R), const hl_tape *t, int order,
                             hl_error *err)
{
    return hl_tape_jit_taylor_lanes(result, fn, t, order, 1, err);
}

hl_status hl_tape_jit_taylor_lanes(void **result, void (**fn)(double *R), const hl_tape *t,
                                   int order, int lanes, hl_error *err)
{
    (void)result, (void)fn, (void)t, (void)order, (void)lanes;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "hamlie was built without libgccjit");
}

void hl_tape_jit_release(void *result)
{
    (void)result;
}

#endif
