/* Rational functions num/den in canonical form (see alg.h): reduction by the
 * atom relations, rationalisation of denominators, gcd cancellation, and the
 * field operations.  Sums and products of elements with unit denominators
 * take a fast path with no gcd at all; otherwise the gcd is taken only
 * against the part of the denominator that can share a factor (Henrici). */
#include <stdlib.h>

#include "alg/alg_internal.h"
#include "base/buf.h"

/* ---- elements ------------------------------------------------------------ */

void hl_alg_init(hl_alg *a, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_init(a->num, ctx->mctx);
    fmpz_mpoly_init(a->den, ctx->mctx);
    fmpz_mpoly_one(a->den, ctx->mctx);
}

void hl_alg_clear(hl_alg *a, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_clear(a->num, ctx->mctx);
    fmpz_mpoly_clear(a->den, ctx->mctx);
}

void hl_alg_set(hl_alg *r, const hl_alg *a, const hl_alg_ctx *ctx)
{
    if (r == a)
        return;
    fmpz_mpoly_set(r->num, a->num, ctx->mctx);
    fmpz_mpoly_set(r->den, a->den, ctx->mctx);
}

void hl_alg_swap(hl_alg *a, hl_alg *b, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_swap(a->num, b->num, ctx->mctx);
    fmpz_mpoly_swap(a->den, b->den, ctx->mctx);
}

void hl_alg_zero(hl_alg *r, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_zero(r->num, ctx->mctx);
    fmpz_mpoly_one(r->den, ctx->mctx);
}

void hl_alg_one(hl_alg *r, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_one(r->num, ctx->mctx);
    fmpz_mpoly_one(r->den, ctx->mctx);
}

void hl_alg_set_si(hl_alg *r, long c, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_set_si(r->num, c, ctx->mctx);
    fmpz_mpoly_one(r->den, ctx->mctx);
}

void hl_alg_set_fmpq(hl_alg *r, const fmpq_t c, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_set_fmpz(r->num, fmpq_numref(c), ctx->mctx);
    fmpz_mpoly_set_fmpz(r->den, fmpq_denref(c), ctx->mctx);
    if (fmpz_is_zero(fmpq_numref(c)))
        fmpz_mpoly_one(r->den, ctx->mctx);
}

void hl_alg_gen(hl_alg *r, int i, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_gen(r->num, i, ctx->mctx);
    fmpz_mpoly_one(r->den, ctx->mctx);
}

void alg_set_var(hl_alg *r, int v, hl_alg_ctx *ctx)
{
    fmpz_mpoly_gen(r->num, v, ctx->mctx);
    fmpz_mpoly_one(r->den, ctx->mctx);
}

void alg_set_poly(hl_alg *r, const fmpz_mpoly_t p, hl_alg_ctx *ctx)
{
    fmpz_mpoly_set(r->num, p, ctx->mctx);
    fmpz_mpoly_one(r->den, ctx->mctx);
    alg_reduce(r->num, ctx);
}

hl_alg *hl_alg_vec_new(int n, const hl_alg_ctx *ctx)
{
    hl_alg *v = hl_xcalloc((size_t)(n > 0 ? n : 1), sizeof *v);
    for (int i = 0; i < n; i++)
        hl_alg_init(&v[i], ctx);
    return v;
}

void hl_alg_vec_free(hl_alg *v, int n, const hl_alg_ctx *ctx)
{
    if (v == NULL)
        return;
    for (int i = 0; i < n; i++)
        hl_alg_clear(&v[i], ctx);
    free(v);
}

/* ---- relations ------------------------------------------------------------ */

/* Split p by the exponent of v: p = sum_k P[k] v^(m k) with deg_v P[k] < m.
 * Returns K (P[0..K] initialised, caller clears). */
static slong split_var(fmpz_mpoly_struct **out, const fmpz_mpoly_t p, int v, slong m,
                       const hl_alg_ctx *ctx)
{
    slong K = fmpz_mpoly_degree_si(p, v, ctx->mctx) / m;
    int nv = alg_nvars(ctx);
    fmpz_mpoly_struct *P = hl_xmalloc((size_t)(K + 1) * sizeof *P);
    ulong *exp = hl_xmalloc((size_t)nv * sizeof *exp);
    for (slong k = 0; k <= K; k++)
        fmpz_mpoly_init(P + k, ctx->mctx);
    for (slong i = 0; i < p->length; i++) {
        fmpz_mpoly_get_term_exp_ui(exp, p, i, ctx->mctx);
        slong k = (slong)exp[v] / m;
        exp[v] %= (ulong)m;
        fmpz_mpoly_push_term_fmpz_ui(P + k, p->coeffs + i, exp, ctx->mctx);
    }
    for (slong k = 0; k <= K; k++)
        fmpz_mpoly_sort_terms(P + k, ctx->mctx); /* monomials stay distinct */
    free(exp);
    *out = P;
    return K;
}

static void free_split(fmpz_mpoly_struct *P, slong K, const hl_alg_ctx *ctx)
{
    for (slong k = 0; k <= K; k++)
        fmpz_mpoly_clear(P + k, ctx->mctx);
    free(P);
}

/* p := p with v^m replaced by rhs (Horner in rhs). */
static void reduce_var(fmpz_mpoly_t p, int v, slong m, const fmpz_mpoly_t rhs,
                       const hl_alg_ctx *ctx)
{
    fmpz_mpoly_struct *P;
    slong K = split_var(&P, p, v, m, ctx);
    fmpz_mpoly_swap(p, P + K, ctx->mctx);
    for (slong k = K - 1; k >= 0; k--) {
        fmpz_mpoly_mul(p, p, rhs, ctx->mctx);
        fmpz_mpoly_add(p, p, P + k, ctx->mctx);
    }
    free_split(P, K, ctx);
}

int alg_reduce(fmpz_mpoly_t p, hl_alg_ctx *ctx)
{
    if (ctx->natoms == 0 || fmpz_mpoly_is_fmpz(p, ctx->mctx))
        return 0;
    fmpz_mpoly_degrees_si(ctx->degs, p, ctx->mctx);
    int need = 0;
    for (int k = 0; k < ctx->natoms && !need; k++) {
        const alg_atom *at = &ctx->atoms[k];
        need = at->rel_deg > 0 && ctx->degs[at->var] >= at->rel_deg;
    }
    if (!need)
        return 0;
    for (int k = ctx->natoms - 1; k >= 0; k--) {
        const alg_atom *at = &ctx->atoms[k];
        if (at->rel_deg > 0 && fmpz_mpoly_degree_si(p, at->var, ctx->mctx) >= at->rel_deg)
            reduce_var(p, at->var, at->rel_deg, at->rel_rhs, ctx);
    }
    return 1;
}

/* Make den free of the quadratic atoms (square roots, sines) by multiplying
 * by conjugates, newest atom first: den = A + B v  ->  A^2 - B^2 rhs. */
static void rationalise(hl_alg *a, hl_alg_ctx *ctx)
{
    for (int k = ctx->natoms - 1; k >= 0; k--) {
        const alg_atom *at = &ctx->atoms[k];
        if (at->rel_deg != 2 || fmpz_mpoly_degree_si(a->den, at->var, ctx->mctx) != 1)
            continue;
        fmpz_mpoly_struct *P;
        slong K = split_var(&P, a->den, at->var, 1, ctx); /* den = P0 + P1 v */
        fmpz_mpoly_t conj, nd, t;
        fmpz_mpoly_init(conj, ctx->mctx);
        fmpz_mpoly_init(nd, ctx->mctx);
        fmpz_mpoly_init(t, ctx->mctx);
        fmpz_mpoly_gen(conj, at->var, ctx->mctx);
        fmpz_mpoly_mul(conj, conj, P + 1, ctx->mctx);
        fmpz_mpoly_sub(conj, P + 0, conj, ctx->mctx);
        fmpz_mpoly_mul(nd, P + 0, P + 0, ctx->mctx);
        fmpz_mpoly_mul(t, P + 1, P + 1, ctx->mctx);
        fmpz_mpoly_mul(t, t, at->rel_rhs, ctx->mctx);
        fmpz_mpoly_sub(nd, nd, t, ctx->mctx);
        alg_reduce(nd, ctx);
        /* A zero here means the argument was a square modulo older relations
         * (a denestable radical): keep the denominator as it is then. */
        if (!fmpz_mpoly_is_zero(nd, ctx->mctx)) {
            fmpz_mpoly_mul(a->num, a->num, conj, ctx->mctx);
            alg_reduce(a->num, ctx);
            fmpz_mpoly_swap(a->den, nd, ctx->mctx);
        }
        fmpz_mpoly_clear(conj, ctx->mctx);
        fmpz_mpoly_clear(nd, ctx->mctx);
        fmpz_mpoly_clear(t, ctx->mctx);
        free_split(P, K, ctx);
    }
}

static void fix_sign(hl_alg *a, const hl_alg_ctx *ctx)
{
    if (a->den->length > 0 && fmpz_sgn(a->den->coeffs + 0) < 0) {
        fmpz_mpoly_neg(a->num, a->num, ctx->mctx);
        fmpz_mpoly_neg(a->den, a->den, ctx->mctx);
    }
}

/* Divide num and den by gcd(num, g) where g is known to hold every common
 * factor (g = den for a full cancellation). */
static void cancel_with(hl_alg *a, const fmpz_mpoly_t g, hl_alg_ctx *ctx)
{
    if (fmpz_mpoly_is_zero(a->num, ctx->mctx)) {
        fmpz_mpoly_one(a->den, ctx->mctx);
        return;
    }
    if (fmpz_mpoly_is_one(g, ctx->mctx))
        return;
    fmpz_mpoly_t h;
    fmpz_mpoly_init(h, ctx->mctx);
    if (fmpz_mpoly_gcd(h, a->num, g, ctx->mctx) && !fmpz_mpoly_is_one(h, ctx->mctx)) {
        fmpz_mpoly_divides(a->num, a->num, h, ctx->mctx);
        fmpz_mpoly_divides(a->den, a->den, h, ctx->mctx);
    }
    fmpz_mpoly_clear(h, ctx->mctx);
    fix_sign(a, ctx);
}

void alg_canonicalise(hl_alg *a, hl_alg_ctx *ctx)
{
    alg_reduce(a->num, ctx);
    alg_reduce(a->den, ctx);
    rationalise(a, ctx);
    fix_sign(a, ctx);
    fmpz_mpoly_t d;
    fmpz_mpoly_init(d, ctx->mctx);
    fmpz_mpoly_set(d, a->den, ctx->mctx);
    cancel_with(a, d, ctx);
    fmpz_mpoly_clear(d, ctx->mctx);
}

/* ---- arithmetic ------------------------------------------------------------ */

static void add_sub(hl_alg *r, const hl_alg *a, const hl_alg *b, int sub, hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (fmpz_mpoly_is_one(a->den, mc) && fmpz_mpoly_is_one(b->den, mc)) {
        if (sub)
            fmpz_mpoly_sub(r->num, a->num, b->num, mc);
        else
            fmpz_mpoly_add(r->num, a->num, b->num, mc);
        fmpz_mpoly_one(r->den, mc);
        return;
    }
    hl_alg t;
    hl_alg_init(&t, ctx);
    if (fmpz_mpoly_equal(a->den, b->den, mc)) {
        if (sub)
            fmpz_mpoly_sub(t.num, a->num, b->num, mc);
        else
            fmpz_mpoly_add(t.num, a->num, b->num, mc);
        fmpz_mpoly_set(t.den, a->den, mc);
        cancel_with(&t, t.den, ctx);
    } else {
        fmpz_mpoly_t g, ad, bd, u;
        fmpz_mpoly_init(g, mc);
        fmpz_mpoly_init(ad, mc);
        fmpz_mpoly_init(bd, mc);
        fmpz_mpoly_init(u, mc);
        if (fmpz_mpoly_is_one(a->den, mc) || fmpz_mpoly_is_one(b->den, mc))
            fmpz_mpoly_one(g, mc);
        else
            fmpz_mpoly_gcd(g, a->den, b->den, mc);
        fmpz_mpoly_divides(ad, a->den, g, mc); /* a->den / g */
        fmpz_mpoly_divides(bd, b->den, g, mc);
        fmpz_mpoly_mul(t.num, a->num, bd, mc);
        fmpz_mpoly_mul(u, b->num, ad, mc);
        if (sub)
            fmpz_mpoly_sub(t.num, t.num, u, mc);
        else
            fmpz_mpoly_add(t.num, t.num, u, mc);
        fmpz_mpoly_mul(t.den, a->den, bd, mc);
        int changed = alg_reduce(t.num, ctx);
        changed |= alg_reduce(t.den, ctx);
        if (changed)
            alg_canonicalise(&t, ctx);
        else
            cancel_with(&t, g, ctx);
        fmpz_mpoly_clear(g, mc);
        fmpz_mpoly_clear(ad, mc);
        fmpz_mpoly_clear(bd, mc);
        fmpz_mpoly_clear(u, mc);
    }
    hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
}

void hl_alg_add(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx)
{
    add_sub(r, a, b, 0, ctx);
}

void hl_alg_sub(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx)
{
    add_sub(r, a, b, 1, ctx);
}

void hl_alg_neg(hl_alg *r, const hl_alg *a, hl_alg_ctx *ctx)
{
    fmpz_mpoly_neg(r->num, a->num, ctx->mctx);
    fmpz_mpoly_set(r->den, a->den, ctx->mctx);
}

/* q = a / gcd(a, b), g receives the gcd; skipped when b is 1. */
static void strip_common(fmpz_mpoly_t qa, fmpz_mpoly_t qb, const fmpz_mpoly_t a,
                         const fmpz_mpoly_t b, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_t g;
    fmpz_mpoly_init(g, ctx->mctx);
    if (fmpz_mpoly_is_one(b, ctx->mctx) || !fmpz_mpoly_gcd(g, a, b, ctx->mctx)
        || fmpz_mpoly_is_one(g, ctx->mctx)) {
        fmpz_mpoly_set(qa, a, ctx->mctx);
        fmpz_mpoly_set(qb, b, ctx->mctx);
    } else {
        fmpz_mpoly_divides(qa, a, g, ctx->mctx);
        fmpz_mpoly_divides(qb, b, g, ctx->mctx);
    }
    fmpz_mpoly_clear(g, ctx->mctx);
}

void hl_alg_mul(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (fmpz_mpoly_is_one(a->den, mc) && fmpz_mpoly_is_one(b->den, mc)) {
        fmpz_mpoly_mul(r->num, a->num, b->num, mc);
        fmpz_mpoly_one(r->den, mc);
        alg_reduce(r->num, ctx); /* gcd with den 1 is trivial */
        return;
    }
    hl_alg t;
    fmpz_mpoly_t an, bn, ad, bd;
    hl_alg_init(&t, ctx);
    fmpz_mpoly_init(an, mc);
    fmpz_mpoly_init(bn, mc);
    fmpz_mpoly_init(ad, mc);
    fmpz_mpoly_init(bd, mc);
    strip_common(an, bd, a->num, b->den, ctx);
    strip_common(bn, ad, b->num, a->den, ctx);
    fmpz_mpoly_mul(t.num, an, bn, mc);
    fmpz_mpoly_mul(t.den, ad, bd, mc);
    int changed = alg_reduce(t.num, ctx);
    changed |= alg_reduce(t.den, ctx);
    if (changed)
        alg_canonicalise(&t, ctx);
    else if (fmpz_mpoly_is_zero(t.num, mc))
        fmpz_mpoly_one(t.den, mc);
    hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
    fmpz_mpoly_clear(an, mc);
    fmpz_mpoly_clear(bn, mc);
    fmpz_mpoly_clear(ad, mc);
    fmpz_mpoly_clear(bd, mc);
}

void hl_alg_scalar_mul_fmpq(hl_alg *r, const hl_alg *a, const fmpq_t c, hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (fmpq_is_zero(c) || fmpz_mpoly_is_zero(a->num, mc)) {
        hl_alg_zero(r, ctx);
        return;
    }
    fmpz_t g, h;
    fmpz_init(g);
    fmpz_init(h);
    fmpz_mpoly_scalar_mul_fmpz(r->num, a->num, fmpq_numref(c), mc);
    fmpz_mpoly_scalar_mul_fmpz(r->den, a->den, fmpq_denref(c), mc);
    /* only the integer contents can have gained a common factor */
    _fmpz_vec_content(g, r->num->coeffs, r->num->length);
    _fmpz_vec_content(h, r->den->coeffs, r->den->length);
    fmpz_gcd(g, g, h);
    if (!fmpz_is_one(g)) {
        fmpz_mpoly_scalar_divexact_fmpz(r->num, r->num, g, mc);
        fmpz_mpoly_scalar_divexact_fmpz(r->den, r->den, g, mc);
    }
    fix_sign(r, ctx);
    fmpz_clear(g);
    fmpz_clear(h);
}

/* r = 1/a for a nonzero a. */
static void inv(hl_alg *r, const hl_alg *a, hl_alg_ctx *ctx)
{
    hl_alg t;
    hl_alg_init(&t, ctx);
    fmpz_mpoly_set(t.num, a->den, ctx->mctx);
    fmpz_mpoly_set(t.den, a->num, ctx->mctx);
    fix_sign(&t, ctx);
    /* gcd is already 1; only the quadratic atoms of the old numerator need
     * to leave the denominator */
    rationalise(&t, ctx);
    fix_sign(&t, ctx);
    fmpz_mpoly_t d;
    fmpz_mpoly_init(d, ctx->mctx);
    fmpz_mpoly_set(d, t.den, ctx->mctx);
    cancel_with(&t, d, ctx);
    fmpz_mpoly_clear(d, ctx->mctx);
    hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
}

hl_status hl_alg_div(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx, hl_error *err)
{
    if (fmpz_mpoly_is_zero(b->num, ctx->mctx))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "division by zero");
    hl_alg t;
    hl_alg_init(&t, ctx);
    inv(&t, b, ctx);
    hl_alg_mul(r, a, &t, ctx);
    hl_alg_clear(&t, ctx);
    return HL_OK;
}

/* The longest coefficient an exact power may have, in bits: as long as
 * the lexer's largest literal (1e10000, 33220 bits) times three.  NOTE: a
 * power of 11 million bits (9.888...^9999.9, found by fuzzing) took
 * minutes, and none of its digits means anything in a Hamiltonian. */
#define ALG_POW_MAX_BITS 100000

static unsigned long coeff_bits(const fmpz_mpoly_t p)
{
    slong b = fmpz_mpoly_max_bits(p); /* < 0 when a coefficient is */
    return (unsigned long)(b < 0 ? -b : b);
}

int alg_check_pow_size(const hl_alg *a, unsigned long n, const hl_alg_ctx *ctx, hl_error *err)
{
    unsigned long bits = coeff_bits(a->num), dbits = coeff_bits(a->den);
    bits = bits > dbits ? bits : dbits;
    /* log2 |c| >= bits - 1: exact for powers of 2 (2^99999 is allowed) */
    if (bits <= 1 || n <= ALG_POW_MAX_BITS / (bits - 1))
        return HL_OK;
    double total = (double)n * (double)(bits - 1);
    return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                        "power too large to compute exactly: about %.3g bits (the limit is %d)",
                        total, ALG_POW_MAX_BITS);
}

hl_status hl_alg_pow_si(hl_alg *r, const hl_alg *a, long e, hl_alg_ctx *ctx, hl_error *err)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (e == 0) {
        hl_alg_one(r, ctx);
        return HL_OK;
    }
    if (fmpz_mpoly_is_zero(a->num, mc)) {
        if (e < 0)
            return hl_error_set(err, HL_EDOM, NULL, -1, 0, "division by zero");
        hl_alg_zero(r, ctx);
        return HL_OK;
    }
    hl_alg t;
    hl_alg_init(&t, ctx);
    if (e < 0)
        inv(&t, a, ctx);
    else
        hl_alg_set(&t, a, ctx);
    unsigned long n = e < 0 ? 0UL - (unsigned long)e : (unsigned long)e;
    int status = alg_check_pow_size(&t, n, ctx, err);
    if (status == HL_OK && n > 1) {
        fmpz_mpoly_pow_ui(t.num, t.num, n, mc);
        fmpz_mpoly_pow_ui(t.den, t.den, n, mc);
        int changed = alg_reduce(t.num, ctx);
        changed |= alg_reduce(t.den, ctx);
        if (changed)
            alg_canonicalise(&t, ctx);
    }
    if (status == HL_OK)
        hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
    return status;
}
