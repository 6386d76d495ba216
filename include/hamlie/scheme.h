/* hamlie — one-step schemes: one definition, two readings.
 *
 * A scheme is written once, for any number N of degrees of freedom, as a
 * ';'-separated list of VECTOR equations (the scheme language):
 *
 *   q, p        the current point (N components each)
 *   Q, P        the next point (unknowns)
 *   D           the step (a scalar)
 *   k1 = ...    a name that is the whole left side of an equation and is not
 *               one of the above is a stage: N more unknowns
 *   Hq(a, b)    the gradient dH/dq at the point (a, b) (a vector)
 *   Hp(a, b)    the gradient dH/dp at (a, b) (a vector)
 *   H(a, b)     the Hamiltonian at (a, b) (a scalar)
 *   dot(a, b)   sum_j a_j b_j (a scalar)
 *   int(s, f)   the integral of f over s in [0, 1] (f scalar or vector)
 *   sin(a) ...  the expression language's functions, elementwise
 *   pi, numbers, the system's parameters (scalars; a stage's name hides a
 *               parameter of the same name)
 * Arithmetic is elementwise, a scalar combines with every component.
 * Examples: "Q = q + D*Hp(q, p); P = p - D*Hq(q, p)" (explicit Euler),
 * "(Q-q)/D = Hp((q+Q)/2, (p+P)/2); (P-p)/D = -Hq((q+Q)/2, (p+P)/2)".
 *
 * The text is read by the expression parser (hl_parse_list_ext, which hands
 * Hq, Hp, H, dot and int to the scheme reader); src/scheme/read.c then
 * gives each node of the tree its scalar or vector value.
 *
 * Instantiated for a system (hl_scheme_new & co.), a scheme becomes an
 * hl_scheme: m scalar unknowns with reserved names that no user symbol can
 * take ("Q#1", "P#2", "k1#1": the component index is 1-based), m scalar
 * equations lhs = rhs over the system's symbols, D and the unknowns, and
 * the unknowns' values at D = 0 (Q, P: q, p; a stage: the right side of
 * its defining equation at D = 0, in order; an error when that still
 * involves an unknown, e.g. "k = k + D").  Stages are N-vectors (there
 * are no scalar stages).  An integral int(s, f) stays a marked
 * symbol "I#k" whose integrand int_body[k] is written in the symbol "s#";
 * each reading replaces it by a quadrature:
 *   series:  an interpolatory rule on n + 1 equally spaced rational nodes,
 *            exact for polynomials of degree n in s.  The D^k coefficient of
 *            an integrand that depends on s only through s*(Z - z), with
 *            Z - z = O(D) (average vector field, Itoh-Abe), is a polynomial
 *            of degree <= k in s, so the series to O(D^n) is exact.  For a
 *            user's integrand this is assumed, not checked.
 *   numeric: a rule exact for polynomials of degree 2 HL_SCHEME_GAUSS_NODES
 *            - 1 in s: Gauss-Legendre, or the integrand's Taylor series at
 *            s = 1/2 (even terms) where that costs at most half (one sin a
 *            residual for the pendulum's average vector field, not eight)
 *            and the integrand is entire (polynomials, sin, cos, exp, sinh,
 *            cosh of arguments linear in s); each step checks that the
 *            series' truncation is below rounding there and is otherwise
 *            taken again with Gauss-Legendre (hl_scheme_stepper_fallbacks).
 * Both readings consume only this structure; a reading never re-parses.
 *
 * Lifetime: an hl_scheme borrows its system (expressions live in the
 * system's pool); free the scheme before the system.
 */
#ifndef HAMLIE_SCHEME_H
#define HAMLIE_SCHEME_H

#include "hamlie/error.h"
#include "hamlie/expr.h"
#include "hamlie/alg.h"
#include "hamlie/ham.h"
#include "hamlie/series.h"
#include "hamlie/tape.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the instantiated scheme (read-only for callers) ------------------ */

typedef struct hl_scheme {
    hl_system *sys;          /* borrowed */
    char *name;              /* "gauss2", "user", ... */
    int N;                   /* degrees of freedom */
    int m;                   /* number of unknowns = number of equations */
    char **unknown;          /* reserved names, m */
    char **display;          /* names for messages ("X", "PX", "k1[2]"), m */
    const hl_expr **z0;      /* unknown's value at D = 0 (system symbols), m */
    const hl_expr **lhs;     /* equation i: lhs[i] = rhs[i], m */
    const hl_expr **rhs;
    int *defines;            /* equation i's left side is unknown defines[i], or -1 */
    int *expl;               /* equation i is explicit: defines[i] >= 0 and its
                                right side uses only unknowns defined by
                                equations before i */
    int all_explicit;        /* every equation explicit: steps by evaluation */
    int *iQ, *iP;            /* indices in unknown[] of Q_j and P_j, N each */
    int nint;                /* integrals */
    char **int_name;         /* "I#1", ... */
    const hl_expr **int_body;/* integrand, in the symbol HL_SCHEME_S */
} hl_scheme;

#define HL_SCHEME_S "s#"

void hl_scheme_free(hl_scheme *s); /* NULL is a no-op */

/* ---- the catalog ------------------------------------------------------- */

enum {
    HL_SCHEME_SYMPLECTIC = 1 << 0,  /* a canonical map for every H */
    HL_SCHEME_PRESERVES_H = 1 << 1, /* H(Q, P) = H(q, p) exactly */
    HL_SCHEME_IMPLICIT = 1 << 2,    /* implicit for a general H */
    HL_SCHEME_SEPARABLE = 1 << 3,   /* explicit only when H = T(p) + V(q) */
    HL_SCHEME_OSCILLATOR = 1 << 4,  /* only for H = (p^2 + q^2)/2, one dof */
    HL_SCHEME_QUADRATIC = 1 << 5    /* only for H quadratic in the phase variables */
};

#define HL_SCHEME_EXACT (-1)
#define HL_SCHEME_ORDER_N (-2) /* a family: the order is the N of the name */

/* The truncated Lie series is a family, lie1 .. lie20 (lie1 is explicit
 * Euler).  20 because the step's own truncation D^(N+1)/(N+1)! g^(N+1) z is
 * then below double rounding for any step D < 1 (1/21! = 2e-20): higher
 * orders change no double, and their terms grow factorially (Kepler).  The
 * adaptive Taylor integrator (flow.h) is the tool for high orders. */
#define HL_SCHEME_LIE_MAX 20

typedef struct hl_scheme_info {
    const char *name;
    const char *description;
    int order;      /* theoretical order; HL_SCHEME_EXACT for a scheme exact
                       on its system; HL_SCHEME_ORDER_N for the family lieN */
    unsigned flags;
} hl_scheme_info;

/* The catalog as listed: the family lieN is one entry. */
int hl_scheme_catalog_count(void);
const hl_scheme_info *hl_scheme_catalog(int i);
/* A scheme's info by name, members of lieN included ("lie6": order 6);
 * NULL if none. */
const hl_scheme_info *hl_scheme_lookup(const char *name);

/* Instantiate catalog scheme `name` for sys: a catalog name, or lieN with
 * N = 1..HL_SCHEME_LIE_MAX; "lie" alone is lie<param> (param > 0), param is
 * ignored by the others.  HL_EINVAL for an unknown name (the message lists
 * the catalog, or the range of N), for a system without H, and for an
 * oscillator-only scheme on another system. */
hl_status hl_scheme_new(hl_scheme **out, const char *name, int param, hl_system *sys,
                        hl_error *err);

/* The language text of a catalog scheme that has one (NULL for the C
 * generators: rk4, gauss*, lie, yoshida4, itoh-abe, gonzalez). */
const char *hl_scheme_text(const char *name);

/* ---- user schemes ------------------------------------------------------ */

/* A definition in the scheme language (above), for sys. */
hl_status hl_scheme_from_text(hl_scheme **out, const char *def, hl_system *sys, hl_error *err);

/* A map "X = ...; P = ..." or equations "(X-x)/D = (P+p)/2; ..." written
 * with the system's own names: the next point is the variable's name in
 * upper case (or first letter upper: Px) or followed by a prime (x'); "H"
 * is the Hamiltonian.  A map must give each image once, as "image = f"; the
 * right sides may use images given before (X = ...; P = p - D*X). */
hl_status hl_scheme_from_map(hl_scheme **out, const char *map, hl_system *sys, hl_error *err);
hl_status hl_scheme_from_equations(hl_scheme **out, const char *eqs, hl_system *sys, hl_error *err);

/* ---- generators -------------------------------------------------------- */

/* Runge-Kutta on z' = J grad H from a Butcher tableau with s stages:
 * A[i*s + j] and b[i] are expressions in the expression language ("1/4",
 * "1/4 - sqrt(3)/6").  Stage unknowns k_i (dq) and l_i (dp). */
hl_status hl_scheme_rk(hl_scheme **out, const char *name, int s, const char *const *A,
                       const char *const *b, hl_system *sys, hl_error *err);

/* The truncated Lie series Q = sum_{k<=n} D^k/k! g^k q (and P). */
hl_status hl_scheme_lie(hl_scheme **out, int n, hl_system *sys, hl_error *err);

/* The composition psi_{c_r D} o ... o psi_{c_1 D} of instances of the
 * language scheme `text` (c_i expressions: "1/(2 - 2^(1/3))"). */
hl_status hl_scheme_compose(hl_scheme **out, const char *name, const char *text, int r,
                            const char *const *c, hl_system *sys, hl_error *err);

/* The exact flow exp(D g) z in closed form when the field is affine (H of
 * degree <= 2 in the phase variables; parameters allowed) and H couples no
 * two pairs: per pair cos/sin of sqrt(w2) D, cosh/sinh for a rational
 * w2 < 0, polynomials for w2 = 0 (w2 = H_qq H_pp - H_qp^2).  images: 2N
 * elements (Q_1..Q_N, P_1..P_N).  Coupled pairs with rational coefficients:
 * per normal mode (spectral projectors of A^2, A = J Hess H, when its
 * minimal polynomial is squarefree with real roots and factors of degree
 * <= 2; the coefficients a + b sqrt(d)).  HL_EINVAL when H is not
 * quadratic, HL_EUNSUP (the reason named) for coupled pairs otherwise.
 * _map writes the same as a map "x' = ...; p' = ..." (hl_scheme_from_map
 * reads it back); *map is malloc'd. */
hl_status hl_scheme_linear_flow(hl_alg *images, hl_system *sys, hl_error *err);
hl_status hl_scheme_linear_flow_map(char **map, hl_system *sys, hl_error *err);
/* 1 when hl_scheme_linear_flow succeeds for sys (the catalog's "exact"
 * applies), else 0. */
int hl_scheme_linear_flow_applies(hl_system *sys);
/* For a quadratic H that couples its pairs and has a closed form: its
 * normal modes as text, one per eigenvalue of A^2, e.g. "elliptic w =
 * sqrt(5/2 - sqrt(13)/2); elliptic w = sqrt(sqrt(13)/2 + 5/2)" (w the
 * frequency, or the rate of a hyperbolic mode; "free" for w = 0), malloc'd.
 * HL_EUNSUP when H does not couple its pairs or has no closed form here. */
hl_status hl_scheme_linear_modes(char **text, hl_system *sys, hl_error *err);

/* ---- the symbolic reading ---------------------------------------------- */

/* Z[0..N-1] = Q, Z[N..2N-1] = P as series in D to O(D^n) (Z initialised by
 * the caller; they are overwritten).  Explicit schemes are evaluated in
 * order (Taylor mode); others are solved order by order (hl_series_solve).
 * Errors (HL_EINVAL): not the identity at D = 0, not determined at D = 0,
 * and, when the system has H and n >= 2, not consistent: the D^1
 * coefficient is not the generator (dH/dp, -dH/dq). */
hl_status hl_scheme_expand(hl_series *Z, const hl_scheme *s, int n, hl_error *err);

/* ---- the numeric reading -------------------------------------------------- */

/* A stepper: the scheme compiled to tapes (tape.h) for steps in double.
 * Explicit schemes: the equations are inlined in order into one tape
 * z, D -> (Q, P) (shared subexpressions computed once).  Others: an unknown
 * that an equation gives explicitly (U = an expression free of U: Q and P of
 * a Runge-Kutta scheme) is substituted into the other equations, and Newton
 * solves the rest F = lhs - rhs (simplified Newton: the Jacobian dF/dU, from
 * hl_expr_diff compiled with F, is evaluated and factored at the start and
 * again only when convergence slows; it stops when a correction is at
 * rounding level), starting from the unknowns' values at D = 0 with (Q, P)
 * predicted by explicit Euler; the next point is the one Newton's
 * convergence test computed (hl_newton_output).  Integrals: the numeric
 * rule above.  An equation that divides by an expression in the unknowns
 * is first put in exact canonical form (alg.h), which
 * removes 0/0 such as the paper's (P^2 - p^2)/(P - p) at P = p.  Every
 * parameter must have a value.  The stepper keeps no reference to the
 * scheme (its tapes are self-contained); it borrows nothing. */
#define HL_SCHEME_GAUSS_NODES 8
#define HL_SCHEME_NEWTON_MAX 50

typedef struct hl_scheme_stepper hl_scheme_stepper;

hl_status hl_scheme_stepper_new(hl_scheme_stepper **out, const hl_scheme *s, hl_error *err);
void hl_scheme_stepper_free(hl_scheme_stepper *st); /* NULL is a no-op */

/* One step: z[0..N-1] = q, z[N..2N-1] = p are replaced by (Q, P).  t is the
 * time of z (for messages only); the stepper counts its steps.  HL_ENOCONV
 * when Newton does not converge in HL_SCHEME_NEWTON_MAX iterations (the
 * message names the step and the time), HL_EDOM when a value is not
 * finite; z is left untouched on failure. */
hl_status hl_scheme_step(hl_scheme_stepper *st, double *z, double D, double t, hl_error *err);

/* Compile the stepper's tapes to machine code (tape.h: hl_tape_jit) when
 * a run of nsteps steps evaluates each of them often enough for the
 * compilation to pay (tape.h: hl_tape_compile_pays, hl_newton_compile_pays);
 * the steps stay the same bit for bit.
 * Best effort: without libgccjit, or if compiling fails, the interpreter
 * goes on.  Returns how many tapes are now machine code. */
int hl_scheme_stepper_jit(hl_scheme_stepper *st, long nsteps);

/* Newton iterations taken by the last step (0 for an explicit scheme). */
int hl_scheme_stepper_iterations(const hl_scheme_stepper *st);

/* Steps taken with Gauss-Legendre rules since the last restart because a
 * Taylor rule's truncation was above rounding there (a long step:
 * |Q - q| > 1.16 for the pendulum's average vector field); once they are
 * at least 64 and half of the steps, the Gauss rules take every step. */
long hl_scheme_stepper_fallbacks(const hl_scheme_stepper *st);

/* Set the count of steps taken (the step number in messages), e.g. to 0
 * for a new run with the same stepper (its compiled tapes are kept), or to
 * where a caller that stepped by other means hands over. */
void hl_scheme_stepper_restart(hl_scheme_stepper *st, long steps);

/* An explicit scheme's step as expressions over q_1..q_N, p_1..p_N and D
 * (integrals replaced by the stepper's Gauss sums): Z[0..2N-1] = (Q, P), the
 * expressions the stepper compiles, in the system's pool.  For callers that
 * compile the step together with other expressions (the runner fuses it
 * with H).  HL_EINVAL for an implicit scheme. */
hl_status hl_scheme_step_exprs(const hl_expr **Z, const hl_scheme *s, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
