/* Antiderivatives in one base symbol x of the elements whose numerator is a
 * polynomial in x, sin(x) and cos(x) (any other factor free of x) over a
 * denominator free of x: the Hamiltonians of error fields of trigonometric
 * systems (the pendulum) are built from these.
 *
 * With s = sin x, c = cos x (the normal form keeps s to degree <= 1):
 *   int x^m       = x^(m+1)/(m+1)
 *   int s c^b     = -c^(b+1)/(b+1)
 *   int c^b       = s c^(b-1)/b + (b-1)/b int c^(b-2),   int c = s,  int 1 = x
 *   int x^m s^a c^b = x^m G - m int x^(m-1) G,            G = int s^a c^b
 * (by parts; G has degree <= 1 in x, so m decreases).  Anything else is "not
 * found", and every result is checked by differentiating it back. */
#include "alg/alg_internal.h"

typedef struct trig {
    int x;    /* the variable */
    int s, c; /* mpoly variables of sin(x), cos(x), or -1 */
} trig;

/* Is atom variable v sin(x) or cos(x) exactly? */
static int is_trig_of(const alg_atom *a, int x, hl_alg_ctx *ctx)
{
    if (a->kind != ATOM_SIN && a->kind != ATOM_COS)
        return 0;
    hl_alg g;
    hl_alg_init(&g, ctx);
    hl_alg_gen(&g, x, ctx);
    int same = hl_alg_equal(&a->arg, &g, ctx);
    hl_alg_clear(&g, ctx);
    return same;
}

/* The trig atoms of x, and whether anything else in p depends on x. */
static int scan(trig *t, const fmpz_mpoly_t p, int x, hl_alg_ctx *ctx)
{
    t->x = x;
    t->s = t->c = -1;
    for (int k = 0; k < ctx->natoms; k++) {
        const alg_atom *a = &ctx->atoms[k];
        if (!a->dep[x])
            continue;
        if (is_trig_of(a, x, ctx)) {
            if (a->kind == ATOM_SIN)
                t->s = a->var;
            else
                t->c = a->var;
        } else if (alg_poly_has_var(p, a->var, ctx))
            return 0; /* exp(x), sqrt(x), sin(2x), ...: not handled */
    }
    return 1;
}

static void var_pow(hl_alg *r, int v, ulong e, hl_alg_ctx *ctx)
{
    hl_alg g;
    hl_alg_init(&g, ctx);
    alg_set_var(&g, v, ctx);
    hl_alg_one(r, ctx);
    for (ulong i = 0; i < e; i++)
        hl_alg_mul(r, r, &g, ctx);
    hl_alg_clear(&g, ctx);
}

static void scale(hl_alg *r, long num, long den, hl_alg_ctx *ctx)
{
    fmpq_t q;
    fmpq_init(q);
    fmpq_set_si(q, num, (ulong)den);
    hl_alg_scalar_mul_fmpq(r, r, q, ctx);
    fmpq_clear(q);
}

/* G = int s^a c^b dx (a <= 1). */
static void trig_integral(hl_alg *G, const trig *t, ulong a, ulong b, hl_alg_ctx *ctx)
{
    hl_alg u;
    hl_alg_init(&u, ctx);
    if (a == 1) { /* -c^(b+1)/(b+1) */
        var_pow(G, t->c, b + 1, ctx);
        scale(G, -1, (long)b + 1, ctx);
    } else if (b == 0) {
        hl_alg_gen(G, t->x, ctx);
    } else if (b == 1) {
        alg_set_var(G, t->s, ctx);
    } else { /* s c^(b-1)/b + (b-1)/b int c^(b-2) */
        trig_integral(&u, t, 0, b - 2, ctx);
        scale(&u, (long)b - 1, (long)b, ctx);
        var_pow(G, t->c, b - 1, ctx);
        hl_alg s;
        hl_alg_init(&s, ctx);
        alg_set_var(&s, t->s, ctx);
        hl_alg_mul(G, G, &s, ctx);
        scale(G, 1, (long)b, ctx);
        hl_alg_add(G, G, &u, ctx);
        hl_alg_clear(&s, ctx);
    }
    hl_alg_clear(&u, ctx);
}

static void poly_integral(hl_alg *r, const fmpz_mpoly_t p, const trig *t, hl_alg_ctx *ctx);

/* int x^m s^a c^b dx */
static void monomial_integral(hl_alg *r, const trig *t, ulong m, ulong a, ulong b,
                              hl_alg_ctx *ctx)
{
    if (a == 0 && b == 0) {
        var_pow(r, t->x, m + 1, ctx);
        scale(r, 1, (long)m + 1, ctx);
        return;
    }
    trig_integral(r, t, a, b, ctx);
    if (m == 0)
        return;
    /* x^m G - m int x^(m-1) G */
    hl_alg G, xm, rest;
    hl_alg_init(&G, ctx);
    hl_alg_init(&xm, ctx);
    hl_alg_init(&rest, ctx);
    hl_alg_set(&G, r, ctx);
    var_pow(&xm, t->x, m - 1, ctx);
    hl_alg_mul(&rest, &xm, &G, ctx); /* x^(m-1) G: a polynomial over an integer */
    hl_alg I;
    hl_alg_init(&I, ctx);
    poly_integral(&I, rest.num, t, ctx);
    hl_alg den;
    hl_alg_init(&den, ctx);
    fmpz_mpoly_set(den.num, rest.den, ctx->mctx);
    hl_error err;
    hl_alg_div(&I, &I, &den, ctx, &err); /* den: a nonzero integer, cannot fail */
    scale(&I, -(long)m, 1, ctx);
    hl_alg_gen(&xm, t->x, ctx);
    hl_alg_mul(&xm, &xm, &rest, ctx); /* x^m G */
    hl_alg_add(r, &xm, &I, ctx);
    hl_alg_clear(&G, ctx);
    hl_alg_clear(&xm, ctx);
    hl_alg_clear(&rest, ctx);
    hl_alg_clear(&I, ctx);
    hl_alg_clear(&den, ctx);
}

/* int p dx, term by term: each term's factors free of x stay outside. */
static void poly_integral(hl_alg *r, const fmpz_mpoly_t p, const trig *t, hl_alg_ctx *ctx)
{
    slong nv = fmpz_mpoly_ctx_nvars(ctx->mctx);
    ulong *exp = flint_malloc((size_t)nv * sizeof *exp);
    fmpz_t coef;
    fmpz_init(coef);
    hl_alg term, I;
    hl_alg_init(&term, ctx);
    hl_alg_init(&I, ctx);
    hl_alg_zero(r, ctx);
    for (slong i = 0; i < fmpz_mpoly_length(p, ctx->mctx); i++) {
        fmpz_mpoly_get_term_exp_ui(exp, p, i, ctx->mctx);
        fmpz_mpoly_get_term_coeff_fmpz(coef, p, i, ctx->mctx);
        ulong m = exp[t->x], a = t->s >= 0 ? exp[t->s] : 0, b = t->c >= 0 ? exp[t->c] : 0;
        exp[t->x] = 0;
        if (t->s >= 0)
            exp[t->s] = 0;
        if (t->c >= 0)
            exp[t->c] = 0;
        fmpz_mpoly_t mono;
        fmpz_mpoly_init(mono, ctx->mctx);
        fmpz_mpoly_push_term_fmpz_ui(mono, coef, exp, ctx->mctx);
        alg_set_poly(&term, mono, ctx);
        fmpz_mpoly_clear(mono, ctx->mctx);
        monomial_integral(&I, t, m, a, b, ctx);
        hl_alg_mul(&I, &I, &term, ctx);
        hl_alg_add(r, r, &I, ctx);
    }
    hl_alg_clear(&term, ctx);
    hl_alg_clear(&I, ctx);
    fmpz_clear(coef);
    flint_free(exp);
}

hl_status hl_alg_antiderivative(hl_alg *r, int *found, const hl_alg *f, int x, hl_alg_ctx *ctx,
                                hl_error *err)
{
    *found = 0;
    if (x < 0 || x >= ctx->nbase)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "not a base symbol: %d", x);
    trig t;
    if (!scan(&t, f->num, x, ctx) || alg_poly_has_var(f->den, x, ctx) ||
        (t.s >= 0 && alg_poly_has_var(f->den, t.s, ctx)) ||
        (t.c >= 0 && alg_poly_has_var(f->den, t.c, ctx)))
        return HL_OK;
    for (int k = 0; k < ctx->natoms; k++) /* other atoms of x in the denominator */
        if (ctx->atoms[k].dep[x] && alg_poly_has_var(f->den, ctx->atoms[k].var, ctx))
            return HL_OK;
    hl_alg I, den, d;
    hl_alg_init(&I, ctx);
    hl_alg_init(&den, ctx);
    hl_alg_init(&d, ctx);
    poly_integral(&I, f->num, &t, ctx);
    fmpz_mpoly_set(den.num, f->den, ctx->mctx);
    int st = hl_alg_div(&I, &I, &den, ctx, err);
    /* the check that makes every rule above safe to get wrong */
    if (st == HL_OK)
        st = hl_alg_diff(&d, &I, x, ctx, err);
    if (st == HL_OK && hl_alg_equal(&d, f, ctx)) {
        hl_alg_swap(r, &I, ctx);
        *found = 1;
    }
    hl_alg_clear(&I, ctx);
    hl_alg_clear(&den, ctx);
    hl_alg_clear(&d, ctx);
    return st;
}
