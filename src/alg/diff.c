/* Partial derivatives: d/dv = partial in v + sum over atoms a of
 * (partial in a) * da/dv, where da/dv comes from the atom's rule and is
 * cached in the atom.  Everything is put over one denominator Q D^2 and
 * cancelled once. */
#include <stdlib.h>

#include "alg/alg_internal.h"
#include "base/buf.h"

/* r = a' * f, with f given as num/den polynomials (den with lc > 0). */
static void times_frac(hl_alg *r, const hl_alg *da, const fmpz_mpoly_t fnum,
                       const fmpz_mpoly_t fden, hl_alg_ctx *ctx)
{
    hl_alg f;
    hl_alg_init(&f, ctx);
    fmpz_mpoly_set(f.num, fnum, ctx->mctx);
    fmpz_mpoly_set(f.den, fden, ctx->mctx);
    alg_canonicalise(&f, ctx);
    hl_alg_mul(r, da, &f, ctx);
    hl_alg_clear(&f, ctx);
}

/* d atan2(y, x)/dv = (x y' - y x')/(x^2 + y^2) */
static int atan2_deriv(hl_alg *r, const alg_atom *at, int v, hl_alg_ctx *ctx, hl_error *err)
{
    const hl_alg *y = &at->arg, *x = &at->arg2;
    hl_alg dy, dx, s, t;
    hl_alg_init(&dy, ctx);
    hl_alg_init(&dx, ctx);
    hl_alg_init(&s, ctx);
    hl_alg_init(&t, ctx);
    int status = hl_alg_diff(&dy, y, v, ctx, err);
    if (status == HL_OK)
        status = hl_alg_diff(&dx, x, v, ctx, err);
    if (status == HL_OK) {
        hl_alg_mul(&t, x, &dy, ctx);
        hl_alg_mul(&s, y, &dx, ctx);
        hl_alg_sub(&t, &t, &s, ctx);
        hl_alg_mul(&s, x, x, ctx);
        hl_alg_mul(&dy, y, y, ctx);
        hl_alg_add(&s, &s, &dy, ctx);
        status = hl_alg_div(r, &t, &s, ctx, err);
    }
    hl_alg_clear(&dy, ctx);
    hl_alg_clear(&dx, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&t, ctx);
    return status;
}

/* d(atom k)/d(base v), uncached. */
static int atom_deriv(hl_alg *r, int k, int v, hl_alg_ctx *ctx, hl_error *err)
{
    alg_atom *at = &ctx->atoms[k];
    if (at->kind == ATOM_ATAN2)
        return atan2_deriv(r, at, v, ctx, err);
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    hl_alg da, t;
    hl_alg_init(&da, ctx);
    hl_alg_init(&t, ctx);
    int status = at->kind == ATOM_PI ? HL_OK : hl_alg_diff(&da, &at->arg, v, ctx, err);
    fmpz_mpoly_t n, d;
    fmpz_mpoly_init(n, mc);
    fmpz_mpoly_init(d, mc);
    if (status != HL_OK || at->kind == ATOM_PI || fmpz_mpoly_is_zero(da.num, mc)) {
        hl_alg_zero(r, ctx);
        goto done;
    }
    switch (at->kind) {
    case ATOM_SQRT: /* r' = r u'/(2u) */
    case ATOM_ROOT: /* w' = w u'/(q u) */
        fmpz_mpoly_gen(n, at->var, mc);
        fmpz_mpoly_scalar_mul_si(d, at->arg.num, at->kind == ATOM_SQRT ? 2 : at->q, mc);
        times_frac(r, &da, n, d, ctx);
        break;
    case ATOM_SIN: /* cos u * u' */
        alg_set_var(&t, ctx->atoms[at->partner].var, ctx);
        hl_alg_mul(r, &da, &t, ctx);
        break;
    case ATOM_COS: /* -sin u * u' */
        alg_set_var(&t, ctx->atoms[at->partner].var, ctx);
        hl_alg_neg(&t, &t, ctx);
        hl_alg_mul(r, &da, &t, ctx);
        break;
    case ATOM_EXP:
        alg_set_var(&t, at->var, ctx);
        hl_alg_mul(r, &da, &t, ctx);
        break;
    case ATOM_LOG: status = hl_alg_div(r, &da, &at->arg, ctx, err); break;
    case ATOM_ATAN: /* u'/(1 + u^2) */
        hl_alg_mul(&t, &at->arg, &at->arg, ctx);
        hl_alg_one(r, ctx);
        hl_alg_add(&t, &t, r, ctx);
        status = hl_alg_div(r, &da, &t, ctx, err);
        break;
    case ATOM_ASIN: /* +-u'/sqrt(1 - u^2) */
    case ATOM_ACOS:
        hl_alg_mul(&t, &at->arg, &at->arg, ctx);
        hl_alg_one(r, ctx);
        hl_alg_sub(&t, r, &t, ctx);
        status = hl_alg_apply(&t, HL_SQRT, &t, ctx, err);
        if (status == HL_OK)
            status = hl_alg_div(r, &da, &t, ctx, err);
        if (status == HL_OK && at->kind == ATOM_ACOS)
            hl_alg_neg(r, r, ctx);
        break;
    case ATOM_PI:
    case ATOM_ATAN2: break; /* pi: 0 above; atan2: atan2_deriv */
    }
done:
    fmpz_mpoly_clear(n, mc);
    fmpz_mpoly_clear(d, mc);
    hl_alg_clear(&da, ctx);
    hl_alg_clear(&t, ctx);
    return status;
}

static int atom_deriv_cached(const hl_alg **out, int k, int v, hl_alg_ctx *ctx, hl_error *err)
{
    alg_atom *at = &ctx->atoms[k];
    if (!at->dknown[v]) {
        hl_alg t;
        hl_alg_init(&t, ctx);
        int status = atom_deriv(&t, k, v, ctx, err);
        if (status != HL_OK) {
            hl_alg_clear(&t, ctx);
            return status;
        }
        at = &ctx->atoms[k]; /* the table never moves, but be explicit */
        hl_alg_swap(&at->dcache[v], &t, ctx);
        hl_alg_clear(&t, ctx);
        at->dknown[v] = 1;
    }
    *out = &at->dcache[v];
    return HL_OK;
}

/* The derivative of a polynomial p, as P/Q, given the factors f_j = dx_j/dv
 * over the common denominator Q: P = sum_j (dp/dx_j) fnum_j (Q / fden_j). */
static void poly_deriv(fmpz_mpoly_t P, const fmpz_mpoly_t p, int nf, const int *fv,
                       fmpz_mpoly_struct *fmul, hl_alg_ctx *ctx)
{
    fmpz_mpoly_t t;
    fmpz_mpoly_init(t, ctx->mctx);
    fmpz_mpoly_zero(P, ctx->mctx);
    for (int j = 0; j < nf; j++) {
        fmpz_mpoly_derivative(t, p, fv[j], ctx->mctx);
        if (fmpz_mpoly_is_zero(t, ctx->mctx))
            continue;
        fmpz_mpoly_mul(t, t, fmul + j, ctx->mctx);
        fmpz_mpoly_add(P, P, t, ctx->mctx);
    }
    fmpz_mpoly_clear(t, ctx->mctx);
}

hl_status hl_alg_diff(hl_alg *r, const hl_alg *a, int var, hl_alg_ctx *ctx, hl_error *err)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (var < 0 || var >= ctx->nbase)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no base symbol %d", var);
    int nv = alg_nvars(ctx), nf = 0, status = HL_OK;
    slong *dn = hl_xmalloc((size_t)nv * sizeof *dn), *dd = hl_xmalloc((size_t)nv * sizeof *dd);
    int *fv = hl_xmalloc((size_t)nv * sizeof *fv);
    const hl_alg **fa = hl_xmalloc((size_t)nv * sizeof *fa);
    fmpz_mpoly_degrees_si(dn, a->num, mc);
    fmpz_mpoly_degrees_si(dd, a->den, mc);
    /* the variables through which a depends on var, with their derivatives */
    if (dn[var] > 0 || dd[var] > 0) {
        fv[nf] = var;
        fa[nf++] = NULL; /* d var/d var = 1 */
    }
    for (int k = 0; k < ctx->natoms && status == HL_OK; k++) {
        int v = ctx->atoms[k].var;
        if ((dn[v] <= 0 && dd[v] <= 0) || !ctx->atoms[k].dep[var])
            continue;
        const hl_alg *d;
        status = atom_deriv_cached(&d, k, var, ctx, err);
        if (status == HL_OK && !fmpz_mpoly_is_zero(d->num, mc)) {
            fv[nf] = v;
            fa[nf++] = d;
        }
    }
    free(dn);
    free(dd);
    if (status != HL_OK || nf == 0) {
        if (status == HL_OK)
            hl_alg_zero(r, ctx);
        free(fv);
        free(fa);
        return status;
    }
    /* Q = lcm of the factors' denominators; fmul_j = fnum_j * Q/fden_j */
    fmpz_mpoly_t Q, g, t;
    fmpz_mpoly_init(Q, mc);
    fmpz_mpoly_init(g, mc);
    fmpz_mpoly_init(t, mc);
    fmpz_mpoly_one(Q, mc);
    for (int j = 0; j < nf; j++) {
        if (fa[j] == NULL || fmpz_mpoly_is_one(fa[j]->den, mc))
            continue;
        fmpz_mpoly_gcd(g, Q, fa[j]->den, mc);
        fmpz_mpoly_divides(t, fa[j]->den, g, mc);
        fmpz_mpoly_mul(Q, Q, t, mc);
    }
    fmpz_mpoly_struct *fmul = hl_xmalloc((size_t)nf * sizeof *fmul);
    for (int j = 0; j < nf; j++) {
        fmpz_mpoly_init(fmul + j, mc);
        if (fa[j] == NULL) {
            fmpz_mpoly_set(fmul + j, Q, mc);
        } else {
            fmpz_mpoly_divides(t, Q, fa[j]->den, mc);
            fmpz_mpoly_mul(fmul + j, fa[j]->num, t, mc);
        }
    }
    hl_alg res;
    hl_alg_init(&res, ctx);
    poly_deriv(res.num, a->num, nf, fv, fmul, ctx);
    if (fmpz_mpoly_is_one(a->den, mc)) {
        fmpz_mpoly_set(res.den, Q, mc);
    } else {
        /* (N'D - N D')/(Q D^2) = (N' (D/g) - N (D'/g)) / (Q D (D/g)), g = gcd(D, D') */
        fmpz_mpoly_t Dp, Dg;
        fmpz_mpoly_init(Dp, mc);
        fmpz_mpoly_init(Dg, mc);
        poly_deriv(Dp, a->den, nf, fv, fmul, ctx);
        fmpz_mpoly_gcd(g, a->den, Dp, mc);
        fmpz_mpoly_divides(Dg, a->den, g, mc);
        fmpz_mpoly_divides(Dp, Dp, g, mc);
        fmpz_mpoly_mul(res.num, res.num, Dg, mc);
        fmpz_mpoly_mul(t, a->num, Dp, mc);
        fmpz_mpoly_sub(res.num, res.num, t, mc);
        fmpz_mpoly_mul(res.den, Q, a->den, mc);
        fmpz_mpoly_mul(res.den, res.den, Dg, mc);
        fmpz_mpoly_clear(Dp, mc);
        fmpz_mpoly_clear(Dg, mc);
    }
    alg_canonicalise(&res, ctx);
    hl_alg_swap(r, &res, ctx);
    hl_alg_clear(&res, ctx);
    for (int j = 0; j < nf; j++)
        fmpz_mpoly_clear(fmul + j, mc);
    free(fmul);
    fmpz_mpoly_clear(Q, mc);
    fmpz_mpoly_clear(g, mc);
    fmpz_mpoly_clear(t, mc);
    free(fv);
    free(fa);
    return status;
}
