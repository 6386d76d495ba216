/* The computations the paper's formula rows share (formulas_impl.h): the
 * oscillator, the paper's schemes analysed by the library
 * (hl_analysis_compute), and their closed maps solved from the printed
 * discrete equations by exact linear algebra (an independent route). */
#include <stdlib.h>
#include <string.h>

#include "paper/formulas_impl.h"

/* explicit Euler, and implicit midpoint (an implicit, symplectic scheme): two
 * different schemes, so that a relation cannot hold by a coincidence of one */
static const char *const REL_SCHEMES[NREL] = {
    "Q = q + D*Hp(q, p); P = p - D*Hq(q, p)",
    "(Q-q)/D = Hp((q+Q)/2, (p+P)/2); (P-p)/D = -Hq((q+Q)/2, (p+P)/2)"};

/* The paper's discrete equations, as printed (X, P the next point). */
static const char EQ_EULER[] = "(X-x)/D = p; (P-p)/D = -x";
static const char EQ_DG[] = "(X-x)/D = (P^2-p^2)/(2*(P-p)); (P-p)/D = -(X^2-x^2)/(2*(X-x))";

/* ---- small helpers ------------------------------------------------------ */

/* "a; b" -> out[0], out[1] (or one component when there is no ';'). */
int paper_read_comps(hl_alg *out, int ncomp, hl_system *sys, const char *text, hl_error *err)
{
    char *t = hl_xstrdup(text), *semi = strchr(t, ';');
    int st;
    if ((semi != NULL) != (ncomp == 2)) {
        free(t);
        return hl_error_set(err, HL_EPARSE, text, -1, 0, "expected %d component%s separated by ';'",
                            ncomp, ncomp == 2 ? "s" : "");
    }
    if (semi != NULL)
        *semi = '\0';
    st = hl_system_read(&out[0], sys, t, err);
    if (st == HL_OK && semi != NULL)
        st = hl_system_read(&out[1], sys, semi + 1, err);
    free(t);
    return st;
}

void paper_alg_D(hl_alg *r, hl_system *sys)
{
    hl_alg_gen(r, hl_system_var_D(sys), hl_system_ctx(sys));
}

void paper_alg_z(hl_alg *r, int i, hl_system *sys)
{
    hl_alg_gen(r, i == 0 ? hl_system_var_q(sys, 0) : hl_system_var_p(sys, 0), hl_system_ctx(sys));
}

/* Solve two equations "lhs = rhs; lhs = rhs", linear in the next point
 * (X, P) once put in canonical form, for the map: exact Cramer's rule in the
 * two-dof context lin2 (where X and P are symbols), then read back into the
 * oscillator's context through hamlie's text syntax. */
static int solve_linear_map(hl_alg *map, struct hl_paper_work *w, const char *eqs, hl_error *err)
{
    hl_system *L = w->lin2;
    hl_alg_ctx *ctx = hl_system_ctx(L);
    int vX = hl_system_var_q(L, 1), vP = hl_system_var_p(L, 1);
    hl_alg *F = hl_alg_vec_new(2, ctx), *a = hl_alg_vec_new(2, ctx), *b = hl_alg_vec_new(2, ctx),
           *c = hl_alg_vec_new(2, ctx), *t = hl_alg_vec_new(4, ctx), zero[2];
    int st = HL_OK, vars[2] = {vX, vP};
    char *copy = hl_xstrdup(eqs), *parts[2] = {copy, strchr(copy, ';')};
    hl_alg_init(&zero[0], ctx);
    hl_alg_init(&zero[1], ctx);
    if (parts[1] == NULL) {
        st = hl_error_set(err, HL_EINVAL, eqs, -1, 0, "expected two equations");
        goto done;
    }
    *parts[1]++ = '\0';
    for (int i = 0; i < 2 && st == HL_OK; i++) {
        char *eq = strchr(parts[i], '=');
        hl_buf b2;
        if (eq == NULL) {
            st = hl_error_set(err, HL_EINVAL, eqs, -1, 0, "equation %d has no '='", i + 1);
            break;
        }
        *eq = '\0';
        hl_buf_init(&b2);
        hl_buf_printf(&b2, "(%s) - (%s)", parts[i], eq + 1);
        st = hl_system_read(&F[i], L, b2.s, err);
        hl_buf_clear(&b2);
        if (st == HL_OK)
            st = hl_alg_diff(&a[i], &F[i], vX, ctx, err);
        if (st == HL_OK)
            st = hl_alg_diff(&b[i], &F[i], vP, ctx, err);
        if (st == HL_OK)
            st = hl_alg_subst(&c[i], &F[i], 2, vars, zero, ctx, err);
        if (st == HL_OK &&
            (hl_alg_depends_on(&a[i], vX, ctx) || hl_alg_depends_on(&a[i], vP, ctx) ||
             hl_alg_depends_on(&b[i], vX, ctx) || hl_alg_depends_on(&b[i], vP, ctx)))
            st = hl_error_set(err, HL_EUNSUP, eqs, -1, 0,
                              "equation %d is not linear in the next point", i + 1);
    }
    if (st != HL_OK)
        goto done;
    /* det = a1 b2 - a2 b1; X = (b1 c2 - b2 c1)/det; P = (a2 c1 - a1 c2)/det */
    hl_alg_mul(&t[0], &a[0], &b[1], ctx);
    hl_alg_mul(&t[1], &a[1], &b[0], ctx);
    hl_alg_sub(&t[0], &t[0], &t[1], ctx);
    if (hl_alg_is_zero(&t[0], ctx)) {
        st = hl_error_set(err, HL_EDOM, eqs, -1, 0, "the equations do not determine (X, P)");
        goto done;
    }
    hl_alg_mul(&t[1], &b[0], &c[1], ctx);
    hl_alg_mul(&t[2], &b[1], &c[0], ctx);
    hl_alg_sub(&t[1], &t[1], &t[2], ctx);
    hl_alg_mul(&t[2], &a[1], &c[0], ctx);
    hl_alg_mul(&t[3], &a[0], &c[1], ctx);
    hl_alg_sub(&t[2], &t[2], &t[3], ctx);
    for (int i = 0; i < 2 && st == HL_OK; i++) {
        if ((st = hl_alg_div(&t[1 + i], &t[1 + i], &t[0], ctx, err)) != HL_OK)
            break;
        char *txt = hl_format_alg(&t[1 + i], ctx, hl_system_pool(L), HL_STYLE_TEXT);
        st = hl_system_read(&map[i], w->osc, txt, err);
        free(txt);
    }
done:
    free(copy);
    hl_alg_clear(&zero[0], ctx);
    hl_alg_clear(&zero[1], ctx);
    hl_alg_vec_free(F, 2, ctx);
    hl_alg_vec_free(a, 2, ctx);
    hl_alg_vec_free(b, 2, ctx);
    hl_alg_vec_free(c, 2, ctx);
    hl_alg_vec_free(t, 4, ctx);
    return st;
}

/* Does the closed map agree with the series psi to O(D^n)? (-1: could not
 * expand the map) */
int paper_map_matches_series(const hl_alg *map, const hl_series *psi, int n, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int ok = 1;
    for (int i = 0; i < 2 && ok == 1; i++) {
        hl_series s, t;
        hl_series_init(&s, 0, ctx);
        hl_series_init(&t, 0, ctx);
        if (hl_series_from_alg(&s, &map[i], hl_system_var_D(sys), n, ctx, NULL) != HL_OK)
            ok = -1;
        else {
            hl_series_set(&t, &psi[i], ctx);
            hl_series_set_length(&t, n, ctx);
            ok = hl_series_equal(&s, &t, ctx);
        }
        hl_series_clear(&s, ctx);
        hl_series_clear(&t, ctx);
    }
    return ok;
}

/* The scheme (a catalog name, else its text) analysed to v_n by the
 * library, with the parts asked for (HL_ANALYSIS_*); the v_k always two
 * ways, without a budget. */
int paper_expand_catalog(analysed *out, const char *name, const char *text, unsigned parts,
                         hl_system *sys, int n, hl_error *err)
{
    hl_analysis_opts o;
    hl_analysis_opts_default(&o);
    o.order = n;
    o.parts = parts;
    o.invariants_degree = 0;
    o.K_route_budget = 0;
    int st = name != NULL ? hl_scheme_new(&out->s, name, 0, sys, err)
                          : hl_scheme_from_text(&out->s, text, sys, err);
    if (st == HL_OK)
        st = hl_analysis_compute(&out->a, &o, out->s, sys, err);
    return st;
}

void paper_analysed_clear(analysed *x)
{
    hl_analysis_free(x->a);
    hl_scheme_free(x->s);
    x->a = NULL;
    x->s = NULL;
}

static int new_system(hl_system **sys, const char *H, const char *pairs, hl_error *err)
{
    hl_system_spec spec = {H, pairs, NULL, NULL, NULL};
    return hl_system_new(sys, &spec, err);
}

void paper_work_clear(struct hl_paper_work *w)
{
    if (w->osc != NULL) {
        hl_alg_ctx *ctx = hl_system_ctx(w->osc);
        hl_alg_vec_free(w->g, 2, ctx);
        hl_alg_vec_free(w->exact_map, 2, ctx);
        hl_alg_vec_free(w->euler_map, 2, ctx);
        hl_alg_vec_free(w->dg_map, 2, ctx);
        paper_analysed_clear(&w->exact);
        paper_analysed_clear(&w->euler);
        paper_analysed_clear(&w->dg);
    }
    if (w->cub != NULL) {
        hl_alg_ctx *ctx = hl_system_ctx(w->cub);
        for (int s = 0; s < NREL; s++) {
            paper_analysed_clear(&w->rel[s]);
            hl_alg_vec_free(w->psiT_cub[s], 2, ctx);
        }
        hl_alg_vec_free(w->g_cub, 2, ctx);
    }
    free(w->euler_map_how);
    free(w->dg_map_how);
    hl_system_free(w->osc);
    hl_system_free(w->lin2);
    hl_system_free(w->cub);
    memset(w, 0, sizeof *w);
}

static char *map_how(const char *eqs, int match, const char *scheme)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b,
                  "solved exactly (Cramer) from the printed equations %s; its Taylor "
                  "series %s the catalog scheme %s expanded to O(D^%d)",
                  eqs,
                  match == 1   ? "equals"
                  : match == 0 ? "DIFFERS from"
                               : "(not expandable) vs",
                  scheme, NV + 1);
    return hl_buf_take(&b);
}

int paper_work_init(struct hl_paper_work *w, hl_error *err)
{
    int st;
    memset(w, 0, sizeof *w);
    if ((st = new_system(&w->osc, "(p^2+x^2)/2", "x:p", err)) != HL_OK ||
        (st = new_system(&w->lin2, "(p^2+x^2)/2 + (P^2+X^2)/2", "x:p,X:P", err)) != HL_OK ||
        (st = new_system(&w->cub, "(p^2+x^2)/2 + x^3/3", "x:p", err)) != HL_OK)
        return st;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    w->g = hl_alg_vec_new(2, ctx);
    w->exact_map = hl_alg_vec_new(2, ctx);
    w->euler_map = hl_alg_vec_new(2, ctx);
    w->dg_map = hl_alg_vec_new(2, ctx);
    if ((st = hl_generator(&w->g[0], &w->g[1], w->osc, err)) != HL_OK)
        return st;
    if ((st = paper_expand_catalog(&w->exact, "exact-rotation", NULL, 0, w->osc, NV, err)) !=
            HL_OK ||
        (st = paper_expand_catalog(&w->euler, "paper-euler", NULL, 0, w->osc, NV, err)) != HL_OK ||
        (st = paper_expand_catalog(&w->dg, "paper-dg", NULL, HL_ANALYSIS_TIME, w->osc, NV, err)) !=
            HL_OK)
        return st;
    {
        hl_scheme *s = NULL;
        if ((st = hl_scheme_new(&s, "exact-rotation", 0, w->osc, err)) == HL_OK)
            st = hl_errors_scheme_map(w->exact_map, s, err);
        hl_scheme_free(s);
        if (st != HL_OK)
            return st;
    }
    if ((st = solve_linear_map(w->euler_map, w, EQ_EULER, err)) != HL_OK ||
        (st = solve_linear_map(w->dg_map, w, EQ_DG, err)) != HL_OK)
        return st;
    w->euler_map_how =
        map_how(EQ_EULER, paper_map_matches_series(w->euler_map, w->euler.a->psi, NV + 1, w->osc),
                "paper-euler");
    w->dg_map_how = map_how(
        EQ_DG, paper_map_matches_series(w->dg_map, w->dg.a->psi, NV + 1, w->osc), "paper-dg");
    /* the nonlinear test system for the relations between K and the v_k */
    hl_alg_ctx *cc = hl_system_ctx(w->cub);
    w->g_cub = hl_alg_vec_new(2, cc);
    if ((st = hl_generator(&w->g_cub[0], &w->g_cub[1], w->cub, err)) != HL_OK)
        return st;
    for (int s = 0; s < NREL; s++) {
        st = paper_expand_catalog(&w->rel[s], NULL, REL_SCHEMES[s], 0, w->cub, NCUB, err);
        if (st != HL_OK)
            return st;
        w->psiT_cub[s] = hl_alg_vec_new(2, cc);
        for (int i = 0; i < 2; i++)
            hl_series_to_alg(&w->psiT_cub[s][i], &w->rel[s].a->psi[i], hl_system_var_D(w->cub), cc);
    }
    return HL_OK;
}

char *paper_strf(const char *fmt, const char *a)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, fmt, a);
    return hl_buf_take(&b);
}

const char *paper_agree_text(const hl_vfields *e)
{
    return e->agree ? "agree" : "DISAGREE";
}
