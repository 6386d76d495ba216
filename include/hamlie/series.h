/* hamlie — exact truncated power series in the step.
 *
 * A series is c[0] + c[1] D + ... + c[n-1] D^(n-1) + O(D^n) whose coefficients
 * are exact elements of an algebra context (alg.h): rational functions of the
 * phase variables, parameters and atoms, free of D.  The series variable is
 * only a position here; "D" is whatever the caller expands in (usually the
 * context's step symbol, see hl_series_to_alg / hl_series_from_alg).
 *
 * This is the exact engine under scheme expansion and error analysis (§4 of
 * the paper): Taylor mode on expression DAGs (hl_series_eval_expr), implicit
 * schemes solved order by order (hl_series_solve), Lie series exp(D g) z
 * (hl_series_lie), composition of series maps and the paper's
 * K(D) = psi_{-D} o d/dD psi_D (hl_series_compose, hl_series_scheme_K).
 *
 * Precision: a series knows n, its number of coefficients.  The result of an
 * operation has the smallest n of its series inputs (constants are exact, so
 * D * a is known to one order more than a: see hl_series_shift).  Outputs may
 * alias inputs.  Functions taking an hl_error may fail: HL_EDOM (division by a
 * series vanishing at D = 0, log or non-integer power of such a series, a
 * pole at D = 0, or an alg domain error on a constant term), HL_EINVAL (a
 * symbol without a value, a malformed scheme), HL_ELIMIT (n above
 * HL_SERIES_MAX_N, alg out of atoms).
 */
#ifndef HAMLIE_SERIES_H
#define HAMLIE_SERIES_H

#include <flint/fmpq.h>
#include "hamlie/error.h"
#include "hamlie/expr.h"
#include "hamlie/alg.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest number of coefficients a series-building function accepts. */
#define HL_SERIES_MAX_N 1000

typedef struct hl_series {
    hl_alg *c; /* c[0..n-1]: the coefficient of D^k is c[k] */
    int n;     /* known modulo D^n */
    int alloc; /* allocated (and initialised) entries of c */
} hl_series;

/* ---- memory and simple values ----------------------------------------- */

void hl_series_init(hl_series *s, int n, const hl_alg_ctx *ctx); /* s = O(D^n) */
void hl_series_clear(hl_series *s, const hl_alg_ctx *ctx);
/* Vectors of m series (each O(D^n) at first); hl_series_vec_free(NULL, ...)
 * is a no-op. */
hl_series *hl_series_vec_new(int m, int n, const hl_alg_ctx *ctx);
void hl_series_vec_free(hl_series *s, int m, const hl_alg_ctx *ctx);
void hl_series_set(hl_series *r, const hl_series *a, const hl_alg_ctx *ctx);
void hl_series_swap(hl_series *a, hl_series *b);
/* Change n: truncate, or pad with zero coefficients. */
void hl_series_set_length(hl_series *s, int n, const hl_alg_ctx *ctx);
void hl_series_zero(hl_series *r, int n, const hl_alg_ctx *ctx);
/* r = a (a constant), known to O(D^n). */
void hl_series_set_alg(hl_series *r, const hl_alg *a, int n, const hl_alg_ctx *ctx);
/* r = a + D (the series of a variable around a), known to O(D^n). */
void hl_series_set_var(hl_series *r, const hl_alg *a, int n, const hl_alg_ctx *ctx);

/* Are the known coefficients all zero / pairwise equal?  Equality compares
 * the first min(a->n, b->n) coefficients. */
int hl_series_is_zero(const hl_series *a, hl_alg_ctx *ctx);
int hl_series_equal(const hl_series *a, const hl_series *b, hl_alg_ctx *ctx);
/* Index of the first coefficient that is not zero, or a->n if none. */
int hl_series_valuation(const hl_series *a, hl_alg_ctx *ctx);

/* ---- arithmetic ------------------------------------------------------- */

void hl_series_add(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx);
void hl_series_sub(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx);
void hl_series_neg(hl_series *r, const hl_series *a, hl_alg_ctx *ctx);
void hl_series_mul(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx);
/* HL_EDOM when b's constant term is zero. */
hl_status hl_series_div(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx,
                        hl_error *err);
void hl_series_scalar_mul(hl_series *r, const hl_series *a, const hl_alg *c, hl_alg_ctx *ctx);
void hl_series_scalar_mul_fmpq(hl_series *r, const hl_series *a, const fmpq_t c, hl_alg_ctx *ctx);
/* a^e for an integer e (e < 0 needs a nonzero constant term). */
hl_status hl_series_pow_si(hl_series *r, const hl_series *a, long e, hl_alg_ctx *ctx,
                           hl_error *err);
/* a^e for a rational e: a non-integer e needs a nonzero constant term. */
hl_status hl_series_pow_fmpq(hl_series *r, const hl_series *a, const fmpq_t e, hl_alg_ctx *ctx,
                             hl_error *err);

/* d/dD (n drops by one), a(-D), and D^k a (n grows by k). */
void hl_series_derivative(hl_series *r, const hl_series *a, hl_alg_ctx *ctx);
void hl_series_reflect(hl_series *r, const hl_series *a, hl_alg_ctx *ctx);
void hl_series_shift(hl_series *r, const hl_series *a, int k, hl_alg_ctx *ctx);

/* f(a) for an expression-language function, by the Taylor recurrences
 * (Hairer-Norsett-Wanner I.8, Jorba-Zou): only f at the constant term goes
 * through the algebra layer (hl_alg_apply); the rest is exact arithmetic. */
hl_status hl_series_apply(hl_series *r, hl_fun f, const hl_series *a, hl_alg_ctx *ctx,
                          hl_error *err);

/* ---- conversion ------------------------------------------------------- */

/* r = sum_k s->c[k] var^k, the truncated series as an element (var a base
 * symbol; the coefficients should not depend on it). */
void hl_series_to_alg(hl_alg *r, const hl_series *s, int var, hl_alg_ctx *ctx);

/* Expand a in base symbol var to O(var^n).  a rational in var with atoms free
 * of var is expanded by series division; otherwise (sin(D), sqrt(1+D)) by
 * Taylor mode on a's expression.  HL_EDOM for a pole at var = 0. */
hl_status hl_series_from_alg(hl_series *r, const hl_alg *a, int var, int n, hl_alg_ctx *ctx,
                             hl_error *err);

/* ---- Taylor mode on expressions --------------------------------------- */

/* out = e with each symbol names[i] replaced by the series vals[i] (each
 * with at least n coefficients), to O(D^n).  The DAG is compiled once (shared
 * subterms evaluated once, symbol-free subterms folded exactly by the algebra
 * layer, integer powers as products so they accept a zero constant term) and
 * run coefficient by coefficient.  HL_EINVAL naming a symbol with no value;
 * HL_EDOM as for the functions above. */
hl_status hl_series_eval_expr(hl_series *out, const hl_expr *e, int nsym, const char *const *names,
                              const hl_series *vals, int n, hl_alg_ctx *ctx, hl_error *err);

/* ---- schemes ------------------------------------------------------------ */

/* Solve a scheme order by order.  eqs[0..m-1] are equations lhs = rhs (rhs
 * NULL means lhs = 0) in the m unknowns unknowns[0..m-1] (names that are not
 * base symbols of ctx, e.g. "X", "P"), the step symbol `step` and the base
 * symbols of ctx (which stand for themselves).  z0[i] is unknown i at step 0
 * (normally the matching phase variable).  Finds Z[i], n coefficients each,
 * with every equation satisfied to O(step^n).
 *
 * An equation regular at step 0 as written (no divisor in the unknowns or
 * the step vanishing there, and not vanishing identically there) is kept as
 * written.  Any other is replaced by the numerator of lhs - rhs, cleared of
 * the largest power of the step dividing it, so (X - x)/D = ... is accepted.  The
 * numerators must vanish at (z0, step = 0) ("the scheme is not the identity at
 * D = 0") and their Jacobian in the unknowns there must be invertible ("the
 * scheme does not determine (X, P) at D = 0").  Then, for k = 1..n-1,
 * Z_k = -J0^{-1} [N(Z_{<k})]_k.  Z[0..m-1] must be initialised; they are
 * left unchanged on error.  An equation vanishing at D = 0 for every Z
 * through an atom (sin(D) (X - x - D p) = 0) is divided by D in the series
 * sense.  Both checks use hl_alg_is_zero, so they may be numeric: see
 * hl_alg_ctx_numeric_used. */
hl_status hl_series_solve(hl_series *Z, int m, const hl_eqn *eqs, const char *const *unknowns,
                          const hl_alg *z0, const char *step, int n, hl_alg_ctx *ctx,
                          hl_error *err);

/* Lie series of phi: r->c[k] = g^k phi / k!, k < n, for the generator of H
 * with canonical pairs (qvars[j], pvars[j]), j < ndof (base-symbol indices):
 *   g f = sum_j df/dq_j dH/dp_j - df/dp_j dH/dq_j. */
hl_status hl_series_lie(hl_series *r, const hl_alg *phi, const hl_alg *H, int ndof,
                        const int *qvars, const int *pvars, int n, hl_alg_ctx *ctx, hl_error *err);

/* Composition of series maps: r[i] = A[i](z; D) with base symbol vars[j]
 * replaced by the series B[j] (j < nvars), i < m, to O(D^n) where n is the
 * least of the n of the A[i] and B[j].  var_D is the base symbol of the step
 * (the coefficients of A and B must be free of it); base symbols other than
 * vars stand for themselves. */
hl_status hl_series_compose(hl_series *r, int m, const hl_series *A, int nvars, const int *vars,
                            const hl_series *B, int var_D, hl_alg_ctx *ctx, hl_error *err);

/* K(D) = psi_{-D} o d/dD psi_D of §4 (eq. Err): K[i] = (d psi_i/dD)
 * evaluated at z = psi(z; -D), for a map given by m = 2N series psi[i], the
 * image of base symbol vars[i].  n of K is one less than that of psi. */
hl_status hl_series_scheme_K(hl_series *K, int m, const hl_series *psi, const int *vars, int var_D,
                             hl_alg_ctx *ctx, hl_error *err);

/* The same within a size budget: HL_ELIMIT once the coefficients of the
 * composition's work, all together, pass max_terms terms (0: no limit),
 * checked as each is formed.  K(D) of a scheme whose expansion is large (Gonzalez on
 * Henon-Heiles) swells past any useful size. */
hl_status hl_series_scheme_K_bounded(hl_series *K, int m, const hl_series *psi, const int *vars,
                                     int var_D, long max_terms, hl_alg_ctx *ctx, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
