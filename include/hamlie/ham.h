/* hamlie — Hamiltonian systems and §2 of the paper.
 *
 * A system is N pairs (q_j, p_j) of canonical variables, parameters (symbols
 * that are neither; symbolic, or given values), the step symbol D, and
 * usually a Hamiltonian H.  It owns an expression pool and an exact-algebra
 * context whose base symbols are q_1..q_N, p_1..p_N, the symbolic parameters,
 * then D, in that order.
 *
 * Default pairing when no pairs are given (first rule that fits the symbols
 * of H and of the extra formulas):
 *   px, py, pz (any p<letter> whose <letter> is not itself a momentum) pair
 *   with x, y, z;  p1..pN with q1..qN;  p with q, else p with x.
 * The pairs keep the order of --pairs; inferred ones (and the parameters)
 * are in a fixed order that does not depend on how H is written: x, y, z;
 * then indexed names by letters and index as a number (q2 before q10); then
 * the rest by name.  H itself is kept with its terms and factors in a fixed
 * order (hl_expr_ordered), so its numbers do not depend on that either.
 * The step is named "D" unless the spec names it otherwise (a Morse depth D
 * is a parameter once the step is called, say, "h"); the step cannot appear
 * in H nor in a function of the phase variables (hl_system_read_phase), nor
 * be a variable or a parameter.  "H" in a formula names the Hamiltonian,
 * "pi" is pi.
 *
 * Every function reading user text reports errors with the position in that
 * text (err->src, err->pos).
 */
#ifndef HAMLIE_HAM_H
#define HAMLIE_HAM_H

#include "hamlie/error.h"
#include "hamlie/expr.h"
#include "hamlie/alg.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_system hl_system;

typedef struct hl_system_spec {
    const char *H;            /* the Hamiltonian, or NULL (a map-only system) */
    const char *pairs;        /* "x:px,y:py", or NULL for the default pairing */
    const char *params;       /* "k=2,omega=1/3": parameter values, or NULL */
    const char *const *extra; /* NULL-terminated list of other formulas whose
                                 symbols count when inferring variables, or NULL */
    const char *step;         /* the step's name, or NULL for "D" */
} hl_system_spec;

hl_status hl_system_new(hl_system **out, const hl_system_spec *spec, hl_error *err);
void hl_system_free(hl_system *sys); /* NULL is a no-op */

int hl_system_ndof(const hl_system *sys);
const char *hl_system_coord(const hl_system *sys, int j);    /* q_j's name */
const char *hl_system_momentum(const hl_system *sys, int j); /* p_j's name */
int hl_system_nparams(const hl_system *sys);                 /* symbolic ones */
const char *hl_system_param(const hl_system *sys, int i);
int hl_system_has_H(const hl_system *sys);
const char *hl_system_step(const hl_system *sys); /* the step's name: "D" or the spec's */

hl_alg_ctx *hl_system_ctx(hl_system *sys);
hl_pool *hl_system_pool(hl_system *sys);
const hl_alg *hl_system_H(const hl_system *sys);
const hl_expr *hl_system_H_expr(const hl_system *sys); /* ordered, params set */

/* Parameters given a value (--param): their number, names and values. */
int hl_system_nset(const hl_system *sys);
const char *hl_system_set_name(const hl_system *sys, int i);
const hl_expr *hl_system_set_value(const hl_system *sys, int i);

/* Base-symbol indices in the algebra context. */
int hl_system_var_q(const hl_system *sys, int j); /* = j */
int hl_system_var_p(const hl_system *sys, int j); /* = N + j */
int hl_system_var_D(const hl_system *sys);

/* Read a formula of this system: its symbols must be coordinates, momenta,
 * symbolic parameters, the step, or H.  Set parameters are substituted. */
hl_status hl_system_read(hl_alg *out, hl_system *sys, const char *formula, hl_error *err);

/* The same for a function of the phase variables (an integral, a bracket's
 * argument, an observable): the step is refused, pointing at it. */
hl_status hl_system_read_phase(hl_alg *out, hl_system *sys, const char *formula, hl_error *err);

/* Read a map "X = f; P = g" giving the image of every phase variable.  An
 * image is matched to its variable by name (the left side is the variable's
 * name in upper case, or the name followed by a prime: X or x'); else the
 * items are taken in the order q_1..q_N, p_1..p_N.  A named image may use
 * the images named before it ("P = p - D*sin(q); Q = q + D*P"); one used
 * before it is given (an implicit map) is refused, pointing at it.  images
 * has 2N entries. */
hl_status hl_system_read_map(hl_alg *images, hl_system *sys, const char *map, hl_error *err);

/* ---- §2: bracket and generator --------------------------------------- */

/* {a,b} = sum_j da/dq_j db/dp_j - db/dq_j da/dp_j */
hl_status hl_bracket(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_system *sys, hl_error *err);

/* The evolution generator g = sum_j xi_j d/dq_j + eta_j d/dp_j with
 * xi_j = dH/dp_j, eta_j = -dH/dq_j (arrays of N elements each). */
hl_status hl_generator(hl_alg *xi, hl_alg *eta, hl_system *sys, hl_error *err);

/* g o phi = {phi, H} */
hl_status hl_generator_apply(hl_alg *r, const hl_alg *phi, hl_system *sys, hl_error *err);

/* Lie series.  terms[k] = g^k phi for k = 0..order (order+1 entries).
 * Refuses (HL_ELIMIT) an order above HL_LIE_MAX_ORDER, and a series whose
 * terms together hold more than HL_LIE_MAX_TERMS polynomial terms (about
 * 1.6 GB for Kepler, whose coefficients grow like factorials): once a few orders are known, their growth is extrapolated and a
 * request that would not fit is refused at once, saying which order would. */
#define HL_LIE_MAX_ORDER 200
#define HL_LIE_MAX_TERMS 2000000L
hl_status hl_lie_terms(hl_alg *terms, const hl_alg *phi, int order, hl_system *sys, hl_error *err);

/* The same, calling progress(k, order, arg) after each g^k phi (may be
 * NULL); a non-zero return stops it (HL_ESTOP, terms[0..k] computed). */
hl_status hl_lie_terms_watched(hl_alg *terms, const hl_alg *phi, int order, hl_system *sys,
                               hl_progress_fn progress, void *arg, hl_error *err);

/* exp(D g) phi truncated after D^order: sum_k D^k/k! g^k phi. */
hl_status hl_lie_series(hl_alg *r, const hl_alg *phi, int order, hl_system *sys, hl_error *err);

/* ---- §2: checks -------------------------------------------------------- */

/* Is I an integral of motion ({I,H} = 0)?  The bracket is returned in br
 * (if not NULL) so the caller can show what is left over. */
hl_status hl_check_integral(int *yes, hl_alg *br, const hl_alg *I, hl_system *sys, hl_error *err);

/* Brackets {f_i, f_j} for i < j, row-major into the n x n matrix br
 * (antisymmetric; diagonal zero).  *all_zero says whether they are in involution. */
hl_status hl_check_involution(int *all_zero, hl_alg *br, const hl_alg *f, int n, hl_system *sys,
                              hl_error *err);

/* Rank of the Jacobian d(f_1..f_n)/d(q,p) over the field of rational
 * functions (exact elimination; the numeric zero test may be used, see alg.h). */
hl_status hl_jacobian_rank(int *rank, const hl_alg *f, int n, hl_system *sys, hl_error *err);

/* The 2N x 2N matrix of brackets {Z_a, Z_b} of a map's images Z = (Q, P)
 * (row-major).  The map is canonical when it equals J = [[0, I], [-I, 0]];
 * *canonical says whether it does, for every value of D. */
hl_status hl_check_canonical(int *canonical, hl_alg *br, const hl_alg *images, hl_system *sys,
                             hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
