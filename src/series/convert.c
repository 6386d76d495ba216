/* Between series and algebra elements: the truncated series as a polynomial
 * in a base symbol, and the expansion of an element in a base symbol. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "series/series_impl.h"

/* ---- the symbol table for Taylor mode ---------------------------------------- */

void series_table_init(series_table *t, int var_D, int n, hl_alg_ctx *ctx)
{
    int nb = hl_alg_ctx_nbase(ctx);
    t->nsym = 0;
    t->alloc = nb + 8;
    t->names = hl_xmalloc((size_t)t->alloc * sizeof *t->names);
    t->vals = hl_xmalloc((size_t)t->alloc * sizeof *t->vals);
    hl_alg g;
    hl_alg_init(&g, ctx);
    for (int i = 0; i < nb; i++) {
        t->names[i] = hl_alg_ctx_name(ctx, i);
        hl_series_init(&t->vals[i], n, ctx);
        if (i == var_D) {
            if (n > 1)
                hl_alg_one(&t->vals[i].c[1], ctx);
        } else if (n > 0) {
            hl_alg_gen(&g, i, ctx);
            hl_alg_set(&t->vals[i].c[0], &g, ctx);
        }
    }
    t->nsym = nb;
    hl_alg_clear(&g, ctx);
}

void series_table_clear(series_table *t, const hl_alg_ctx *ctx)
{
    for (int i = 0; i < t->nsym; i++)
        hl_series_clear(&t->vals[i], ctx);
    free(t->names);
    free(t->vals);
}

int series_table_bind(series_table *t, const char *name, const hl_series *v, const hl_alg_ctx *ctx)
{
    for (int i = 0; i < t->nsym; i++)
        if (strcmp(t->names[i], name) == 0) {
            hl_series_set(&t->vals[i], v, ctx);
            return i;
        }
    if (t->nsym == t->alloc) {
        t->alloc *= 2;
        t->names = hl_xrealloc(t->names, (size_t)t->alloc * sizeof *t->names);
        t->vals = hl_xrealloc(t->vals, (size_t)t->alloc * sizeof *t->vals);
    }
    t->names[t->nsym] = name;
    hl_series_init(&t->vals[t->nsym], 0, ctx);
    hl_series_set(&t->vals[t->nsym], v, ctx);
    return t->nsym++;
}

int series_table_eval(hl_series *out, const hl_expr *e, const series_table *t, int n,
                      hl_alg_ctx *ctx, hl_error *err)
{
    return hl_series_eval_expr(out, e, t->nsym, (const char *const *)t->names, t->vals, n, ctx,
                               err);
}

/* ---- series <-> element ---------------------------------------------------------- */

void hl_series_to_alg(hl_alg *r, const hl_series *s, int var, hl_alg_ctx *ctx)
{
    hl_alg acc, x;
    hl_alg_init(&acc, ctx);
    hl_alg_init(&x, ctx);
    hl_alg_gen(&x, var, ctx);
    for (int k = s->n - 1; k >= 0; k--) { /* Horner */
        hl_alg_mul(&acc, &acc, &x, ctx);
        hl_alg_add(&acc, &acc, &s->c[k], ctx);
    }
    hl_alg_swap(r, &acc, ctx);
    hl_alg_clear(&acc, ctx);
    hl_alg_clear(&x, ctx);
}

/* The coefficients of the polynomial p (an mpoly of ctx) in var, up to var^(n-1).
 * HL_EINVAL when p's atoms involve var. */
static int poly_series(hl_series *r, const fmpz_mpoly_t p, int var, int n, hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    hl_alg a;
    hl_alg_init(&a, ctx);
    fmpz_mpoly_set(a.num, p, mc);
    hl_series_zero(r, n, ctx);
    long deg = hl_alg_degree(&a, var, ctx);
    int status = HL_OK;
    for (long k = 0; status == HL_OK && k < n && k <= deg; k++)
        status = hl_alg_coeff(&r->c[k], &a, var, k, ctx, NULL);
    hl_alg_clear(&a, ctx);
    return status;
}

/* a rational in var with atoms free of var: num series / den series.
 * Returns HL_EUNSUP (not an error for the caller) when it is not. */
static int rational_series(hl_series *r, const hl_alg *a, int var, int n, hl_alg_ctx *ctx,
                           hl_error *err)
{
    hl_series num, den;
    hl_series_init(&num, 0, ctx);
    hl_series_init(&den, 0, ctx);
    int status = poly_series(&num, a->num, var, n, ctx);
    if (status == HL_OK)
        status = poly_series(&den, a->den, var, n, ctx);
    if (status != HL_OK) {
        status = HL_EUNSUP;
    } else if (n > 0 && hl_alg_is_zero(&den.c[0], ctx)) {
        /* num/den is reduced, so den(0) = 0 is a true pole */
        status =
            hl_error_set(err, HL_EDOM, NULL, -1, 0, "pole at %s = 0", hl_alg_ctx_name(ctx, var));
    } else {
        status = hl_series_div(r, &num, &den, ctx, err);
    }
    hl_series_clear(&num, ctx);
    hl_series_clear(&den, ctx);
    return status;
}

/* The expansion of the polynomial p by Taylor mode on its expression. */
static int taylor_poly(hl_series *r, const fmpz_mpoly_t p, int var, int n, hl_alg_ctx *ctx,
                       hl_error *err)
{
    hl_alg a;
    hl_alg_init(&a, ctx);
    fmpz_mpoly_set(a.num, p, hl_alg_ctx_mpoly(ctx));
    hl_pool *pool = hl_pool_new();
    series_table t;
    series_table_init(&t, var, n, ctx);
    int status = series_table_eval(r, hl_alg_to_expr(&a, ctx, pool), &t, n, ctx, err);
    series_table_clear(&t, ctx);
    hl_pool_free(pool);
    hl_alg_clear(&a, ctx);
    return status;
}

/* Atoms in var (sin D, sqrt(1 + D)): Taylor mode on numerator and
 * denominator apart, so that a common zero at var = 0 through the atoms
 * (sin(D)/D) cancels instead of failing as a division by zero. */
static int atom_series(hl_series *r, const hl_alg *a, int var, int n, hl_alg_ctx *ctx,
                       hl_error *err)
{
    enum { EXTRA = 8 }; /* how deep a common zero is looked for */
    hl_series num, den;
    hl_series_init(&num, 0, ctx);
    hl_series_init(&den, 0, ctx);
    int status = taylor_poly(&den, a->den, var, n + EXTRA, ctx, err);
    int v = status == HL_OK ? hl_series_valuation(&den, ctx) : 0;
    if (status == HL_OK && v >= EXTRA)
        status =
            hl_error_set(err, HL_EDOM, NULL, -1, 0, "pole at %s = 0", hl_alg_ctx_name(ctx, var));
    if (status == HL_OK)
        status = taylor_poly(&num, a->num, var, n + v, ctx, err);
    if (status == HL_OK && hl_series_valuation(&num, ctx) < v)
        status =
            hl_error_set(err, HL_EDOM, NULL, -1, 0, "pole at %s = 0", hl_alg_ctx_name(ctx, var));
    if (status == HL_OK) {
        for (int k = 0; k < n; k++) { /* divide both by var^v */
            hl_alg_swap(&num.c[k], &num.c[k + v], ctx);
            hl_alg_swap(&den.c[k], &den.c[k + v], ctx);
        }
        hl_series_set_length(&num, n, ctx);
        hl_series_set_length(&den, n, ctx);
        status = hl_series_div(r, &num, &den, ctx, err);
    }
    hl_series_clear(&num, ctx);
    hl_series_clear(&den, ctx);
    return status;
}

hl_status hl_series_from_alg(hl_series *r, const hl_alg *a, int var, int n, hl_alg_ctx *ctx,
                             hl_error *err)
{
    if (n < 0 || n > HL_SERIES_MAX_N)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "series length %d outside 0..%d", n,
                            HL_SERIES_MAX_N);
    if (var < 0 || var >= hl_alg_ctx_nbase(ctx))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no base symbol number %d", var);
    int status = rational_series(r, a, var, n, ctx, err);
    if (status != HL_EUNSUP)
        return status;
    return atom_series(r, a, var, n, ctx, err);
}
