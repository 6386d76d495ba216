/* The whole error analysis of one scheme as one call (analysis.h,
 * hl_analysis_compute): expansion -> v_k two ways -> the leading field
 * classified -> closed map and K(D) -> invariants -> modified field and
 * Hamiltonian -> tau(D) -> the corrected scheme.  The command line (errors)
 * and the paper's checks (reproduce) only read the result. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/analysis.h"
#include "hamlie/scheme.h"

void hl_analysis_opts_default(hl_analysis_opts *o)
{
    o->order = 4;
    o->correct = 0;
    o->invariants_degree = 2;
    o->K_route_budget = HL_ANALYSIS_K_ROUTE_BUDGET;
    o->K_closed_budget = HL_ANALYSIS_K_CLOSED_BUDGET;
    o->parts = HL_ANALYSIS_ALL;
}

/* The v_k of psi and their leading field classified. */
static int fields_and_leading(hl_vfields *e, hl_errfield *F, int *have_F, const hl_series *psi,
                              const hl_analysis *A, long budget, hl_error *err)
{
    int st = hl_vfields_compute_bounded(e, psi, A->sys, A->n, budget > 0 ? budget : 0, err);
    if (st == HL_OK && e->checked && !e->agree)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "internal error: v_%d computed two ways (expansion, K(D)) disagree",
                            e->disagree_k);
    if (st == HL_OK && e->leading) {
        st = hl_errfield_classify(F, hl_vfields_v(e, e->leading), A->sys, err);
        *have_F = st == HL_OK;
    }
    return st;
}

/* The size of A->m formulas written out (hl_expr_tree_size): what printing
 * them would cost. */
static double printed_size(const hl_alg *v, const hl_analysis *A)
{
    double n = 0;
    for (int i = 0; i < A->m; i++)
        n +=
            hl_expr_tree_size(hl_alg_to_expr(&v[i], hl_system_ctx(A->sys), hl_system_pool(A->sys)));
    return n;
}

/* An explicit scheme's map and K(D) in closed form: bonuses, each left out
 * (and said why) past its limit. */
static int closed_forms(hl_analysis *A, long K_budget, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    A->map = hl_alg_vec_new(A->m, ctx);
    A->K = hl_alg_vec_new(A->m, ctx);
    int st = hl_errors_scheme_map(A->map, A->scheme, err);
    if (st == HL_ELIMIT) {
        snprintf(A->map_omitted, sizeof A->map_omitted, "%s", err->msg);
        hl_error_clear(err);
        return HL_OK;
    }
    if (st != HL_OK)
        return st;
    double nodes = printed_size(A->map, A);
    if (nodes > HL_PRINT_MAX_NODES) { /* a bonus: left out, not the whole output refused */
        snprintf(A->map_omitted, sizeof A->map_omitted,
                 "%.0f terms and operators written out (the print limit is %d)", nodes,
                 HL_PRINT_MAX_NODES);
        return HL_OK;
    }
    A->closed = 1;
    st = hl_errors_K_closed_bounded(A->K, &A->K_terms, A->map, K_budget, A->sys, err);
    if (st != HL_OK && st != HL_ELIMIT)
        return st;
    if (st == HL_OK && (A->K_printed = printed_size(A->K, A)) <= HL_PRINT_MAX_NODES)
        A->have_K = 1;
    hl_error_clear(err);
    return HL_OK;
}

/* Part 5: polynomial and Darboux invariants of the leading field. */
static int invariants(hl_analysis *A, hl_error *err)
{
    const hl_alg *v = hl_vfields_v(&A->fields, A->fields.leading);
    int st = hl_field_poly_invariants(&A->inv_poly, &A->n_inv_poly, &A->inv_poly_applicable, v,
                                      A->invariants_degree, A->sys, err);
    if (st == HL_OK)
        st = hl_field_darboux_invariants(&A->inv_darboux, &A->n_inv_darboux,
                                         &A->inv_darboux_applicable, v, A->invariants_degree,
                                         A->sys, err);
    return st;
}

/* Part 6: f_1..f_nmod, and their Hamiltonians while every one has one. */
static int modified(hl_analysis *A, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    A->nmod = A->n < HL_ANALYSIS_MODIFIED_MAX ? A->n : HL_ANALYSIS_MODIFIED_MAX;
    A->mod_fields = hl_alg_vec_new((A->nmod + 1) * A->m, ctx);
    A->mod_H = hl_alg_vec_new(A->nmod + 1, ctx);
    int st = hl_modified_field(A->mod_fields, A->psi, A->sys, A->nmod, err);
    if (st != HL_OK)
        return st;
    A->mod_H_all = 1;
    hl_alg_set(&A->mod_H[1], hl_system_H(A->sys), ctx);
    for (int j = 2; j <= A->nmod && A->mod_H_all; j++) {
        hl_errfield G;
        st = hl_errfield_classify(&G, A->mod_fields + j * A->m, A->sys, err);
        if (st == HL_OK) {
            A->mod_H_all = G.hamiltonian && G.have_h;
            hl_alg_swap(&A->mod_H[j], &G.h, ctx);
        }
        hl_errfield_clear(&G, A->sys);
        if (st != HL_OK)
            return st;
    }
    return HL_OK;
}

/* Part 4: psi = exp(tau(D) g)?  As a series, and in closed form from the
 * map (explicit) or identified from the series (implicit). */
static int time_reparametrisation(hl_analysis *A, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    hl_alg *tc;
    A->tried_tau = 1;
    hl_series_init(&A->tau, 0, ctx);
    tc = A->tau_forms = hl_alg_vec_new(3, ctx);
    int st = hl_errors_time_series(&A->tau, &A->tau_ok, &A->tau_fail, A->psi, A->sys, A->n, err);
    if (st != HL_OK)
        return st;
    if (A->closed)
        return hl_errors_time_closed(&tc[0], &tc[1], &A->tau_closed, &tc[2], &A->have_D2, A->map,
                                     A->sys, err);
    st = hl_errors_time_closed_series(&tc[0], &tc[1], &A->tau_closed, &tc[2], A->psi, A->sys, A->n,
                                      err);
    A->have_D2 = A->tau_series_only = A->tau_closed;
    return st;
}

/* psi_D - sum_{k=2}^M D^k/k! v_k, as series (and map when closed), analysed. */
static int corrected(hl_analysis *A, long budget, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    A->cpsi = hl_series_vec_new(A->m, 0, ctx);
    hl_errors_correct_series(A->cpsi, A->psi, &A->fields, A->correct, A->sys);
    if (A->closed) {
        A->cmap = hl_alg_vec_new(A->m, ctx);
        for (int i = 0; i < A->m; i++)
            hl_alg_set(&A->cmap[i], &A->map[i], ctx);
        hl_errors_correct_map(A->cmap, &A->fields, A->correct, A->sys);
    }
    A->have_cfields = 1;
    return fields_and_leading(&A->cfields, &A->cleading, &A->have_cleading, A->cpsi, A, budget,
                              err);
}

static int compute(hl_analysis *A, const hl_analysis_opts *o, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    int st;
    A->psi = hl_series_vec_new(A->m, 0, ctx);
    if ((st = hl_scheme_expand(A->psi, A->scheme, A->n + 1, err)) != HL_OK ||
        (st = fields_and_leading(&A->fields, &A->leading, &A->have_leading, A->psi, A,
                                 o->K_route_budget, err)) != HL_OK)
        return st;
    if (A->fields.K != NULL) { /* computed by the K route of the check */
        A->K_series = hl_series_vec_new(A->m, 0, ctx);
        for (int i = 0; i < A->m; i++)
            hl_series_set(&A->K_series[i], &A->fields.K[i], ctx);
    }
    if ((o->parts & HL_ANALYSIS_CLOSED) && A->scheme->all_explicit && A->scheme->nint == 0 &&
        (st = closed_forms(A, o->K_closed_budget, err)) != HL_OK)
        return st;
    if ((o->parts & HL_ANALYSIS_INVARIANTS) && A->have_leading && A->invariants_degree > 0 &&
        (st = invariants(A, err)) != HL_OK)
        return st;
    if ((o->parts & HL_ANALYSIS_MODIFIED) && (st = modified(A, err)) != HL_OK)
        return st;
    int maybe_time_shift =
        A->fields.leading == 0 || (A->have_leading && A->leading.kind == HL_ERRFIELD_TIME_SHIFT);
    if ((o->parts & HL_ANALYSIS_TIME) && maybe_time_shift &&
        (st = time_reparametrisation(A, err)) != HL_OK)
        return st;
    if (A->correct)
        st = corrected(A, o->K_route_budget, err);
    return st;
}

hl_status hl_analysis_compute(hl_analysis **out, const hl_analysis_opts *opts,
                              const struct hl_scheme *s, hl_system *sys, hl_error *err)
{
    hl_analysis_opts defaults;
    if (opts == NULL) {
        hl_analysis_opts_default(&defaults);
        opts = &defaults;
    }
    *out = NULL;
    if (opts->order < 2 || opts->order > HL_ANALYSIS_MAX_ORDER)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the order must be between 2 and %d, not %d", HL_ANALYSIS_MAX_ORDER,
                            opts->order);
    if (opts->correct != 0 && (opts->correct < 2 || opts->correct > opts->order))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the correction must be between 2 and the order %d, not %d",
                            opts->order, opts->correct);
    hl_analysis *A = hl_xcalloc(1, sizeof *A);
    A->sys = sys;
    A->scheme = s;
    A->m = 2 * hl_system_ndof(sys);
    A->n = opts->order;
    A->correct = opts->correct;
    A->invariants_degree = opts->invariants_degree;
    A->K_closed_budget = opts->K_closed_budget;
    A->names = hl_xmalloc((size_t)A->m * sizeof *A->names);
    for (int i = 0; i < A->m; i++)
        A->names[i] =
            i < A->m / 2 ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - A->m / 2);
    int st = compute(A, opts, err);
    if (st != HL_OK)
        hl_analysis_free(A);
    else
        *out = A;
    return st;
}

void hl_analysis_free(hl_analysis *A)
{
    if (A == NULL)
        return;
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    int m = A->m;
    hl_series_vec_free(A->psi, m, ctx);
    hl_series_vec_free(A->K_series, m, ctx);
    hl_series_vec_free(A->cpsi, m, ctx);
    if (A->fields.v != NULL || A->fields.vK != NULL)
        hl_vfields_clear(&A->fields, A->sys);
    if (A->have_cfields)
        hl_vfields_clear(&A->cfields, A->sys);
    if (A->have_leading)
        hl_errfield_clear(&A->leading, A->sys);
    if (A->have_cleading)
        hl_errfield_clear(&A->cleading, A->sys);
    hl_alg_vec_free(A->map, m, ctx);
    hl_alg_vec_free(A->K, m, ctx);
    hl_alg_vec_free(A->cmap, m, ctx);
    hl_alg_vec_free(A->inv_poly, A->n_inv_poly, ctx);
    hl_alg_vec_free(A->inv_darboux, A->n_inv_darboux, ctx);
    if (A->mod_fields != NULL) {
        hl_alg_vec_free(A->mod_fields, (A->nmod + 1) * m, ctx);
        hl_alg_vec_free(A->mod_H, A->nmod + 1, ctx);
    }
    if (A->tried_tau) {
        hl_series_clear(&A->tau, ctx);
        hl_alg_vec_free(A->tau_forms, 3, ctx);
    }
    free(A->names);
    free(A);
}
