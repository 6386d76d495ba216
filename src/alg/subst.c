/* Simultaneous substitution of base symbols.  Every variable gets an image:
 * a base symbol its value (or itself), an atom the same function of its
 * substituted argument (re-made, so it may become a new atom or a known
 * value).  Then num and den are composed with the images: with unit
 * denominators by FLINT's composition, else term by term over the common
 * denominator prod d_i^(deg_i). */
#include <math.h>
#include <stdlib.h>

#include "alg/alg_internal.h"
#include "base/buf.h"

static int remake_atom(hl_alg *r, const alg_atom *at, const hl_alg *arg, const hl_alg *arg2,
                       hl_alg_ctx *ctx, hl_error *err)
{
    fmpq_t e;
    int status;
    switch (at->kind) {
    case ATOM_SQRT: return hl_alg_apply(r, HL_SQRT, arg, ctx, err);
    case ATOM_ROOT:
        fmpq_init(e);
        fmpq_set_si(e, 1, (ulong)at->q);
        status = hl_alg_pow_fmpq(r, arg, e, ctx, err);
        fmpq_clear(e);
        return status;
    case ATOM_SIN: return hl_alg_apply(r, HL_SIN, arg, ctx, err);
    case ATOM_COS: return hl_alg_apply(r, HL_COS, arg, ctx, err);
    case ATOM_EXP: return hl_alg_apply(r, HL_EXP, arg, ctx, err);
    case ATOM_LOG: return hl_alg_apply(r, HL_LOG, arg, ctx, err);
    case ATOM_ATAN: return hl_alg_apply(r, HL_ATAN, arg, ctx, err);
    case ATOM_ASIN: return hl_alg_apply(r, HL_ASIN, arg, ctx, err);
    case ATOM_ACOS: return hl_alg_apply(r, HL_ACOS, arg, ctx, err);
    case ATOM_PI: return hl_alg_pi(r, ctx, err);
    case ATOM_ATAN2: return hl_alg_apply2(r, HL_ATAN2, arg, arg2, ctx, err);
    }
    return HL_OK;
}

/* A size budget for one substitution (hl_alg_subst_bounded): a term count
 * no polynomial may pass, and the work left, in term-pair products, which
 * is asked for before each product (its cost, and the most terms it may
 * give, is the product of the lengths), so a swell stops before it costs. */
typedef struct size_budget {
    long terms;    /* 0: no budget */
    double work;   /* term pairs left */
    long reached;  /* the largest size seen (or a product's bound, at the stop) */
} size_budget;

#define BUDGET_WORK_PER_TERM 1000.0 /* work allowed: this many pairs per term */

static int budget_size(size_budget *b, slong length)
{
    if (length > b->reached)
        b->reached = length;
    return b->terms == 0 || length <= b->terms;
}

/* May a product of la and lb terms (la^e for a power) be formed? */
static int budget_product(size_budget *b, double bound)
{
    if (b->terms == 0)
        return 1;
    b->work -= bound;
    if (b->work >= 0)
        return 1;
    if (bound > (double)b->reached)
        b->reached = bound > 1e18 ? (long)1e18 : (long)bound;
    return 0;
}

/* u = base^e and t *= u, within the budget */
static int mul_power(fmpz_mpoly_t t, fmpz_mpoly_t u, const fmpz_mpoly_t base, ulong e,
                     size_budget *b, const fmpz_mpoly_ctx_struct *mc)
{
    double lu = pow((double)base->length, (double)e);
    if (!budget_product(b, lu) || !budget_product(b, lu * (double)t->length))
        return 0;
    fmpz_mpoly_pow_ui(u, base, e, mc);
    fmpz_mpoly_mul(t, t, u, mc);
    return budget_size(b, u->length) && budget_size(b, t->length);
}

/* P(images) * prod_i den_i^(bound_i) as a polynomial (term by term);
 * 0 when it stopped over the budget. */
static int compose_terms(fmpz_mpoly_t out, const fmpz_mpoly_t p, const hl_alg *img,
                         const slong *bound, size_budget *b, hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    int nv = alg_nvars(ctx);
    ulong *exp = hl_xmalloc((size_t)nv * sizeof *exp);
    fmpz_mpoly_t t, u;
    fmpz_mpoly_init(t, mc);
    fmpz_mpoly_init(u, mc);
    fmpz_mpoly_zero(out, mc);
    int within = 1;
    for (slong i = 0; i < p->length && within; i++) {
        fmpz_mpoly_get_term_exp_ui(exp, p, i, ctx->mctx);
        fmpz_mpoly_set_fmpz(t, p->coeffs + i, mc);
        for (int v = 0; v < nv && within; v++) {
            if (exp[v] > 0)
                within = mul_power(t, u, img[v].num, exp[v], b, mc);
            if (within && bound[v] > 0 && (ulong)bound[v] > exp[v] &&
                !fmpz_mpoly_is_one(img[v].den, mc))
                within = mul_power(t, u, img[v].den, (ulong)bound[v] - exp[v], b, mc);
        }
        if (within) {
            fmpz_mpoly_add(out, out, t, mc);
            within = budget_size(b, out->length);
        }
    }
    fmpz_mpoly_clear(t, mc);
    fmpz_mpoly_clear(u, mc);
    free(exp);
    return within;
}

typedef struct subst_state {
    int n;
    const int *vars;
    hl_alg *img;          /* image of every variable, valid where known */
    unsigned char *known;
    unsigned char *moved; /* the image differs from the variable */
    int natoms0;          /* atoms made while substituting need no image */
    size_budget budget;
} subst_state;

static int subst_rec(hl_alg *r, const hl_alg *a, subst_state *st, hl_alg_ctx *ctx,
                     hl_error *err);

static int budget_error(const subst_state *st, hl_error *err)
{
    return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                        "the substitution exceeds its budget of %ld terms (%ld reached)",
                        st->budget.terms, st->budget.reached);
}

/* The image of atom k, made on demand: atoms that do not occur are never
 * touched, and an argument only involves older atoms, so this ends. */
static int atom_image(int k, subst_state *st, hl_alg_ctx *ctx, hl_error *err)
{
    const alg_atom *at = &ctx->atoms[k];
    if (st->known[at->var])
        return HL_OK;
    int dep = 0, status = HL_OK;
    for (int i = 0; i < st->n; i++)
        dep |= at->dep[st->vars[i]];
    if (dep && at->kind != ATOM_PI) {
        hl_alg arg, arg2;
        hl_alg_init(&arg, ctx);
        hl_alg_init(&arg2, ctx);
        status = subst_rec(&arg, &at->arg, st, ctx, err);
        if (status == HL_OK && at->kind == ATOM_ATAN2)
            status = subst_rec(&arg2, &at->arg2, st, ctx, err);
        if (status == HL_OK)
            status = remake_atom(&st->img[at->var], at, &arg, &arg2, ctx, err);
        hl_alg_clear(&arg, ctx);
        hl_alg_clear(&arg2, ctx);
        st->moved[at->var] = 1;
    }
    st->known[at->var] = 1;
    return status;
}

static int subst_rec(hl_alg *r, const hl_alg *a, subst_state *st, hl_alg_ctx *ctx,
                     hl_error *err)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    int nv = alg_nvars(ctx), status = HL_OK;
    slong *dn = hl_xmalloc((size_t)nv * sizeof *dn), *dd = hl_xmalloc((size_t)nv * sizeof *dd);
    fmpz_mpoly_degrees_si(dn, a->num, mc);
    fmpz_mpoly_degrees_si(dd, a->den, mc);
    for (int k = 0; k < st->natoms0 && status == HL_OK; k++)
        if (dn[ctx->atoms[k].var] > 0 || dd[ctx->atoms[k].var] > 0)
            status = atom_image(k, st, ctx, err);
    int all_poly = 1, any = 0;
    for (int v = 0; v < nv && status == HL_OK; v++) {
        dn[v] = dn[v] > dd[v] ? dn[v] : dd[v]; /* the bound on both */
        if (!st->moved[v] || dn[v] <= 0)
            continue;
        any = 1;
        all_poly &= fmpz_mpoly_is_one(st->img[v].den, mc);
    }
    hl_alg t;
    hl_alg_init(&t, ctx);
    if (status != HL_OK || !any) {
        hl_alg_set(&t, a, ctx);
    } else {
        /* images of every variable: unmoved ones stand for themselves */
        hl_alg *self = hl_alg_vec_new(nv, ctx);
        for (int v = 0; v < nv; v++) {
            if (st->moved[v])
                hl_alg_set(&self[v], &st->img[v], ctx);
            else
                alg_set_var(&self[v], v, ctx);
        }
        if (all_poly && st->budget.terms == 0) {
            fmpz_mpoly_struct **C = hl_xmalloc((size_t)nv * sizeof *C);
            for (int v = 0; v < nv; v++)
                C[v] = self[v].num;
            fmpz_mpoly_compose_fmpz_mpoly(t.num, a->num, C, mc, mc);
            fmpz_mpoly_compose_fmpz_mpoly(t.den, a->den, C, mc, mc);
            free(C);
        } else {
            for (int v = 0; v < nv; v++)
                if (!st->moved[v])
                    dn[v] = 0; /* no denominator to clear */
            if (!compose_terms(t.num, a->num, self, dn, &st->budget, ctx) ||
                !compose_terms(t.den, a->den, self, dn, &st->budget, ctx))
                status = budget_error(st, err);
        }
        hl_alg_vec_free(self, nv, ctx);
    }
    /* the canonical form multiplies num by den's conjugates */
    if (status == HL_OK && any &&
        !budget_product(&st->budget, (double)t.num->length * (double)t.den->length))
        status = budget_error(st, err);
    if (status == HL_OK && any) {
        if (fmpz_mpoly_is_zero(t.den, mc))
            status = hl_error_set(err, HL_EDOM, NULL, -1, 0, "division by zero");
        else
            alg_canonicalise(&t, ctx);
        /* a denominator that vanishes only modulo the relations */
        if (status == HL_OK && fmpz_mpoly_is_zero(t.den, mc))
            status = hl_error_set(err, HL_EDOM, NULL, -1, 0, "division by zero");
    }
    if (status == HL_OK)
        hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
    free(dn);
    free(dd);
    return status;
}

hl_status hl_alg_subst(hl_alg *r, const hl_alg *a, int n, const int *vars, const hl_alg *vals,
                       hl_alg_ctx *ctx, hl_error *err)
{
    long reached;
    return hl_alg_subst_bounded(r, &reached, a, n, vars, vals, 0, ctx, err);
}

hl_status hl_alg_subst_bounded(hl_alg *r, long *reached, const hl_alg *a, int n, const int *vars,
                               const hl_alg *vals, long max_terms, hl_alg_ctx *ctx, hl_error *err)
{
    *reached = 0;
    int nv = alg_nvars(ctx);
    for (int i = 0; i < n; i++)
        if (vars[i] < 0 || vars[i] >= ctx->nbase)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no base symbol %d", vars[i]);
    subst_state st;
    st.n = n;
    st.vars = vars;
    st.natoms0 = ctx->natoms;
    st.budget.terms = max_terms > 0 ? max_terms : 0;
    st.budget.work = BUDGET_WORK_PER_TERM * (double)st.budget.terms;
    st.budget.reached = 0;
    st.img = hl_alg_vec_new(nv, ctx);
    st.known = hl_xcalloc((size_t)nv, 1);
    st.moved = hl_xcalloc((size_t)nv, 1);
    for (int i = 0; i < n; i++) {
        hl_alg_set(&st.img[vars[i]], &vals[i], ctx);
        st.moved[vars[i]] = st.known[vars[i]] = 1;
    }
    int status = subst_rec(r, a, &st, ctx, err);
    *reached = st.budget.reached;
    hl_alg_vec_free(st.img, nv, ctx);
    free(st.known);
    free(st.moved);
    return status;
}
