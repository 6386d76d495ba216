/* The Taylor-ODE recursion of a tape compiled by libgccjit: hl_tape_native's
 * in-process back end (native.c prints the same program as C for the
 * system compiler).  The libgccjit plumbing it shares with the other
 * compilers is in jit_common.c; point evaluation and iteration are in
 * jit_eval.c, the Newton solve in jit_newton.c.  Without libgccjit at
 * build time hl_tape_jit_taylor reports HL_EUNSUP and native.c uses the
 * system compiler or the interpreter runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "tape/jit_impl.h"
#include "tape/tape_impl.h"

#ifdef HAMLIE_HAVE_GCCJIT

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
        f = hl_jit_import1(&T->J, name);
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
                 gcc_jit_context_new_call(T->J.c, NULL, hl_jit_import_lib(&T->J, HL_OP_POWK), 2,
                                          args));
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
                 gcc_jit_context_new_call(T->J.c, NULL, hl_jit_import_lib(&T->J, HL_OP_ATAN2), 2,
                                          args));
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
    gcc_jit_context *c;
    int fma;
    /* -O1 as native.c: -O2's scheduling costs much compile time on these
     * long blocks for little gain */
    hl_status status = hl_jit_context_new(&c, 1, &fma, err);
    if (status != HL_OK)
        return status;
    tj Tv = {.S = order + 1, .fma = fma}, *T = &Tv;
    hl_jit_init(&T->J, c, t);
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
    gcc_jit_result *res;
    void *f;
    status = hl_jit_compile(&res, &f, c, "hl_native", "the recursion", err);
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

#else /* no libgccjit */

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
