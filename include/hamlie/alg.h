/* hamlie — exact algebra.
 *
 * An element is a rational function over Q in the context's variables:
 *   base symbols  (phase variables, parameters, the step D), given at creation;
 *   atoms         one per distinct transcendental or algebraic subterm
 *                 (sin u, cos u, exp u, log u, sqrt u, atan u, pi, ...), made on
 *                 demand, each with its derivative rule and its relations.
 * Polynomials are FLINT fmpz_mpoly over one fixed mpoly context whose variables
 * are the base symbols followed by room for max_atoms atoms.
 *
 * Canonical form (kept after every operation; hl_alg_is_canonical checks it):
 *   a = num / den with num, den in Z[vars], gcd(num, den) = 1, the leading
 *   coefficient of den positive (den = 1 for polynomials, num = 0 => den = 1);
 *   num reduced by the atom relations (sin^2 = 1 - cos^2 style: degree <= 1 in
 *   one atom of each sin/cos pair and in each square root);
 *   den free of those quadratic atoms (rationalised).
 * With a single family of atoms this form is unique, so zero is decided
 * exactly.  Where several atoms might be related (exp and log, sin u and
 * sin 2u, ...) hl_alg_is_zero also evaluates at random points in high
 * precision with Arb; the context remembers that it did, and callers say so.
 *
 * Functions taking an hl_error may fail: HL_EDOM (division by zero, log 0,
 * sqrt of a negative constant), HL_EINVAL (unknown symbol), HL_ELIMIT (more
 * atoms than the context has room for).  Outputs may alias inputs.
 */
#ifndef HAMLIE_ALG_H
#define HAMLIE_ALG_H

#include <flint/fmpz_mpoly.h>
#include <flint/fmpq.h>
#include <arb.h>
#include "hamlie/error.h"
#include "hamlie/expr.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_alg_ctx hl_alg_ctx;

typedef struct hl_alg {
    fmpz_mpoly_t num;
    fmpz_mpoly_t den;
} hl_alg;

/* ---- context ---------------------------------------------------------- */

/* nbase base symbols (copied), room for max_atoms atoms (0 = default 32). */
hl_alg_ctx *hl_alg_ctx_new(int nbase, const char *const *names, int max_atoms);
void hl_alg_ctx_free(hl_alg_ctx *ctx); /* NULL is a no-op */

int hl_alg_ctx_nbase(const hl_alg_ctx *ctx);
const char *hl_alg_ctx_name(const hl_alg_ctx *ctx, int i);
int hl_alg_ctx_index(const hl_alg_ctx *ctx, const char *name); /* -1 if none */
int hl_alg_ctx_natoms(const hl_alg_ctx *ctx);

/* The FLINT context, for code that works on num and den directly. */
const fmpz_mpoly_ctx_struct *hl_alg_ctx_mpoly(const hl_alg_ctx *ctx);

/* Print order: the series symbol (base symbol var, e.g. the step D; -1 for
 * none).  hl_alg_to_expr then writes terms by ascending power of it, then by
 * descending total degree in the others ("x + D*p", "1 + D^2"), and puts it
 * first in each monomial ("D^2*x").  Without it: total degree descending. */
void hl_alg_ctx_set_step(hl_alg_ctx *ctx, int var);
int hl_alg_ctx_step(const hl_alg_ctx *ctx); /* -1 if none */

/* Was a numeric (Arb) test used to decide a zero since the last reset? */
int hl_alg_ctx_numeric_used(const hl_alg_ctx *ctx);
void hl_alg_ctx_reset_numeric_used(hl_alg_ctx *ctx);

/* Results too large to print (report.h writes a note in their place,
 * hl_expr_tree_size > HL_PRINT_MAX_NODES): the size of the largest one
 * since the context was made, 0 if none, so that a command refuses its
 * output rather than print part of it. */
double hl_alg_ctx_unprinted(const hl_alg_ctx *ctx);
void hl_alg_ctx_note_unprinted(hl_alg_ctx *ctx, double nodes);

/* ---- elements --------------------------------------------------------- */

void hl_alg_init(hl_alg *a, const hl_alg_ctx *ctx); /* a = 0 */
void hl_alg_clear(hl_alg *a, const hl_alg_ctx *ctx);
void hl_alg_set(hl_alg *r, const hl_alg *a, const hl_alg_ctx *ctx);
void hl_alg_swap(hl_alg *a, hl_alg *b, const hl_alg_ctx *ctx);
void hl_alg_zero(hl_alg *r, const hl_alg_ctx *ctx);
void hl_alg_one(hl_alg *r, const hl_alg_ctx *ctx);
void hl_alg_set_si(hl_alg *r, long c, const hl_alg_ctx *ctx);
void hl_alg_set_fmpq(hl_alg *r, const fmpq_t c, const hl_alg_ctx *ctx);
void hl_alg_gen(hl_alg *r, int i, const hl_alg_ctx *ctx); /* base symbol i */

/* Arrays of elements. */
hl_alg *hl_alg_vec_new(int n, const hl_alg_ctx *ctx);
void hl_alg_vec_free(hl_alg *v, int n, const hl_alg_ctx *ctx); /* NULL is a no-op */

/* ---- arithmetic ------------------------------------------------------- */

void hl_alg_add(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx);
void hl_alg_sub(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx);
void hl_alg_neg(hl_alg *r, const hl_alg *a, hl_alg_ctx *ctx);
void hl_alg_mul(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx);
void hl_alg_scalar_mul_fmpq(hl_alg *r, const hl_alg *a, const fmpq_t c, hl_alg_ctx *ctx);
hl_status hl_alg_div(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx, hl_error *err);
hl_status hl_alg_pow_si(hl_alg *r, const hl_alg *a, long e, hl_alg_ctx *ctx, hl_error *err);

/* ---- conversion ------------------------------------------------------- */

/* Read an expression.  Every symbol must be a base symbol (else HL_EINVAL
 * naming it); functions become atoms; a^(p/q) with a rational exponent uses
 * powers and roots; a^b with b not constant is exp(b*log(a)). */
hl_status hl_alg_from_expr(hl_alg *r, const hl_expr *e, hl_alg_ctx *ctx, hl_error *err);

/* Write as an expression the way a person would (rules in print.c): terms
 * collected and ordered (see hl_alg_ctx_set_step), a minus on the first
 * factor ("-x*D", never "-(x*D)"), the denominator factored, the numerator
 * split by square roots with sqrt(u)/u^2 shown as 1/u^(3/2), a common factor
 * pulled out only when that is shorter, atoms as functions.  Printing only:
 * hl_alg_from_expr of the result gives back a exactly. */
const hl_expr *hl_alg_to_expr(const hl_alg *a, const hl_alg_ctx *ctx, hl_pool *pool);

/* A polynomial's text without the expression DAG, for printing large
 * results fast (print_poly.c): a = r * rest, split as report's formatters
 * split hl_alg_to_expr(a), with rest's text in style appended to *rest:
 * kind NONE (a is the number r, nothing appended), PRODUCT (a product of
 * powers of symbols, r its signed coefficient) or SUM (at least two terms:
 * r = 1, or the common factor pulled out, hl_alg_to_expr's rule).  The
 * bytes are those of hl_expr_print on the DAG.  Returns 0, appending
 * nothing, when it does not apply: style not text or SymPy, a not a
 * polynomial in the base symbols, more than max_terms terms, or a symbol
 * SymPy would print as Symbol('...'); then print hl_alg_to_expr(a). */
typedef struct hl_buf hl_buf;
typedef enum hl_alg_rest { HL_ALG_REST_NONE, HL_ALG_REST_PRODUCT, HL_ALG_REST_SUM } hl_alg_rest;
int hl_alg_poly_split_text(hl_buf *rest, fmpq_t r, hl_alg_rest *kind, const hl_alg *a,
                           const hl_alg_ctx *ctx, hl_pool *pool, hl_style style, long max_terms);

/* ---- calculus and structure ------------------------------------------- */

/* Partial derivative with respect to base symbol var (chain rule through atoms). */
hl_status hl_alg_diff(hl_alg *r, const hl_alg *a, int var, hl_alg_ctx *ctx, hl_error *err);

/* An antiderivative in base symbol x of f whose numerator is a polynomial in
 * x, sin(x) and cos(x) (other factors free of x) over a denominator free
 * of x (reduction formulas and integration by parts; antideriv.c).  *found
 * = 0, not an error, for anything else; a result is always checked: its
 * derivative in x is f exactly.  No constant is added. */
hl_status hl_alg_antiderivative(hl_alg *r, int *found, const hl_alg *f, int x, hl_alg_ctx *ctx,
                                hl_error *err);

/* Simultaneous substitution of base symbols vars[i] by vals[i]; atoms whose
 * arguments change become (possibly new) atoms. */
hl_status hl_alg_subst(hl_alg *r, const hl_alg *a, int n, const int *vars, const hl_alg *vals,
                       hl_alg_ctx *ctx, hl_error *err);

/* hl_alg_subst with a size budget, checked as the result grows: HL_ELIMIT,
 * and *reached the terms seen when it stopped, once a numerator or
 * denominator would exceed max_terms terms (or the canonical form's
 * products max_terms^2/10 term pairs).  max_terms <= 0: no budget. */
hl_status hl_alg_subst_bounded(hl_alg *r, long *reached, const hl_alg *a, int n, const int *vars,
                               const hl_alg *vals, long max_terms, hl_alg_ctx *ctx, hl_error *err);

/* Zero test: exact where the canonical form decides, else numeric (see top). */
int hl_alg_is_zero(const hl_alg *a, hl_alg_ctx *ctx);
int hl_alg_equal(const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx);

/* Is a a rational constant?  If so and c != NULL, set c. */
int hl_alg_is_fmpq(const hl_alg *a, fmpq_t c, const hl_alg_ctx *ctx);

/* Does a depend on base symbol var (directly or through an atom)? */
int hl_alg_depends_on(const hl_alg *a, int var, const hl_alg_ctx *ctx);

/* Coefficient of var^k when a is a polynomial in base symbol var (its
 * denominator and atoms free of var); HL_EINVAL otherwise. */
hl_status hl_alg_coeff(hl_alg *r, const hl_alg *a, int var, long k, hl_alg_ctx *ctx, hl_error *err);
long hl_alg_degree(const hl_alg *a, int var, const hl_alg_ctx *ctx); /* -1 for 0 */

/* Number of terms of num plus den: the size of an element. */
long hl_alg_length(const hl_alg *a, const hl_alg_ctx *ctx);

/* Evaluate with Arb at a point: vals[i] is the value of base symbol i.
 * HL_EDOM if a denominator or a function's domain is hit (ball contains 0). */
hl_status hl_alg_eval_arb(arb_t r, const hl_alg *a, arb_srcptr vals, slong prec, hl_alg_ctx *ctx,
                          hl_error *err);

/* Checker for tests: are all the canonical-form invariants above true? */
int hl_alg_is_canonical(const hl_alg *a, const hl_alg_ctx *ctx);

/* ---- functions (added by the alg layer) --------------------------------- */

/* r = f(a) for an expression-language function (sin, sqrt, tanh, ...):
 * tan = sin/cos, sinh/cosh/tanh through exp; exact values where they are
 * known (sin 0, sqrt(9/4), cos(pi/3), log 1); HL_EDOM outside the domain. */
hl_status hl_alg_apply(hl_alg *r, hl_fun f, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err);

/* r = f(a, b) for a function of two arguments: atan2(y, x), the angle of
 * (x, y) in (-pi, pi].  Exact where y and x are rational (atan2(0, 0) is
 * HL_EDOM); atan(y/x) where x is a positive number; odd in y. */
hl_status hl_alg_apply2(hl_alg *r, hl_fun f, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx,
                        hl_error *err);

/* r = pi. */
hl_status hl_alg_pi(hl_alg *r, hl_alg_ctx *ctx, hl_error *err);

/* r = a^e for a rational e: powers, square roots, q-th roots. */
hl_status hl_alg_pow_fmpq(hl_alg *r, const hl_alg *a, const fmpq_t e, hl_alg_ctx *ctx,
                          hl_error *err);

/* r = a^b: pow_fmpq when b is a rational constant, else exp(b*log(a)). */
hl_status hl_alg_pow(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
