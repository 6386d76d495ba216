/* hamlie errors: the symbolic analysis (hl_analysis) written as text or
 * LaTeX.  Nothing is computed here but what printing needs. */
#include <stdlib.h>

#include <flint/fmpq.h>

#include "cli/errors.h"

#define K_PRINT_MAX 200 /* terms of K's closed form printed in text */

/* ---- text and LaTeX --------------------------------------------------- */

static void put_alg(hl_buf *out, const hl_alg *a, const hl_analysis *A, hl_style st)
{
    char *s = hl_format_alg(a, hl_system_ctx(A->sys), hl_system_pool(A->sys), st);
    hl_buf_puts(out, s);
    free(s);
}

static void put_field(hl_buf *out, const hl_alg *v, const hl_analysis *A, hl_style st)
{
    char *s = hl_format_vector_field(A->m, A->names, v, hl_system_ctx(A->sys),
                                     hl_system_pool(A->sys), st);
    hl_buf_puts(out, s);
    free(s);
}

static void put_map(hl_buf *out, const char *title, const hl_alg *img, const hl_analysis *A,
                    hl_style st)
{
    hl_buf_printf(out, "%s\n", title);
    for (int i = 0; i < A->m; i++) {
        char *nm = cli_image_name(A->sys, i);
        hl_buf_printf(out, "  %s = ", nm);
        put_alg(out, &img[i], A, st);
        hl_buf_puts(out, "\n");
        free(nm);
    }
}

/* A time shift c·D^k/k! puts the point ahead of the flow when c > 0. */
static const char *shift_direction(const hl_alg *c, const hl_analysis *A)
{
    fmpq_t q;
    fmpq_init(q);
    const char *dir = "shifted (by the sign of c)";
    if (hl_alg_is_fmpq(c, q, hl_system_ctx(A->sys)))
        dir = fmpq_sgn(q) > 0 ? "ahead" : "behind";
    fmpq_clear(q);
    return dir;
}

static void put_classification(hl_buf *out, const hl_vfields *e, const hl_errfield *F,
                               const hl_analysis *A, hl_style st)
{
    int k = e->leading;
    hl_buf_printf(out, "leading error v_%d: ", k);
    switch (F->kind) {
    case HL_ERRFIELD_TIME_SHIFT:
        hl_buf_puts(out, "c·g with c = ");
        put_alg(out, &F->lambda, A, st);
        hl_buf_printf(out,
                      ", a pure time translation: the point stays on its trajectory, "
                      "|c|·%s^%d/%d! %s in time\n",
                      hl_system_step(A->sys), k, k, shift_direction(&F->lambda, A));
        break;
    case HL_ERRFIELD_PARALLEL:
        hl_buf_puts(out, "parallel to g: v = λ(z)·g with λ = ");
        put_alg(out, &F->lambda, A, st);
        hl_buf_puts(out, "\n");
        break;
    case HL_ERRFIELD_SCALING:
        hl_buf_puts(out, "a scaling: v = Σ c_j z_j ∂/∂z_j with");
        for (int i = 0; i < A->m; i++) {
            hl_buf_printf(out, "%s c_%s = ", i ? "," : "", A->names[i]);
            put_alg(out, &F->scale[i], A, st);
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
        put_alg(out, &F->h, A, st);
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
char *errors_tau_text(const hl_analysis *A, int W, hl_style st)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    hl_alg *c = hl_alg_vec_new(A->tau.n, ctx);
    for (int k = 0; k < A->tau.n; k++)
        if (!(W && k == 1))
            hl_alg_set(&c[k], &A->tau.c[k], ctx);
    char *s = hl_format_series(c, A->tau.n - 1, hl_system_step(A->sys), 0, ctx,
                               hl_system_pool(A->sys), st);
    hl_alg_vec_free(c, A->tau.n, ctx);
    return s;
}

static void put_time(hl_buf *out, const hl_analysis *A, hl_style st)
{
    const char *D = hl_system_step(A->sys);
    if (!A->tau_ok) {
        hl_buf_printf(out,
                      "time reparametrisation: none (the %s^%d term is not a constant "
                      "multiple of g z: not a pure time translation)\n",
                      D, A->tau_fail);
        return;
    }
    char *t = errors_tau_text(A, 0, st), *w = errors_tau_text(A, 1, st);
    hl_buf_printf(out, "time reparametrisation: psi_%s = exp(tau(%s) g) + O(%s^%d)\n", D, D, D,
                  A->n + 1);
    hl_buf_printf(out, "  tau(%s) = %s + O(%s^%d)\n  W(%s) = tau(%s) - %s = %s + O(%s^%d)\n", D, t,
                  D, A->n + 1, D, D, D, w, D, A->n + 1);
    free(t);
    free(w);
    if (A->tau_closed) {
        hl_buf_puts(out, "  closed form: tan(tau/2) = M12/(1 + M11) = ");
        put_alg(out, &A->tau_forms[1], A, st);
        hl_buf_puts(out, ", tau = ");
        put_alg(out, &A->tau_forms[0], A, st);
        if (A->tau_series_only)
            hl_buf_printf(out, " (identified from the series to O(%s^%d), not proved)", D,
                          A->n + 1);
        hl_buf_puts(out, "\n");
    }
    if (A->have_D2) {
        hl_buf_printf(out, "  two steps of %s are one step of %s' = ", D, D);
        put_alg(out, &A->tau_forms[2], A, st);
        hl_buf_puts(out, "\n");
    }
}

static void put_invariants(hl_buf *out, const hl_analysis *A, hl_style st)
{
    int k = A->fields.leading;
    if (!A->inv_poly_applicable) {
        hl_buf_printf(out, "invariants of v_%d: not a polynomial field over Q, not searched\n", k);
        return;
    }
    hl_buf_printf(out, "polynomial invariants of v_%d of degree <= %d:", k, A->invariants_degree);
    for (int i = 0; i < A->n_inv_poly; i++) {
        hl_buf_puts(out, i ? ", " : " ");
        put_alg(out, &A->inv_poly[i], A, st);
    }
    hl_buf_puts(out, A->n_inv_poly ? " (each checked: v(phi) = 0)\n" : " none\n");
    if (A->inv_darboux_applicable) {
        hl_buf_printf(out, "rational invariants of v_%d (ratios of Darboux polynomials):", k);
        for (int i = 0; i < A->n_inv_darboux; i++) {
            hl_buf_puts(out, i ? ", " : " ");
            put_alg(out, &A->inv_darboux[i], A, st);
        }
        hl_buf_puts(out, A->n_inv_darboux ? " (each checked: v(phi) = 0)\n" : " none found\n");
    }
}

static void put_modified(hl_buf *out, const hl_analysis *A, hl_style st)
{
    const char *D = hl_system_step(A->sys);
    hl_buf_printf(out,
                  "modified vector field: exp(%s f~) = psi_%s + O(%s^%d), "
                  "f~ = f_1 + %s f_2 + ... (f_1 = g):\n",
                  D, D, D, A->nmod + 1, D);
    for (int j = 2; j <= A->nmod; j++) {
        hl_buf_printf(out, "  f_%d = ", j);
        put_field(out, A->mod_fields + j * A->m, A, st);
        hl_buf_puts(out, "\n");
    }
    if (!A->mod_H_all) {
        hl_buf_puts(out, "  modified Hamiltonian: not found (some f_j is not Hamiltonian, "
                         "or its h is not polynomial)\n");
        return;
    }
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    hl_alg *c = hl_alg_vec_new(A->nmod, ctx);
    for (int j = 1; j <= A->nmod; j++)
        hl_alg_set(&c[j - 1], &A->mod_H[j], ctx);
    char *s = hl_format_series(c, A->nmod - 1, D, 0, ctx, hl_system_pool(A->sys), st);
    hl_buf_printf(out, "  modified Hamiltonian: H~ = %s + O(%s^%d)\n", s, D, A->nmod);
    free(s);
    hl_alg_vec_free(c, A->nmod, ctx);
}

void errors_write_text(hl_buf *out, const hl_analysis *A, const char *input, cli_format f)
{
    int latex = f == CLI_LATEX;
    hl_style st = latex ? HL_STYLE_LATEX : HL_STYLE_TEXT;
    const char *pre = latex ? "% " : "", *D = hl_system_step(A->sys);
    hl_buf_printf(out, "%sscheme: %s\n", pre, input);
    hl_buf_printf(out, "%sH = ", pre);
    put_alg(out, hl_system_H(A->sys), A, st);
    hl_buf_puts(out, "\n");
    if (A->closed)
        put_map(out, "map:", A->map, A, st);
    else if (A->map_omitted[0])
        hl_buf_printf(out, "%smap: closed form omitted: %s\n", pre, A->map_omitted);
    for (int k = 2; k <= A->n; k++) {
        hl_buf_printf(out, latex ? "v_{%d} = " : "v_%d = ", k);
        put_field(out, hl_vfields_v(&A->fields, k), A, st);
        hl_buf_puts(out, "\n");
    }
    if (A->fields.checked)
        hl_buf_printf(out, "%sv_k computed two ways: agree\n", pre);
    else
        hl_buf_printf(out,
                      "%sv_k computed one way: the check by K(D) omitted (its work "
                      "passed the budget of %ld terms)\n",
                      pre, A->fields.budget);
    put_order(out, &A->fields);
    if (A->have_leading)
        put_classification(out, &A->fields, &A->leading, A, st);
    if (A->closed && !A->have_K && A->K_printed > HL_PRINT_MAX_NODES)
        hl_buf_printf(out,
                      "K(D) = psi_{-D} o d/dD psi_D: closed form omitted: %.0f terms and "
                      "operators written out (the print limit is %d)\n",
                      A->K_printed, HL_PRINT_MAX_NODES);
    else if (A->closed && !A->have_K)
        hl_buf_printf(out,
                      "K(D) = psi_{-D} o d/dD psi_D: closed form omitted: %ld terms "
                      "(over the budget of %ld)\n",
                      A->K_terms, A->K_closed_budget);
    if (A->have_K) {
        long len = 0;
        for (int i = 0; i < A->m; i++)
            len += hl_alg_length(&A->K[i], hl_system_ctx(A->sys));
        hl_buf_printf(out, "K(%s) = psi_{-%s} o d/d%s psi_%s in closed form:", D, D, D, D);
        if (len > K_PRINT_MAX)
            hl_buf_printf(out, " %ld terms, not printed (see --json)\n", len);
        else {
            hl_buf_puts(out, "\n");
            for (int i = 0; i < A->m; i++) {
                hl_buf_printf(out, "  K_%s = ", A->names[i]);
                put_alg(out, &A->K[i], A, st);
                hl_buf_puts(out, "\n");
            }
        }
    }
    if (A->K_series == NULL)
        hl_buf_printf(out, "K(%s) series: omitted (its work passed the budget of %ld terms)\n", D,
                      A->fields.budget);
    else
        hl_buf_printf(out, "K(%s) series to O(%s^%d):\n", D, D, A->n);
    for (int i = 0; i < A->m && A->K_series != NULL; i++) {
        char *s = hl_format_series(A->K_series[i].c, A->K_series[i].n - 1, D, 0,
                                   hl_system_ctx(A->sys), hl_system_pool(A->sys), st);
        hl_buf_printf(out, "  K_%s = %s\n", A->names[i], s);
        free(s);
    }
    if (A->have_leading && A->invariants_degree > 0)
        put_invariants(out, A, st);
    if (A->tried_tau)
        put_time(out, A, st);
    put_modified(out, A, st);
    if (A->correct) {
        hl_buf_printf(out, "corrected scheme (v_2..v_%d subtracted):\n", A->correct);
        if (A->cmap != NULL)
            put_map(out, "corrected map:", A->cmap, A, st);
        else
            hl_buf_printf(out, "  psi_%s(z) - sum_{k=2}^{%d} %s^k/k! v_k(z)\n", D, A->correct, D);
        put_order(out, &A->cfields);
        if (A->have_cleading)
            put_classification(out, &A->cfields, &A->cleading, A, st);
    }
    cli_numeric_note(out, A->sys, f);
}
