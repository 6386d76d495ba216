/* Evaluation with Arb, the zero test, and the structure functions. */
#include <stdlib.h>

#include "alg/alg_internal.h"
#include "base/buf.h"

#define ZERO_PREC 256
#define ZERO_POINTS 3
#define ZERO_TRIES 20
#define ZERO_RAD_EXP (-200)

/* ---- evaluation -------------------------------------------------------------- */

typedef struct eval_state {
    arb_srcptr base;
    arb_ptr atom;          /* values of the atoms, valid where known[k] */
    unsigned char *known;
    slong prec;
    hl_alg_ctx *ctx;
} eval_state;

static int eval_poly(arb_t r, const fmpz_mpoly_t p, eval_state *st, hl_error *err);

static int eval_frac(arb_t r, const hl_alg *a, eval_state *st, hl_error *err)
{
    arb_t d;
    int status = eval_poly(r, a->num, st, err);
    if (status != HL_OK || fmpz_mpoly_is_one(a->den, st->ctx->mctx))
        return status;
    arb_init(d);
    status = eval_poly(d, a->den, st, err);
    if (status == HL_OK && arb_contains_zero(d))
        status = hl_error_set(err, HL_EDOM, NULL, -1, 0, "division by zero");
    if (status == HL_OK)
        arb_div(r, r, d, st->prec);
    arb_clear(d);
    return status;
}

static const char *atom_fun_name(alg_atom_kind k)
{
    static const char *const names[] = {"sqrt", "root", "sin", "cos", "exp",
                                        "log", "atan", "asin", "acos", "pi", "atan2"};
    return names[k];
}

static int eval_atom(int k, eval_state *st, hl_error *err)
{
    if (st->known[k])
        return HL_OK;
    const alg_atom *at = &st->ctx->atoms[k];
    arb_ptr y = st->atom + k;
    slong prec = st->prec;
    arb_t x, x2;
    arb_init(x);
    arb_init(x2);
    int status = at->kind == ATOM_PI ? HL_OK : eval_frac(x, &at->arg, st, err);
    if (status == HL_OK && at->kind == ATOM_ATAN2)
        status = eval_frac(x2, &at->arg2, st, err);
    if (status != HL_OK) {
        arb_clear(x);
        arb_clear(x2);
        return status;
    }
    switch (at->kind) {
    case ATOM_SQRT: arb_sqrt(y, x, prec); break;
    case ATOM_ROOT:
        if (arb_is_negative(x) && (at->q & 1)) {
            arb_neg(x, x);
            arb_root_ui(y, x, (ulong)at->q, prec);
            arb_neg(y, y);
        } else {
            arb_root_ui(y, x, (ulong)at->q, prec);
        }
        break;
    case ATOM_SIN: arb_sin(y, x, prec); break;
    case ATOM_COS: arb_cos(y, x, prec); break;
    case ATOM_EXP: arb_exp(y, x, prec); break;
    case ATOM_LOG: arb_log(y, x, prec); break;
    case ATOM_ATAN: arb_atan(y, x, prec); break;
    case ATOM_ASIN: arb_asin(y, x, prec); break;
    case ATOM_ACOS: arb_acos(y, x, prec); break;
    case ATOM_PI: arb_const_pi(y, prec); break;
    case ATOM_ATAN2: arb_atan2(y, x, x2, prec); break; /* arb_atan2(r, y, x) */
    }
    arb_clear(x);
    arb_clear(x2);
    if (!arb_is_finite(y))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "%s evaluated outside its domain",
                            atom_fun_name(at->kind));
    st->known[k] = 1;
    return HL_OK;
}

static int eval_poly(arb_t r, const fmpz_mpoly_t p, eval_state *st, hl_error *err)
{
    hl_alg_ctx *ctx = st->ctx;
    int nv = alg_nvars(ctx), status = HL_OK;
    slong *degs = hl_xmalloc((size_t)nv * sizeof *degs);
    fmpz_mpoly_degrees_si(degs, p, ctx->mctx);
    for (int k = 0; k < ctx->natoms && status == HL_OK; k++)
        if (degs[ctx->nbase + k] > 0)
            status = eval_atom(k, st, err);
    free(degs);
    if (status != HL_OK)
        return status;
    ulong *exp = hl_xmalloc((size_t)nv * sizeof *exp);
    arb_t t, u;
    arb_init(t);
    arb_init(u);
    arb_zero(r);
    for (slong i = 0; i < p->length; i++) {
        fmpz_mpoly_get_term_exp_ui(exp, p, i, ctx->mctx);
        arb_set_fmpz(t, p->coeffs + i);
        for (int v = 0; v < nv; v++) {
            if (exp[v] == 0)
                continue;
            arb_srcptr x = v < ctx->nbase ? st->base + v : st->atom + (v - ctx->nbase);
            arb_pow_ui(u, x, exp[v], st->prec);
            arb_mul(t, t, u, st->prec);
        }
        arb_add(r, r, t, st->prec);
    }
    arb_clear(t);
    arb_clear(u);
    free(exp);
    return HL_OK;
}

static void state_init(eval_state *st, arb_srcptr vals, slong prec, hl_alg_ctx *ctx)
{
    st->base = vals;
    st->atom = _arb_vec_init(ctx->natoms + 1);
    st->known = hl_xcalloc((size_t)ctx->natoms + 1, 1);
    st->prec = prec;
    st->ctx = ctx;
}

static void state_clear(eval_state *st)
{
    _arb_vec_clear(st->atom, st->ctx->natoms + 1);
    free(st->known);
}

hl_status hl_alg_eval_arb(arb_t r, const hl_alg *a, arb_srcptr vals, slong prec, hl_alg_ctx *ctx,
                          hl_error *err)
{
    eval_state st;
    state_init(&st, vals, prec, ctx);
    int status = eval_frac(r, a, &st, err);
    state_clear(&st);
    return status;
}

/* ---- zero test ------------------------------------------------------------------ */

/* Could the atoms of p satisfy a relation the canonical form does not know? */
static int needs_numeric(const fmpz_mpoly_t p, const hl_alg_ctx *ctx)
{
    fmpz_mpoly_degrees_si(ctx->degs, p, ctx->mctx);
    int family = -1;
    for (int k = 0; k < ctx->natoms; k++) {
        const alg_atom *at = &ctx->atoms[k];
        if (ctx->degs[at->var] <= 0)
            continue;
        if (at->kind == ATOM_ROOT || at->kind == ATOM_PI || at->nested)
            return 1;
        if (family >= 0 && at->family != family)
            return 1;
        family = at->family;
    }
    return 0;
}

/* Evaluate p at random points in (0.1, 0.9): zero at every point where it
 * can be evaluated, to 2^-200, and at ZERO_POINTS points at least. */
static int numeric_zero(const fmpz_mpoly_t p, hl_alg_ctx *ctx)
{
    flint_rand_t state;
    flint_randinit(state); /* fixed seed: the answer must not vary by run */
    arb_ptr vals = _arb_vec_init(ctx->nbase + 1);
    arb_t y;
    arb_init(y);
    int good = 0, zero = 1;
    for (int tries = 0; tries < ZERO_TRIES && good < ZERO_POINTS && zero; tries++) {
        for (int v = 0; v < ctx->nbase; v++) {
            arb_set_ui(vals + v, 100000 + n_randint(state, 800001));
            arb_div_ui(vals + v, vals + v, 1000000, ZERO_PREC);
        }
        eval_state st;
        state_init(&st, vals, ZERO_PREC, ctx);
        if (eval_poly(y, p, &st, NULL) == HL_OK) {
            good++;
            zero = arb_contains_zero(y) && mag_cmp_2exp_si(arb_radref(y), ZERO_RAD_EXP) < 0;
        }
        state_clear(&st);
    }
    arb_clear(y);
    _arb_vec_clear(vals, ctx->nbase + 1);
    flint_randclear(state);
    return zero && good >= ZERO_POINTS;
}

int hl_alg_is_zero(const hl_alg *a, hl_alg_ctx *ctx)
{
    if (fmpz_mpoly_is_zero(a->num, ctx->mctx))
        return 1;
    if (!needs_numeric(a->num, ctx))
        return 0;
    if (!numeric_zero(a->num, ctx))
        return 0;
    ctx->numeric_used = 1;
    return 1;
}

int hl_alg_equal(const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx)
{
    if (fmpz_mpoly_equal(a->num, b->num, ctx->mctx) && fmpz_mpoly_equal(a->den, b->den, ctx->mctx))
        return 1;
    hl_alg t;
    hl_alg_init(&t, ctx);
    hl_alg_sub(&t, a, b, ctx);
    int z = hl_alg_is_zero(&t, ctx);
    hl_alg_clear(&t, ctx);
    return z;
}

/* ---- structure ------------------------------------------------------------------ */

int hl_alg_is_fmpq(const hl_alg *a, fmpq_t c, const hl_alg_ctx *ctx)
{
    if (!fmpz_mpoly_is_fmpz(a->num, ctx->mctx) || !fmpz_mpoly_is_fmpz(a->den, ctx->mctx))
        return 0;
    if (c != NULL) {
        fmpz_mpoly_get_fmpz(fmpq_numref(c), a->num, ctx->mctx);
        fmpz_mpoly_get_fmpz(fmpq_denref(c), a->den, ctx->mctx);
        fmpq_canonicalise(c);
    }
    return 1;
}

int hl_alg_depends_on(const hl_alg *a, int var, const hl_alg_ctx *ctx)
{
    if (var < 0 || var >= ctx->nbase)
        return 0;
    unsigned char *dep = hl_xcalloc((size_t)ctx->nbase + 1, 1);
    alg_depends_mask(dep, a, ctx);
    int d = dep[var];
    free(dep);
    return d;
}

/* Is a polynomial in base symbol var: den and atoms free of it? */
static int poly_in(const hl_alg *a, int var, const hl_alg_ctx *ctx)
{
    if (var < 0 || var >= ctx->nbase || alg_poly_has_var(a->den, var, ctx))
        return 0;
    fmpz_mpoly_degrees_si(ctx->degs, a->num, ctx->mctx);
    for (int k = 0; k < ctx->natoms; k++)
        if (ctx->degs[ctx->nbase + k] > 0 && ctx->atoms[k].dep[var])
            return 0;
    fmpz_mpoly_degrees_si(ctx->degs, a->den, ctx->mctx);
    for (int k = 0; k < ctx->natoms; k++)
        if (ctx->degs[ctx->nbase + k] > 0 && ctx->atoms[k].dep[var])
            return 0;
    return 1;
}

hl_status hl_alg_coeff(hl_alg *r, const hl_alg *a, int var, long k, hl_alg_ctx *ctx, hl_error *err)
{
    if (!poly_in(a, var, ctx))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "not a polynomial in '%s'",
                            (var >= 0 && var < ctx->nbase) ? ctx->names[var] : "?");
    int nv = alg_nvars(ctx);
    ulong *exp = hl_xmalloc((size_t)nv * sizeof *exp);
    hl_alg t;
    hl_alg_init(&t, ctx);
    for (slong i = 0; i < a->num->length; i++) {
        fmpz_mpoly_get_term_exp_ui(exp, a->num, i, ctx->mctx);
        if (k < 0 || exp[var] != (ulong)k)
            continue;
        exp[var] = 0;
        fmpz_mpoly_push_term_fmpz_ui(t.num, a->num->coeffs + i, exp, ctx->mctx);
    }
    free(exp);
    fmpz_mpoly_sort_terms(t.num, ctx->mctx);
    fmpz_mpoly_set(t.den, a->den, ctx->mctx);
    alg_canonicalise(&t, ctx);
    hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
    return HL_OK;
}

long hl_alg_degree(const hl_alg *a, int var, const hl_alg_ctx *ctx)
{
    if (var < 0 || var >= ctx->nbase || fmpz_mpoly_is_zero(a->num, ctx->mctx))
        return -1;
    return fmpz_mpoly_degree_si(a->num, var, ctx->mctx);
}

long hl_alg_length(const hl_alg *a, const hl_alg_ctx *ctx)
{
    return (long)(a->num->length + a->den->length);
}

int hl_alg_is_canonical(const hl_alg *a, const hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (!fmpz_mpoly_is_canonical(a->num, mc) || !fmpz_mpoly_is_canonical(a->den, mc))
        return 0;
    if (fmpz_mpoly_is_zero(a->den, mc) || fmpz_sgn(a->den->coeffs + 0) <= 0)
        return 0;
    if (fmpz_mpoly_is_zero(a->num, mc))
        return fmpz_mpoly_is_one(a->den, mc);
    int nv = alg_nvars(ctx), ok = 1;
    slong *dn = hl_xmalloc((size_t)nv * sizeof *dn), *dd = hl_xmalloc((size_t)nv * sizeof *dd);
    fmpz_mpoly_degrees_si(dn, a->num, mc);
    fmpz_mpoly_degrees_si(dd, a->den, mc);
    for (int v = ctx->nbase + ctx->natoms; v < nv; v++)
        ok &= dn[v] <= 0 && dd[v] <= 0; /* no unmade atom */
    for (int k = 0; k < ctx->natoms; k++) {
        const alg_atom *at = &ctx->atoms[k];
        if (at->rel_deg == 0)
            continue;
        ok &= dn[at->var] < at->rel_deg && dd[at->var] < at->rel_deg;
        if (at->rel_deg == 2)
            ok &= dd[at->var] <= 0;
    }
    free(dn);
    free(dd);
    if (ok) {
        fmpz_mpoly_t g;
        fmpz_mpoly_init(g, mc);
        ok = fmpz_mpoly_gcd(g, a->num, a->den, mc) && fmpz_mpoly_is_one(g, mc);
        fmpz_mpoly_clear(g, mc);
    }
    return ok;
}
