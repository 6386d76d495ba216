/* hamlie — error analysis of one-step schemes (§4 of the paper).
 *
 * For a scheme psi_D with expansion psi_D(z) = sum_k D^k psi_k(z), the error
 * fields v_k (k >= 2) are defined by
 *   psi_D - exp(D g) = sum_k D^k/k! v_k,  v_k(z_j) = k! ([D^k] psi_j - g^k z_j / k!).
 * They are computed twice: directly (the expansion minus the Lie series) and
 * from K(D) = psi_{-D} o d/dD psi_D alone, order by order: with
 * psi~ = exp(D g) + sum_{j<k} D^j/j! v_j, the identity
 *   K(z; D) = (d/dD psi_D)(psi_{-D}(z))
 * gives v_k = (k-1)! ([D^(k-1)] K - [D^(k-1)] K~), K~ the K of psi~.
 * (The paper's printed second and third differences are not used.)
 *
 * The leading field v_m is classified (hl_errfield_kind).
 *
 * hl_analysis_compute (at the end) runs the whole of §4 in one call and
 * returns one struct: what `hamlie errors` prints, what `hamlie reproduce`
 * checks, and what a binding would return.  The functions above it are its
 * pieces, for a caller who wants one of them alone.
 */
#ifndef HAMLIE_ANALYSIS_H
#define HAMLIE_ANALYSIS_H

#include "hamlie/error.h"
#include "hamlie/alg.h"
#include "hamlie/ham.h"
#include "hamlie/series.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hl_errfield_kind {
    HL_ERRFIELD_ZERO = 0,     /* v = 0 */
    HL_ERRFIELD_TIME_SHIFT,   /* v = c g, c a constant */
    HL_ERRFIELD_PARALLEL,     /* v = lambda(z) g, lambda not constant */
    HL_ERRFIELD_SCALING,      /* v = sum_j c_j z_j d/dz_j, constants c_j */
    HL_ERRFIELD_HAMILTONIAN,  /* v = J grad h */
    HL_ERRFIELD_GENERAL
} hl_errfield_kind;

typedef struct hl_errfield {
    hl_errfield_kind kind;
    hl_alg lambda;   /* TIME_SHIFT, PARALLEL: v = lambda g */
    hl_alg *scale;   /* SCALING: c_j, 2N entries (NULL otherwise) */
    int hamiltonian; /* the Hamiltonian conditions hold (also for the kinds above) */
    int have_h;      /* h found (polynomial fields, homogeneous Euler formula) */
    hl_alg h;        /* v = J grad h: v(q_j) = dh/dp_j, v(p_j) = -dh/dq_j */
} hl_errfield;

typedef struct hl_vfields {
    int N;          /* degrees of freedom */
    int n;          /* v_k known for k = 2..n */
    hl_alg *v;      /* v[k*2N + i], k = 0..n (k < 2 are zero): direct */
    hl_alg *vK;     /* the same from K alone (zero when not checked) */
    int checked;    /* the K route was run (hl_vfields_compute) */
    int agree;      /* checked, and the two computations agree for every k */
    int disagree_k; /* first k where they do not (0 if they agree) */
    int leading;    /* m: the least k with v_k != 0, or 0 if none up to n */
    int order;      /* m - 1, or n when no error up to n (exact to that order) */
    hl_series *K;   /* K(D)'s series, 2N of psi's length - 1, when the K route
                     * computed it (else NULL) */
    long budget;    /* hl_vfields_compute_bounded: the K route's budget, and */
    int over_budget; /* it passed it: checked = agree = 0, the v_k direct only */
} hl_vfields;

/* psi: 2N series (Q_1..Q_N, P_1..P_N) known to at least O(D^(n+1)).
 * Fills e (call hl_vfields_clear after, also on failure). */
hl_status hl_vfields_compute(hl_vfields *e, const hl_series *psi, hl_system *sys, int n,
                             hl_error *err);

/* The same with the K route (a check) within a size budget: once a
 * coefficient of a composition passes max_terms terms
 * (hl_series_scheme_K_bounded) the route stops and e->over_budget = 1,
 * checked = agree = 0; e->K is kept when its own composition fitted.  The
 * v_k, leading and order come from the direct route either way. */
hl_status hl_vfields_compute_bounded(hl_vfields *e, const hl_series *psi, hl_system *sys, int n,
                                     long max_terms, hl_error *err);
void hl_vfields_clear(hl_vfields *e, hl_system *sys);

/* The direct route alone (the expansion minus the Lie series): v, leading
 * and order as above, checked = agree = 0.  Several times faster where
 * the K route dominates (RK4 on Henon-Heiles to order 8: 2-4 ms against 72). */
hl_status hl_vfields_compute_direct(hl_vfields *e, const hl_series *psi, hl_system *sys, int n,
                                    hl_error *err);

/* The field of v_k: 2N components. */
static inline hl_alg *hl_vfields_v(const hl_vfields *e, int k)
{
    return e->v + k * 2 * e->N;
}

/* Classify a vector field v (2N components on (q, p)) against the generator. */
hl_status hl_errfield_classify(hl_errfield *f, const hl_alg *v, hl_system *sys, hl_error *err);
void hl_errfield_clear(hl_errfield *f, hl_system *sys);

/* Do the 2N components v satisfy the Hamiltonian conditions
 * d a_i/d q_j + d b_j/d p_i = 0, d a_i/d p_j = d a_j/d p_i, d b_i/d q_j = d b_j/d q_i
 * (a = v(q), b = v(p))? */
hl_status hl_errfield_is_hamiltonian(int *yes, const hl_alg *v, hl_system *sys, hl_error *err);

/* ---- closed forms and corrections --------------------------------------- */

struct hl_scheme;

/* The images (Q_1..Q_N, P_1..P_N) of an explicit scheme (s->all_explicit) in
 * closed form: its equations evaluated in order.  HL_EINVAL for an implicit
 * scheme or one with integrals; HL_ELIMIT when functions (sqrt, sin, a
 * non-integer power) nest more than HL_ERRORS_MAP_MAX_NESTING deep in the
 * images, whose exact normal form swells (yoshida4 on Kepler: 4 deep, no
 * answer in a minute), or when a bound on the terms of one equation's value
 * expanded (the earlier ones' terms raised to its powers) exceeds
 * HL_ERRORS_MAP_MAX_STAGE_BOUND (yoshida4 on p^2/2 + q^6/6: degree 5^6). */
#define HL_ERRORS_MAP_MAX_NESTING 3
#define HL_ERRORS_MAP_MAX_STAGE_BOUND 1e6
hl_status hl_errors_scheme_map(hl_alg *images, const struct hl_scheme *s, hl_error *err);

/* K(D) = (d/dD psi_D)(psi_{-D}(z)) in closed form for a map given by its 2N
 * images (hl_alg_subst of psi_{-D}'s components into d psi/dD). */
hl_status hl_errors_K_closed(hl_alg *K, const hl_alg *images, hl_system *sys, hl_error *err);

/* The same within a size budget (hl_alg_subst_bounded): HL_ELIMIT, and
 * *reached the terms an intermediate polynomial reached, once one exceeds
 * max_terms; K is then left partial.  The closed form of a scheme that
 * nests radicals (Stormer-Verlet on Kepler) swells past any printable size. */
hl_status hl_errors_K_closed_bounded(hl_alg *K, long *reached, const hl_alg *images, long max_terms,
                                     hl_system *sys, hl_error *err);

/* The corrected scheme psi_D - sum_{k=2}^{m} D^k/k! v_k (m <= e->n):
 * as series (out: 2N series, the length of psi's) and, when images is not
 * NULL, as a map (images replaced in place). */
void hl_errors_correct_series(hl_series *out, const hl_series *psi, const hl_vfields *e, int m,
                              hl_system *sys);
void hl_errors_correct_map(hl_alg *images, const hl_vfields *e, int m, hl_system *sys);

/* ---- time reparametrisation (part 4) ----------------------------------- */

/* The series tau(D) = D + a_2 D^2 + ... + a_n D^n with
 * psi_D = exp(tau(D) g) + O(D^(n+1)), solved order by order: the D^k
 * coefficient of psi minus that of exp(tau_{<k}(D) g) z must be a_k g z with
 * a_k free of the phase variables.  *ok = 0 and *fail_k = k when it is not
 * (psi is then not a pure time translation at order k).  tau gets n + 1
 * coefficients.  psi: 2N series known to O(D^(n+1)). */
hl_status hl_errors_time_series(hl_series *tau, int *ok, int *fail_k, const hl_series *psi,
                                hl_system *sys, int n, hl_error *err);

/* Closed form for a map of one dof on H = (p^2 + q^2)/2 that is linear,
 * z -> M(D) z, and a rotation (M11 = M22, M12 = -M21, M11^2 + M12^2 = 1):
 * tan(tau/2) = M12/(1 + M11) =: r, tau = 2 atan(r).  When r = c D (c a
 * constant) also the step D2 with psi_D o psi_D = psi_{D2}: r(D2) = tan(tau)
 * = 2r/(1 - r^2), D2 = 2D/(1 - c^2 D^2).  *ok = 0 when the map is not such
 * a rotation; *have_D2 = 0 when r is not c D. */
hl_status hl_errors_time_closed(hl_alg *tau, hl_alg *r, int *ok, hl_alg *D2, int *have_D2,
                                const hl_alg *images, hl_system *sys, hl_error *err);

/* ---- invariants of a field (part 5) ------------------------------------ */

#define HL_INVARIANTS_MAX_MONOMIALS 2000

/* Polynomial first integrals of the field v (2N components, polynomials in
 * the phase variables with rational coefficients) of degree 1..degree: a
 * basis of {phi : v(phi) = 0}, by exact linear algebra over Q on the
 * coefficients (FLINT nullspace), each checked with v(phi) = 0.  *out is a
 * new vector of *count elements (hl_alg_vec_free it with *count, NULL when
 * 0).  *applicable = 0 when v is not such a polynomial field. */
hl_status hl_field_poly_invariants(hl_alg **out, int *count, int *applicable, const hl_alg *v,
                                   int degree, hl_system *sys, hl_error *err);

/* For a linear field (components linear forms over Q): rational first
 * integrals phi1/phi2 from Darboux polynomials, eigenvectors of v acting on
 * homogeneous polynomials of degree d = 1..degree with rational eigenvalues,
 * paired within one eigenvalue (the first eigenvector divided by each
 * other); each checked with v(phi) = 0.  *applicable = 0 when v is not
 * linear. */
hl_status hl_field_darboux_invariants(hl_alg **out, int *count, int *applicable, const hl_alg *v,
                                      int degree, hl_system *sys, hl_error *err);

/* ---- backward error analysis (part 6) ----------------------------------- */

/* The modified vector field f~ = f_1 + D f_2 + D^2 f_3 + ... (f_1 = f, the
 * generator's field) with exp(D f~) z = psi_D(z) + O(D^(n+1)), matched order
 * by order: exp(D F) z = sum_k D^k/k! L_F^k z, L_F phi = sum_i F_i dphi/dz_i,
 * and f_(j+1) = [D^(j+1)] (psi - exp(D F_(<=j)) z).  mf[j*2N + i], j = 1..n
 * (mf has (n+1)*2N entries; j = 0 is left zero).  psi: 2N series known to
 * O(D^(n+1)). */
hl_status hl_modified_field(hl_alg *mf, const hl_series *psi, hl_system *sys, int n, hl_error *err);

/* The same from psi's series alone (implicit schemes): when every
 * coefficient is linear in (q, p) with constant coefficients, a rotation to
 * O(D^(n+1)), and the series of r = M12/(1 + M11) is c D + O(D^(n+1)),
 * *ok = 1 and tau = 2 atan(c D), r = c D, D2 = 2D/(1 - c^2 D^2): identified
 * from the series to the order computed, not proved. */
hl_status hl_errors_time_closed_series(hl_alg *tau, hl_alg *r, int *ok, hl_alg *D2,
                                       const hl_series *psi, hl_system *sys, int n, hl_error *err);

/* ---- the whole analysis: one call (hamlie errors, reproduce) ------------ */


#define HL_ANALYSIS_MAX_ORDER 40
#define HL_ANALYSIS_MODIFIED_MAX 5 /* the modified field to f_5 (D^4) at most */
/* Terms an intermediate polynomial of K's closed form may reach: the closed
 * form is a bonus, and for a scheme that nests radicals (Stormer-Verlet on
 * Kepler) it swells without end.  The v_k never depend on it. */
#define HL_ANALYSIS_K_CLOSED_BUDGET 5000
/* Terms the coefficients of one composition of the K route (the check of
 * the v_k) may reach together: past it (Gonzalez on Henon-Heiles, Yoshida
 * on Kepler) the v_k are computed one way only, and the result says so. */
#define HL_ANALYSIS_K_ROUTE_BUDGET 250000

/* The parts past the v_k, each a bonus that may be left out. */
enum {
    HL_ANALYSIS_CLOSED = 1 << 0,     /* explicit schemes: the map and K(D) in closed form */
    HL_ANALYSIS_INVARIANTS = 1 << 1, /* invariants of the leading field (part 5) */
    HL_ANALYSIS_TIME = 1 << 2,       /* tau(D) when the leading field is c g (part 4) */
    HL_ANALYSIS_MODIFIED = 1 << 3,   /* modified field and Hamiltonian (part 6) */
    HL_ANALYSIS_ALL = (1 << 4) - 1
};

typedef struct hl_analysis_opts {
    int order;             /* n: v_2..v_n, 2..HL_ANALYSIS_MAX_ORDER */
    int correct;           /* M in 2..n: also psi_D - sum_{k<=M} D^k/k! v_k; 0: not */
    int invariants_degree; /* 0..8 (0: no search) */
    long K_route_budget;   /* hl_vfields_compute_bounded's budget; <= 0: none */
    long K_closed_budget;  /* hl_errors_K_closed_bounded's budget */
    unsigned parts;        /* HL_ANALYSIS_* */
} hl_analysis_opts;

/* Order 4, no correction, invariants to degree 2, the budgets above, every
 * part: what `hamlie errors` computes without options. */
void hl_analysis_opts_default(hl_analysis_opts *o);

/* Everything the analysis of one scheme found.  Flags say which parts are
 * there; what is not there is zeroed/NULL. */
typedef struct hl_analysis {
    hl_system *sys;                 /* borrowed from the caller */
    const struct hl_scheme *scheme; /* borrowed from the caller */
    int m, n;                       /* 2N phase variables; v_2..v_n */
    const char **names;             /* the m phase variable names (the system's) */
    hl_series *psi;                 /* m series: the expansion to O(D^(n+1)) */
    hl_vfields fields;              /* v_2..v_n, two ways unless over budget */
    hl_errfield leading;            /* the leading field classified, if have_leading */
    int have_leading;
    hl_series *K_series; /* K(D)'s series (m), NULL past the K route's budget */

    /* HL_ANALYSIS_CLOSED, explicit schemes without integrals */
    int closed;                         /* map in closed form (and printable) */
    hl_alg *map;                        /* m images */
    char map_omitted[HL_ERROR_MSG_MAX]; /* explicit, but the map left out: why */
    int have_K;                         /* K's closed form within budget and printable */
    hl_alg *K;                          /* m components */
    long K_terms;                       /* else the terms it reached (over budget) */
    long K_closed_budget;               /* the budget it was given */
    double K_printed;                   /* or its size written out (hl_expr_tree_size) */

    /* HL_ANALYSIS_INVARIANTS, when have_leading and invariants_degree > 0 */
    int invariants_degree, inv_poly_applicable, inv_darboux_applicable;
    int n_inv_poly, n_inv_darboux;
    hl_alg *inv_poly, *inv_darboux;

    /* HL_ANALYSIS_TIME: tried when there is no error or it is c g */
    int tried_tau, tau_ok, tau_fail;
    hl_series tau; /* tau(D), n + 1 coefficients */
    int tau_closed, have_D2, tau_series_only;
    hl_alg *tau_forms; /* tau, tan(tau/2), D2 in closed form (3) */

    /* HL_ANALYSIS_MODIFIED */
    int nmod;           /* f_1..f_nmod, nmod = min(n, HL_ANALYSIS_MODIFIED_MAX) */
    hl_alg *mod_fields; /* (nmod+1)*m: f_j at mod_fields + j*m */
    hl_alg *mod_H;      /* nmod+1: mod_H[j] the h of f_j */
    int mod_H_all;      /* every f_j Hamiltonian with its h found */

    /* opts->correct */
    int correct;
    hl_series *cpsi; /* the corrected series (m) */
    hl_alg *cmap;    /* the corrected map, when closed */
    hl_vfields cfields;
    hl_errfield cleading;
    int have_cfields, have_cleading;
} hl_analysis;

/* The error analysis of the scheme s on sys (paper §4): the expansion, the
 * v_k two ways (an "internal error" when they disagree), the leading field
 * classified, then the parts asked for in opts->parts and the corrected
 * scheme.  Every budget is a bonus's: past it the part is left out and the
 * result says so (map_omitted, have_K, fields.over_budget); the v_k never
 * depend on one.  opts NULL: hl_analysis_opts_default's.  *out is NULL on
 * failure (err set).  s and sys must outlive
 * *out; hl_analysis_free(NULL) is a no-op. */
hl_status hl_analysis_compute(hl_analysis **out, const hl_analysis_opts *opts,
                              const struct hl_scheme *s, hl_system *sys, hl_error *err);
void hl_analysis_free(hl_analysis *a);

#ifdef __cplusplus
}
#endif

#endif
