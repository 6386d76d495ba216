/* One rule per operation: what hamlie knows of an operation (its value at a
 * point, its Taylor recurrence), written once, against a small emitter
 * interface that every back end implements.
 *
 * A rule does not compute: it says what to compute, through the emitter's
 * calls (a constant, a coefficient of an operand, +, -, *, a reciprocal, a
 * libm-like function, a convolution sum, store).  A back end decides what a
 * value is:
 *   - the double and Arb interpreters (taylor.c, taylor_arb.c): numbers;
 *   - the C text and gccjit compilers (emit_c.c, jit_taylor.c): code;
 *   - the exact series of src/series (hl_alg coefficients) and the dual
 *     numbers of src/analysis/numeric.c: coefficients of their own kind.
 * So adding an operation means writing its rule in src/rules/, one file
 * per operation (heyoka's one-file-per-primitive pattern), and its entry in
 * the table of rules.c; no back end changes.
 *
 * Rules run at a known coefficient index k (0..order): at k = 0 the point
 * rule, after it the recurrence.  Loops over j inside a rule run when the
 * rule runs: the compilers unroll them, the interpreters record them once
 * per layout (see the interpreters' notes).
 *
 * Bit for bit.  Every double back end must compute the same IEEE operations
 * in the same order, so that an interpreted run and a compiled run agree to
 * the last bit.  The order is fixed here, not in the back ends:
 *   - each emitter call is one rounded operation (no fused multiply-add
 *     unless the rule asks for fma; compilers run with -ffp-contract=off);
 *   - a convolution (hl_em_conv) sums its terms in the order of
 *     hl_conv_plan (rules.c): the terms that read no coefficient k ("known"
 *     terms) from the highest j down, in four lanes by position (the
 *     i-th term added into lane i mod 4), lanes added as (l0 + l1) + (l2 + l3)
 *     (empty lanes left out), then the fresh terms (those reading a
 *     coefficient k) one by one, the term of operand x before that of y;
 *   - a term is x[j] y[k-j]; a weighted term (w x[j]) y[k-j], with
 *     w = wa j + wb rounded as written; a fresh x[k] term (w y[0]) x[k]
 *     (x[k] y[0] unweighted); a square's pair term (2 x[j]) x[k-j], its
 *     middle term x[k/2] x[k/2]; a sum of one term is that term.
 * The exact back ends (hl_alg, dual numbers) follow the same calls; order
 * does not change exact results.
 */
#ifndef HAMLIE_RULES_RULE_H
#define HAMLIE_RULES_RULE_H

#include "hamlie/tape.h"

/* A value of the back end: a double, a pointer to the back end's own object
 * (an arb, an hl_alg, a gcc_jit_rvalue, a C expression's text), or an index
 * into the back end's table of values.  The back end owns what it points to
 * (temporaries live until the rule returns, or to the end of the step). */
typedef union hl_ev {
    double d;
    void *p;
    long i;
} hl_ev;

/* The operands of an instruction, as a rule names them. */
typedef enum hl_slot {
    HL_SLOT_D, /* the result */
    HL_SLOT_A, /* the first operand */
    HL_SLOT_B, /* the second operand (a constant for the K ops: read coef 0) */
    HL_SLOT_X, /* the auxiliary series (second result, or kept for the recurrence) */
    HL_SLOT_COUNT
} hl_slot;

/* The point functions a rule may call.  Each back end maps them to libm,
 * Arb, exact algebra (hl_alg_apply) or gccjit imports, once, in a table. */
typedef enum hl_pfn {
    HL_PFN_SIN, HL_PFN_COS, HL_PFN_TAN, HL_PFN_SINH, HL_PFN_COSH, HL_PFN_TANH,
    HL_PFN_EXP, HL_PFN_LOG, HL_PFN_SQRT, HL_PFN_ATAN, HL_PFN_ASIN, HL_PFN_ACOS,
    HL_PFN_ASINH,
    HL_PFN_ATAN2, /* two arguments (y, x) */
    HL_PFN_POW,   /* two arguments (base, exponent) */
    HL_PFN_COUNT
} hl_pfn;

/* A convolution sum_{j=lo..hi} w(j) x[j] y[k-j], w(j) = wa j + wb when
 * weighted (wa, wb back-end values), else 1.  sym: x == y and the sum is
 * taken by symmetry (2 sum_{j<k/2} x[j] x[k-j] + x[k/2]^2), as a square's.
 * An empty range sums to nothing: hl_em_conv returns has = 0. */
typedef struct hl_conv {
    hl_slot x, y;
    int lo, hi, k;
    int weighted;
    hl_ev wa, wb;
    int sym;
} hl_conv;

typedef struct hl_em hl_em;

/* The emitter: one table of calls per back end.  ctx is the back end's
 * state at the current instruction; every call may be made at any k. */
typedef struct hl_em_ops {
    hl_ev (*num)(hl_em *em, long p, long q);        /* the rational p/q (q > 0) */
    hl_ev (*coef)(hl_em *em, hl_slot s, int j);     /* coefficient j of operand s */
    void (*store)(hl_em *em, hl_slot s, int j, hl_ev v);
    hl_ev (*add)(hl_em *em, hl_ev a, hl_ev b);
    hl_ev (*sub)(hl_em *em, hl_ev a, hl_ev b);
    hl_ev (*mul)(hl_em *em, hl_ev a, hl_ev b);
    hl_ev (*neg)(hl_em *em, hl_ev a);
    hl_ev (*div)(hl_em *em, hl_ev a, hl_ev b);      /* a / b, one rounding */
    hl_ev (*fma)(hl_em *em, hl_ev a, hl_ev b, hl_ev c); /* a b + c, one rounding */
    hl_ev (*call)(hl_em *em, hl_pfn f, hl_ev a, hl_ev b); /* b unused for one argument */
    /* The sum of a convolution's terms (order: see the top of this file);
     * *has = 0 and an unspecified value for an empty one. */
    hl_ev (*conv)(hl_em *em, const hl_conv *c, int *has);
    /* Values kept from coefficient 0 for the later ones (a reciprocal of a
     * coefficient 0, say): keep at k = 0, kept at k > 0.  Slots 0..1. */
    void (*keep)(hl_em *em, int slot, hl_ev v);
    hl_ev (*kept)(hl_em *em, int slot);
} hl_em_ops;

struct hl_em {
    const hl_em_ops *ops;
};

/* A rule: the point value and the Taylor recurrence of one operation.
 * point(em) stores coefficient 0 of D (and of X where X is a second result,
 * as cos beside sin) from coefficient 0 of A and B: point evaluation.
 * taylor(em, k) stores coefficient k of D and X from coefficients 0..k of
 * A, B and 0..k-1 of D, X; at k = 0 it gives point's values (it calls it)
 * and fills what the recurrence keeps (an auxiliary series, reciprocals). */
typedef struct hl_rule {
    const char *name;
    void (*point)(hl_em *em);
    void (*taylor)(hl_em *em, int k);
} hl_rule;

/* The point functions (funcs.c, one table): libm's name, the language's
 * function (HL_FUN_COUNT for pow), the number of arguments, the value in
 * double. */
const char *hl_pfn_name(hl_pfn f);
hl_fun hl_pfn_fun(hl_pfn f);
int hl_pfn_arity(hl_pfn f);
double hl_pfn_eval(hl_pfn f, double a, double b);

/* The operation that computes the language's function f; *second (if not
 * NULL) = 1 when f's value is the op's second result X (cos, cosh). */
hl_op hl_fun_op(hl_fun f, int *second);

/* The rule of op (rules.c: the table, one entry per hl_op). */
const hl_rule *hl_rule_of(hl_op op);

/* f / n for the Taylor-ODE step z[k+1] = f[k] / (k + 1), the same in every
 * double back end: fma(f, hi, f lo) with hi + lo = 1/n to twice double
 * precision (a product by 1/n alone has a rounding error of fixed sign that
 * drifts the phase over many steps; a division is slow).  lo == 0 when 1/n
 * is exact, and then the product f hi is f / n exactly. */
void hl_rule_recip_split(double *hi, double *lo, int n);

/* The order of a double convolution's terms (the bit-for-bit contract):
 * fills idx[0..n-1] with the j of the known terms in the order they are
 * added, lane[i] their lane, and fresh[0..nf-1] the j of the fresh terms in
 * the order they are added after.  idx and lane hold hi - lo + 1 entries. */
void hl_conv_plan(const hl_conv *c, int *idx, int *lane, int *n, int fresh[2], int *nf);

/* Shorthands for rules: E is the emitter. */
#define EV_NUM(E, p, q) ((E)->ops->num((E), (p), (q)))
#define EV_COEF(E, s, j) ((E)->ops->coef((E), (s), (j)))
#define EV_STORE(E, s, j, v) ((E)->ops->store((E), (s), (j), (v)))
#define EV_ADD(E, a, b) ((E)->ops->add((E), (a), (b)))
#define EV_SUB(E, a, b) ((E)->ops->sub((E), (a), (b)))
#define EV_MUL(E, a, b) ((E)->ops->mul((E), (a), (b)))
#define EV_NEG(E, a) ((E)->ops->neg((E), (a)))
#define EV_DIV(E, a, b) ((E)->ops->div((E), (a), (b)))
#define EV_FMA(E, a, b, c) ((E)->ops->fma((E), (a), (b), (c)))
#define EV_CALL(E, f, a) ((E)->ops->call((E), (f), (a), (a)))
#define EV_CALL2(E, f, a, b) ((E)->ops->call((E), (f), (a), (b)))
#define EV_KEEP(E, s, v) ((E)->ops->keep((E), (s), (v)))
#define EV_KEPT(E, s) ((E)->ops->kept((E), (s)))

#endif /* HAMLIE_RULES_RULE_H */
