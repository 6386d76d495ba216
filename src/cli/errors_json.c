/* hamlie errors: the symbolic analysis (hl_analysis) written as JSON
 * (docs/json.md) through the one writer, hl_json. */
#include <stdlib.h>

#include "cli/errors.h"

static const char *kind_name(hl_errfield_kind k)
{
    static const char *const n[] = {"zero",    "time_shift",  "parallel",
                                    "scaling", "hamiltonian", "general"};
    return n[k];
}

/* ---- JSON --------------------------------------------------------------- */

static void json_alg(hl_json *j, const char *key, const hl_alg *a, const hl_analysis *A)
{
    char *s = hl_format_alg(a, hl_system_ctx(A->sys), hl_system_pool(A->sys), HL_STYLE_SYMPY);
    hl_json_kv_string(j, key, s);
    free(s);
}

static void json_field(hl_json *j, const char *key, const hl_alg *v, const hl_analysis *A)
{
    hl_json_key(j, key);
    hl_json_vector_field(j, A->m, A->names, v, hl_system_ctx(A->sys), hl_system_pool(A->sys),
                         HL_STYLE_SYMPY);
}

/* K's D^0..D^(N-1) coefficients, one field each */
static void json_K_coefficients(hl_json *j, const hl_analysis *A)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    hl_json_array_begin(j);
    hl_alg *c = hl_alg_vec_new(A->m, ctx);
    for (int k = 0; k < A->n; k++) {
        for (int i = 0; i < A->m; i++)
            hl_alg_set(&c[i], &A->K_series[i].c[k], ctx);
        hl_json_vector_field(j, A->m, A->names, c, ctx, hl_system_pool(A->sys), HL_STYLE_SYMPY);
    }
    hl_alg_vec_free(c, A->m, ctx);
    hl_json_array_end(j);
}

static void json_analysis(hl_json *j, const hl_vfields *e, const hl_errfield *F, int have_F,
                          const hl_analysis *A)
{
    hl_json_key(j, "fields");
    hl_json_array_begin(j);
    for (int k = 2; k <= e->n; k++) {
        hl_json_object_begin(j);
        hl_json_kv_int(j, "k", k);
        json_field(j, "v", hl_vfields_v(e, k), A);
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
        json_alg(j, "lambda", &F->lambda, A);
    if (F->kind == HL_ERRFIELD_SCALING)
        json_field(j, "scale", F->scale, A);
    hl_json_kv_bool(j, "hamiltonian", F->hamiltonian);
    if (F->hamiltonian && F->have_h)
        json_alg(j, "h", &F->h, A);
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

/* "invariants": the leading field's, or null */
static void json_invariants(hl_json *j, const hl_analysis *A)
{
    hl_json_key(j, "invariants");
    if (A->have_leading && A->invariants_degree > 0 && A->inv_poly_applicable) {
        hl_json_object_begin(j);
        hl_json_kv_int(j, "degree", A->invariants_degree);
        hl_json_key(j, "polynomial");
        json_algs(j, A->inv_poly, A->n_inv_poly, A->sys);
        hl_json_key(j, "rational");
        if (A->inv_darboux_applicable)
            json_algs(j, A->inv_darboux, A->n_inv_darboux, A->sys);
        else
            hl_json_null(j);
        hl_json_object_end(j);
    } else
        hl_json_null(j);
}

/* "modified": f_1..f_J and their Hamiltonians */
static void json_modified(hl_json *j, const hl_analysis *A)
{
    hl_json_key(j, "modified");
    hl_json_object_begin(j);
    hl_json_kv_int(j, "terms", A->nmod);
    hl_json_key(j, "fields");
    hl_json_array_begin(j);
    for (int k = 1; k <= A->nmod; k++)
        hl_json_vector_field(j, A->m, A->names, A->mod_fields + k * A->m, hl_system_ctx(A->sys),
                             hl_system_pool(A->sys), HL_STYLE_SYMPY);
    hl_json_array_end(j);
    hl_json_key(j, "hamiltonians");
    if (A->mod_H_all)
        json_algs(j, A->mod_H + 1, A->nmod, A->sys);
    else
        hl_json_null(j);
    hl_json_object_end(j);
}

/* "time": tau(D), when tried, or null */
static void json_time(hl_json *j, const hl_analysis *A)
{
    hl_json_key(j, "time");
    if (A->tried_tau) {
        hl_json_object_begin(j);
        hl_json_kv_bool(j, "pure_time_translation", A->tau_ok);
        hl_json_key(j, "fails_at");
        if (A->tau_ok)
            hl_json_null(j);
        else
            hl_json_int(j, A->tau_fail);
        if (A->tau_ok) {
            char *t = errors_tau_text(A, 0, HL_STYLE_SYMPY),
                 *w = errors_tau_text(A, 1, HL_STYLE_SYMPY);
            hl_json_kv_string(j, "tau_series", t);
            hl_json_kv_string(j, "W_series", w);
            free(t);
            free(w);
        }
        if (A->tau_closed) {
            json_alg(j, "tau", &A->tau_forms[0], A);
            json_alg(j, "tan_half_tau", &A->tau_forms[1], A);
        }
        if (A->have_D2)
            json_alg(j, "double_step", &A->tau_forms[2], A);
        hl_json_kv_bool(j, "closed_form_from_series", A->tau_series_only);
        hl_json_object_end(j);
    } else
        hl_json_null(j);
}

void errors_write_json(hl_buf *out, const hl_analysis *A, const char *source, const char *input)
{
    hl_json j;
    hl_json_init_buf(&j, out);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "errors");
    cli_json_system(&j, A->sys);
    hl_json_key(&j, "scheme");
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "source", source);
    hl_json_kv_string(&j, "name", A->scheme->name);
    hl_json_kv_string(&j, "input", input);
    hl_json_kv_bool(&j, "explicit", A->closed);
    hl_json_object_end(&j);
    hl_json_kv_int(&j, "order_computed", A->n);
    if (A->closed)
        json_field(&j, "map", A->map, A);
    else if (A->map_omitted[0])
        hl_json_kv_string(&j, "map_omitted", A->map_omitted);
    json_analysis(&j, &A->fields, &A->leading, A->have_leading, A);
    if (A->have_K)
        json_field(&j, "K", A->K, A);
    else if (A->closed) {
        hl_json_key(&j, "K");
        hl_json_null(&j);
        hl_json_key(&j, "K_omitted");
        hl_json_object_begin(&j);
        int printed = A->K_printed > HL_PRINT_MAX_NODES;
        hl_json_kv_string(&j, "reason", printed ? "print_limit" : "size_budget");
        hl_json_kv_int(&j, "terms", printed ? (long)A->K_printed : A->K_terms);
        hl_json_kv_int(&j, "budget", printed ? HL_PRINT_MAX_NODES : A->K_closed_budget);
        hl_json_object_end(&j);
    }
    hl_json_key(&j, "K_coefficients");
    if (A->K_series == NULL)
        hl_json_null(&j);
    else
        json_K_coefficients(&j, A);
    json_invariants(&j, A);
    json_modified(&j, A);
    json_time(&j, A);
    hl_json_key(&j, "corrected");
    if (A->correct) {
        hl_json_object_begin(&j);
        hl_json_kv_int(&j, "subtracted_up_to", A->correct);
        if (A->cmap != NULL)
            json_field(&j, "map", A->cmap, A);
        json_analysis(&j, &A->cfields, &A->cleading, A->have_cleading, A);
        hl_json_object_end(&j);
    } else
        hl_json_null(&j);
    hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(hl_system_ctx(A->sys)));
    hl_json_object_end(&j);
    hl_json_finish(&j);
}
