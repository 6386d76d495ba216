/* The paper's relations between K(D) and the v_k (formulas_impl.h),
 * checked on a nonlinear system (H = (p^2+x^2)/2 + x^3/3) with two
 * schemes, where a linear example could hide a wrong term: the left side
 * k! [D^k] K, the printed right side evaluated term by term. */
#include <stdlib.h>
#include <string.h>

#include "paper/formulas_impl.h"

/* d^k K/dD^k at 0 = k! [D^k] K for test scheme s on the cubic system. */
static int rel_lhs(hl_alg *out, struct hl_paper_work *w, int k, int s, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(w->cub);
    const hl_series *K = w->rel[s].a->K_series;
    if (K[0].n <= k || K[1].n <= k)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "K known only to O(D^%d)", K[0].n);
    fmpq_t f;
    fmpq_init(f);
    fmpz_fac_ui(fmpq_numref(f), (ulong)k);
    for (int i = 0; i < 2; i++)
        hl_alg_scalar_mul_fmpq(&out[i], &K[i].c[k], f, ctx);
    fmpq_clear(f);
    return HL_OK;
}

/* The left side of the D^k relation on the first test scheme. */
int paper_f_rel(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how, hl_error *err)
{
    int k = r->arg;
    int st = rel_lhs(out, w, k, 0, err);
    if (st != HL_OK)
        return st;
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b,
                  "left side d^%dK/dD^%d at 0 = %d! [D^%d] K, K from the scheme's series; "
                  "checked on H = (p^2+x^2)/2 + x^3/3 (nonlinear) for %s and for %s (the "
                  "relation must hold for both); the print's right side evaluated with "
                  "the true v_k (direct and via K: the two %s, %s), read as the paper's "
                  "(Err) does: operators on functions composed, A o B (z) = A(B(z)), "
                  "g phi = {phi, H}, v_k phi = k! [D^k] (phi o psi_D - phi o exp(D g)); "
                  "hamlie itself uses the exact identity K = (d/dD psi)(psi_{-D}), "
                  "v_k = (k-1)! ([D^(k-1)] K - [D^(k-1)] K~) with psi~ = exp(D g) + "
                  "sum_{j<k} D^j/j! v_j",
                  k, k, k, k, REL_NAMES[0], REL_NAMES[1], paper_agree_text(&w->rel[0].a->fields),
                  paper_agree_text(&w->rel[1].a->fields));
    *how = hl_buf_take(&b);
    return HL_OK;
}

/* An operator of the paper's relations applied to a function phi of the
 * cubic system, for test scheme s: g phi = {phi, H}; v_k phi =
 * k! [D^k] (phi(psi_D(z)) - phi(exp(D g) z)) = k! [D^k] phi(psi_D(z)) - g^k phi.
 * This is the paper's reading: in (Err) w_D = psi_D - exp(D g) acts on
 * functions as an operator (not a derivation); on a coordinate, v_k z_i is
 * the field's component. */
static int apply_op(hl_alg *r, int k, const hl_alg *phi, struct hl_paper_work *w, int sch,
                    hl_error *err)
{
    hl_system *sys = w->cub;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    if (k == 0)
        return hl_generator_apply(r, phi, sys, err);
    int vars[2] = {hl_system_var_q(sys, 0), hl_system_var_p(sys, 0)};
    hl_alg s;
    hl_alg *terms = hl_alg_vec_new(k + 1, ctx);
    fmpq_t f;
    int st;
    hl_alg_init(&s, ctx);
    fmpq_init(f);
    st = hl_alg_subst(&s, phi, 2, vars, w->psiT_cub[sch], ctx, err);
    if (st == HL_OK)
        st = hl_alg_coeff(&s, &s, hl_system_var_D(sys), k, ctx, err);
    if (st == HL_OK)
        st = hl_lie_terms(terms, phi, k, sys, err);
    if (st == HL_OK) {
        fmpz_fac_ui(fmpq_numref(f), (ulong)k);
        hl_alg_scalar_mul_fmpq(&s, &s, f, ctx);
        hl_alg_sub(r, &s, &terms[k], ctx);
    }
    fmpq_clear(f);
    hl_alg_clear(&s, ctx);
    hl_alg_vec_free(terms, k + 1, ctx);
    return st;
}

/* The print's right side "+1 v3 -2 g.v2 ..." evaluated on the cubic system
 * for test scheme sch (operators composed: A.B z = A(B(z))).  Term `flip`
 * (0-based; -1: none) is taken with the opposite sign; *nterms gets the
 * number of terms. */
int paper_eval_rel(hl_alg *out, int *nterms, struct hl_paper_work *w, int sch, const char *text,
                   int flip, hl_error *err)
{
    hl_system *sys = w->cub;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    char *copy = hl_xstrdup(text), *save = NULL;
    hl_alg f, t;
    int st = HL_OK, term = 0;
    hl_alg_init(&f, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_zero(&out[0], ctx);
    hl_alg_zero(&out[1], ctx);
    for (char *tok = strtok_r(copy, " ", &save); tok != NULL && st == HL_OK;
         tok = strtok_r(NULL, " ", &save), term++) {
        char *word = strtok_r(NULL, " ", &save), *end;
        long c = strtol(tok, &end, 10);
        if (*end != '\0' || word == NULL) {
            st = hl_error_set(err, HL_EPARSE, text, -1, 0,
                              "expected 'coefficient word' pairs at '%s'", tok);
            break;
        }
        if (term == flip)
            c = -c;
        int ops[16], nops = 0;
        char *wsave = NULL;
        for (char *op = strtok_r(word, ".", &wsave); op != NULL; op = strtok_r(NULL, ".", &wsave)) {
            int k = -1;
            if (strcmp(op, "g") == 0)
                k = 0;
            else if (op[0] == 'v' && op[1] >= '2' && op[1] <= '0' + NCUB && op[2] == '\0')
                k = op[1] - '0';
            if (k < 0 || nops == 16) {
                st = hl_error_set(err, HL_EPARSE, text, -1, 0, "unknown operator '%s'", op);
                break;
            }
            ops[nops++] = k;
        }
        for (int i = 0; i < 2 && st == HL_OK; i++) {
            paper_alg_z(&f, i, sys);
            for (int j = nops - 1; j >= 0 && st == HL_OK; j--)
                st = apply_op(&f, ops[j], &f, w, sch, err);
            hl_alg_set_si(&t, c, ctx);
            hl_alg_mul(&t, &t, &f, ctx);
            hl_alg_add(&out[i], &out[i], &t, ctx);
        }
    }
    if (nterms != NULL)
        *nterms = term;
    free(copy);
    hl_alg_clear(&f, ctx);
    hl_alg_clear(&t, ctx);
    return st;
}

/* Does the D^k relation `text` (term flip's sign changed) hold for every
 * test scheme from `from` on?  (0 also when it cannot be evaluated.) */
int paper_rel_holds(struct hl_paper_work *w, const char *text, int flip, int k, int from)
{
    hl_alg_ctx *ctx = hl_system_ctx(w->cub);
    hl_alg *l = hl_alg_vec_new(2, ctx), *v = hl_alg_vec_new(2, ctx);
    int ok = 1;
    for (int s = from; s < NREL && ok; s++)
        ok = rel_lhs(l, w, k, s, NULL) == HL_OK &&
             paper_eval_rel(v, NULL, w, s, text, flip, NULL) == HL_OK &&
             hl_alg_equal(&v[0], &l[0], ctx) && hl_alg_equal(&v[1], &l[1], ctx);
    hl_alg_vec_free(l, 2, ctx);
    hl_alg_vec_free(v, 2, ctx);
    return ok;
}

/* The term of the print whose sign, changed, makes the relation hold for
 * every test scheme (-1 if no single sign does): a computed correction. */
int paper_rel_sign_fix(struct hl_paper_work *w, const char *text, int k, int nterms)
{
    for (int j = 0; j < nterms; j++)
        if (paper_rel_holds(w, text, j, k, 0))
            return j;
    return -1;
}

/* The relation's text with the sign of term j changed, a new string. */
char *paper_rel_flipped(const char *text, int j)
{
    char *copy = hl_xstrdup(text), *save = NULL;
    hl_buf b;
    int term = 0;
    hl_buf_init(&b);
    for (char *tok = strtok_r(copy, " ", &save); tok != NULL; tok = strtok_r(NULL, " ", &save)) {
        char *word = strtok_r(NULL, " ", &save);
        if (word == NULL)
            break;
        long c = strtol(tok, NULL, 10);
        hl_buf_printf(&b, "%s%+ld %s", term == 0 ? "" : " ", term == j ? -c : c, word);
        term++;
    }
    free(copy);
    return hl_buf_take(&b);
}

/* The text of term j of a relation ("-1 v3.g"), copied. */
char *paper_rel_term(const char *text, int j)
{
    char *copy = hl_xstrdup(text), *save = NULL, *res = NULL;
    int term = 0;
    for (char *tok = strtok_r(copy, " ", &save); tok != NULL; tok = strtok_r(NULL, " ", &save)) {
        char *word = strtok_r(NULL, " ", &save);
        if (word == NULL)
            break;
        if (term++ == j) {
            hl_buf b;
            hl_buf_init(&b);
            hl_buf_printf(&b, "%s %s", tok, word);
            res = hl_buf_take(&b);
            break;
        }
    }
    free(copy);
    return res != NULL ? res : hl_xstrdup("?");
}
