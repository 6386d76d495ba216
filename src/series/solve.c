/* Implicit schemes solved order by order in the step.
 *
 * An equation that is regular at D = 0 as written is solved as written:
 * N = lhs - rhs.  Regular: no divisor in the unknowns or the step vanishes
 * at D = 0 with the unknowns at z0, and N does not vanish identically
 * there.  (A Runge-Kutta stage of Kepler, k = -q'/|q'|^3 with
 * q' = q + D a k, is regular; over a common denominator its numerator
 * swells, gauss2 on planar Kepler to D^7 took 40 s.)  Any other equation is
 * read in an auxiliary algebra context whose base symbols are those of the
 * caller's context plus the unknowns, so that lhs - rhs becomes a reduced
 * fraction: its numerator N is what is solved (this is what makes
 * (X - x)/D = ... or the paper's discrete gradient (P^2 - p^2)/(P - p)
 * regular at D = 0), after dividing out the largest power of D that
 * divides it.  Then with J0 = dN/dZ at (z0, D = 0) invertible,
 *   N(Z_{<k} + D^k Z_k) = N(Z_{<k}) + D^k J0 Z_k + O(D^(k+1)),
 * so Z_k = -J0^{-1} [N(Z_{<k})]_k.  The numerators are compiled once into a
 * Taylor program run coefficient by coefficient (taylor.c), so order k costs
 * one new coefficient of every node, not a whole new series. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "series/series_impl.h"

typedef struct solver {
    int m, n, var_D;
    const char *step;
    hl_alg_ctx *ctx; /* the caller's */
    hl_alg_ctx *aux; /* base symbols of ctx, the unknowns, maybe the step */
    hl_pool *pool;
    const char **start_names;     /* the unknowns and the step, */
    const hl_expr **start_values; /* their values at D = 0 (z0 and 0) */
    const hl_expr **N; /* the numerators, as expressions */
    hl_alg *Jinv;      /* m x m, row-major */
    series_table tab;  /* values of every symbol: base symbols, unknowns, step */
    int *iZ, iD;       /* where the unknowns and the step are in tab */
    int nn;            /* length of the input series: max(n, 2) */
    series_prog *prog; /* the numerators compiled */
} solver;

/* D^v divides every term of a's numerator: divide it out (den dropped). */
static void strip_monomial(hl_alg *a, int aux_D, const hl_alg_ctx *aux)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(aux);
    fmpz_mpoly_one(a->den, mc);
    slong v = -1; /* least exponent of D over the terms */
    for (slong t = 0; t < fmpz_mpoly_length(a->num, mc); t++) {
        slong e = fmpz_mpoly_get_term_var_exp_si(a->num, t, aux_D, mc);
        if (v < 0 || e < v)
            v = e;
    }
    if (v > 0) {
        fmpz_mpoly_t dv;
        fmpz_mpoly_init(dv, mc);
        fmpz_mpoly_gen(dv, aux_D, mc);
        fmpz_mpoly_pow_ui(dv, dv, (ulong)v, mc);
        fmpz_mpoly_divides(a->num, a->num, dv, mc); /* exact by construction */
        fmpz_mpoly_clear(dv, mc);
    }
}

/* a still vanishes at D = 0 for every Z: D divides it through an atom
 * (sin(D) (X - x - D p) = 0).  Expand in D with the unknowns symbolic, drop
 * the zero coefficients, keep the next n: a polynomial in D. */
static int strip_series(hl_alg *a, int aux_D, solver *S, hl_error *err)
{
    int len = 2 * S->n + 8;
    hl_series s;
    hl_series_init(&s, 0, S->aux);
    int status = hl_series_from_alg(&s, a, aux_D, len, S->aux, err);
    if (status == HL_OK) {
        int v = hl_series_valuation(&s, S->aux);
        if (v == len)
            status = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                  "the equation holds for every value of the unknowns");
        else if (v + S->n > len)
            status = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                                  "the equation vanishes to order %d at %s = 0", v, S->step);
        else {
            for (int k = 0; k < S->n; k++)
                hl_alg_swap(&s.c[k], &s.c[k + v], S->aux);
            hl_series_set_length(&s, S->n, S->aux);
            hl_series_to_alg(a, &s, aux_D, S->aux);
        }
    }
    hl_series_clear(&s, S->aux);
    return status;
}

/* Does d depend on the unknowns or the step and vanish at D = 0 with the
 * unknowns at z0?  (A divisor that cannot be read there counts as one.) */
static int vanishes_at_start(const hl_expr *d, void *arg)
{
    solver *S = arg;
    int dep = 0;
    for (int j = 0; j <= S->m && !dep; j++)
        dep = hl_expr_has_symbol(d, S->start_names[j]);
    if (!dep)
        return 0;
    const hl_expr *d0 = hl_expr_subst(S->pool, d, S->m + 1, S->start_names, S->start_values);
    hl_alg a;
    hl_alg_init(&a, S->aux);
    int r = hl_alg_from_expr(&a, d0, S->aux, NULL) != HL_OK || hl_alg_is_zero(&a, S->aux);
    hl_alg_clear(&a, S->aux);
    return r;
}

/* Is F = lhs - rhs regular at D = 0 as written (see the top)? */
static int regular_as_written(const hl_expr *F, solver *S)
{
    if (hl_expr_divides_by(F, vanishes_at_start, S))
        return 0;
    const hl_expr *F0 = hl_expr_subst(S->pool, F, 1, &S->start_names[S->m],
                                      &S->start_values[S->m]);
    hl_alg a;
    hl_alg_init(&a, S->aux);
    int r = hl_alg_from_expr(&a, F0, S->aux, NULL) == HL_OK && !hl_alg_is_zero(&a, S->aux);
    hl_alg_clear(&a, S->aux);
    return r;
}

/* lhs - rhs of an equation as written when it is regular at D = 0; else
 * read in the auxiliary context, its numerator without the power of D it
 * is divisible by. */
static int numerator(const hl_expr **out, const hl_eqn *eq, int aux_D, solver *S, hl_error *err)
{
    const hl_expr *F = eq->rhs ? hl_sub(S->pool, eq->lhs, eq->rhs) : eq->lhs;
    if (regular_as_written(F, S)) {
        *out = F;
        return HL_OK;
    }
    hl_alg a, b;
    hl_alg_init(&a, S->aux);
    hl_alg_init(&b, S->aux);
    int status = hl_alg_from_expr(&a, eq->lhs, S->aux, err);
    if (status == HL_OK && eq->rhs)
        status = hl_alg_from_expr(&b, eq->rhs, S->aux, err);
    if (status == HL_OK) {
        hl_alg_sub(&a, &a, &b, S->aux);
        strip_monomial(&a, aux_D, S->aux);
        hl_alg zero;
        hl_alg_init(&zero, S->aux);
        status = hl_alg_subst(&b, &a, 1, &aux_D, &zero, S->aux, err);
        hl_alg_clear(&zero, S->aux);
        if (status == HL_OK && hl_alg_is_zero(&b, S->aux))
            status = strip_series(&a, aux_D, S, err);
    }
    if (status == HL_OK)
        *out = hl_alg_to_expr(&a, S->aux, S->pool);
    hl_alg_clear(&a, S->aux);
    hl_alg_clear(&b, S->aux);
    return status;
}

static int setup_aux(solver *S, int m, const hl_eqn *eqs, const char *const *unknowns,
                     const hl_alg *z0, const char *step, hl_error *err)
{
    int nb = hl_alg_ctx_nbase(S->ctx);
    const char **names = hl_xmalloc((size_t)(nb + m + 1) * sizeof *names);
    int k = 0;
    for (int i = 0; i < nb; i++)
        names[k++] = hl_alg_ctx_name(S->ctx, i);
    for (int i = 0; i < m; i++)
        names[k++] = unknowns[i];
    if (S->var_D < 0)
        names[k++] = step;
    S->aux = hl_alg_ctx_new(k, names, 64);
    free(names);
    int aux_D = S->var_D >= 0 ? S->var_D : k - 1;
    S->start_names = hl_xmalloc((size_t)(m + 1) * sizeof *S->start_names);
    S->start_values = hl_xmalloc((size_t)(m + 1) * sizeof *S->start_values);
    for (int j = 0; j < m; j++) {
        S->start_names[j] = unknowns[j];
        S->start_values[j] = hl_alg_to_expr(&z0[j], S->ctx, S->pool);
    }
    S->start_names[m] = step;
    S->start_values[m] = hl_num_si(S->pool, 0);
    int status = HL_OK;
    for (int i = 0; status == HL_OK && i < m; i++) {
        status = numerator(&S->N[i], &eqs[i], aux_D, S, err);
        if (status != HL_OK)
            hl_error_prefix(err, "in equation %d", i + 1);
    }
    return status;
}

/* Set the unknowns' input series to z0[j] + T [j == col] (col < 0: no T) and
 * the step's to zero or to the series D. */
static void set_point(solver *S, const hl_alg *z0, int col, int d_zero)
{
    for (int j = 0; j < S->m; j++) {
        hl_series *u = &S->tab.vals[S->iZ[j]];
        if (j == col)
            hl_series_set_var(u, &z0[j], S->nn, S->ctx);
        else
            hl_series_set_alg(u, &z0[j], S->nn, S->ctx);
    }
    hl_series *d = &S->tab.vals[S->iD];
    hl_series_zero(d, S->nn, S->ctx);
    if (!d_zero)
        hl_alg_one(&d->c[1], S->ctx);
}

/* "(X, P)", malloc'd */
static char *list_names(int m, const char *const *names)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_putc(&b, '(');
    for (int i = 0; i < m; i++)
        hl_buf_printf(&b, "%s%s", i ? ", " : "", names[i]);
    hl_buf_putc(&b, ')');
    return hl_buf_take(&b);
}

/* Gauss-Jordan on the m x m matrix A (destroyed): Jinv = A^{-1}, or 0. */
static int invert(hl_alg *Jinv, hl_alg *A, int m, hl_alg_ctx *ctx)
{
    hl_alg t, p;
    hl_alg_init(&t, ctx);
    hl_alg_init(&p, ctx);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            hl_alg_set_si(&Jinv[i * m + j], i == j, ctx);
    int ok = 1;
    for (int c = 0; ok && c < m; c++) {
        int r = c;
        while (r < m && hl_alg_is_zero(&A[r * m + c], ctx))
            r++;
        if (r == m) {
            ok = 0;
            break;
        }
        for (int j = 0; j < m; j++) {
            hl_alg_swap(&A[r * m + j], &A[c * m + j], ctx);
            hl_alg_swap(&Jinv[r * m + j], &Jinv[c * m + j], ctx);
        }
        hl_alg_one(&t, ctx);
        hl_alg_div(&t, &t, &A[c * m + c], ctx, NULL); /* nonzero: checked */
        for (int j = 0; j < m; j++) {
            hl_alg_mul(&A[c * m + j], &A[c * m + j], &t, ctx);
            hl_alg_mul(&Jinv[c * m + j], &Jinv[c * m + j], &t, ctx);
        }
        for (int i = 0; i < m; i++) {
            if (i == c || series_trivially_zero(&A[i * m + c], ctx))
                continue;
            hl_alg_set(&t, &A[i * m + c], ctx);
            for (int j = 0; j < m; j++) {
                hl_alg_mul(&p, &t, &A[c * m + j], ctx);
                hl_alg_sub(&A[i * m + j], &A[i * m + j], &p, ctx);
                hl_alg_mul(&p, &t, &Jinv[c * m + j], ctx);
                hl_alg_sub(&Jinv[i * m + j], &Jinv[i * m + j], &p, ctx);
            }
        }
    }
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&p, ctx);
    return ok;
}

/* Check N(z0, 0) = 0 and build J0^{-1}: column j of J0 is the T coefficient
 * of N(z0 + T e_j) with D = 0. */
static int linearise(solver *S, const char *const *unknowns, const hl_alg *z0, const char *step,
                     hl_error *err)
{
    int m = S->m, status = HL_OK;
    hl_alg *A = hl_alg_vec_new(m * m, S->ctx);
    for (int j = 0; status == HL_OK && j < m; j++) {
        set_point(S, z0, j, 1);
        status = series_prog_step(S->prog, 0, S->tab.vals, S->ctx, err);
        if (status == HL_OK)
            status = series_prog_step(S->prog, 1, S->tab.vals, S->ctx, err);
        if (status != HL_OK) {
            hl_error_prefix(err, "at %s = 0", step);
            break;
        }
        for (int i = 0; i < m; i++) {
            const hl_series *v = series_prog_root(S->prog, i);
            if (j == 0 && !hl_alg_is_zero(&v->c[0], S->ctx)) {
                hl_buf b;
                hl_buf_init(&b);
                for (int q = 0; q < m; q++) {
                    char *s = hl_expr_print(hl_alg_to_expr(&z0[q], S->ctx, S->pool), HL_STYLE_TEXT);
                    hl_buf_printf(&b, "%s%s = %s", q ? ", " : "", unknowns[q], s);
                    free(s);
                }
                char *at = hl_buf_take(&b);
                status = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                      "the scheme is not the identity at %s = 0: equation %d "
                                      "does not hold at %s, %s = 0",
                                      step, i + 1, at, step);
                free(at);
                break;
            }
            hl_alg_set(&A[i * m + j], &v->c[1], S->ctx);
        }
    }
    if (status == HL_OK && !invert(S->Jinv, A, m, S->ctx)) {
        char *z = list_names(m, unknowns);
        status = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                              "the scheme does not determine %s at %s = 0: the Jacobian of "
                              "the equations in %s is singular there",
                              z, step, z);
        free(z);
    }
    hl_alg_vec_free(A, m * m, S->ctx);
    return status;
}

static int check_names(int m, const char *const *unknowns, const char *step, const hl_alg_ctx *ctx,
                       hl_error *err)
{
    for (int i = 0; i < m; i++) {
        if (hl_alg_ctx_index(ctx, unknowns[i]) >= 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "the unknown '%s' is also a symbol of the system", unknowns[i]);
        if (strcmp(unknowns[i], step) == 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the unknown '%s' is also the step",
                                unknowns[i]);
        for (int j = 0; j < i; j++)
            if (strcmp(unknowns[i], unknowns[j]) == 0)
                return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the unknown '%s' is repeated",
                                    unknowns[i]);
    }
    return HL_OK;
}

/* Orders 1..n-1.  Step k with Z_k = 0 gives r = [N(Z_{<k})]_k; then
 * Z_k = -J0^{-1} r, and step k again so the program's order-k coefficients
 * are those of the true Z (later orders build on them). */
static int orders(solver *S, hl_error *err)
{
    int m = S->m, status = HL_OK;
    hl_alg t, p;
    hl_alg_init(&t, S->ctx);
    hl_alg_init(&p, S->ctx);
    hl_alg *r = hl_alg_vec_new(m, S->ctx);
    int k = 1;
    for (; status == HL_OK && k < S->n; k++) {
        status = series_prog_step(S->prog, k, S->tab.vals, S->ctx, err);
        if (status != HL_OK)
            break; /* k stays the failing order */
        for (int i = 0; i < m; i++)
            hl_alg_set(&r[i], &series_prog_root(S->prog, i)->c[k], S->ctx);
        for (int j = 0; j < m; j++) {
            hl_alg_zero(&t, S->ctx);
            for (int i = 0; i < m; i++) {
                hl_alg_mul(&p, &S->Jinv[j * m + i], &r[i], S->ctx);
                hl_alg_sub(&t, &t, &p, S->ctx);
            }
            hl_alg_set(&S->tab.vals[S->iZ[j]].c[k], &t, S->ctx);
        }
        if (k + 1 < S->n)
            status = series_prog_step(S->prog, k, S->tab.vals, S->ctx, err);
        if (status != HL_OK)
            break;
    }
    if (status != HL_OK)
        hl_error_prefix(err, "at order %d", k);
    hl_alg_vec_free(r, m, S->ctx);
    hl_alg_clear(&t, S->ctx);
    hl_alg_clear(&p, S->ctx);
    return status;
}

hl_status hl_series_solve(hl_series *Z, int m, const hl_eqn *eqs, const char *const *unknowns,
                          const hl_alg *z0, const char *step, int n, hl_alg_ctx *ctx, hl_error *err)
{
    if (m < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no equations");
    if (n < 1 || n > HL_SERIES_MAX_N)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "series length %d outside 1..%d", n,
                            HL_SERIES_MAX_N);
    int status = check_names(m, unknowns, step, ctx, err);
    if (status != HL_OK)
        return status;

    solver S;
    memset(&S, 0, sizeof S);
    S.m = m;
    S.n = n;
    S.nn = n > 2 ? n : 2; /* the Jacobian needs two coefficients */
    S.ctx = ctx;
    S.var_D = hl_alg_ctx_index(ctx, step);
    S.step = step;
    S.pool = hl_pool_new();
    S.N = hl_xcalloc((size_t)m, sizeof *S.N);
    S.iZ = hl_xcalloc((size_t)m, sizeof *S.iZ);
    S.Jinv = hl_alg_vec_new(m * m, ctx);
    series_table_init(&S.tab, S.var_D, S.nn, ctx);
    hl_series zs;
    hl_series_init(&zs, S.nn, ctx);
    for (int j = 0; j < m; j++)
        S.iZ[j] = series_table_bind(&S.tab, unknowns[j], &zs, ctx);
    S.iD = series_table_bind(&S.tab, step, &zs, ctx);
    hl_series_clear(&zs, ctx);

    status = setup_aux(&S, m, eqs, unknowns, z0, step, err);
    if (status == HL_OK)
        status = series_prog_compile(&S.prog, m, S.N, S.tab.nsym, (const char *const *)S.tab.names,
                                     S.nn, ctx, err);
    if (status == HL_OK)
        status = linearise(&S, unknowns, z0, step, err);
    if (status == HL_OK) {
        set_point(&S, z0, -1, 0);
        status = series_prog_step(S.prog, 0, S.tab.vals, ctx, err);
    }
    if (status == HL_OK)
        status = orders(&S, err);
    for (int j = 0; status == HL_OK && j < m; j++) {
        hl_series_set(&Z[j], &S.tab.vals[S.iZ[j]], ctx);
        hl_series_set_length(&Z[j], n, ctx);
    }
    series_prog_free(S.prog, ctx);
    series_table_clear(&S.tab, ctx);
    hl_alg_vec_free(S.Jinv, m * m, ctx);
    free(S.N);
    free(S.iZ);
    free(S.start_names);
    free(S.start_values);
    hl_alg_ctx_free(S.aux);
    hl_pool_free(S.pool);
    return status;
}
