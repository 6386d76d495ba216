/* hamlie errors: the error fields v_k of a scheme (paper §4), computed two
 * ways, the order, the leading error classified, K(D), corrected schemes.
 * Its own options (--scheme, --equations, --correct) are taken out of argv
 * before the common parser sees the rest, as run does. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "hamlie/analysis.h"
#include "hamlie/exact.h"
#include "hamlie/numerr.h"
#include "hamlie/scheme.h"

#define ERRORS_MAX_ORDER 40
#define MOD_MAX 5 /* the modified field is computed to f_5 (D^4) at most */
#define K_PRINT_MAX 200 /* terms of K's closed form printed in text */
/* Terms an intermediate polynomial of K's closed form may reach: the closed
 * form is a bonus, and for a scheme that nests radicals (Stormer-Verlet on
 * Kepler) it swells without end.  The v_k never depend on it. */
#define K_CLOSED_BUDGET 5000
/* Terms the coefficients of one composition of the K route (the check of
 * the v_k) may reach together: past it (Gonzalez on Henon-Heiles, Yoshida on Kepler)
 * the v_k are computed one way only, and the output says so. */
#define K_ROUTE_BUDGET 250000

const char cmd_errors_help[] =
    "usage: hamlie errors -H FORMULA (--scheme NAME | --map MAP | --equations EQS)\n"
    "                     [--order N] [--correct M] [--invariants-degree d] [options]\n"
    "       hamlie errors -H FORMULA (--scheme NAME | --map MAP | --equations EQS)\n"
    "                     --numeric --at 'q=1.3,p=0' [--order N] [--json]\n"
    "\n"
    "Error analysis of a one-step scheme psi_D (paper §4).  The error fields v_k,\n"
    "k = 2..N, are defined by  psi_D - exp(D g) = sum_k D^k/k! v_k  and computed two\n"
    "ways: from the scheme's expansion minus the Lie series, and from\n"
    "K(D) = psi_{-D} o d/dD psi_D alone, order by order; the two must agree.  The\n"
    "order of the scheme is (the least k with v_k != 0) - 1.  The leading field\n"
    "is classified: a time shift c g, parallel to g (lambda(z) g), a scaling, a\n"
    "Hamiltonian field (with its h when polynomial), or general.  For an explicit\n"
    "scheme the map and K(D) are printed in closed form.  Also: invariants of the\n"
    "leading field (--invariants-degree), the time reparametrisation tau(D) when it\n"
    "is c g, and the modified vector field (backward error analysis) with its\n"
    "modified Hamiltonian when polynomial.\n"
    "\n"
    "  -H, --hamiltonian F  the Hamiltonian (required)\n"
    "  --scheme NAME        a scheme of the catalog (hamlie schemes lists them)\n"
    "  --map MAP            an explicit map 'X = ...; P = ...'\n"
    "  --equations EQS      an implicit scheme '(X-x)/D = ...; (P-p)/D = ...'\n"
    "  -n, --order N        compute v_2..v_N (2..40; default 4)\n"
    "  --correct M          also analyse psi_D - sum_{k=2}^M D^k/k! v_k (M <= N)\n"
    "  --invariants-degree d  search polynomial invariants of the leading field up\n"
    "                       to degree d, and Darboux ratios for a linear field\n"
    "                       (0..8, default 2; 0: no search)\n"
    "  --numeric            numeric analysis at the point --at, in double precision:\n"
    "                       the values v_k(z) and K(D)'s Taylor coefficients at z,\n"
    "                       by Taylor mode (no symbolic expansion; any scheme,\n"
    "                       implicit ones solved order by order), the order and\n"
    "                       the leading k (|v_k(z)| above 1e-10 k! times the size\n"
    "                       of the D^k coefficients: round-off).  --order 2..60\n"
    "                       --scheme exact for an H without a closed form (1 dof,\n"
    "                       the orbit by quadrature) is analysed this way only,\n"
    "                       from its own series at z (--order 2..8; K is not\n"
    "                       computed)\n"
    "  --at 'q=1.3,p=0'     the point: every phase variable, a number each\n"
    "  --pairs x:px,y:py    the canonical pairs\n"
    "  --param k=2          give a parameter a value (repeatable)\n"
    "  --json               print a JSON object (schema: docs/json.md)\n"
    "  --latex              print formulas as LaTeX\n"
    "  -h, --help           show this help\n"
    "\n"
    "Exit status: 0 computed; 2 usage or input error (unknown scheme, a scheme\n"
    "that is not consistent or not determined at D = 0, ...).\n"
    "Example: hamlie errors -H '(p^2+x^2)/2' --scheme euler --order 7\n";

typedef struct err_opts {
    const char *scheme, *equations, *correct_s, *invdeg_s, *at;
    int correct, invdeg, numeric;
} err_opts;

static void found_opt(void *arg, int k, const char *value)
{
    err_opts *r = arg;
    const char **slot[] = {&r->scheme, &r->equations, &r->correct_s, &r->invdeg_s, &r->at};
    if (k == 5)
        r->numeric = 1;
    else
        *slot[k] = value;
}

/* The usage checks of errors' options, after parsing (cli_begin). */
static int check_opts(void *arg, cli_opts *o, const cli_command *cmd)
{
    err_opts *r = arg;
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: the error analysis needs a Hamiltonian");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s'", o->args[0]);
    int nsrc = (r->scheme != NULL) + (o->map != NULL) + (r->equations != NULL);
    if (nsrc != 1)
        return cli_usage(cmd, nsrc == 0 ? "give a scheme: --scheme NAME, --map or --equations"
                                        : "give only one of --scheme, --map and --equations");
    if (!o->have_order)
        o->order = 4;
    if (r->numeric && r->at == NULL)
        return cli_usage(cmd, "--numeric needs the point: --at 'q=1.3,p=0'");
    if (!r->numeric && r->at != NULL)
        return cli_usage(cmd, "--at is the point of the numeric analysis: add --numeric");
    if (r->numeric && (r->correct_s != NULL || r->invdeg_s != NULL))
        return cli_usage(cmd, "--correct and --invariants-degree are symbolic: not with "
                              "--numeric");
    int maxn = r->numeric ? HL_NUMERR_MAX_ORDER : ERRORS_MAX_ORDER;
    if (o->order < 2 || o->order > maxn)
        return cli_usage(cmd, "--order must be between 2 and %d, not %d", maxn, o->order);
    if (r->correct_s != NULL) {
        char *end;
        long v = strtol(r->correct_s, &end, 10);
        if (*r->correct_s == '\0' || *end != '\0')
            return cli_usage(cmd, "--correct wants a whole number, not '%s'", r->correct_s);
        if (v < 2 || v > o->order)
            return cli_usage(cmd, "--correct must be between 2 and the order %d, not %s",
                             o->order, r->correct_s);
        r->correct = (int)v;
    }
    r->invdeg = 2;
    if (r->invdeg_s != NULL) {
        char *end;
        long v = strtol(r->invdeg_s, &end, 10);
        if (*r->invdeg_s == '\0' || *end != '\0' || v < 0 || v > 8)
            return cli_usage(cmd, "--invariants-degree wants a whole number 0..8, not '%s'",
                             r->invdeg_s);
        r->invdeg = (int)v;
    }
    return -1;
}

/* Everything computed, kept for the writers. */
typedef struct result {
    hl_system *sys;
    hl_scheme *s;
    int N, m, n;
    const char **names;  /* phase variable names, 2N */
    hl_series *psi;      /* expansion to O(D^(n+1)) */
    hl_vfields e;
    hl_errfield F;
    int have_F;
    int closed;          /* explicit: map and K in closed form */
    hl_alg *map, *K;
    char map_omitted[HL_ERROR_MSG_MAX]; /* explicit, but the map not in closed form: why */
    int have_K;          /* K's closed form within its budget */
    long K_terms;        /* else the terms it reached */
    double K_printed;    /* or, if within it, its size written out past the print limit */
    hl_series *Ks;       /* K's Taylor series */
    int correct;
    hl_series *cpsi;     /* corrected series */
    hl_alg *cmap;        /* corrected map (closed) */
    hl_vfields ce;
    hl_errfield cF;
    int have_cF, have_ce;
    int tried_tau, tau_ok, tau_fail; /* part 4: psi = exp(tau(D) g)? */
    hl_series tau;
    int tau_closed, have_D2, tau_series_only;
    hl_alg *tc;                      /* tau, tan(tau/2), D2 in closed form */
    int invdeg, inv_poly_app, inv_dar_app, ninv_poly, ninv_dar; /* part 5 */
    hl_alg *inv_poly, *inv_dar;
    int nmod;                        /* part 6: f_1..f_nmod */
    hl_alg *mf, *mh;                 /* fields ((nmod+1)*m), Hamiltonians (nmod+1) */
    int mh_all;                      /* every f_j Hamiltonian with h found */
} result;

static hl_series *series_vec(int m, hl_alg_ctx *ctx)
{
    hl_series *s = hl_xmalloc((size_t)m * sizeof *s);
    for (int i = 0; i < m; i++)
        hl_series_init(&s[i], 0, ctx);
    return s;
}

static void series_vec_free(hl_series *s, int m, hl_alg_ctx *ctx)
{
    if (s == NULL)
        return;
    for (int i = 0; i < m; i++)
        hl_series_clear(&s[i], ctx);
    free(s);
}

static int analyse(hl_vfields *e, hl_errfield *F, int *have_F, const hl_series *psi, result *R,
                   hl_error *err)
{
    int st = hl_vfields_compute_bounded(e, psi, R->sys, R->n, K_ROUTE_BUDGET, err);
    if (st == HL_OK && e->checked && !e->agree)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "internal error: v_%d computed two ways (expansion, K(D)) disagree",
                            e->disagree_k);
    if (st == HL_OK && e->leading) {
        st = hl_errfield_classify(F, hl_vfields_v(e, e->leading), R->sys, err);
        *have_F = st == HL_OK;
    }
    return st;
}

static int make_scheme(result *R, const err_opts *r, const cli_opts *o, hl_error *err)
{
    hl_system *sys = R->sys;
    int st;
    if (o->map != NULL) {
        if ((st = hl_scheme_from_map(&R->s, o->map, sys, err)) != HL_OK)
            hl_error_prefix(err, "in --map");
    } else if (r->equations != NULL) {
        if ((st = hl_scheme_from_equations(&R->s, r->equations, sys, err)) != HL_OK)
            hl_error_prefix(err, "in --equations");
    } else
        st = hl_scheme_new(&R->s, r->scheme, 0, sys, err);
    return st;
}

/* The size of R->m formulas written out (hl_expr_tree_size): what printing
 * them would cost. */
static double printed_size(const hl_alg *v, const result *R)
{
    double n = 0;
    for (int i = 0; i < R->m; i++)
        n += hl_expr_tree_size(hl_alg_to_expr(&v[i], hl_system_ctx(R->sys),
                                              hl_system_pool(R->sys)));
    return n;
}

/* An explicit scheme's map and K(D) in closed form: bonuses, each left out
 * (and said why) past its limit. */
static int closed_forms(result *R, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(R->sys);
    R->map = hl_alg_vec_new(R->m, ctx);
    R->K = hl_alg_vec_new(R->m, ctx);
    int st = hl_errors_scheme_map(R->map, R->s, err);
    if (st == HL_ELIMIT) {
        snprintf(R->map_omitted, sizeof R->map_omitted, "%s", err->msg);
        hl_error_clear(err);
        return HL_OK;
    }
    if (st != HL_OK)
        return st;
    double nodes = printed_size(R->map, R);
    if (nodes > HL_PRINT_MAX_NODES) { /* a bonus: left out, not the whole output refused */
        snprintf(R->map_omitted, sizeof R->map_omitted,
                 "%.0f terms and operators written out (the print limit is %d)", nodes,
                 HL_PRINT_MAX_NODES);
        return HL_OK;
    }
    R->closed = 1;
    st = hl_errors_K_closed_bounded(R->K, &R->K_terms, R->map, K_CLOSED_BUDGET, R->sys, err);
    if (st != HL_OK && st != HL_ELIMIT)
        return st;
    if (st == HL_OK && (R->K_printed = printed_size(R->K, R)) <= HL_PRINT_MAX_NODES)
        R->have_K = 1;
    hl_error_clear(err);
    return HL_OK;
}

static int compute(result *R, const err_opts *r, const cli_opts *o, hl_error *err)
{
    hl_system *sys = R->sys;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int st;
    if ((st = make_scheme(R, r, o, err)) != HL_OK)
        return st;
    R->psi = series_vec(R->m, ctx);
    if ((st = hl_scheme_expand(R->psi, R->s, R->n + 1, err)) != HL_OK)
        return st;
    if ((st = analyse(&R->e, &R->F, &R->have_F, R->psi, R, err)) != HL_OK)
        return st;
    if (R->e.K != NULL) { /* computed by the K route of the check */
        R->Ks = series_vec(R->m, ctx);
        for (int i = 0; i < R->m; i++)
            hl_series_set(&R->Ks[i], &R->e.K[i], ctx);
    }
    if (R->s->all_explicit && R->s->nint == 0 && (st = closed_forms(R, err)) != HL_OK)
        return st;
    if (R->have_F && R->invdeg > 0) {
        const hl_alg *v = hl_vfields_v(&R->e, R->e.leading);
        if ((st = hl_field_poly_invariants(&R->inv_poly, &R->ninv_poly, &R->inv_poly_app, v,
                                           R->invdeg, sys, err)) != HL_OK ||
            (st = hl_field_darboux_invariants(&R->inv_dar, &R->ninv_dar, &R->inv_dar_app, v,
                                              R->invdeg, sys, err)) != HL_OK)
            return st;
    }
    R->nmod = R->n < MOD_MAX ? R->n : MOD_MAX;
    R->mf = hl_alg_vec_new((R->nmod + 1) * R->m, ctx);
    R->mh = hl_alg_vec_new(R->nmod + 1, ctx);
    if ((st = hl_modified_field(R->mf, R->psi, sys, R->nmod, err)) != HL_OK)
        return st;
    R->mh_all = 1;
    hl_alg_set(&R->mh[1], hl_system_H(sys), ctx);
    for (int j = 2; j <= R->nmod && R->mh_all; j++) {
        hl_errfield G;
        if ((st = hl_errfield_classify(&G, R->mf + j * R->m, sys, err)) != HL_OK) {
            hl_errfield_clear(&G, sys);
            return st;
        }
        R->mh_all = G.hamiltonian && G.have_h;
        hl_alg_swap(&R->mh[j], &G.h, ctx);
        hl_errfield_clear(&G, sys);
    }
    if (R->e.leading == 0 ||
        (R->have_F && R->F.kind == HL_ERRFIELD_TIME_SHIFT)) { /* maybe a time translation */
        R->tried_tau = 1;
        hl_series_init(&R->tau, 0, ctx);
        R->tc = hl_alg_vec_new(3, ctx);
        if ((st = hl_errors_time_series(&R->tau, &R->tau_ok, &R->tau_fail, R->psi, sys, R->n,
                                        err)) != HL_OK)
            return st;
        if (R->closed && (st = hl_errors_time_closed(&R->tc[0], &R->tc[1], &R->tau_closed,
                                                     &R->tc[2], &R->have_D2, R->map, sys,
                                                     err)) != HL_OK)
            return st;
        if (!R->closed) { /* implicit: identify tau from the series */
            if ((st = hl_errors_time_closed_series(&R->tc[0], &R->tc[1], &R->tau_closed,
                                                   &R->tc[2], R->psi, sys, R->n, err)) != HL_OK)
                return st;
            R->have_D2 = R->tau_series_only = R->tau_closed;
        }
    }
    if (R->correct) {
        R->cpsi = series_vec(R->m, ctx);
        hl_errors_correct_series(R->cpsi, R->psi, &R->e, R->correct, sys);
        if (R->closed) {
            R->cmap = hl_alg_vec_new(R->m, ctx);
            for (int i = 0; i < R->m; i++)
                hl_alg_set(&R->cmap[i], &R->map[i], ctx);
            hl_errors_correct_map(R->cmap, &R->e, R->correct, sys);
        }
        R->have_ce = 1;
        st = analyse(&R->ce, &R->cF, &R->have_cF, R->cpsi, R, err);
    }
    return st;
}

static void result_free(result *R)
{
    if (R->sys == NULL)
        return;
    hl_alg_ctx *ctx = hl_system_ctx(R->sys);
    series_vec_free(R->psi, R->m, ctx);
    series_vec_free(R->Ks, R->m, ctx);
    series_vec_free(R->cpsi, R->m, ctx);
    if (R->e.v != NULL || R->e.vK != NULL)
        hl_vfields_clear(&R->e, R->sys);
    if (R->have_ce)
        hl_vfields_clear(&R->ce, R->sys);
    if (R->have_F)
        hl_errfield_clear(&R->F, R->sys);
    if (R->have_cF)
        hl_errfield_clear(&R->cF, R->sys);
    hl_alg_vec_free(R->map, R->m, ctx);
    hl_alg_vec_free(R->K, R->m, ctx);
    hl_alg_vec_free(R->cmap, R->m, ctx);
    hl_alg_vec_free(R->inv_poly, R->ninv_poly, ctx);
    if (R->mf != NULL) {
        hl_alg_vec_free(R->mf, (R->nmod + 1) * R->m, ctx);
        hl_alg_vec_free(R->mh, R->nmod + 1, ctx);
    }
    hl_alg_vec_free(R->inv_dar, R->ninv_dar, ctx);
    if (R->tried_tau) {
        hl_series_clear(&R->tau, ctx);
        hl_alg_vec_free(R->tc, 3, ctx);
    }
    hl_scheme_free(R->s);
    free(R->names);
}

static const char *kind_name(hl_errfield_kind k)
{
    static const char *const n[] = {"zero", "time_shift", "parallel", "scaling", "hamiltonian",
                                    "general"};
    return n[k];
}

/* ---- text and LaTeX --------------------------------------------------- */

static void put_alg(hl_buf *out, const hl_alg *a, result *R, hl_style st)
{
    char *s = hl_format_alg(a, hl_system_ctx(R->sys), hl_system_pool(R->sys), st);
    hl_buf_puts(out, s);
    free(s);
}

static void put_field(hl_buf *out, const hl_alg *v, result *R, hl_style st)
{
    char *s = hl_format_vector_field(R->m, R->names, v, hl_system_ctx(R->sys),
                                     hl_system_pool(R->sys), st);
    hl_buf_puts(out, s);
    free(s);
}

static void put_map(hl_buf *out, const char *title, const hl_alg *img, result *R, hl_style st)
{
    hl_buf_printf(out, "%s\n", title);
    for (int i = 0; i < R->m; i++) {
        char *nm = cli_image_name(R->sys, i);
        hl_buf_printf(out, "  %s = ", nm);
        put_alg(out, &img[i], R, st);
        hl_buf_puts(out, "\n");
        free(nm);
    }
}

/* A time shift c·D^k/k! puts the point ahead of the flow when c > 0. */
static const char *shift_direction(const hl_alg *c, result *R)
{
    fmpq_t q;
    fmpq_init(q);
    const char *dir = "shifted (by the sign of c)";
    if (hl_alg_is_fmpq(c, q, hl_system_ctx(R->sys)))
        dir = fmpq_sgn(q) > 0 ? "ahead" : "behind";
    fmpq_clear(q);
    return dir;
}

static void put_classification(hl_buf *out, const hl_vfields *e, const hl_errfield *F, result *R,
                               hl_style st)
{
    int k = e->leading;
    hl_buf_printf(out, "leading error v_%d: ", k);
    switch (F->kind) {
    case HL_ERRFIELD_TIME_SHIFT:
        hl_buf_puts(out, "c·g with c = ");
        put_alg(out, &F->lambda, R, st);
        hl_buf_printf(out, ", a pure time translation: the point stays on its trajectory, "
                           "|c|·%s^%d/%d! %s in time\n", hl_system_step(R->sys), k, k,
                      shift_direction(&F->lambda, R));
        break;
    case HL_ERRFIELD_PARALLEL:
        hl_buf_puts(out, "parallel to g: v = λ(z)·g with λ = ");
        put_alg(out, &F->lambda, R, st);
        hl_buf_puts(out, "\n");
        break;
    case HL_ERRFIELD_SCALING:
        hl_buf_puts(out, "a scaling: v = Σ c_j z_j ∂/∂z_j with");
        for (int i = 0; i < R->m; i++) {
            hl_buf_printf(out, "%s c_%s = ", i ? "," : "", R->names[i]);
            put_alg(out, &F->scale[i], R, st);
        }
        hl_buf_puts(out, "\n");
        break;
    case HL_ERRFIELD_HAMILTONIAN:
        hl_buf_puts(out, "a Hamiltonian vector field\n");
        break;
    default:
        hl_buf_puts(out, "general (not parallel to g, not a scaling, not Hamiltonian)\n");
    }
    if (F->hamiltonian && F->have_h) {
        hl_buf_puts(out, "  Hamiltonian: yes, v = J∇h with h = ");
        put_alg(out, &F->h, R, st);
        hl_buf_puts(out, "\n");
    } else if (F->hamiltonian)
        hl_buf_puts(out, "  Hamiltonian: yes; h not found in closed form\n");
    else
        hl_buf_puts(out, "  Hamiltonian: no\n");
}

static void put_order(hl_buf *out, const hl_vfields *e)
{
    if (e->leading)
        hl_buf_printf(out, "order: %d (leading error v_%d)\n", e->order, e->leading);
    else
        hl_buf_printf(out, "no error up to order %d (exact to the order computed)\n", e->n);
}

/* tau(D) and W(D) = tau(D) - D as series: tau's coefficients, shifted. */
static char *tau_text(result *R, int W, hl_style st)
{
    hl_alg_ctx *ctx = hl_system_ctx(R->sys);
    hl_alg *c = hl_alg_vec_new(R->tau.n, ctx);
    for (int k = 0; k < R->tau.n; k++)
        if (!(W && k == 1))
            hl_alg_set(&c[k], &R->tau.c[k], ctx);
    char *s = hl_format_series(c, R->tau.n - 1, hl_system_step(R->sys), 0, ctx,
                               hl_system_pool(R->sys), st);
    hl_alg_vec_free(c, R->tau.n, ctx);
    return s;
}

static void put_time(hl_buf *out, result *R, hl_style st)
{
    const char *D = hl_system_step(R->sys);
    if (!R->tau_ok) {
        hl_buf_printf(out, "time reparametrisation: none (the %s^%d term is not a constant "
                           "multiple of g z: not a pure time translation)\n", D, R->tau_fail);
        return;
    }
    char *t = tau_text(R, 0, st), *w = tau_text(R, 1, st);
    hl_buf_printf(out, "time reparametrisation: psi_%s = exp(tau(%s) g) + O(%s^%d)\n", D, D, D,
                  R->n + 1);
    hl_buf_printf(out, "  tau(%s) = %s + O(%s^%d)\n  W(%s) = tau(%s) - %s = %s + O(%s^%d)\n", D,
                  t, D, R->n + 1, D, D, D, w, D, R->n + 1);
    free(t);
    free(w);
    if (R->tau_closed) {
        hl_buf_puts(out, "  closed form: tan(tau/2) = M12/(1 + M11) = ");
        put_alg(out, &R->tc[1], R, st);
        hl_buf_puts(out, ", tau = ");
        put_alg(out, &R->tc[0], R, st);
        if (R->tau_series_only)
            hl_buf_printf(out, " (identified from the series to O(%s^%d), not proved)", D,
                          R->n + 1);
        hl_buf_puts(out, "\n");
    }
    if (R->have_D2) {
        hl_buf_printf(out, "  two steps of %s are one step of %s' = ", D, D);
        put_alg(out, &R->tc[2], R, st);
        hl_buf_puts(out, "\n");
    }
}

static void put_invariants(hl_buf *out, result *R, hl_style st)
{
    int k = R->e.leading;
    if (!R->inv_poly_app) {
        hl_buf_printf(out, "invariants of v_%d: not a polynomial field over Q, not searched\n", k);
        return;
    }
    hl_buf_printf(out, "polynomial invariants of v_%d of degree <= %d:", k, R->invdeg);
    for (int i = 0; i < R->ninv_poly; i++) {
        hl_buf_puts(out, i ? ", " : " ");
        put_alg(out, &R->inv_poly[i], R, st);
    }
    hl_buf_puts(out, R->ninv_poly ? " (each checked: v(phi) = 0)\n" : " none\n");
    if (R->inv_dar_app) {
        hl_buf_printf(out, "rational invariants of v_%d (ratios of Darboux polynomials):", k);
        for (int i = 0; i < R->ninv_dar; i++) {
            hl_buf_puts(out, i ? ", " : " ");
            put_alg(out, &R->inv_dar[i], R, st);
        }
        hl_buf_puts(out, R->ninv_dar ? " (each checked: v(phi) = 0)\n" : " none found\n");
    }
}

static void put_modified(hl_buf *out, result *R, hl_style st)
{
    const char *D = hl_system_step(R->sys);
    hl_buf_printf(out, "modified vector field: exp(%s f~) = psi_%s + O(%s^%d), "
                       "f~ = f_1 + %s f_2 + ... (f_1 = g):\n", D, D, D, R->nmod + 1, D);
    for (int j = 2; j <= R->nmod; j++) {
        hl_buf_printf(out, "  f_%d = ", j);
        put_field(out, R->mf + j * R->m, R, st);
        hl_buf_puts(out, "\n");
    }
    if (!R->mh_all) {
        hl_buf_puts(out, "  modified Hamiltonian: not found (some f_j is not Hamiltonian, "
                         "or its h is not polynomial)\n");
        return;
    }
    hl_alg_ctx *ctx = hl_system_ctx(R->sys);
    hl_alg *c = hl_alg_vec_new(R->nmod, ctx);
    for (int j = 1; j <= R->nmod; j++)
        hl_alg_set(&c[j - 1], &R->mh[j], ctx);
    char *s = hl_format_series(c, R->nmod - 1, D, 0, ctx, hl_system_pool(R->sys), st);
    hl_buf_printf(out, "  modified Hamiltonian: H~ = %s + O(%s^%d)\n", s, D, R->nmod);
    free(s);
    hl_alg_vec_free(c, R->nmod, ctx);
}

static void write_text(hl_buf *out, result *R, const err_opts *r, const cli_opts *o)
{
    int latex = o->format == CLI_LATEX;
    hl_style st = latex ? HL_STYLE_LATEX : HL_STYLE_TEXT;
    const char *pre = latex ? "% " : "", *D = hl_system_step(R->sys);
    hl_buf_printf(out, "%sscheme: %s\n", pre,
                  r->scheme ? r->scheme : o->map ? o->map : r->equations);
    hl_buf_printf(out, "%sH = ", pre);
    put_alg(out, hl_system_H(R->sys), R, st);
    hl_buf_puts(out, "\n");
    if (R->closed)
        put_map(out, "map:", R->map, R, st);
    else if (R->map_omitted[0])
        hl_buf_printf(out, "%smap: closed form omitted: %s\n", pre, R->map_omitted);
    for (int k = 2; k <= R->n; k++) {
        hl_buf_printf(out, latex ? "v_{%d} = " : "v_%d = ", k);
        put_field(out, hl_vfields_v(&R->e, k), R, st);
        hl_buf_puts(out, "\n");
    }
    if (R->e.checked)
        hl_buf_printf(out, "%sv_k computed two ways: agree\n", pre);
    else
        hl_buf_printf(out, "%sv_k computed one way: the check by K(D) omitted (its work "
                           "passed the budget of %d terms)\n", pre, K_ROUTE_BUDGET);
    put_order(out, &R->e);
    if (R->have_F)
        put_classification(out, &R->e, &R->F, R, st);
    if (R->closed && !R->have_K && R->K_printed > HL_PRINT_MAX_NODES)
        hl_buf_printf(out, "K(D) = psi_{-D} o d/dD psi_D: closed form omitted: %.0f terms and "
                           "operators written out (the print limit is %d)\n",
                      R->K_printed, HL_PRINT_MAX_NODES);
    else if (R->closed && !R->have_K)
        hl_buf_printf(out, "K(D) = psi_{-D} o d/dD psi_D: closed form omitted: %ld terms "
                           "(over the budget of %d)\n", R->K_terms, K_CLOSED_BUDGET);
    if (R->have_K) {
        long len = 0;
        for (int i = 0; i < R->m; i++)
            len += hl_alg_length(&R->K[i], hl_system_ctx(R->sys));
        hl_buf_printf(out, "K(%s) = psi_{-%s} o d/d%s psi_%s in closed form:", D, D, D, D);
        if (len > K_PRINT_MAX)
            hl_buf_printf(out, " %ld terms, not printed (see --json)\n", len);
        else {
            hl_buf_puts(out, "\n");
            for (int i = 0; i < R->m; i++) {
                hl_buf_printf(out, "  K_%s = ", R->names[i]);
                put_alg(out, &R->K[i], R, st);
                hl_buf_puts(out, "\n");
            }
        }
    }
    if (R->Ks == NULL)
        hl_buf_printf(out, "K(%s) series: omitted (its work passed the budget of %d terms)\n", D,
                      K_ROUTE_BUDGET);
    else
        hl_buf_printf(out, "K(%s) series to O(%s^%d):\n", D, D, R->n);
    for (int i = 0; i < R->m && R->Ks != NULL; i++) {
        char *s = hl_format_series(R->Ks[i].c, R->Ks[i].n - 1, D, 0, hl_system_ctx(R->sys),
                                   hl_system_pool(R->sys), st);
        hl_buf_printf(out, "  K_%s = %s\n", R->names[i], s);
        free(s);
    }
    if (R->have_F && R->invdeg > 0)
        put_invariants(out, R, st);
    if (R->tried_tau)
        put_time(out, R, st);
    put_modified(out, R, st);
    if (R->correct) {
        hl_buf_printf(out, "corrected scheme (v_2..v_%d subtracted):\n", R->correct);
        if (R->cmap != NULL)
            put_map(out, "corrected map:", R->cmap, R, st);
        else
            hl_buf_printf(out, "  psi_%s(z) - sum_{k=2}^{%d} %s^k/k! v_k(z)\n", D, R->correct, D);
        put_order(out, &R->ce);
        if (R->have_cF)
            put_classification(out, &R->ce, &R->cF, R, st);
    }
    cli_numeric_note(out, R->sys, o->format);
}

/* ---- JSON --------------------------------------------------------------- */

static void json_alg(hl_json *j, const char *key, const hl_alg *a, result *R)
{
    char *s = hl_format_alg(a, hl_system_ctx(R->sys), hl_system_pool(R->sys), HL_STYLE_SYMPY);
    hl_json_kv_string(j, key, s);
    free(s);
}

static void json_field(hl_json *j, const char *key, const hl_alg *v, result *R)
{
    hl_json_key(j, key);
    hl_json_vector_field(j, R->m, R->names, v, hl_system_ctx(R->sys), hl_system_pool(R->sys),
                         HL_STYLE_SYMPY);
}

/* K's D^0..D^(N-1) coefficients, one field each */
static void json_K_coefficients(hl_json *j, result *R)
{
    hl_alg_ctx *ctx = hl_system_ctx(R->sys);
    hl_json_array_begin(j);
    hl_alg *c = hl_alg_vec_new(R->m, ctx);
    for (int k = 0; k < R->n; k++) {
        for (int i = 0; i < R->m; i++)
            hl_alg_set(&c[i], &R->Ks[i].c[k], ctx);
        hl_json_vector_field(j, R->m, R->names, c, ctx, hl_system_pool(R->sys), HL_STYLE_SYMPY);
    }
    hl_alg_vec_free(c, R->m, ctx);
    hl_json_array_end(j);
}

static void json_analysis(hl_json *j, const hl_vfields *e, const hl_errfield *F, int have_F,
                          result *R)
{
    hl_json_key(j, "fields");
    hl_json_array_begin(j);
    for (int k = 2; k <= e->n; k++) {
        hl_json_object_begin(j);
        hl_json_kv_int(j, "k", k);
        json_field(j, "v", hl_vfields_v(e, k), R);
        hl_json_object_end(j);
    }
    hl_json_array_end(j);
    if (e->over_budget) {
        hl_json_key(j, "two_ways_agree");
        hl_json_null(j);
        hl_json_key(j, "check_omitted");
        hl_json_object_begin(j);
        hl_json_kv_string(j, "reason", "size_budget");
        hl_json_kv_int(j, "budget", e->budget);
        hl_json_object_end(j);
    } else
        hl_json_kv_bool(j, "two_ways_agree", e->agree);
    hl_json_kv_int(j, "order", e->order);
    hl_json_kv_bool(j, "exact_to_order_computed", e->leading == 0);
    hl_json_key(j, "leading");
    if (!have_F) {
        hl_json_null(j);
        return;
    }
    hl_json_object_begin(j);
    hl_json_kv_int(j, "k", e->leading);
    hl_json_kv_string(j, "kind", kind_name(F->kind));
    if (F->kind == HL_ERRFIELD_TIME_SHIFT || F->kind == HL_ERRFIELD_PARALLEL)
        json_alg(j, "lambda", &F->lambda, R);
    if (F->kind == HL_ERRFIELD_SCALING)
        json_field(j, "scale", F->scale, R);
    hl_json_kv_bool(j, "hamiltonian", F->hamiltonian);
    if (F->hamiltonian && F->have_h)
        json_alg(j, "h", &F->h, R);
    else {
        hl_json_key(j, "h");
        hl_json_null(j);
    }
    hl_json_object_end(j);
}

/* A JSON array of n expressions, each a string sympy reads. */
static void json_algs(hl_json *j, const hl_alg *a, int n, hl_system *sys)
{
    hl_json_array_begin(j);
    for (int i = 0; i < n; i++) {
        char *t = hl_format_alg(&a[i], hl_system_ctx(sys), hl_system_pool(sys), HL_STYLE_SYMPY);
        hl_json_string(j, t);
        free(t);
    }
    hl_json_array_end(j);
}

static void write_json(hl_buf *out, result *R, const err_opts *r, const cli_opts *o)
{
    hl_json j;
    hl_json_init_buf(&j, out);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "errors");
    cli_json_system(&j, R->sys);
    hl_json_key(&j, "scheme");
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "source", r->scheme ? "catalog" : o->map ? "map" : "equations");
    hl_json_kv_string(&j, "name", R->s->name);
    hl_json_kv_string(&j, "input", r->scheme ? r->scheme : o->map ? o->map : r->equations);
    hl_json_kv_bool(&j, "explicit", R->closed);
    hl_json_object_end(&j);
    hl_json_kv_int(&j, "order_computed", R->n);
    if (R->closed)
        json_field(&j, "map", R->map, R);
    else if (R->map_omitted[0])
        hl_json_kv_string(&j, "map_omitted", R->map_omitted);
    json_analysis(&j, &R->e, &R->F, R->have_F, R);
    if (R->have_K)
        json_field(&j, "K", R->K, R);
    else if (R->closed) {
        hl_json_key(&j, "K");
        hl_json_null(&j);
        hl_json_key(&j, "K_omitted");
        hl_json_object_begin(&j);
        int printed = R->K_printed > HL_PRINT_MAX_NODES;
        hl_json_kv_string(&j, "reason", printed ? "print_limit" : "size_budget");
        hl_json_kv_int(&j, "terms", printed ? (long)R->K_printed : R->K_terms);
        hl_json_kv_int(&j, "budget", printed ? HL_PRINT_MAX_NODES : K_CLOSED_BUDGET);
        hl_json_object_end(&j);
    }
    hl_json_key(&j, "K_coefficients");
    if (R->Ks == NULL)
        hl_json_null(&j);
    else
        json_K_coefficients(&j, R);
    hl_json_key(&j, "invariants");
    if (R->have_F && R->invdeg > 0 && R->inv_poly_app) {
        hl_json_object_begin(&j);
        hl_json_kv_int(&j, "degree", R->invdeg);
        hl_json_key(&j, "polynomial");
        json_algs(&j, R->inv_poly, R->ninv_poly, R->sys);
        hl_json_key(&j, "rational");
        if (R->inv_dar_app)
            json_algs(&j, R->inv_dar, R->ninv_dar, R->sys);
        else
            hl_json_null(&j);
        hl_json_object_end(&j);
    } else
        hl_json_null(&j);
    hl_json_key(&j, "modified");
    hl_json_object_begin(&j);
    hl_json_kv_int(&j, "terms", R->nmod);
    hl_json_key(&j, "fields");
    hl_json_array_begin(&j);
    for (int k = 1; k <= R->nmod; k++)
        hl_json_vector_field(&j, R->m, R->names, R->mf + k * R->m, hl_system_ctx(R->sys),
                             hl_system_pool(R->sys), HL_STYLE_SYMPY);
    hl_json_array_end(&j);
    hl_json_key(&j, "hamiltonians");
    if (R->mh_all)
        json_algs(&j, R->mh + 1, R->nmod, R->sys);
    else
        hl_json_null(&j);
    hl_json_object_end(&j);
    hl_json_key(&j, "time");
    if (R->tried_tau) {
        hl_json_object_begin(&j);
        hl_json_kv_bool(&j, "pure_time_translation", R->tau_ok);
        hl_json_key(&j, "fails_at");
        if (R->tau_ok)
            hl_json_null(&j);
        else
            hl_json_int(&j, R->tau_fail);
        if (R->tau_ok) {
            char *t = tau_text(R, 0, HL_STYLE_SYMPY), *w = tau_text(R, 1, HL_STYLE_SYMPY);
            hl_json_kv_string(&j, "tau_series", t);
            hl_json_kv_string(&j, "W_series", w);
            free(t);
            free(w);
        }
        if (R->tau_closed) {
            json_alg(&j, "tau", &R->tc[0], R);
            json_alg(&j, "tan_half_tau", &R->tc[1], R);
        }
        if (R->have_D2)
            json_alg(&j, "double_step", &R->tc[2], R);
        hl_json_kv_bool(&j, "closed_form_from_series", R->tau_series_only);
        hl_json_object_end(&j);
    } else
        hl_json_null(&j);
    hl_json_key(&j, "corrected");
    if (R->correct) {
        hl_json_object_begin(&j);
        hl_json_kv_int(&j, "subtracted_up_to", R->correct);
        if (R->cmap != NULL)
            json_field(&j, "map", R->cmap, R);
        json_analysis(&j, &R->ce, &R->cF, R->have_cF, R);
        hl_json_object_end(&j);
    } else
        hl_json_null(&j);
    hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(hl_system_ctx(R->sys)));
    hl_json_object_end(&j);
    hl_json_finish(&j);
}

/* ---- --numeric: the analysis at one point (numerr.h) ---------------------- */

/* z from "q=1.3,p=0": every phase variable once, each a number.  -1, or 2
 * after a usage message. */
static int parse_at(double *z, const char *at, result *R, const cli_command *cmd)
{
    int *seen = calloc((size_t)R->m, sizeof *seen);
    char *copy = hl_xstrdup(at), *save = NULL;
    int rc = -1;
    for (char *it = strtok_r(copy, ",", &save); it != NULL && rc < 0;
         it = strtok_r(NULL, ",", &save)) {
        while (*it == ' ')
            it++;
        char *eq = strchr(it, '=');
        if (eq == NULL) {
            rc = cli_usage(cmd, "--at: '%s' is not 'name=value'", it);
            break;
        }
        *eq = '\0';
        char *name = it, *e = name + strlen(name);
        while (e > name && e[-1] == ' ')
            *--e = '\0';
        int i = 0;
        while (i < R->m && strcmp(R->names[i], name) != 0)
            i++;
        if (i == R->m) {
            rc = cli_usage(cmd, "--at: '%s' is not a phase variable of H", name);
            break;
        }
        if (seen[i]) {
            rc = cli_usage(cmd, "--at: '%s' is given twice", name);
            break;
        }
        char *end;
        double v = strtod(eq + 1, &end);
        while (*end == ' ')
            end++;
        if (end == eq + 1 || *end != '\0' || !isfinite(v)) {
            rc = cli_usage(cmd, "--at: the value of '%s' is not a number: '%s'", name, eq + 1);
            break;
        }
        z[i] = v;
        seen[i] = 1;
    }
    for (int i = 0; i < R->m && rc < 0; i++)
        if (!seen[i])
            rc = cli_usage(cmd, "--at: no value for '%s' (give every phase variable)",
                           R->names[i]);
    free(copy);
    free(seen);
    return rc;
}

static void put_num_vec(hl_buf *out, const double *v, result *R)
{
    for (int i = 0; i < R->m; i++)
        hl_buf_printf(out, "%s%s = %.17g", i ? ", " : "", R->names[i], v[i]);
}

static void write_numeric_text(hl_buf *out, const hl_numerr *nr, const double *z, result *R,
                               const err_opts *r, const cli_opts *o)
{
    int m = R->m;
    hl_buf_printf(out, "scheme: %s\n", r->scheme ? r->scheme : o->map ? o->map : r->equations);
    hl_buf_puts(out, "H = ");
    put_alg(out, hl_system_H(R->sys), R, HL_STYLE_TEXT);
    hl_buf_puts(out, "\nat: ");
    put_num_vec(out, z, R);
    hl_buf_printf(out, "\nnumeric analysis at the point (double precision, Taylor mode) to "
                       "order %d\n", nr->n);
    for (int k = 2; k <= nr->n; k++) {
        hl_buf_printf(out, "v_%d(z) = (", k);
        put_num_vec(out, nr->v + k * m, R);
        hl_buf_printf(out, ")  |v_%d| = %.3g %s threshold %.3g\n", k, nr->vnorm[k],
                      nr->vnorm[k] > nr->thresh[k] ? ">" : "<=", nr->thresh[k]);
    }
    if (nr->leading)
        hl_buf_printf(out, "order: %d (leading error v_%d: the least k with |v_k(z)| above "
                           "round-off)\n", nr->order, nr->leading);
    else
        hl_buf_printf(out, "order: at least %d (no v_k above round-off up to k = %d)\n",
                      nr->order, nr->n);
    hl_buf_puts(out, "round-off threshold for v_k: 1e-10 · k! · max_i(|[D^k] psi_i| + "
                     "|g^k z_i / k!|)\n");
    if (isnan(nr->K[0])) /* a series from elsewhere: hl_numerr_from_series */
        hl_buf_puts(out, "  (at least its upper concave hull in log over k: a coefficient "
                         "that vanishes at z is\n  round-off of its neighbours' size in a "
                         "series not computed exactly)\n");
    if (isnan(nr->K[0])) {
        hl_buf_puts(out, "K(D): not computed (it needs the scheme at other points than z)\n");
        return;
    }
    hl_buf_printf(out, "K(D) = (d/dD psi_D)(psi_{-D}(z)), coefficients to D^%d:\n", nr->n - 1);
    for (int k = 0; k < nr->n; k++) {
        hl_buf_printf(out, "  D^%d: ", k);
        put_num_vec(out, nr->K + k * m, R);
        hl_buf_puts(out, "\n");
    }
}

static void json_num(hl_buf *b, double x)
{
    if (isfinite(x))
        hl_buf_printf(b, "%.17g", x);
    else
        hl_buf_puts(b, "null");
}

static void json_num_vec(hl_buf *b, const double *v, result *R)
{
    hl_buf_puts(b, "{");
    for (int i = 0; i < R->m; i++) {
        if (i)
            hl_buf_puts(b, ", ");
        hl_json_escape(b, R->names[i]);
        hl_buf_puts(b, ": ");
        json_num(b, v[i]);
    }
    hl_buf_puts(b, "}");
}

static void write_numeric_json(hl_buf *b, const hl_numerr *nr, const double *z, result *R,
                               const err_opts *r, const cli_opts *o)
{
    int m = R->m;
    /* the system's keys as the symbolic mode writes them (hl_json has no
     * numbers: the rest is written by hand) */
    hl_buf head;
    hl_buf_init(&head);
    hl_json j;
    hl_json_init_buf(&j, &head);
    hl_json_object_begin(&j);
    cli_json_system(&j, R->sys);
    hl_json_object_end(&j);
    hl_json_finish(&j);
    char *h = hl_buf_take(&head);
    size_t hl = strlen(h);
    while (hl > 0 && (h[hl - 1] == '\n' || h[hl - 1] == ' '))
        hl--;
    hl_buf_puts(b, "{\"command\": \"errors\", \"mode\": \"numeric\", ");
    if (hl >= 2) /* without its braces */
        hl_buf_printf(b, "%.*s", (int)(hl - 2), h + 1);
    free(h);
    hl_buf_clear(&head);
    hl_buf_puts(b, ", \"numeric_zero_test\": false, \"scheme\": {\"source\": ");
    hl_json_escape(b, r->scheme ? "catalog" : o->map ? "map" : "equations");
    hl_buf_puts(b, ", \"name\": ");
    hl_json_escape(b, R->s != NULL ? R->s->name : r->scheme);
    hl_buf_puts(b, ", \"input\": ");
    hl_json_escape(b, r->scheme ? r->scheme : o->map ? o->map : r->equations);
    hl_buf_printf(b, ", \"explicit\": %s}, \"at\": ",
                  R->s == NULL || R->s->all_explicit ? "true" : "false");
    json_num_vec(b, z, R);
    hl_buf_printf(b, ", \"order_computed\": %d, \"fields\": [", nr->n);
    for (int k = 2; k <= nr->n; k++) {
        hl_buf_printf(b, "%s{\"k\": %d, \"v\": ", k > 2 ? ", " : "", k);
        json_num_vec(b, nr->v + k * m, R);
        hl_buf_puts(b, ", \"norm\": ");
        json_num(b, nr->vnorm[k]);
        hl_buf_puts(b, ", \"threshold\": ");
        json_num(b, nr->thresh[k]);
        hl_buf_printf(b, ", \"nonzero\": %s}", nr->vnorm[k] > nr->thresh[k] ? "true" : "false");
    }
    hl_buf_printf(b, "], \"order\": %d, \"leading\": ", nr->order);
    if (nr->leading)
        hl_buf_printf(b, "%d", nr->leading);
    else
        hl_buf_puts(b, "null");
    hl_buf_printf(b, ", \"exact_to_order_computed\": %s, \"K_coefficients\": [",
                  nr->leading ? "false" : "true");
    for (int k = 0; k < nr->n; k++) {
        if (k)
            hl_buf_puts(b, ", ");
        json_num_vec(b, nr->K + k * m, R);
    }
    hl_buf_puts(b, "], \"flow_coefficients\": [");
    for (int k = 0; k <= nr->n; k++) {
        if (k)
            hl_buf_puts(b, ", ");
        json_num_vec(b, nr->flow + k * m, R);
    }
    hl_buf_puts(b, "]}\n");
}

/* --scheme exact for an H whose exact flow has no closed form here: the
 * numeric exact scheme of exact.h (hl_exact_flow), analysed from its own
 * series at the point. */
static int numeric_exact(const result *R, const err_opts *r)
{
    return r->scheme != NULL && strcmp(r->scheme, "exact") == 0 &&
           !hl_scheme_linear_flow_applies(R->sys);
}

static int exact_numerr(hl_numerr *nr, result *R, const double *z, hl_error *err)
{
    hl_exact_flow *f = NULL;
    double *psi = hl_xmalloc((size_t)(R->n + 1) * R->m * sizeof *psi);
    int st = hl_exact_flow_new(&f, R->sys, err);
    /* beyond this order the coefficients show the orbit table's pieces
     * (exact.h), not an error of the scheme: refused rather than reported */
    if (st == HL_OK && !hl_exact_flow_is_linear(f) && R->n > HL_EXACT_SERIES_ACCURATE)
        st = hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                          "its series comes from the orbit table's Taylor pieces of degree "
                          "%d and is accurate to round-off up to D^%d: --order at most %d, "
                          "not %d",
                          HL_EXACT_SERIES_DEGREE, HL_EXACT_SERIES_ACCURATE,
                          HL_EXACT_SERIES_ACCURATE, R->n);
    if (st == HL_OK)
        st = hl_exact_flow_series(psi, z, R->n, f, err);
    if (st == HL_OK)
        st = hl_numerr_from_series(nr, R->sys, z, psi, R->n, err);
    if (st != HL_OK)
        hl_error_prefix(err, "the exact scheme");
    hl_exact_flow_free(f);
    free(psi);
    return st;
}

/* The whole --numeric path after the system is built: -1 on success with
 * the output in out, else the exit code. */
static int run_numeric(hl_buf *out, result *R, const err_opts *r, const cli_opts *o,
                       const cli_command *cmd)
{
    double *z = hl_xmalloc((size_t)R->m * sizeof *z);
    int rc = parse_at(z, r->at, R, cmd);
    hl_error err;
    hl_error_clear(&err);
    hl_numerr nr;
    memset(&nr, 0, sizeof nr);
    if (rc < 0 && numeric_exact(R, r)) {
        if (exact_numerr(&nr, R, z, &err) != HL_OK)
            rc = cli_fail(&err);
    } else {
        if (rc < 0 && make_scheme(R, r, o, &err) != HL_OK)
            rc = cli_fail(&err);
        if (rc < 0 && hl_numerr_compute(&nr, R->s, z, R->n, &err) != HL_OK) {
            hl_error_prefix(&err, "numeric analysis");
            rc = cli_fail(&err);
        }
    }
    if (rc < 0) {
        if (o->format == CLI_JSON)
            write_numeric_json(out, &nr, z, R, r, o);
        else
            write_numeric_text(out, &nr, z, R, r, o);
    }
    hl_numerr_clear(&nr);
    free(z);
    return rc;
}

int cmd_errors(int argc, char **argv)
{
    const cli_command *cmd = cli_find("errors");
    err_opts r;
    cli_opts o;
    result R;
    memset(&r, 0, sizeof r);
    memset(&o, 0, sizeof o);
    memset(&R, 0, sizeof R);
    /* errors' own options, in found_opt's order; the rest goes to cli_parse */
    static const cli_own own[] = {
        {"--scheme", 0},  {"--equations", 0},         {"--correct", 0},
        {"--invariants-degree", 0}, {"--at", 0}, {"--numeric", 1}};
    static const cli_begin_spec spec = {own, 6, found_opt, check_opts,
                                        CLI_OPT_H | CLI_OPT_MAP | CLI_OPT_ORDER, 64};
    char **av;
    int rc = cli_begin(&av, &o, &R.sys, argc, argv, cmd, &spec, &r);
    hl_error err;
    hl_error_clear(&err);
    if (rc < 0) {
        R.N = hl_system_ndof(R.sys);
        R.m = 2 * R.N;
        R.n = o.order;
        R.correct = r.correct;
        R.invdeg = r.invdeg;
        R.names = hl_xmalloc((size_t)R.m * sizeof *R.names);
        for (int i = 0; i < R.m; i++)
            R.names[i] = i < R.N ? hl_system_coord(R.sys, i) : hl_system_momentum(R.sys, i - R.N);
        if (!r.numeric && numeric_exact(&R, &r))
            rc = cli_usage(cmd, "the exact scheme of this H is numeric (action-angle by "
                                "quadrature, exact.h): analyse it at a point with --numeric "
                                "--at '%s=...,%s=...'",
                           R.names[0], R.names[R.N]);
        else if (r.numeric) {
            hl_buf out;
            hl_buf_init(&out);
            rc = run_numeric(&out, &R, &r, &o, cmd);
            if (rc < 0)
                rc = cli_emit(&out, CLI_OK);
            hl_buf_clear(&out);
        } else if (compute(&R, &r, &o, &err) != HL_OK)
            rc = cli_fail(&err);
    }
    if (rc < 0) {
        hl_buf out;
        hl_buf_init(&out);
        if (o.format == CLI_JSON)
            write_json(&out, &R, &r, &o);
        else
            write_text(&out, &R, &r, &o);
        rc = cli_emit_results(&out, CLI_OK, R.sys);
        hl_buf_clear(&out);
    }
    hl_system *sys = R.sys;
    result_free(&R);
    hl_system_free(sys);
    cli_opts_clear(&o);
    free(av);
    return rc;
}
