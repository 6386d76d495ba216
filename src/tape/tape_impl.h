/* Internals of the tape layer shared by compile.c, eval.c and taylor*.c. */
#ifndef HAMLIE_TAPE_IMPL_H
#define HAMLIE_TAPE_IMPL_H

#include <flint/fmpq.h>
#include <arb.h>
#include "hamlie/tape.h"

typedef struct hl_instr {
    int op;   /* hl_op */
    int d;    /* destination */
    int a, b; /* operands (b: a constant register for the K ops; -1 if none) */
    int x;    /* aux register (SINCOS .. ACOS), else -1 */
} hl_instr;

/* A constant leaf: a rational literal or pi. */
typedef struct hl_leaf {
    int reg;
    int is_pi;
    fmpq_t q;
} hl_leaf;

struct hl_tape {
    int nin, nout, nregs;
    int *outreg;            /* nout registers */
    hl_instr *code;         /* the body: instructions depending on inputs */
    int ncode;
    hl_instr *pro;          /* the prologue: instructions on constants only */
    int npro;
    hl_leaf *leaf;
    int nleaf;
    unsigned char *isconst; /* nregs flags */

    double *rd;             /* double registers; constants filled at compile */

    arb_ptr ra;             /* Arb registers; constants valid at ra_prec */
    slong ra_prec;          /* 0 = constants not computed yet */

    double *td;             /* Taylor double: nregs * ts coefficients */
    struct hl_prog *tprog;  /* the rules recorded for this layout (prog_impl.h) */
    struct hl_prog *pprog;  /* the point rules recorded over rd (eval.c) */
    void *native_so;        /* hl_tape_native: the loaded object, its entry, */
    void (*native_fn)(double *R); /* and the order it was made for */
    int native_order;
    void *jit_result;       /* hl_tape_jit: the compiled evaluation (a gcc_jit_result) */
    void (*jit_fn)(const double *in, double *out); /* and its entry; eval_d calls it */
    long (*jit_iter)(double *z, long n); /* hl_tape_iterate's loop, if nout <= nin */
    long (*jit_watch)(double *z, long n, double w0, double *dev); /* hl_tape_iterate_watch's */
    void *native_jit;       /* hl_tape_native through libgccjit: the gcc_jit_result */
    int ts;                 /* td's stride (order + 1), 0 = not laid out */
    size_t tdcap;

    arb_ptr ta;             /* Taylor Arb: nregs * tas coefficients */
    int tas;
    slong ta_prec;
    size_t tacap;
    struct hl_arb_em *aem; /* the Arb emitter of the body (arb_em_impl.h) */
};

/* The ODE step of every double back end (prog.c, jit_taylor.c, emit_c.c),
 * z_i[k+1] = f_i[k] / (k+1): input i's coefficient k+1 is the coefficient
 * k of register reg times hi + lo, as fma(c, hi, c lo), or c hi where lo
 * is 0 (hl_rule_recip_split: the quotient rounded once).  Where input i's
 * derivative is another input j whose derivative is computed (q' = p, a
 * mechanical system's coordinate), z_i[k+1] = z_j[k] / (k+1) is taken as
 * f_j[k-1] / (k (k+1)): one rounding where there were two, and the chain
 * from one order to the next (q, f, p, q) one division shorter (taylor.c). */
typedef struct hl_ode_source {
    int reg, k;
    double hi, lo;
} hl_ode_source;
void hl_tape_ode_source(hl_ode_source *src, const hl_tape *t, int i, int k);

/* newton.c: hl_newton */
typedef int (*hl_newton_jit_fn)(const double *x, double *U, int *iters, double *last,
                                double *Z);
struct hl_newton {
    hl_tape *start, *F, *FJ; /* borrowed */
    hl_tape *Z;              /* convergence on Z(x, U) if not NULL (borrowed) */
    int nx, m, max_iter, nz;
    double *in, *out, *A, *b, *dinv, *z, *zprev;
    int *piv;
    void *jit_result;        /* hl_newton_jit: the gcc_jit_result and its entry */
    hl_newton_jit_fn jit_fn;
};

/* eval.c */
void hl_tape_run_arb(const hl_instr *code, int n, arb_ptr r, slong prec);
void hl_tape_consts_arb(arb_ptr r, slong prec, const hl_tape *tape);

/* jit_taylor.c: the Taylor-ODE recursion of emit_c.c compiled by libgccjit
 * (HL_EUNSUP without it); the result is released by hl_tape_jit_release. */
hl_status hl_tape_jit_taylor(void **result, void (**fn)(double *R), const hl_tape *t, int order,
                             hl_error *err);
void hl_tape_jit_release(void *result);
/* The same recursion with every value a vector of lanes doubles (lanes a
 * power of 2 up to HL_TAPE_BATCH_MAX_LANES; 1 is hl_tape_jit_taylor): R
 * holds coefficient j of input i of lane l at (i * (order+1) + j) * lanes
 * + l, aligned to lanes doubles (jit_batch.c). */
hl_status hl_tape_jit_taylor_lanes(void **result, void (**fn)(double *R), const hl_tape *t,
                                   int order, int lanes, hl_error *err);

#endif
