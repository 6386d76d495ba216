/* Element -> expression, written the way a person would: numerator terms in
 * the stored order (total degree descending, then variable order), each
 * with its rational coefficient when the denominator is a number; else
 * numerator over the factored denominator, with sqrt(u) in the numerator
 * and u^k in the denominator merged into u^(k - 1/2). */
#include <stdlib.h>

#include "alg/alg_internal.h"
#include <flint/fmpz_mpoly_factor.h>
#include "base/buf.h"

typedef struct printer {
    const hl_alg_ctx *ctx;
    hl_pool *pool;
    const hl_expr **atom; /* memo: expression of each atom */
    ulong *exp;
} printer;

static const hl_expr *frac_expr(printer *pr, const hl_alg *a);

static const hl_expr *atom_expr(printer *pr, int k)
{
    if (pr->atom[k] != NULL)
        return pr->atom[k];
    const alg_atom *at = &pr->ctx->atoms[k];
    const hl_expr *arg = at->kind == ATOM_PI ? NULL : frac_expr(pr, &at->arg), *e = NULL;
    static const hl_fun fun[] = {HL_SQRT, HL_SQRT, HL_SIN, HL_COS, HL_EXP,
                                 HL_LOG, HL_ATAN, HL_ASIN, HL_ACOS, HL_SQRT};
    if (at->kind == ATOM_PI)
        e = hl_pi(pr->pool);
    else if (at->kind == ATOM_ROOT)
        e = hl_pow(pr->pool, arg, hl_num_frac(pr->pool, 1, (ulong)at->q));
    else
        e = hl_call(pr->pool, fun[at->kind], arg);
    pr->atom[k] = e;
    return e;
}

/* v^e for a variable. */
static const hl_expr *var_pow(printer *pr, int v, ulong e)
{
    const hl_alg_ctx *ctx = pr->ctx;
    if (v < ctx->nbase) {
        const hl_expr *x = hl_sym(pr->pool, ctx->names[v]);
        return e == 1 ? x : hl_pow(pr->pool, x, hl_num_si(pr->pool, (long)e));
    }
    int k = v - ctx->nbase;
    const alg_atom *at = &ctx->atoms[k];
    if (at->kind == ATOM_ROOT && e > 1) { /* u^(e/q), not (u^(1/q))^e */
        const hl_expr *u = frac_expr(pr, &at->arg);
        return hl_pow(pr->pool, u, hl_num_frac(pr->pool, (long)e, (ulong)at->q));
    }
    const hl_expr *x = atom_expr(pr, k);
    return e == 1 ? x : hl_pow(pr->pool, x, hl_num_si(pr->pool, (long)e));
}

/* |c| times the monomial of term i of p (skipping variable skip), built
 * left to right as it is read: 3*x*y/2 is ((3*x)*y)/2. */
static const hl_expr *term_expr(printer *pr, const fmpq_t c, const fmpz_mpoly_t p, slong i,
                                int skip)
{
    const hl_alg_ctx *ctx = pr->ctx;
    hl_pool *pool = pr->pool;
    int nv = alg_nvars(ctx);
    /* own copy: printing an atom's argument reuses the printer */
    ulong *exp = hl_xmalloc((size_t)nv * sizeof *exp);
    fmpz_mpoly_get_term_exp_ui(exp, p, i, ctx->mctx);
    fmpq_t a, n;
    fmpq_init(a);
    fmpq_init(n);
    fmpq_abs(a, c);
    const hl_expr *m = NULL;
    int constant = 1;
    for (int v = 0; v < nv; v++)
        constant &= exp[v] == 0 || v == skip;
    if (!constant && !fmpz_is_one(fmpq_numref(a))) {
        fmpz_set(fmpq_numref(n), fmpq_numref(a));
        m = hl_num_fmpq(pool, n);
    }
    for (int v = 0; v < nv; v++) {
        if (exp[v] == 0 || v == skip)
            continue;
        const hl_expr *f = var_pow(pr, v, exp[v]);
        m = m == NULL ? f : hl_mul(pool, m, f);
    }
    if (m == NULL) {
        m = hl_num_fmpq(pool, a); /* a constant term: one literal */
    } else if (!fmpz_is_one(fmpq_denref(a))) {
        fmpz_set(fmpq_numref(n), fmpq_denref(a));
        m = hl_div(pool, m, hl_num_fmpq(pool, n));
    }
    fmpq_clear(a);
    fmpq_clear(n);
    free(exp);
    return m;
}

/* sum_i (coeff_i / c) * monomial_i with signs; skip: a variable divided out
 * of every term (or -1). */
static const hl_expr *sum_expr(printer *pr, const fmpz_mpoly_t p, const fmpz_t c, int skip)
{
    const hl_expr *s = NULL;
    fmpq_t q;
    fmpq_init(q);
    for (slong i = 0; i < p->length; i++) {
        fmpz_set(fmpq_numref(q), p->coeffs + i);
        fmpz_set(fmpq_denref(q), c);
        fmpq_canonicalise(q);
        const hl_expr *t = term_expr(pr, q, p, i, skip);
        int neg = fmpq_sgn(q) < 0;
        if (s == NULL && neg && t->kind == HL_NUM)
            s = hl_num_fmpq(pr->pool, q); /* -3/4 is a literal */
        else if (s == NULL)
            s = neg ? hl_neg(pr->pool, t) : t;
        else
            s = neg ? hl_sub(pr->pool, s, t) : hl_add(pr->pool, s, t);
    }
    fmpq_clear(q);
    return s != NULL ? s : hl_num_si(pr->pool, 0);
}

/* Is every term of p of degree exactly 1 in v? */
static int linear_in_every_term(const fmpz_mpoly_t p, int v, printer *pr)
{
    for (slong i = 0; i < p->length; i++) {
        fmpz_mpoly_get_term_exp_ui(pr->exp, p, i, pr->ctx->mctx);
        if (pr->exp[v] != 1)
            return 0;
    }
    return p->length > 0;
}

/* Order factors as a person lists them: lower degree first, then fewer
 * terms, then FLINT's comparison (so the output does not depend on the
 * order factorisation found them in). */
static int factor_before(const fmpz_mpoly_t a, const fmpz_mpoly_t b, const fmpz_mpoly_ctx_t mc)
{
    slong da = fmpz_mpoly_total_degree_si(a, mc), db = fmpz_mpoly_total_degree_si(b, mc);
    if (da != db)
        return da < db;
    if (a->length != b->length)
        return a->length < b->length;
    return fmpz_mpoly_cmp(a, b, mc) < 0;
}

static void sort_factors(fmpz_mpoly_factor_t f, const fmpz_mpoly_ctx_t mc)
{
    for (slong i = 1; i < f->num; i++)
        for (slong j = i; j > 0 && factor_before(f->poly + j, f->poly + j - 1, mc); j--) {
            fmpz_mpoly_swap(f->poly + j, f->poly + j - 1, mc);
            fmpz_swap(f->exp + j, f->exp + j - 1);
        }
}

static const hl_expr *frac_expr(printer *pr, const hl_alg *a)
{
    const hl_alg_ctx *ctx = pr->ctx;
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    hl_pool *pool = pr->pool;
    if (fmpz_mpoly_is_fmpz(a->den, mc)) {
        fmpz_t c;
        fmpz_init(c);
        fmpz_mpoly_get_fmpz(c, a->den, mc);
        const hl_expr *e = sum_expr(pr, a->num, c, -1);
        fmpz_clear(c);
        return e;
    }
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, mc);
    if (!fmpz_mpoly_factor(f, a->den, mc)) {
        fmpz_mpoly_factor_fit_length(f, 1, mc);
        fmpz_one(f->constant);
        fmpz_mpoly_set(f->poly + 0, a->den, mc);
        fmpz_one(f->exp + 0);
        f->num = 1;
    }
    /* unit-normal factors (lc > 0); the sign goes to the constant */
    for (slong i = 0; i < f->num; i++)
        if (fmpz_sgn(f->poly[i].coeffs + 0) < 0) {
            fmpz_mpoly_neg(f->poly + i, f->poly + i, mc);
            if (fmpz_is_odd(f->exp + i))
                fmpz_neg(f->constant, f->constant);
        }
    sort_factors(f, mc);
    /* a sqrt(u) dividing every numerator term, u a factor of den: the
     * numerator skips it and factor `half` loses 1/2 from its exponent */
    int skip = -1;
    slong half = -1;
    for (int k = 0; k < ctx->natoms && skip < 0; k++) {
        const alg_atom *at = &ctx->atoms[k];
        if (at->kind != ATOM_SQRT || !linear_in_every_term(a->num, at->var, pr))
            continue;
        for (slong i = 0; i < f->num; i++)
            if (fmpz_mpoly_equal(f->poly + i, at->arg.num, mc)) {
                skip = at->var;
                half = i;
                break;
            }
    }
    int neg = fmpz_sgn(a->num->coeffs + 0) < 0; /* shown as a unary minus */
    fmpz_mpoly_t n;
    fmpz_mpoly_init(n, mc);
    if (neg)
        fmpz_mpoly_neg(n, a->num, mc);
    else
        fmpz_mpoly_set(n, a->num, mc);
    fmpz_t one;
    fmpz_init_set_ui(one, 1);
    const hl_expr *num = sum_expr(pr, n, one, skip);
    if (neg && num->kind == HL_NUM) { /* -1/u: the literal -1 */
        fmpq_t c;
        fmpq_init(c);
        fmpq_neg(c, num->num);
        num = hl_num_fmpq(pool, c);
        fmpq_clear(c);
    } else if (neg) { /* -x/u, -(x + y)/u: the minus belongs to the numerator */
        num = hl_neg(pool, num);
    }
    const hl_expr *den = NULL;
    fmpz_abs(f->constant, f->constant);
    if (!fmpz_is_one(f->constant)) {
        fmpq_t c;
        fmpq_init(c);
        fmpz_set(fmpq_numref(c), f->constant);
        den = hl_num_fmpq(pool, c);
        fmpq_clear(c);
    }
    for (slong i = 0; i < f->num; i++) {
        const hl_expr *b = sum_expr(pr, f->poly + i, one, -1), *p;
        long e = fmpz_get_si(f->exp + i);
        if (i == half)
            p = e == 1 ? hl_call(pool, HL_SQRT, b) : hl_pow(pool, b, hl_num_frac(pool, 2 * e - 1, 2));
        else
            p = e == 1 ? b : hl_pow(pool, b, hl_num_si(pool, e));
        den = den == NULL ? p : hl_mul(pool, den, p);
    }
    const hl_expr *e = hl_div(pool, num, den);
    fmpz_clear(one);
    fmpz_mpoly_clear(n, mc);
    fmpz_mpoly_factor_clear(f, mc);
    return e;
}

const hl_expr *hl_alg_to_expr(const hl_alg *a, const hl_alg_ctx *ctx, hl_pool *pool)
{
    printer pr;
    pr.ctx = ctx;
    pr.pool = pool;
    pr.atom = hl_xcalloc((size_t)ctx->natoms + 1, sizeof *pr.atom);
    pr.exp = hl_xmalloc((size_t)alg_nvars(ctx) * sizeof *pr.exp);
    const hl_expr *e = frac_expr(&pr, a);
    free(pr.atom);
    free(pr.exp);
    return e;
}
